// Contact fields as a user reads them in the HDF5/XDMF output (issue 13; docs/deck.md,
// "Outputs"; docs/contact.md, "Output"):
//   1. contact_pressure: a block pressed onto a rigid plane by a uniform dead traction p on
//      its top (frictionless, symmetry rollers: a homogeneous state the mesh reproduces
//      exactly) shows p at every node of the contact surface, on every facet type (line2 of
//      tri3 and quad4, line3 of tri6, tri3 of tet4, tri6 of tet10, quad4 of hex8); and
//      against another body (tri6 interface of two tet10 blocks) the master side's
//      contact_master_traction too (mesh/SurfaceProjection.hpp).
//   2. contact_gap: the gap at every slave node (0 where the block touches the plane, the
//      distance to a second plane above its top where it does not), NaN at every other
//      node (not 0, which would read as touching).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <utility>
#include <string>
#include <vector>

#include "H5Results.hpp"
#include "deck/Config.hpp"
#include "run/Simulation.hpp"
#include "TestDir.hpp"

using namespace stentor;
namespace fs = std::filesystem;
using H5 = stentor::testing::H5Results;

namespace {

fs::path work_dir() { return stentor::testing::test_dir("contact_output"); }
const std::string kInputs = std::string(STENTOR_SOURCE_DIR) + "/inputs/";
constexpr double kP = 1e4;  // the applied traction [Pa]: 2 % strain of the rubber below

// A structured unit cube of 3 x 3 x 3 hexahedra with the face groups of inputs/block3d.geo.
std::string hex_cube_geo() {
  fs::create_directories(work_dir());
  const fs::path p = work_dir() / "hex_cube.geo";
  std::ofstream(p) << R"X(SetFactory("OpenCASCADE");
Box(1) = {0, 0, 0, 1, 1, 1};
Transfinite Curve{:} = 4;
Transfinite Surface{:};
Recombine Surface{:};
Transfinite Volume{1};
e = 1e-3;
Physical Volume("block") = {1};
Physical Surface("left") = Surface In BoundingBox{-e, -e, -e, e, 1 + e, 1 + e};
Physical Surface("front") = Surface In BoundingBox{-e, -e, -e, 1 + e, e, 1 + e};
Physical Surface("bottom") = Surface In BoundingBox{-e, -e, -e, 1 + e, 1 + e, e};
Physical Surface("top") = Surface In BoundingBox{-e, -e, 1 - e, 1 + e, 1 + e, 1 + e};
)X";
  return p.string();
}

struct BlockCase {
  std::string name;
  int dim;
  int order;
  bool recombine;  // quads (2D)
  bool hex;        // the structured hexahedral cube (3D)
};

// The unit square / cube on the rigid plane y = 0 (z = 0 in 3D), pressed by the dead
// traction p on its top; rollers on x = 0 (and y = 0 in 3D) remove the rigid motions. A
// second pair, "lid", has the top's nodes as slaves against the plane y = 1.2 (z = 1.2),
// which they never reach.
std::string block_on_plane_deck(const BlockCase& c) {
  const bool d3 = c.dim == 3;
  const std::string geo = c.hex ? hex_cube_geo() : kInputs + (d3 ? "block3d.geo" : "block2d.geo");
  const auto roller = [](const std::string& group, const std::string& comp) {
    return R"X(<ParameterList name=")X" + group + R"X("><Parameter name="type" type="string" value="Dirichlet"/>
      <Parameter name="boundary" type="string" value=")X" + group + R"X("/>
      <Parameter name="components" type="string" value=")X" + comp + R"X("/></ParameterList>)X";
  };
  const std::string rollers = roller("left", "x") + (d3 ? roller("front", "y") : "");
  const std::string p = std::to_string(-kP);
  return R"X(<ParameterList name="stentor">
  <ParameterList name="Mesh"><Parameter name="file" type="string" value=")X" + geo + R"X("/>
    <Parameter name="size" type="double" value=")X" + (d3 ? "0.4" : "0.2") + R"X("/>
    <Parameter name="order" type="int" value=")X" + std::to_string(c.order) + R"X("/>
    <Parameter name="recombine" type="bool" value=")X" + (c.recombine ? "true" : "false") + R"X("/></ParameterList>
  <ParameterList name="Materials"><ParameterList name="rubber">
    <Parameter name="C1" type="double" value="0.5e6"/><Parameter name="C2" type="double" value="0.005e6"/>
    <Parameter name="D" type="double" value="0.35e6"/></ParameterList></ParameterList>
  <ParameterList name="Bodies"><ParameterList name="block">
    <Parameter name="material" type="string" value="rubber"/></ParameterList></ParameterList>
  <ParameterList name="Boundary Conditions">)X" + rollers + R"X(
    <ParameterList name="press"><Parameter name="type" type="string" value="traction"/>
      <Parameter name="boundary" type="string" value="top"/>
      <Parameter name="traction" type="Array(double)" value=")X" + (d3 ? "{0, 0, " + p + "}" : "{0, " + p + "}") + R"X("/>
    </ParameterList></ParameterList>
  <ParameterList name="Contact"><ParameterList name="floor">
    <Parameter name="slave" type="string" value="bottom"/><Parameter name="obstacle" type="string" value="plane"/>
    <Parameter name="point" type="Array(double)" value=")X" + (d3 ? "{0, 0, 0}" : "{0, 0}") + R"X("/>
    <Parameter name="normal" type="Array(double)" value=")X" + (d3 ? "{0, 0, 1}" : "{0, 1}") + R"X("/>
  </ParameterList><ParameterList name="lid">
    <Parameter name="slave" type="string" value="top"/><Parameter name="obstacle" type="string" value="plane"/>
    <Parameter name="point" type="Array(double)" value=")X" + (d3 ? "{0, 0, 1.2}" : "{0, 1.2}") + R"X("/>
    <Parameter name="normal" type="Array(double)" value=")X" + (d3 ? "{0, 0, -1}" : "{0, -1}") + R"X("/>
  </ParameterList></ParameterList>
  <ParameterList name="Stepping"><Parameter name="steps" type="int" value="1"/></ParameterList>
  <ParameterList name="Linear Solver"><Parameter name="method" type="string" value="direct"/></ParameterList>
  <ParameterList name="Output"><Parameter name="basename" type="string" value="block"/></ParameterList>
</ParameterList>
)X";
}

