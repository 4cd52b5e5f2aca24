// Parallel HDF5 output (io/XdmfWriter.hpp with a communicator, run/OutputRows.hpp): on
// any number of ranks the file's datasets and attributes and the .xdmf text are bitwise
// those of the serial writer given the whole fields, and the nodal recovery from cells
// spread over the ranks equals the serial recover_at_nodes bitwise (the same summation
// order). The mesh: two bodies, quadrilaterals and triangles (a "Mixed" topology), sharing
// the nodes of x = 4, and a node of no cell. On one rank (ctest's default) the parallel
// path is the serial one; tests/cli runs this file on 2 and 3 ranks (mpi.parallel_output.*).
// The output built from a Distribution (xdmf_mesh_on_rows, NodeRows, recover_on_rows)
// reads no mesh data a rank's part of the mesh will not have: given a mesh whose other
// nodes' coordinates are NaN and whose other cells' nodes are wrong, its file is still
// bitwise the serial one.
#include <gtest/gtest.h>
#include <hdf5.h>
#include <mpi.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include <Tpetra_Core.hpp>
#include <limits>

#include "io/XdmfWriter.hpp"
#include "mesh/NodalRecovery.hpp"
#include "parallel/Distribution.hpp"
#include "run/OutputRows.hpp"

using namespace stentor;

namespace {

// nx x ny quadrilaterals on [0,4]x[0,ny] (block "quads"), then 2 nx' x ny triangles on
// [4,7] (block "tris"); node (i, j) = j * (nx + 1 + 3) + i; one node of no cell at the end.
Mesh two_bodies(int ny) {
  const int nq = 4, nt = 3, row = nq + nt + 1;
  Mesh m;
  m.dim = 2;
  for (int j = 0; j <= ny; ++j)
    for (int i = 0; i < row; ++i) m.x.insert(m.x.end(), {double(i), double(j) + 0.1 * i, 0.0});
  m.x.insert(m.x.end(), {9.0, 9.0, 0.0});
  CellBlock q, t;
  q.name = "quads", q.type = CellType::Quad4, q.nodes_per_cell = 4;
  t.name = "tris", t.type = CellType::Tri3, t.nodes_per_cell = 3;
  const auto n = [&](int i, int j) { return GId(j * row + i); };
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nq; ++i) q.conn.insert(q.conn.end(), {n(i, j), n(i + 1, j), n(i + 1, j + 1), n(i, j + 1)});
  for (int j = 0; j < ny; ++j)
    for (int i = nq; i < nq + nt; ++i) {
      t.conn.insert(t.conn.end(), {n(i, j), n(i + 1, j), n(i + 1, j + 1)});
      t.conn.insert(t.conn.end(), {n(i, j), n(i + 1, j + 1), n(i, j + 1)});
    }
  GId id = 0;
  for (CellBlock* b : {&q, &t})
    for (std::size_t c = 0; c < b->num_cells(); ++c) b->cell_id.push_back(id++);
  m.volumes = {q, t};
  return m;
}

// A value without structure: bits in every digit.
double value(std::size_t i, int j) { return std::sin(1.0 + 0.37 * double(i) + 1.91 * j) * std::exp(0.01 * double(i)); }

