// A rank's part of the mesh (mesh/MeshPart.hpp): what it holds, cut on one rank, and the
// parallel layout built from parts equal to the one built from the whole mesh. The second
// test runs on several ranks as mpi.mesh_part.np3 (tests/cli/CMakeLists.txt).
#include <gtest/gtest.h>
#include <mpi.h>

#include <Tpetra_Core.hpp>
#include <algorithm>
#include <set>

#include "bc/Loads.hpp"
#include "mesh/GmshReader.hpp"
#include "mesh/MeshComm.hpp"
#include "mesh/MeshPart.hpp"
#include "parallel/Distribution.hpp"
#include "../mesh/InputMesh.hpp"

using namespace stentor;

namespace {

// Global node ids of whole-mesh cell c of block b.
std::set<GId> cell_nodes(const CellBlock& b, std::size_t c) {
  const auto npc = static_cast<std::size_t>(b.nodes_per_cell);
  return std::set<GId>(b.conn.begin() + static_cast<std::ptrdiff_t>(c * npc), b.conn.begin() + static_cast<std::ptrdiff_t>((c + 1) * npc));
}

// `sided`: the whole mesh with its facets' sides; `whole_groups` as given to mesh_part.
void expect_part_of(const Mesh& sided, const std::vector<int>& cell_part, int r, const std::vector<std::string>& whole_groups,
                    const Mesh& p) {
  const Mesh& whole = sided;
  ASSERT_TRUE(p.partial);
  EXPECT_EQ(p.num_nodes(), whole.num_nodes());
  EXPECT_EQ(p.num_volume_cells(), whole.num_volume_cells());
  EXPECT_EQ(p.bounding_box().diagonal(), whole.bounding_box().diagonal());
  std::set<GId> touched, on_cells;
  for (const auto& b : whole.volumes)
    for (std::size_t c = 0; c < b.num_cells(); ++c)
      if (cell_part[static_cast<std::size_t>(b.cell_id[c])] == r)
        for (GId g : cell_nodes(b, c)) touched.insert(g);
  ASSERT_EQ(p.volumes.size(), whole.volumes.size());
  for (std::size_t bi = 0; bi < whole.volumes.size(); ++bi) {
    const CellBlock &w = whole.volumes[bi], &q = p.volumes[bi];
    EXPECT_EQ(q.name, w.name);
    EXPECT_EQ(q.whole_cells, w.num_cells());
    EXPECT_TRUE(std::is_sorted(q.cell_id.begin(), q.cell_id.end()));
    std::size_t k = 0;  // the stored cells are exactly those of part r and those touching its nodes
    for (std::size_t c = 0; c < w.num_cells(); ++c) {
      const std::set<GId> nodes = cell_nodes(w, c);
      const bool mine = cell_part[static_cast<std::size_t>(w.cell_id[c])] == r;
      const bool near = std::any_of(nodes.begin(), nodes.end(), [&](GId g) { return touched.count(g) > 0; });
      if (!mine && !near) continue;
      ASSERT_LT(k, q.num_cells());
      EXPECT_EQ(q.cell_id[k], w.cell_id[c]);
      EXPECT_EQ(q.part[k], cell_part[static_cast<std::size_t>(w.cell_id[c])]);
      EXPECT_EQ(cell_nodes(q, k), nodes);
      EXPECT_EQ(locate_cell(p, w.cell_id[c]), std::make_pair(bi, k));
      on_cells.insert(nodes.begin(), nodes.end());
      ++k;
    }
    EXPECT_EQ(k, q.num_cells());
  }
  // Boundary groups: whole ones whole, of the others the cells on this part's cells (and
  // facets bounding no cell), in order, with the whole mesh's sides.
  std::set<GId> expect_nodes = on_cells;
  ASSERT_EQ(p.boundaries.size(), whole.boundaries.size());
  for (std::size_t bi = 0; bi < whole.boundaries.size(); ++bi) {
    const CellBlock &w = whole.boundaries[bi], &q = p.boundaries[bi];
    const bool all = std::find(whole_groups.begin(), whole_groups.end(), w.name) != whole_groups.end();
    std::size_t k = 0;
    for (std::size_t c = 0; c < w.num_cells(); ++c) {
      const std::set<GId> nodes = cell_nodes(w, c);
      const bool on = std::all_of(nodes.begin(), nodes.end(), [&](GId g) { return on_cells.count(g) > 0; });
      if (!all && !on && (w.side.empty() || w.side[c] != 0)) continue;
      ASSERT_LT(k, q.num_cells()) << w.name;
      EXPECT_EQ(cell_nodes(q, k), nodes);
      if (!w.side.empty()) {
        EXPECT_EQ(q.side[k], w.side[c]);
        EXPECT_EQ(q.adjacent[k], w.adjacent[c]);
      }
      expect_nodes.insert(nodes.begin(), nodes.end());
      ++k;
    }
    EXPECT_EQ(k, q.num_cells()) << w.name;
    if (all) EXPECT_EQ(q.conn, w.conn);
  }
  EXPECT_EQ(std::vector<GId>(expect_nodes.begin(), expect_nodes.end()), p.node_ids);
  for (GId g : p.node_ids)
    for (int d = 0; d < 3; ++d) EXPECT_EQ(p.coord(g)[d], whole.coord(g)[d]);
  EXPECT_THROW(p.coord(static_cast<GId>(whole.num_nodes())), std::logic_error);
}

}  // namespace

