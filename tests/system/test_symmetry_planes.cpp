// Dirichlet sets with components = normal (a roller or symmetry plane at any angle,
// assembly/PlaneConstraints.cpp; docs/deck.md):
//  1. the uniaxial unit block of test_reactions.cpp rotated by 40 degrees about (1, 1, 1),
//     held by rollers on three faces (whose edges and corner lie on two and three planes)
//     and pulled by 0.2 along the fourth face's normal: the stored energy equals the
//     aligned block's with Cartesian rollers, each roller's reaction is the force P11 A0
//     along its plane's normal (the aligned run's reaction), the unloaded rollers carry
//     nothing, to 1e-9;
//  2. the S6 ring (elastic, coarse) expanded by a rigid cylinder to its peak: the one-
//     strut sector (Mesh->Stent->sector = period, theta in [0, 22.5 deg], its oblique
//     plane held with components = normal and its inner nodes on that plane in contact)
//     gives the quarter ring's displacements at every common node to 1e-8 of the largest
//     (measured: 3e-15), with the same Newton iterations to +-2; the oblique plane's
//     reaction is normal to it;
//  3. the 3D contact patch test (inputs/contact_patch3d.xml: two blocks with non-matching
//     hex8 interfaces, node-to-segment, pressed by a uniform traction) with its mesh rotated
//     by 40 degrees about (1, 1, 1), rollers along the normals of the base and the two
//     symmetry faces and the traction rotated: slave and master nodes lie on the planes
//     (the reactions sent to the master nodes are projected on them). The stored energy
//     and the base's reaction (the total force, along the base's normal) equal the
//     aligned run's to 1e-9;
//  4. dynamics (Gonzalez, Newmark): the rotated block (the aligned mesh's nodes rotated) on
//     its three rollers, set moving by the rotated initial velocity (1, 0.5, 0.3) m/s (its
//     normal parts removed on the rollers, as the Cartesian rollers zero them) and a
//     constant body force (Newmark's initial acceleration solves M a0 = f(0)), vibrates
//     with the aligned block's energies to 1e-9 at every step (measured 2e-13), and with
//     Gonzalez closes its energy balance per step to 1e-12 of E0 (the rollers do no work);
//  5. the projected tangent against central differences of the projected residual
//     (the rotated block with a follower pressure on the pulled face, at a non-homogeneous
//     state on the planes, along a direction on them);
//  6. bad input: a curved group (the stent's inner surface) is refused naming the group;
//     two values for one normal are refused naming the parameter.
#include <gtest/gtest.h>

#include "AssemblerFixture.hpp"
#include "BlockDeck.hpp"
#include "CsvSeries.hpp"
#include "RotatedMesh.hpp"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <string>

#include "deck/Config.hpp"
#include "geometry/MshWriter.hpp"
#include "mesh/GmshReader.hpp"
#include "run/Model.hpp"
#include "run/Simulation.hpp"
#include "TestDir.hpp"

using namespace stentor;
namespace fs = std::filesystem;

