// mesh_to_msh (geometry/MshWriter.hpp): a generated stent written as gmsh 2.2 ASCII and
// read back by gmsh (mesh/GmshReader.hpp) is the same mesh: nodes, cells, groups.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdio>
#include <fstream>
#include <string>

#include "deck/Config.hpp"
#include "geometry/MshWriter.hpp"
#include "geometry/StentGenerator.hpp"
#include "mesh/GmshReader.hpp"
#include "StentFixtures.hpp"

using namespace stentor;

TEST(MshWriter, GmshReadsTheStentBackUnchanged) {
  StentConfig s = test::s6_ring_as_cut();
  s.rings = 2;
  s.ring_length = 0.9;
  s.links_per_ring = 4;
  s.sector = "quarter";
  const Mesh m = generate_stent(s, 1e6, "test");
  const std::string path = "/tmp/stentor_test_msh_writer_" + std::to_string(::getpid()) + ".msh";
  std::ofstream(path) << mesh_to_msh(m);
  MeshConfig cfg;
  cfg.file = path;
  const Mesh r = read_mesh(cfg);
  std::remove(path.c_str());
  ASSERT_EQ(r.dim, 3);
  ASSERT_EQ(r.num_nodes(), m.num_nodes());
  for (std::size_t i = 0; i < m.x.size(); ++i) ASSERT_EQ(r.x[i], m.x[i]) << i;  // 17 digits: exact
  ASSERT_EQ(r.volumes.size(), 1u);
  EXPECT_EQ(r.volumes[0].name, "stent");
  EXPECT_EQ(r.volumes[0].conn, m.volumes[0].conn);
  ASSERT_EQ(r.boundaries.size(), m.boundaries.size());
  for (const CellBlock& b : m.boundaries) {
    bool found = false;
    for (const CellBlock& c : r.boundaries)
      if (c.name == b.name) {
        found = true;
        EXPECT_EQ(c.type, b.type) << b.name;
        EXPECT_EQ(c.conn, b.conn) << b.name;
      }
    EXPECT_TRUE(found) << b.name;
  }
}