// Runs `deck` in system_tests/contact_output/<name>; returns the output folder.
std::string read_text(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

fs::path run_deck(const std::string& name, const std::string& deck) {
  const fs::path dir = work_dir() / name;
  fs::create_directories(dir);
  const fs::path p = dir / "deck.xml";
  std::ofstream(p) << deck;
  const Config cfg = read_deck(p.string());
  RunOptions o;
  o.output_dir = (dir / "out").string();
  o.overwrite = true;
  EXPECT_EQ(run_simulation(cfg, o, nullptr), 0) << name;
  return dir / "out";
}

}  // namespace

// Measured before the projection (force / HRZ-lumped area): tet10 0 at the tri6 corner
// nodes and 1.1875 p at the mid-edge nodes; the other facet types p to 1e-12. With it:
// p to 1e-12 at every contact-surface node of every facet type.
TEST(ContactOutput, UniformPressureOnEveryFacetType) {
  const std::vector<BlockCase> cases = {{"tri3", 2, 1, false, false}, {"tri6", 2, 2, false, false}, {"quad4", 2, 1, true, false},
                                        {"tet4", 3, 1, false, false}, {"tet10", 3, 2, false, false}, {"hex8", 3, 1, false, true}};
  for (const BlockCase& c : cases) {
    const fs::path out = run_deck("uniform_" + c.name, block_on_plane_deck(c));
    H5 h5(out / "block.h5");
    const std::size_t last = h5.times().size() - 1;
    ASSERT_EQ(last, 1u) << c.name;
    const std::string step = "/step_" + std::to_string(last) + "/";
    const auto X = h5.read("/mesh/coordinates"), pr = h5.read(step + "contact_pressure"), st = h5.read(step + "contact_status");
    ASSERT_EQ(pr.size() * 3, X.size()) << c.name;
    double worst = 0.0;
    std::size_t on_surface = 0;
    for (std::size_t n = 0; n < pr.size(); ++n) {
      const double h = X[3 * n + static_cast<std::size_t>(c.dim - 1)];
      const bool bottom = h == 0.0;
      EXPECT_EQ(st[n] >= 0.0, bottom || h == 1.0) << c.name << " node " << n << ": a slave node exactly when on the bottom or the top";
      if (!bottom) {
        EXPECT_EQ(pr[n], 0.0) << c.name << " node " << n;
        continue;
      }
      ++on_surface;
      worst = std::max(worst, std::abs(pr[n] - kP) / kP);
      EXPECT_NEAR(pr[n], kP, 1e-9 * kP) << c.name << " node " << n;
    }
    std::printf("%s: %zu contact-surface nodes, max |contact_pressure - p| / p %.2e\n", c.name.c_str(), on_surface, worst);
    EXPECT_GT(on_surface, 3u) << c.name;
  }
}