// Every dataset's and attribute's bytes (with its dimensions) of an HDF5 file, by path.
std::map<std::string, std::string> contents(const std::string& path) {
  struct Out {
    hid_t f;
    std::map<std::string, std::string> m;
  } out{H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), {}};
  H5Ovisit(out.f, H5_INDEX_NAME, H5_ITER_INC,
           [](hid_t f, const char* name, const H5O_info_t* info, void* p) -> herr_t {
             auto& o = *static_cast<Out*>(p);
             const hid_t obj = H5Oopen(f, name, H5P_DEFAULT);
             for (unsigned a = 0; a < info->num_attrs; ++a) {
               const hid_t at = H5Aopen_by_idx(obj, ".", H5_INDEX_NAME, H5_ITER_INC, a, H5P_DEFAULT, H5P_DEFAULT);
               char an[256] = {0};
               H5Aget_name(at, sizeof an, an);
               const hid_t sp = H5Aget_space(at), ty = H5Aget_type(at);
               o.m[std::string(name) + "@" + an] =
                   std::string(1, '\0') + std::to_string(H5Tget_class(ty)) + ":" + std::to_string(H5Tget_size(ty));
               std::string b(static_cast<std::size_t>(H5Sget_simple_extent_npoints(sp)) * H5Tget_size(ty), '\0');
               H5Aread(at, ty, b.data());
               o.m[std::string(name) + "@" + an] += b;
               H5Tclose(ty), H5Sclose(sp), H5Aclose(at);
             }
             if (info->type == H5O_TYPE_DATASET) {
               const hid_t sp = H5Dget_space(obj), ty = H5Dget_type(obj);
               hsize_t dims[8] = {0};
               const int nd = H5Sget_simple_extent_ndims(sp);
               H5Sget_simple_extent_dims(sp, dims, nullptr);
               std::string key;
               for (int i = 0; i < nd; ++i) key += std::to_string(dims[i]) + "x";
               std::string b(static_cast<std::size_t>(H5Sget_simple_extent_npoints(sp)) * H5Tget_size(ty), '\0');
               H5Dread(obj, ty, H5S_ALL, H5S_ALL, H5P_DEFAULT, b.data());
               o.m[name] = key + std::to_string(H5Tget_class(ty)) + ":" + b;
               H5Tclose(ty), H5Sclose(sp);
             }
             H5Oclose(obj);
             return 0;
           },
           &out);
  H5Fclose(out.f);
  return out.m;
}

std::string text(const std::string& path) {
  std::ifstream in(path);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

template <class T>
std::vector<T> rows_of(const std::vector<T>& all, RowRange r, int k) {
  return std::vector<T>(all.begin() + static_cast<std::ptrdiff_t>(r.begin * k), all.begin() + static_cast<std::ptrdiff_t>(r.end * k));
}

// The same steps written by `w` (this rank's rows of whole fields).
void write_steps(XdmfWriter& w, const Mesh& m) {
  const std::size_t nn = m.num_nodes(), nc = m.num_volume_cells();
  for (int step = 0; step < 2; ++step) {
    std::vector<double> u(3 * nn), s(6 * nn), c(nc), x(3 * nn);
    for (std::size_t i = 0; i < 3 * nn; ++i) u[i] = value(i, step), x[i] = m.x[i] + u[i];
    for (std::size_t i = 0; i < 6 * nn; ++i) s[i] = value(i, 7 + step);
    for (std::size_t i = 0; i < nc; ++i) c[i] = value(i, 3 + step);
    w.begin_step(0.5 * step + 0.1);
    w.node_field("displacement", 3, rows_of(u, w.node_rows(), 3));
    w.node_field("stress nodal", 6, rows_of(s, w.node_rows(), 6));
    w.cell_field("J", 1, rows_of(c, w.cell_rows(), 1));
    w.geometry(rows_of(x, w.node_rows(), 3));
    w.end_step();
  }
}

// Rank 0 compares the .h5 and .xdmf of <dir>/serial and <dir>/parallel.
void expect_same_files(const std::string& dir) {
  const auto a = contents(dir + "/serial/out.h5"), b = contents(dir + "/parallel/out.h5");
  EXPECT_GT(a.size(), 15u);
  ASSERT_EQ(a.size(), b.size());
  for (const auto& [path, bytes] : a) {
    ASSERT_TRUE(b.count(path)) << path;
    EXPECT_TRUE(b.at(path) == bytes) << path << " differs";
  }
  EXPECT_EQ(text(dir + "/serial/out.xdmf"), text(dir + "/parallel/out.xdmf"));
}

// A fresh <binary dir>/<name>.<ranks> with empty serial/ and parallel/ folders.
std::string fresh_dirs(const std::string& name, int rank, int size) {
  const std::string dir = std::string(STENTOR_BINARY_DIR) + "/" + name + "." + std::to_string(size);
  if (rank == 0) {
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir + "/serial");
    std::filesystem::create_directories(dir + "/parallel");
  }
  MPI_Barrier(MPI_COMM_WORLD);
  return dir;
}

