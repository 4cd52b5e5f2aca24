// mesh/NodalRecovery.hpp: volume-weighted nodal averages per body. Two bodies of
// quadrilaterals side by side sharing the nodes of x = 1 (a conforming interface):
//   body A (block 0): cells [0,1]x[0,1] (volume 1) and [0,1]x[1,3] (volume 2);
//   body B (block 1): the cell [1,2]x[0,1] (volume 1), sharing the edge x = 1, y in [0,1].
// Node values: weighted means within a body; the shared nodes take body A's (the first
// block); a constant field is recovered exactly; k > 1 components are kept apart.
#include <gtest/gtest.h>

#include "mesh/NodalRecovery.hpp"

using namespace stentor;

namespace {

// Nodes: 0 (0,0) 1 (1,0) 2 (1,1) 3 (0,1) 4 (1,3) 5 (0,3) 6 (2,0) 7 (2,1) 8 (5,5, no cell).
Mesh two_bodies() {
  Mesh m;
  m.dim = 2;
  m.x = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, 1, 3, 0, 0, 3, 0, 2, 0, 0, 2, 1, 0, 5, 5, 0};
  CellBlock a;
  a.name = "A";
  a.type = CellType::Quad4;
  a.nodes_per_cell = 4;
  a.conn = {0, 1, 2, 3, 3, 2, 4, 5};
  a.cell_id = {0, 1};
  CellBlock b;
  b.name = "B";
  b.type = CellType::Quad4;
  b.nodes_per_cell = 4;
  b.conn = {1, 6, 7, 2};
  b.cell_id = {2};
  m.volumes = {a, b};
  return m;
}

}  // namespace

TEST(NodalRecovery, VolumeWeightedPerBodyFirstBodyAtInterfaces) {
  const Mesh m = two_bodies();
  const std::vector<double> volume = {1.0, 2.0, 1.0};
  // Two components: (10, 1), (40, 2), (100, 3) in cells 0, 1, 2.
  const std::vector<double> v = {10, 1, 40, 2, 100, 3};
  const std::vector<double> r = recover_at_nodes(m, v, 2, volume);
  ASSERT_EQ(r.size(), 18u);
  const double mixed0 = (1 * 10 + 2 * 40) / 3.0, mixed1 = (1 * 1 + 2 * 2) / 3.0;
  const double expect[9][2] = {{10, 1},         {10, 1},  {mixed0, mixed1}, {mixed0, mixed1}, {40, 2},
                               {40, 2},         {100, 3}, {100, 3},         {0, 0}};
  for (int n = 0; n < 9; ++n)
    for (int j = 0; j < 2; ++j) EXPECT_DOUBLE_EQ(r[2 * n + j], expect[n][j]) << "node " << n << " component " << j;
  // Nodes 1 and 2 lie on the interface: body A's values, not a mean with body B's 100.
  // A constant field comes back exactly (node 8, in no cell: 0).
  const std::vector<double> c = recover_at_nodes(m, {7.5, 7.5, 7.5}, 1, volume);
  for (int n = 0; n < 8; ++n) EXPECT_DOUBLE_EQ(c[n], 7.5) << "node " << n;
  EXPECT_EQ(c[8], 0.0);
}