// Against another body: the two tetrahedral blocks of inputs/contact_patch3d.xml with
// matching tri6 interface facets (3 x 3 divisions, Mesh->order 2) under p on the upper
// block's top: a homogeneous state, so the upper block's contact_pressure is p and the
// lower block's contact_master_traction is (0, 0, -p), its contact_master_pressure p, at
// every interface node.
// Measured before the projection: both 0 at the tri6 corner nodes and 1.1875 p at the
// mid-edge nodes.
TEST(ContactOutput, PressureAndMasterTractionUniformOnTri6Interface) {
  std::string deck = read_text(kInputs + "contact_patch3d.xml");
  std::string geo = read_text(kInputs + "two_blocks3d.geo");
  for (const auto& [from, to] : {std::pair<std::string, std::string>{"nu = DefineNumber[4", "nu = DefineNumber[3"}, {"tet = DefineNumber[0", "tet = DefineNumber[1"}})
    geo.replace(geo.find(from), from.size(), to);
  fs::create_directories(work_dir());
  std::ofstream(work_dir() / "two_tet_blocks.geo") << geo;
  const std::string file = R"X(<Parameter name="file" type="string" value="two_blocks3d.geo"/>)X";
  deck.replace(deck.find(file), file.size(),
               R"X(<Parameter name="file" type="string" value=")X" + (work_dir() / "two_tet_blocks.geo").string() +
                   R"X("/><Parameter name="order" type="int" value="2"/>)X");
  const fs::path out = run_deck("tri6_interface", deck);
  H5 h5(out / "contact_patch3d.h5");
  ASSERT_EQ(h5.times().size(), 2u);
  const auto X = h5.read("/mesh/coordinates"), st = h5.read("/step_1/contact_status"), pr = h5.read("/step_1/contact_pressure"),
             tr = h5.read("/step_1/contact_master_traction"), pm = h5.read("/step_1/contact_master_pressure");
  ASSERT_EQ(tr.size(), X.size());
  ASSERT_EQ(pm.size(), st.size());
  int slaves = 0, masters = 0;
  double worst = 0.0;
  for (std::size_t n = 0; n < st.size(); ++n) {
    if (X[3 * n + 2] != 0.5) continue;  // the interface (both sides)
    if (st[n] >= 0.0) {
      ++slaves;
      worst = std::max(worst, std::abs(pr[n] - kP) / kP);
    } else {
      ++masters;
      worst = std::max({worst, std::abs(tr[3 * n]) / kP, std::abs(tr[3 * n + 1]) / kP, std::abs(tr[3 * n + 2] + kP) / kP,
                        std::abs(pm[n] - kP) / kP});
    }
  }
  std::printf("tri6 interface: %d slave and %d master nodes, max deviation from p %.2e\n", slaves, masters, worst);
  EXPECT_EQ(slaves, 49);  // 7 x 7 nodes of a 3 x 3 grid of P2 squares
  EXPECT_EQ(masters, 49);
  EXPECT_LT(worst, 1e-9);
}

// Both sides of a 2D pair with non-matching meshes (inputs/contact_patch2d.xml, 4 / 5
// divisions) under dual mortar, which passes the patch test: contact_pressure on the
// slave nodes and contact_master_pressure on the master nodes are p at every interface
// node (the master side from the forces the slave nodes put on it).
TEST(ContactOutput, MasterPressureEqualsSlavePressureWithMortar) {
  std::string deck = read_text(kInputs + "contact_patch2d.xml");
  const std::string file = R"X(<Parameter name="file" type="string" value="two_blocks.geo"/>)X";
  deck.replace(deck.find(file), file.size(), R"X(<Parameter name="file" type="string" value=")X" + kInputs + R"X(two_blocks.geo"/>)X");
  const std::string master = R"X(<Parameter name="master" type="string" value="lower_top"/>)X";
  deck.replace(deck.find(master), master.size(), master + R"X(<Parameter name="discretization" type="string" value="mortar"/>)X");
  const fs::path out = run_deck("mortar_both_sides", deck);
  H5 h5(out / "contact_patch2d.h5");
  const auto X = h5.read("/mesh/coordinates"), st = h5.read("/step_1/contact_status"), ps = h5.read("/step_1/contact_pressure"),
             pm = h5.read("/step_1/contact_master_pressure");
  int slaves = 0, masters = 0;
  double worst = 0.0;
  for (std::size_t n = 0; n < st.size(); ++n) {
    if (X[3 * n + 1] != 0.5) continue;
    const double p = st[n] >= 0.0 ? ps[n] : pm[n];
    (st[n] >= 0.0 ? slaves : masters) += 1;
    worst = std::max(worst, std::abs(p - kP) / kP);
  }
  std::printf("mortar 4/5: %d slave and %d master nodes, max |p - p0| / p0 %.2e\n", slaves, masters, worst);
  EXPECT_EQ(slaves, 6);
  EXPECT_EQ(masters, 5);
  EXPECT_LT(worst, 1e-9);
}