// Parts 0..2 of a 2D mesh with curves (line3 facets) and points: cells, ghost layer,
// nodes, boundary groups whole or cut with the facets' sides as the whole mesh gives
// them; the serialized part comes back equal.
TEST(MeshPart, HoldsItsCellsTheirNeighboursAndTheWholeBoundaries) {
  const Mesh whole = read_mesh(input_mesh("s4_ring_section.geo", 0.4, 2));
  const std::vector<int> cell_part = partition_cells(whole, 3);
  Mesh sided = whole;
  for (auto& b : sided.boundaries)
    if (cell_dim(b.type) == sided.dim - 1) {
      FacetSides s = facet_sides(sided, b);
      b.side = s.side;
      b.adjacent = s.adjacent;
    }
  const std::vector<std::string> whole_groups{"lumen", "stent_out"};
  for (int r = 0; r < 3; ++r) {
    SCOPED_TRACE("part " + std::to_string(r));
    const Mesh p = mesh_part(sided, cell_part, r, whole_groups);
    expect_part_of(sided, cell_part, r, whole_groups, p);
    for (const std::string g : {"lumen", "adventitia", "stent_in"}) {  // oriented as on the whole mesh
      const auto a = oriented_facets(whole, g, "test"), b = oriented_facets(p, g, "test");
      ASSERT_EQ(a.size(), b.size());
      const CellBlock* pb = nullptr;
      for (const auto& blk : p.boundaries)
        if (blk.name == g) pb = &blk;
      ASSERT_TRUE(pb);
      for (std::size_t i = 0; i < a.size(); ++i) {
        EXPECT_EQ(b[i].orientation, std::vector<double>(pb->side.begin(), pb->side.end()));
        EXPECT_EQ(b[i].adjacent_cell, pb->adjacent);
        if (g == "lumen") EXPECT_EQ(a[i].orientation, b[i].orientation);
      }
    }
    const Mesh back = deserialize_mesh(serialize_mesh(p));
    EXPECT_EQ(back.node_ids, p.node_ids);
    EXPECT_EQ(back.x, p.x);
    EXPECT_EQ(back.whole_nodes, p.whole_nodes);
    EXPECT_EQ(back.volumes[0].part, p.volumes[0].part);
    EXPECT_EQ(back.boundaries[2].side, p.boundaries[2].side);
    EXPECT_EQ(back.volumes[1].whole_cells, p.volumes[1].whole_cells);
  }
}

// On any number of ranks: the layout (owned and ghost nodes, their coordinates, each
// rank's cells and their local connectivity) from the parts that distribute_mesh sends
// equals the one from the whole mesh on every rank; the part holds only a share.
TEST(MeshPart, DistributionFromPartsEqualsDistributionFromTheWholeMesh) {
  const MeshConfig cfg = input_mesh("block3d.geo", 0.25, 2);
  const Mesh whole = read_mesh_on_root(cfg, MPI_COMM_WORLD);
  Mesh part = read_mesh_on_root_only(cfg, MPI_COMM_WORLD);
  distribute_mesh(part, MPI_COMM_WORLD, {"left"});
  const auto comm = Tpetra::getDefaultComm();
  const Distribution a(whole, comm), b(part, comm);
  if (comm->getSize() > 1) {
    EXPECT_TRUE(part.partial);
    EXPECT_LT(part.volumes[0].num_cells(), whole.volumes[0].num_cells());
  }
  ASSERT_EQ(a.num_owned_nodes(), b.num_owned_nodes());
  ASSERT_EQ(a.num_local_nodes(), b.num_local_nodes());
  auto ca = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), a.coords());
  auto cb = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), b.coords());
  for (la::LO l = 0; l < a.num_local_nodes(); ++l) {
    ASSERT_EQ(a.global_node(l), b.global_node(l));
    EXPECT_EQ(b.local_node(a.global_node(l)), l);
    for (int d = 0; d < 3; ++d) EXPECT_EQ(ca(l, d), cb(l, d));
  }
  EXPECT_EQ(b.local_node(static_cast<GId>(whole.num_nodes()) + 5), -1);
  ASSERT_EQ(a.blocks().size(), b.blocks().size());
  for (std::size_t i = 0; i < a.blocks().size(); ++i) {
    const LocalBlock &p = a.blocks()[i], &q = b.blocks()[i];
    EXPECT_EQ(p.cell_ids, q.cell_ids);
    auto hp = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), p.conn);
    auto hq = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), q.conn);
    ASSERT_EQ(hp.extent(0), hq.extent(0));
    for (std::size_t c = 0; c < hp.extent(0); ++c)
      for (int n = 0; n < p.nodes_per_cell; ++n) EXPECT_EQ(hp(c, n), hq(c, n));
    // cell_index points into each mesh's own block: the same cell
    for (std::size_t c = 0; c < p.cell_index.size(); ++c)
      EXPECT_EQ(whole.volumes[static_cast<std::size_t>(p.volume_block)].cell_id[static_cast<std::size_t>(p.cell_index[c])],
                part.volumes[static_cast<std::size_t>(q.volume_block)].cell_id[static_cast<std::size_t>(q.cell_index[c])]);
  }
  EXPECT_EQ(a.owned_map()->getGlobalNumElements(), b.owned_map()->getGlobalNumElements());
}