// `m` with what a rank's part of it would lack spoilt: the coordinates of the nodes this
// rank does not own are NaN, the nodes of the cells that are not its own are wrong (valid
// ids, shifted).
Mesh spoilt(const Mesh& m, const Distribution& dist) {
  Mesh p = m;
  for (std::size_t g = 0; g < m.num_nodes(); ++g)
    if (!dist.owns_node(static_cast<GId>(g)))
      for (int k = 0; k < 3; ++k) p.x[3 * g + k] = std::numeric_limits<double>::quiet_NaN();
  for (std::size_t b = 0; b < m.volumes.size(); ++b) {
    std::vector<char> own(m.volumes[b].num_cells(), 0);
    for (const LocalBlock& lb : dist.blocks())
      if (lb.volume_block == static_cast<int>(b))
        for (GId i : lb.cell_index) own[static_cast<std::size_t>(i)] = 1;
    CellBlock& cb = p.volumes[b];
    const auto npc = static_cast<std::size_t>(cb.nodes_per_cell);
    for (std::size_t c = 0; c < own.size(); ++c)
      for (std::size_t a = 0; a < npc && !own[c]; ++a) cb.conn[c * npc + a] = (cb.conn[c * npc + a] + 5) % GId(m.num_nodes());
  }
  return p;
}

}  // namespace

TEST(ParallelOutput, FileEqualsTheSerialWritersBitwise) {
  int rank = 0, size = 1;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  const std::string dir = fresh_dirs("test_parallel_output", rank, size);
  const Mesh m = two_bodies(5);
  {
    XdmfWriter w(dir + "/parallel", "out", m, MPI_COMM_WORLD);
    std::size_t total[2] = {w.node_rows().size(), w.cell_rows().size()}, sum[2] = {0, 0};
    MPI_Allreduce(total, sum, 2, MPI_UNSIGNED_LONG, MPI_SUM, MPI_COMM_WORLD);
    EXPECT_EQ(sum[0], m.num_nodes());
    EXPECT_EQ(sum[1], m.num_volume_cells());
    write_steps(w, m);
    EXPECT_EQ(w.num_steps(), 2);
  }
  if (rank == 0) {
    {
      XdmfWriter w(dir + "/serial", "out", m);
      write_steps(w, m);
    }
    expect_same_files(dir);
    const auto a = contents(dir + "/serial/out.h5");
    EXPECT_TRUE(a.count("mesh/topology@topology") && a.count("step_1@time") && a.count("mesh/block_1@name"));
    EXPECT_NE(text(dir + "/parallel/out.xdmf").find("TopologyType=\"Mixed\""), std::string::npos);
  }
  MPI_Barrier(MPI_COMM_WORLD);
}

// Cells dealt round-robin (cell id % ranks: no rank's cells or nodes contiguous).
TEST(ParallelOutput, NodalRecoveryOnRowsEqualsSerialBitwise) {
  int rank = 0, size = 1;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  const Mesh m = two_bodies(7);
  const std::size_t nn = m.num_nodes(), nc = m.num_volume_cells();
  std::vector<double> all6(6 * nc), all1(nc), volume(nc);
  for (std::size_t c = 0; c < nc; ++c) {
    for (int j = 0; j < 6; ++j) all6[6 * c + j] = value(c, j);
    all1[c] = value(c, 11);
    volume[c] = 1.0 + 0.5 * value(c, 13);
  }
  std::vector<GId> mine;
  std::vector<double> v6, v1, vol;
  for (std::size_t c = nc; c-- > 0;)  // in descending order: the exchange sorts them
    if (static_cast<int>(c % static_cast<std::size_t>(size)) == rank) {
      mine.push_back(static_cast<GId>(c));
      v6.insert(v6.end(), &all6[6 * c], &all6[6 * c + 6]);
      v1.push_back(all1[c]);
      vol.push_back(volume[c]);
    }
  const RowRange rows = block_rows(nn, rank, size);
  const auto got = recover_on_rows(m, MPI_COMM_WORLD, rows, mine, {&v6, &v1}, {6, 1}, vol);
  ASSERT_EQ(got.size(), 2u);
  const std::vector<double> ref6 = recover_at_nodes(m, all6, 6, volume), ref1 = recover_at_nodes(m, all1, 1, volume);
  EXPECT_EQ(got[0], rows_of(ref6, rows, 6));  // bitwise
  EXPECT_EQ(got[1], rows_of(ref1, rows, 1));
}