// contact_gap where the block of UniformPressureOnEveryFacetType rests on the plane (0, the
// nodes active: status 2 or 3), below the lid (1.2 - the top's height, status
// 1: checked, not in contact) and elsewhere (NaN, status -1). Measured before: 0 on every
// node that is no slave node.
TEST(ContactOutput, GapOnSlaveNodesOnlyNaNElsewhere) {
  for (const BlockCase& c : {BlockCase{"gap_tri6", 2, 2, false, false}, BlockCase{"gap_tet10", 3, 2, false, false}}) {
    const fs::path out = run_deck(c.name, block_on_plane_deck(c));
    H5 h5(out / "block.h5");
    ASSERT_EQ(h5.times().size(), 2u) << c.name;
    const auto X = h5.read("/mesh/coordinates"), u = h5.read("/step_1/displacement"), st = h5.read("/step_1/contact_status"),
               gap = h5.read("/step_1/contact_gap");
    ASSERT_EQ(gap.size() * 3, X.size()) << c.name;
    const auto d = static_cast<std::size_t>(c.dim - 1);
    int n_bottom = 0, n_top = 0, n_other = 0;
    double lid_gap = 0.0;
    for (std::size_t n = 0; n < gap.size(); ++n) {
      const double h = X[3 * n + d], x = h + u[3 * n + d];
      if (h == 0.0) {
        ++n_bottom;
        EXPECT_NEAR(gap[n], 0.0, 1e-12) << c.name << " node " << n;
        EXPECT_GE(st[n], 2.0) << c.name << " node " << n;
      } else if (h == 1.0) {
        ++n_top;
        lid_gap = gap[n];
        EXPECT_NEAR(gap[n], 1.2 - x, 1e-12) << c.name << " node " << n;
        EXPECT_EQ(st[n], 1.0) << c.name << " node " << n;
      } else {
        ++n_other;
        EXPECT_TRUE(std::isnan(gap[n])) << c.name << " node " << n << ": gap " << gap[n];
        EXPECT_EQ(st[n], -1.0) << c.name << " node " << n;
      }
    }
    std::printf("%s: %d bottom nodes (gap 0), %d top nodes (gap to the lid %.6f), %d other nodes (NaN)\n", c.name.c_str(), n_bottom,
                n_top, lid_gap, n_other);
    EXPECT_GT(n_other, n_top);
  }
}

// The rigid obstacles in <basename>_obstacles.xdmf/.h5 (io/Obstacles.hpp): at the field
// file's times, one block per rigid pair named after it ("0: floor; 1: lid"), line segments
// in 2D and quadrilaterals in 3D, every point on its plane (y or z = 0 for the floor, 1.2
// for the lid), displacement 0 (the planes stay put). Before: no such file (a .pvd of .vtp
// files that meshio cannot read as a time series).
TEST(ContactOutput, RigidObstaclesInTheirOwnXdmf) {
  for (const BlockCase& c : {BlockCase{"obstacles_tri3", 2, 1, false, false}, BlockCase{"obstacles_tet4", 3, 1, false, false}}) {
    const fs::path out = run_deck(c.name, block_on_plane_deck(c));
    H5 h5(out / "block_obstacles.h5"), fields(out / "block.h5");
    ASSERT_GE(h5.f, 0) << c.name;
    EXPECT_EQ(h5.times(), fields.times()) << c.name;
    const std::string xs = read_text(out / "block_obstacles.xdmf");
    EXPECT_NE(xs.find(R"(<Information Name="cell_block" Value="0: floor; 1: lid"/>)"), std::string::npos) << c.name;
    EXPECT_NE(xs.find(c.dim == 2 ? R"(TopologyType="Polyline")" : R"(TopologyType="Quadrilateral")"), std::string::npos);
    const std::size_t npc = c.dim == 2 ? 2 : 4;
    const auto topo = h5.read("/mesh/topology"), block = h5.read("/mesh/cell_block");
    ASSERT_EQ(topo.size(), npc * block.size()) << c.name;
    for (std::size_t k = 0; k < h5.times().size(); ++k) {
      const std::string step = "/step_" + std::to_string(k) + "/";
      const auto x = h5.read(step + "coordinates"), u = h5.read(step + "displacement");
      ASSERT_EQ(u.size(), x.size());
      for (double v : u) EXPECT_EQ(v, 0.0);
      int on_floor = 0, on_lid = 0;
      for (std::size_t e = 0; e < block.size(); ++e)
        for (std::size_t a = 0; a < npc; ++a) {
          const double h = x[3 * static_cast<std::size_t>(topo[npc * e + a]) + static_cast<std::size_t>(c.dim - 1)];
          EXPECT_EQ(h, block[e] == 0.0 ? 0.0 : 1.2) << c.name << " cell " << e;
          (block[e] == 0.0 ? on_floor : on_lid) += 1;
        }
      EXPECT_GT(on_floor, 0);
      EXPECT_GT(on_lid, 0);
    }
  }
}