namespace {

fs::path work_dir() { return stentor::testing::test_dir("symmetry_planes"); }

std::string roller(const std::string& name, const std::string& group, const std::string& comps, const std::string& values = "") {
  return stentor::testing::dirichlet_xml(name, group, comps, values);
}

std::string block_deck(const std::string& mesh, const std::string& bcs, const std::string& base) {
  return stentor::testing::block_deck_xml(mesh, bcs, base);
}

RunResult run(const std::string& text, const std::string& name) {
  fs::create_directories(work_dir());
  const fs::path p = work_dir() / (name + ".xml");
  std::ofstream(p) << text;
  const Config cfg = read_deck(p.string());
  RunOptions o;
  o.output_dir = (work_dir() / name).string();
  o.overwrite = true;
  RunResult res;
  EXPECT_EQ(run_simulation(cfg, o, &res), 0) << name;
  return res;
}

using stentor::testing::rotate;

// The mesh rotated node by node, written as <name>.msh (the same cells and groups).
fs::path rotated_msh(const Mesh& m, const std::string& name) { return stentor::testing::rotated_msh(m, work_dir() / (name + ".msh")); }

std::string ring_deck(const std::string& sector) {
  std::ifstream in(std::string(STENTOR_SOURCE_DIR) + "/tests/cli/decks/restart_stent.xml");
  std::string s((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  s = std::regex_replace(s, std::regex(R"X(<Parameter name="checkpoint every"[^>]*>)X"), "");
  // To the peak of the expansion (the cylinder's radius ramp peaks at t = 0.5), in contact.
  s = std::regex_replace(s, std::regex(R"X(name="end time" type="double" value="1.0")X"), R"X(name="end time" type="double" value="0.5")X");
  s = std::regex_replace(s, std::regex(R"X(name="steps" type="int" value="20")X"), R"X(name="steps" type="int" value="10")X");
  s = std::regex_replace(s, std::regex(R"X(<Parameter name="every" type="int" value="5"/>)X"),
                         R"X(<Parameter name="fields" type="bool" value="false"/>)X");
  if (sector == "period") {
    s = std::regex_replace(s, std::regex(R"X(value="quarter")X"), R"X(value="period")X");
    s = std::regex_replace(s, std::regex(R"X(value="symmetry_x"/>\s*<Parameter name="components" type="string" value="x"/>)X"),
                           R"X(value="symmetry_sector"/><Parameter name="components" type="string" value="normal"/>)X");
  }
  return s;
}

}  // namespace

TEST(SymmetryPlanes, RotatedUniaxialBlockOnRollersEqualsTheAlignedOne) {
  fs::create_directories(work_dir());
  const std::string geo = std::string(STENTOR_SOURCE_DIR) + "/inputs/block3d.geo";
  std::ifstream in(geo);
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  text = std::regex_replace(text, std::regex("Physical Volume"), "Rotate {{1, 1, 1}, {0, 0, 0}, 40 * Pi / 180} { Volume{1}; }\nPhysical Volume");
  const fs::path rgeo = work_dir() / "block_rotated.geo";
  std::ofstream(rgeo) << text;

  const RunResult a = run(block_deck(geo, roller("left", "left", "x") + roller("front", "front", "y") + roller("bottom", "bottom", "z") +
                                              roller("pull", "right", "x", "{0.2}"),
                                     "aligned"),
                          "aligned");
  const RunResult r = run(block_deck(rgeo.string(), roller("left", "left", "normal") + roller("front", "front", "normal") +
                                                        roller("bottom", "bottom", "normal") + roller("pull", "right", "normal", "{0.2}"),
                                     "rotated"),
                          "rotated");
  ASSERT_EQ(r.reactions.size(), 4u);
  const double F = a.reactions[3][0];  // P11(1.2) A0
  std::printf("[ planes ] rotated block: W %.15g (aligned %.15g), pull reaction %.12g %.12g %.12g, F = %.12g\n", r.energy, a.energy,
              r.reactions[3][0], r.reactions[3][1], r.reactions[3][2], F);
  EXPECT_GT(F, 4e5);
  EXPECT_NEAR(r.energy, a.energy, 1e-9 * a.energy);
  const auto nx = rotate({1.0, 0.0, 0.0});
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(r.reactions[3][static_cast<std::size_t>(k)], F * nx[static_cast<std::size_t>(k)], 1e-9 * F) << "pull " << k;
    EXPECT_NEAR(r.reactions[0][static_cast<std::size_t>(k)], -F * nx[static_cast<std::size_t>(k)], 1e-9 * F) << "left " << k;
    EXPECT_NEAR(r.reactions[1][static_cast<std::size_t>(k)], 0.0, 1e-9 * F) << "front " << k;
    EXPECT_NEAR(r.reactions[2][static_cast<std::size_t>(k)], 0.0, 1e-9 * F) << "bottom " << k;
  }
}

TEST(SymmetryPlanes, OneStrutSectorOfTheRingEqualsTheQuarter) {
  const RunResult q = run(ring_deck("quarter"), "ring_quarter");
  const RunResult s = run(ring_deck("period"), "ring_sector");
  ASSERT_TRUE(q.converged && s.converged);
  EXPECT_EQ(s.cutbacks, 0);
  EXPECT_NEAR(s.newton_iterations, q.newton_iterations, 2);  // round-off may move one step's last test across the tolerance
  // Common nodes by reference position (the generator builds both from one construction).
  std::map<std::array<long long, 3>, std::size_t> at;
  auto key = [](const double* x) {
    return std::array<long long, 3>{std::llround(x[0] * 1e8), std::llround(x[1] * 1e8), std::llround(x[2] * 1e8)};
  };
  for (std::size_t i = 0; i < q.mesh.num_nodes(); ++i) at[key(q.mesh.coord(static_cast<GId>(i)))] = i;
  double umax = 0.0, dmax = 0.0;
  std::size_t matched = 0;
  for (std::size_t i = 0; i < s.mesh.num_nodes(); ++i) {
    auto it = at.find(key(s.mesh.coord(static_cast<GId>(i))));
    if (it == at.end()) continue;
    ++matched;
    for (std::size_t c = 0; c < 3; ++c) {
      umax = std::max(umax, std::abs(q.displacement[3 * it->second + c]));
      dmax = std::max(dmax, std::abs(s.displacement[3 * i + c] - q.displacement[3 * it->second + c]));
    }
  }
  std::printf("[ planes ] sector vs quarter: %zu of %zu nodes matched, max |u| %.6g mm, max difference %.3g mm\n", matched,
              s.mesh.num_nodes(), umax, dmax);
  EXPECT_EQ(matched, s.mesh.num_nodes());
  EXPECT_GT(umax, 0.01);
  EXPECT_LT(dmax, 1e-8 * umax);
  // The oblique plane (deck order: sym_x became the sector's plane) pushes along its normal only.
  const double th = std::acos(-1.0) / 8.0, n[3] = {-std::sin(th), std::cos(th), 0.0};
  const auto& R = s.reactions[0];
  const double rn = R[0] * n[0] + R[1] * n[1] + R[2] * n[2];
  const double rt = std::sqrt(std::pow(R[0] - rn * n[0], 2) + std::pow(R[1] - rn * n[1], 2) + std::pow(R[2] - rn * n[2], 2));
  EXPECT_LE(rt, 1e-10 * std::abs(rn) + 1e-12);
}

TEST(SymmetryPlanes, RotatedContactPatchEqualsTheAlignedOne) {
  fs::create_directories(work_dir());
  std::ifstream in(std::string(STENTOR_SOURCE_DIR) + "/inputs/contact_patch3d.xml");
  const std::string aligned((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  // The aligned mesh, rotated node by node, as a .msh (the same cells and groups).
  MeshConfig mc;
  mc.file = std::string(STENTOR_SOURCE_DIR) + "/inputs/two_blocks3d.geo";
  const fs::path msh = rotated_msh(read_mesh(mc), "two_blocks_rotated");
  const auto t = rotate({0.0, 0.0, -1e4});
  char traction[128];
  std::snprintf(traction, sizeof traction, "{%.17g, %.17g, %.17g}", t[0], t[1], t[2]);
  std::string rotated = std::regex_replace(aligned, std::regex(R"X(value="two_blocks3d.geo")X"), "value=\"" + msh.string() + "\"");
  rotated = std::regex_replace(rotated, std::regex(R"X(value="\{0, 0, -1e4\}")X"), std::string("value=\"") + traction + "\"");
  rotated = std::regex_replace(rotated, std::regex(R"X(("components" type="string" value=")[xyz]")X"), "$1normal\"");
  ASSERT_NE(rotated.find(R"X(value="normal")X"), std::string::npos);
  ASSERT_NE(rotated.find(traction), std::string::npos);
  std::string aligned_deck = std::regex_replace(
      aligned, std::regex(R"X(value="two_blocks3d.geo")X"), "value=\"" + std::string(STENTOR_SOURCE_DIR) + "/inputs/two_blocks3d.geo\"");
  const RunResult a = run(aligned_deck, "patch_aligned");
  const RunResult r = run(rotated, "patch_rotated");
  ASSERT_TRUE(a.converged && r.converged);
  std::printf("[ planes ] rotated contact patch: W %.15g (aligned %.15g), base reaction %.10g %.10g %.10g (aligned z %.10g)\n", r.energy,
              a.energy, r.reactions[0][0], r.reactions[0][1], r.reactions[0][2], a.reactions[0][2]);
  EXPECT_NEAR(r.energy, a.energy, 1e-9 * a.energy);
  const auto nz = rotate({0.0, 0.0, 1.0});
  for (int k = 0; k < 3; ++k)
    EXPECT_NEAR(r.reactions[0][static_cast<std::size_t>(k)], a.reactions[0][2] * nz[static_cast<std::size_t>(k)], 1e-9 * std::abs(a.reactions[0][2]));
}

TEST(SymmetryPlanes, RotatedBlockVibratesLikeTheAlignedOne) {
  fs::create_directories(work_dir());
  const std::string geo = std::string(STENTOR_SOURCE_DIR) + "/inputs/block3d.geo";
  // The aligned mesh (Mesh->size 0.5, as block_deck asks) rotated node by node: the same cells.
  MeshConfig mc;
  mc.file = geo;
  mc.size = 0.5;
  const fs::path rgeo = rotated_msh(read_mesh(mc), "block_rotated_dyn");
  auto deck = [&](const std::string& g, const std::string& comps, const std::array<double, 3>& v, const std::string& base,
                  const std::string& scheme) {
    char vel[128];
    std::snprintf(vel, sizeof vel, "{%.17g, %.17g, %.17g}", v[0], v[1], v[2]);
    // A constant body force (rotated with the block): Newmark's a0 = M^-1 f(0) is not 0.
    const auto f = comps == "normal" ? rotate({-2e4, 1e4, -5e4}) : std::array<double, 3>{-2e4, 1e4, -5e4};
    char force[160];
    std::snprintf(force, sizeof force, "{%.17g, %.17g, %.17g}", f[0], f[1], f[2]);
    std::string d = block_deck(g, roller("left", "left", comps == "normal" ? "normal" : "x") +
                                      roller("front", "front", comps == "normal" ? "normal" : "y") +
                                      roller("bottom", "bottom", comps == "normal" ? "normal" : "z") +
                                      R"X(<ParameterList name="weight"><Parameter name="type" type="string" value="body force"/>
      <Parameter name="ramp" type="string" value="constant"/><Parameter name="force" type="Array(double)" value=")X" + force +
                                      R"X("/></ParameterList>)X",
                               base);
    d = std::regex_replace(d, std::regex(R"X(<ParameterList name="Mesh">)X"),
                           std::string(R"X(<ParameterList name="Problem"><Parameter name="analysis" type="string" value="dynamic"/></ParameterList>
  <ParameterList name="Initial Conditions"><Parameter name="velocity" type="Array(double)" value=")X") + vel +
                               R"X("/></ParameterList>
  <ParameterList name="Mesh">)X");
    d = std::regex_replace(d, std::regex(R"X(<Parameter name="D" type="double" value="0.35e6"/>)X"),
                           R"X(<Parameter name="D" type="double" value="0.35e6"/><Parameter name="density" type="double" value="1000"/>)X");
    d = std::regex_replace(d, std::regex(R"X(<Parameter name="steps" type="int" value="2"/>)X"),
                           R"X(<Parameter name="steps" type="int" value="20"/><Parameter name="end time" type="double" value="0.02"/>)X");
    d = std::regex_replace(d, std::regex(R"X(<ParameterList name="Linear Solver">)X"),
                           R"X(<ParameterList name="Time Integration"><Parameter name="scheme" type="string" value=")X" + scheme + R"X("/></ParameterList>
  <ParameterList name="Linear Solver">)X");
    return d;
  };
  // Newmark's initial acceleration solves M a0 = f on the planes too (TimeIntegrator::solve_mass).
  for (const std::string scheme : {"gonzalez", "newmark"}) {
    const std::string an = "dyn_aligned_" + scheme, rn = "dyn_rotated_" + scheme;
    const RunResult a = run(deck(geo, "xyz", {1.0, 0.5, 0.3}, an, scheme), an);
    const RunResult r = run(deck(rgeo.string(), "normal", rotate({1.0, 0.5, 0.3}), rn, scheme), rn);
    ASSERT_TRUE(a.converged && r.converged);
    const auto ea = stentor::testing::read_csv(work_dir() / an / (an + "_energy.csv"));
    const auto er = stentor::testing::read_csv(work_dir() / rn / (rn + "_energy.csv"));
    ASSERT_EQ(ea.rows(), er.rows());
    ASSERT_GE(er.rows(), 20u);
    const double E0 = ea["total"][0];
    EXPECT_GT(E0, 0.0);
    double dk = 0.0, ds = 0.0, drift = 0.0;
    for (std::size_t i = 0; i < er.rows(); ++i) {
      dk = std::max(dk, std::abs(er["kinetic"][i] - ea["kinetic"][i]));
      ds = std::max(ds, std::abs(er["strain"][i] - ea["strain"][i]));
      drift = std::max(drift, std::abs(er["total"][i] - er["total"][0]));
    }
    std::printf("[ planes ] rotated block, %s: E0 %.12g J; |dK| %.3g, |dW| %.3g against the aligned run, total drift %.3g J\n",
                scheme.c_str(), E0, dk, ds, drift);
    (void)drift;
    EXPECT_GT(ea["strain"][er.rows() - 1], 1e-3 * E0);  // it vibrates
    EXPECT_LT(dk, 1e-9 * E0);
    EXPECT_LT(ds, 1e-9 * E0);
    double balance = 0.0;
    for (std::size_t i = 0; i < er.rows(); ++i) balance = std::max(balance, std::abs(er["balance_residual"][i]));
    if (scheme == "gonzalez") EXPECT_LT(balance, 1e-12 * E0) << "the energy balance per step";
  }
}

TEST(SymmetryPlanes, ProjectedTangentAgainstFiniteDifferences) {
  fs::create_directories(work_dir());
  MeshConfig mc;
  mc.file = std::string(STENTOR_SOURCE_DIR) + "/inputs/block3d.geo";
  mc.size = 0.5;
  const fs::path msh = rotated_msh(read_mesh(mc), "block_rotated_fd");
  const std::string press =
      R"X(<ParameterList name="p"><Parameter name="type" type="string" value="pressure"/>
      <Parameter name="boundary" type="string" value="right"/><Parameter name="pressure" type="double" value="1e5"/></ParameterList>)X";
  const fs::path deck = work_dir() / "block_fd.xml";
  std::ofstream(deck) << block_deck(msh.string(), roller("left", "left", "normal") + roller("front", "front", "normal") +
                                                      roller("bottom", "bottom", "normal") + press,
                                    "fd");
  const stentor::testing::AssemblerFixture f(read_deck(deck.string()));
  const auto map = f.dist->owned_map();
  // A non-homogeneous state on the planes, and a direction on them.
  la::Vector u(map), v(map), up(map), um(map), r(map), rp(map), rm(map), Kv(map);
  f.fill(u, 1.0);
  f.as->apply_dirichlet(u, 1.0, 1.0);
  f.fill(v, 1.0, 0.7);
  f.as->project_on_planes(v);
  f.as->assemble(u, 1.0, 1.0, r, true);
  f.as->matrix()->apply(v, Kv);
  const double h = 1e-6;
  up.update(1.0, u, h, v, 0.0);
  um.update(1.0, u, -h, v, 0.0);
  f.as->assemble(up, 1.0, 1.0, rp, false);
  f.as->assemble(um, 1.0, 1.0, rm, false);
  rp.update(-1.0, rm, 1.0);
  rp.scale(0.5 / h);
  rp.update(-1.0, Kv, 1.0);
  const double rel = rp.norm2() / Kv.norm2();
  std::printf("[ planes ] projected tangent: |K v - FD| / |K v| = %.2e (|K v| %.3e)\n", rel, Kv.norm2());
  EXPECT_GT(Kv.norm2(), 0.0);
  EXPECT_LT(rel, 1e-7);
}