// Records reach the rank of their row, in the order of the sending ranks.
TEST(ParallelOutput, RouteToRows) {
  int rank = 0, size = 1;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  const std::size_t n = 10;
  for (std::size_t row = 0; row < n; ++row) {
    const int owner = block_row_owner(n, size, row);
    const RowRange r = block_rows(n, owner, size);
    EXPECT_TRUE(row >= r.begin && row < r.end) << row;
  }
  std::vector<long long> ids;
  std::vector<double> values;
  for (long long i = 0; i < static_cast<long long>(n); ++i) ids.push_back(i), values.push_back(100.0 * rank + double(i));
  const Records got = route_to_rows(MPI_COMM_WORLD, n, ids, values, 1);
  const RowRange mine = block_rows(n, rank, size);
  ASSERT_EQ(got.ids.size(), mine.size() * static_cast<std::size_t>(size));
  for (std::size_t i = 0; i < got.ids.size(); ++i) {
    const int from = static_cast<int>(i / mine.size());
    EXPECT_EQ(got.from[i], from);
    EXPECT_EQ(got.ids[i], static_cast<long long>(mine.begin + i % mine.size()));
    EXPECT_EQ(got.values[i], 100.0 * from + double(got.ids[i]));
  }
}

// The writer's mesh, the dof vectors on the node rows and the nodal recovery from a
// Distribution read only what a rank has (spoilt): the file is the serial one bitwise.
TEST(ParallelOutput, FromTheDistributionReadsOnlyWhatARankHas) {
  int rank = 0, size = 1;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  const std::string dir = fresh_dirs("test_parallel_output_dist", rank, size);
  const Mesh m = two_bodies(5);
  const auto comm = Tpetra::getDefaultComm();
  const Distribution dist(m, comm);
  const Mesh part = spoilt(m, dist);
  const std::size_t nn = m.num_nodes(), nc = m.num_volume_cells();
  {
    XdmfWriter w(dir + "/parallel", "out", xdmf_mesh_on_rows(part, dist, MPI_COMM_WORLD), MPI_COMM_WORLD);
    write_steps(w, m);
    // A dof vector on the rows: 3 per node, 0 on the node of no cell (the last).
    NodeRows rows(dist, part.num_nodes(), comm, w.node_rows());
    la::Vector u(dist.owned_map());
    auto uh = u.getLocalViewHost(Tpetra::Access::OverwriteAll);
    for (la::LO l = 0; l < dist.num_owned_nodes(); ++l)
      for (std::size_t k = 0; k < 2; ++k)
        uh(static_cast<std::size_t>(l) * 2 + k, 0) = value(static_cast<std::size_t>(dist.global_node(l)) * 2 + k, 5);
    std::vector<double> expect(3 * nn, 0.0);
    for (std::size_t g = 0; g + 1 < nn; ++g)
      for (std::size_t k = 0; k < 2; ++k) expect[3 * g + k] = value(2 * g + k, 5);
    EXPECT_EQ(rows.values(u), rows_of(expect, w.node_rows(), 3));
    // The recovery from this rank's own cells.
    std::vector<double> all(nc), volume(nc), mine, vol;
    std::vector<GId> ids;
    for (std::size_t c = 0; c < nc; ++c) all[c] = value(c, 17), volume[c] = 1.0 + 0.5 * value(c, 19);
    for (const LocalBlock& lb : dist.blocks())
      for (GId id : lb.cell_ids) {
        ids.push_back(id);
        mine.push_back(all[static_cast<std::size_t>(id)]);
        vol.push_back(volume[static_cast<std::size_t>(id)]);
      }
    const auto got = recover_on_rows(part, MPI_COMM_WORLD, w.node_rows(), ids, {&mine}, {1}, vol);
    ASSERT_EQ(got.size(), 1u);
    EXPECT_EQ(got[0], rows_of(recover_at_nodes(m, all, 1, volume), w.node_rows(), 1));  // bitwise
  }
  if (rank == 0) {
    {
      XdmfWriter w(dir + "/serial", "out", m);
      write_steps(w, m);
    }
    expect_same_files(dir);
  }
  MPI_Barrier(MPI_COMM_WORLD);
}
