// broadcast_mesh / read_mesh_on_root under MPI. Runs on 1 rank as a plain test, and
// on several with e.g. `mpirun -np 3 ./test_mesh_mpi`. Defines its own main (MPI_Init);
// it takes precedence over gtest_main's.
#include <gtest/gtest.h>
#include <mpi.h>

#include "mesh/GmshReader.hpp"
#include "mesh/MeshCheck.hpp"
#include "mesh/MeshComm.hpp"
#include "InputMesh.hpp"

using namespace stentor;

namespace {

void expect_same(const Mesh& a, const Mesh& b) {
  EXPECT_EQ(a.dim, b.dim);
  EXPECT_EQ(a.source, b.source);
  EXPECT_EQ(a.x, b.x);
  for (auto pair : {std::make_pair(&a.volumes, &b.volumes), std::make_pair(&a.boundaries, &b.boundaries)}) {
    ASSERT_EQ(pair.first->size(), pair.second->size());
    for (std::size_t k = 0; k < pair.first->size(); ++k) {
      const auto &p = (*pair.first)[k], &q = (*pair.second)[k];
      EXPECT_EQ(p.name, q.name);
      EXPECT_EQ(p.physical_tag, q.physical_tag);
      EXPECT_EQ(p.type, q.type);
      EXPECT_EQ(p.nodes_per_cell, q.nodes_per_cell);
      EXPECT_EQ(p.conn, q.conn);
      EXPECT_EQ(p.cell_id, q.cell_id);
    }
  }
}

int rank_of(MPI_Comm c) {
  int r = 0;
  MPI_Comm_rank(c, &r);
  return r;
}

}  // namespace

TEST(MeshMpi, BroadcastGivesEveryRankTheRootMesh) {
  const int size_of_world = [] {
    int s = 1;
    MPI_Comm_size(MPI_COMM_WORLD, &s);
    return s;
  }();
  const int root = size_of_world - 1;  // also a non-zero root when run on several ranks
  const MeshConfig cfg = input_mesh("cylinder.geo", 0.2, 2);
  Mesh m;
  if (rank_of(MPI_COMM_WORLD) == root) m = read_mesh(cfg);
  else m.source = "stale";  // replaced
  broadcast_mesh(m, MPI_COMM_WORLD, root);
  const Mesh ref = read_mesh(cfg);  // every rank reads it itself to compare
  expect_same(ref, m);
  EXPECT_NO_THROW(check_mesh(m));
}

TEST(MeshMpi, ReadOnRootBroadcastsMeshOrError) {
  const MeshConfig cfg = input_mesh("block3d.geo", 0.5, 1);
  const Mesh m = read_mesh_on_root(cfg, MPI_COMM_WORLD);
  expect_same(read_mesh(cfg), m);

  MeshConfig bad = cfg;
  bad.file += ".missing";
  try {
    read_mesh_on_root(bad, MPI_COMM_WORLD);
    ADD_FAILURE() << "no InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()).rfind(bad.file + ": cannot open", 0), 0u) << e.what();
  }
}

int main(int argc, char** argv) {
  MPI_Init(&argc, &argv);
  ::testing::InitGoogleTest(&argc, argv);
  // Only rank 0 prints gtest's report.
  if (rank_of(MPI_COMM_WORLD) != 0) {
    auto& listeners = ::testing::UnitTest::GetInstance()->listeners();
    delete listeners.Release(listeners.default_result_printer());
  }
  const int rc = RUN_ALL_TESTS();
  int worst = rc;
  MPI_Allreduce(&rc, &worst, 1, MPI_INT, MPI_MAX, MPI_COMM_WORLD);
  MPI_Finalize();
  return worst;
}