TEST(SymmetryPlanes, CurvedGroupAndExtraValuesAreRefusedNamingThem) {
  fs::create_directories(work_dir());
  std::string curved = ring_deck("quarter");
  curved = std::regex_replace(curved, std::regex(R"X(value="symmetry_x"/>\s*<Parameter name="components" type="string" value="x"/>)X"),
                              R"X(value="inner"/><Parameter name="components" type="string" value="normal"/>)X");
  const fs::path p = work_dir() / "curved.xml";
  std::ofstream(p) << curved;
  const Config cfg = read_deck(p.string());
  Timers timers;
  try {
    Model m(cfg, RunOptions{}, timers);
    ADD_FAILURE() << "a curved group was accepted";
  } catch (const InputError& e) {
    const std::string w = e.what();
    EXPECT_NE(w.find("Boundary Conditions->sym_x->boundary"), std::string::npos) << w;
    EXPECT_NE(w.find("group 'inner' to be planar"), std::string::npos) << w;
  }
  std::string two = std::regex_replace(ring_deck("period"), std::regex(R"X(value="normal"/>)X"),
                                       R"X(value="normal"/><Parameter name="values" type="Array(double)" value="{0, 1}"/>)X");
  const fs::path q = work_dir() / "two_values.xml";
  std::ofstream(q) << two;
  try {
    read_deck(q.string());
    ADD_FAILURE() << "two values for a normal were accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("Boundary Conditions->sym_x->values' must have one value"), std::string::npos) << e.what();
  }
}
