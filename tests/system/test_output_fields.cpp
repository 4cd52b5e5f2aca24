// Output requests and the derived fields (issue 13; docs/deck.md, "Outputs"), on the
// uniaxial block (unit cube, inputs/block3d.geo, P1, symmetry supports, x stretched to
// lambda = 1.2: a homogeneous state the mesh reproduces exactly, as in test_reactions.cpp):
//   - Output->field list: the step groups hold exactly the requested datasets;
//   - Output->times: steps are shortened to end on them and fields are written there
//     (with `every` too large to write anything else), and at the end of every stage;
//   - green_lagrange_strain = ((lambda^2 - 1)/2, (s^2 - 1)/2, (s^2 - 1)/2), log_strain =
//     (ln lambda, ln s, ln s), principal_stress = (sigma_11, 0, 0) with s and sigma_11 from
//     the law's closed-form uniaxial state; the nodal recovery equals the cell values of
//     this homogeneous field; reaction_force summed over a face equals the history CSV's
//     reaction for that face's set.
#include <gtest/gtest.h>
#include <hdf5.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "BlockDeck.hpp"
#include "CsvSeries.hpp"
#include "H5Results.hpp"
#include "deck/Config.hpp"
#include "deck/OutputFields.hpp"
#include "io/Units.hpp"
#include "material/MaterialRegistry.hpp"
#include "run/Simulation.hpp"

using namespace stentor;
namespace fs = std::filesystem;

namespace {

constexpr double kC1 = 0.5e6, kC2 = 0.005e6, kD = 0.35e6;

// Ciarlet–Geymonat under uniaxial stress F = diag(lam, s, s): s^2 from the lateral
// stress-free condition, and P11 (tests/system/test_reactions.cpp).
double lateral_b(double lam) {
  const double a = lam * lam, K = kC1 + 2 * kC2 + kD;
  const double qa = kC2 + kD * a, qb = kC1 + kC2 * a;
  return (-qb + std::sqrt(qb * qb + 4 * qa * K)) / (2 * qa);
}
double uniaxial_P11(double lam) {
  const double a = lam * lam, K = kC1 + 2 * kC2 + kD, b = lateral_b(lam);
  return lam * 2.0 * (kC1 + 2 * kC2 * b + kD * b * b - K / a);
}

// The uniaxial block deck with `output` (parameters of Output) and `stages` (a Stages
// sublist replacing Stepping).
std::string block_deck(const std::string& output, const std::string& stages = "") {
  using stentor::testing::dirichlet_xml;
  const std::string bcs = dirichlet_xml("left", "left", "x") + dirichlet_xml("front", "front", "y") +
                          dirichlet_xml("bottom", "bottom", "z") + dirichlet_xml("right", "right", "x", "{0.2}");
  const std::string geo = std::string(STENTOR_SOURCE_DIR) + "/inputs/block3d.geo";
  return stages.empty() ? stentor::testing::block_deck_xml(geo, bcs, "block", output)
                        : stentor::testing::block_deck_xml(geo, bcs, "block", output, stages);
}

// Runs `deck` in system_tests/output_fields/<name>; returns the output folder.
fs::path run_deck(const std::string& name, const std::string& deck) {
  const fs::path dir = fs::path(STENTOR_BINARY_DIR) / "system_tests" / "output_fields" / name;
  fs::create_directories(dir);
  const fs::path p = dir / "deck.xml";
  std::ofstream(p) << deck;
  const Config cfg = read_deck(p.string());
  RunOptions o;
  o.output_dir = (dir / "out").string();
  o.overwrite = true;
  EXPECT_EQ(run_simulation(cfg, o, nullptr), 0);
  return dir / "out";
}

using H5 = stentor::testing::H5Results;

}  // namespace

// Every field of field list = all on the static block, at t = 0, at Output->times 0.25 and
// 0.7 (steps shortened to them: 0.25, 0.7, 1 instead of 0.5, 1) and at the end; `every`
// 100 writes nothing else.
TEST(OutputFields, UniaxialBlockAllFieldsAtRequestedTimes) {
  const fs::path out = run_deck("all", block_deck(R"X(<Parameter name="field list" type="string" value="all"/>
    <Parameter name="every" type="int" value="100"/>
    <Parameter name="times" type="Array(double)" value="{0.25, 0.7}"/>)X"));
  const auto hist = stentor::testing::read_csv(out / "block_history.csv");
  ASSERT_EQ(hist.rows(), 3u);
  EXPECT_DOUBLE_EQ(hist["time"][0], 0.25);
  EXPECT_NEAR(hist["time"][1], 0.7, 1e-15);
  EXPECT_NEAR(hist["time"][2], 1.0, 1e-15);
  H5 h5(out / "block.h5");
  ASSERT_GE(h5.f, 0);
  const std::vector<double> t = h5.times();
  ASSERT_EQ(t.size(), 4u);
  const double expect_t[4] = {0.0, 0.25, 0.7, 1.0};
  for (int k = 0; k < 4; ++k) EXPECT_NEAR(t[k], expect_t[k], 1e-15) << "step " << k;
  const std::set<std::string> expected = {"displacement", "reaction_force", "cauchy_stress_nodal", "von_mises_nodal",
                                          "cauchy_stress", "von_mises", "principal_stress", "green_lagrange_strain",
                                          "log_strain", "J", "mpi_rank"};
  EXPECT_EQ(h5.names(3), expected);

  // Closed forms at t = 1 (lambda = 1.2), every cell (symmetric tensors stored as 3 x 3).
  const double lam = 1.2, b = lateral_b(lam), s = std::sqrt(b);
  const double sig11 = uniaxial_P11(lam) / b;  // P11 lam / J, J = lam s^2
  const auto E = h5.read("/step_3/green_lagrange_strain"), L = h5.read("/step_3/log_strain");
  const auto P = h5.read("/step_3/principal_stress"), S = h5.read("/step_3/cauchy_stress");
  const std::size_t nc = P.size() / 3;
  ASSERT_GT(nc, 0u);
  ASSERT_EQ(E.size(), 9 * nc);
  const double diagE[3] = {0.5 * (lam * lam - 1), 0.5 * (b - 1), 0.5 * (b - 1)};
  const double diagL[3] = {std::log(lam), std::log(s), std::log(s)};
  for (std::size_t c = 0; c < nc; ++c)
    for (int i = 0; i < 3; ++i) {
      for (int j = 0; j < 3; ++j) {
        EXPECT_NEAR(E[9 * c + 3 * i + j], i == j ? diagE[i] : 0.0, 1e-12) << "cell " << c;
        EXPECT_NEAR(L[9 * c + 3 * i + j], i == j ? diagL[i] : 0.0, 1e-12) << "cell " << c;
      }
      EXPECT_NEAR(P[3 * c + i], i == 0 ? sig11 : 0.0, 1e-8 * sig11) << "cell " << c;
    }
  // Nodal recovery of a homogeneous field: the cell value at every node.
  const auto Sn = h5.read("/step_3/cauchy_stress_nodal"), vm = h5.read("/step_3/von_mises"),
             vmn = h5.read("/step_3/von_mises_nodal");
  const std::size_t nn = vmn.size();
  ASSERT_EQ(Sn.size(), 9 * nn);
  for (std::size_t n = 0; n < nn; ++n) {
    EXPECT_NEAR(vmn[n], vm[0], 1e-10 * sig11);
    for (int k = 0; k < 9; ++k) EXPECT_NEAR(Sn[9 * n + k], S[k], 1e-10 * sig11);
  }
  EXPECT_NEAR(vm[0], sig11, 1e-8 * sig11);
  // reaction_force over each face's nodes: the history's reaction of its set, at every step.
  const auto X = h5.read("/mesh/coordinates");
  ASSERT_EQ(X.size(), 3 * nn);
  struct Face {
    const char* column;
    int axis;     // the constrained component, and the coordinate that is constant on the face
    double at;
  };
  const Face faces[4] = {{"reaction_left_x", 0, 0.0}, {"reaction_right_x", 0, 1.0}, {"reaction_front_y", 1, 0.0},
                         {"reaction_bottom_z", 2, 0.0}};
  for (int k = 1; k <= 3; ++k) {
    const auto R = h5.read("/step_" + std::to_string(k) + "/reaction_force");
    ASSERT_EQ(R.size(), 3 * nn);
    double total_free = 0.0;  // components no set constrains: exactly 0
    for (std::size_t n = 0; n < nn; ++n)
      for (int c = 0; c < 3; ++c) {
        const double x = X[3 * n + static_cast<std::size_t>(c)];
        const bool constrained = (c == 0 && (x == 0.0 || x == 1.0)) || (c > 0 && x == 0.0);
        if (!constrained) total_free += std::fabs(R[3 * n + c]);
      }
    EXPECT_EQ(total_free, 0.0);
    for (const Face& f : faces) {
      double sum = 0.0;
      for (std::size_t n = 0; n < nn; ++n)
        if (X[3 * n + static_cast<std::size_t>(f.axis)] == f.at) sum += R[3 * n + static_cast<std::size_t>(f.axis)];
      EXPECT_NEAR(sum, hist[f.column][static_cast<std::size_t>(k - 1)], 1e-10 * uniaxial_P11(lam)) << f.column << " step " << k;
    }
  }
}

// Only the requested fields, in every step; the default set is today's.
TEST(OutputFields, OnlyRequestedFields) {
  {
    const fs::path out = run_deck("two", block_deck(R"X(<Parameter name="field list" type="string" value="von_mises, log_strain"/>)X"));
    H5 h5(out / "block.h5");
    ASSERT_EQ(h5.times().size(), 3u);
    for (int k = 0; k < 3; ++k) EXPECT_EQ(h5.names(k), (std::set<std::string>{"von_mises", "log_strain"})) << "step " << k;
  }
  {
    const fs::path out = run_deck("default", block_deck(""));
    H5 h5(out / "block.h5");
    ASSERT_EQ(h5.times().size(), 3u);
    EXPECT_EQ(h5.names(2), (std::set<std::string>{"displacement", "cauchy_stress", "von_mises", "J", "mpi_rank"}));
  }
}

// With Stages, fields at the end of every stage whatever `every` says.
TEST(OutputFields, EndOfEveryStage) {
  const std::string stages = R"X(<ParameterList name="Stages">
    <ParameterList name="first"><Parameter name="duration" type="double" value="0.5"/>
      <Parameter name="steps" type="int" value="3"/></ParameterList>
    <ParameterList name="second"><Parameter name="duration" type="double" value="0.5"/>
      <Parameter name="steps" type="int" value="2"/></ParameterList>
  </ParameterList>
)X";
  const fs::path out = run_deck("stages", block_deck(R"X(<Parameter name="every" type="int" value="100"/>
    <Parameter name="times" type="Array(double)" value="{0.75}"/>)X", stages));
  H5 h5(out / "block.h5");
  const std::vector<double> t = h5.times();
  ASSERT_EQ(t.size(), 4u);
  const double expect_t[4] = {0.0, 0.5, 0.75, 1.0};
  for (int k = 0; k < 4; ++k) EXPECT_NEAR(t[k], expect_t[k], 1e-14) << "step " << k;
}

// The catalogue knows every history variable a law of the deck writes (Assembler::cell_fields
// names them from the law), as a plasticity resp. damage field; docs/deck.md's "Outputs"
// table names every field.
template <class Law>
void expect_catalogued(OutputField::Needs needs) {
  for (const auto& h : Law::kHistory) {
    if (!h.output) continue;
    const auto& all = output_fields();
    const auto it = std::find_if(all.begin(), all.end(), [&](const OutputField& f) { return h.name == std::string(f.name); });
    ASSERT_NE(it, all.end()) << h.name;
    EXPECT_EQ(it->needs, needs) << h.name;
  }
}

TEST(OutputFields, CatalogueMatchesLawAndDocs) {
  expect_catalogued<CiarletGeymonatPlasticity>(OutputField::Needs::Plasticity);
  expect_catalogued<NeoHookeanPlasticity>(OutputField::Needs::Plasticity);
  expect_catalogued<NeoHookeanDamage>(OutputField::Needs::Damage);
  std::ifstream in(std::string(STENTOR_SOURCE_DIR) + "/docs/deck.md");
  std::stringstream ss;
  ss << in.rdbuf();
  const std::string doc = ss.str();
  const auto at = doc.find("\n## Outputs\n");
  ASSERT_NE(at, std::string::npos) << "docs/deck.md has no '## Outputs' section";
  const std::string section = doc.substr(at, doc.find("\n## ", at + 1) - at);
  // Each row: | `name` | node/cell | components | SI unit (of the catalogue's quantity) | ...
  const UnitLabels si = unit_labels("SI", 3);
  for (const auto& f : output_fields()) {
    const auto row = section.find(std::string("| `") + f.name + "` |");
    ASSERT_NE(row, std::string::npos) << f.name;
    std::vector<std::string> cells;
    std::istringstream line(section.substr(row + 1, section.find('\n', row) - row - 1));
    for (std::string c; std::getline(line, c, '|');) cells.push_back(c.substr(c.find_first_not_of(' ') == std::string::npos ? c.size() : c.find_first_not_of(' ')));
    for (auto& c : cells) c.erase(c.find_last_not_of(' ') + 1);
    ASSERT_GE(cells.size(), 4u) << f.name;
    EXPECT_EQ(cells[1], f.where == OutputField::Where::Node ? "node" : "cell") << f.name;
    EXPECT_EQ(cells[2], std::to_string(f.components)) << f.name;
    const std::string q = f.quantity;
    const std::string unit = q == "length" ? si.length : q == "velocity" ? si.velocity : q == "stress" ? si.stress
                           : q == "force" ? si.force : q == "-" ? "\u2013" : "";
    EXPECT_EQ(cells[3].substr(0, unit.size()), unit) << f.name << ": " << cells[3];
    if (unit.empty()) EXPECT_EQ(cells[3], "") << f.name;
  }
}

// velocity (dynamics): a block in free flight keeps its initial velocity at every node,
// and its displacement is v t.
TEST(OutputFields, VelocityOfFreeFlight) {
  const std::string geo = std::string(STENTOR_SOURCE_DIR) + "/inputs/block3d.geo";
  const std::string deck = R"X(<ParameterList name="stentor">
  <ParameterList name="Problem"><Parameter name="analysis" type="string" value="dynamic"/></ParameterList>
  <ParameterList name="Mesh"><Parameter name="file" type="string" value=")X" + geo + R"X("/>
    <Parameter name="size" type="double" value="0.5"/></ParameterList>
  <ParameterList name="Materials"><ParameterList name="rubber">
    <Parameter name="C1" type="double" value="0.5e6"/><Parameter name="D" type="double" value="0.35e6"/>
    <Parameter name="density" type="double" value="1000"/></ParameterList></ParameterList>
  <ParameterList name="Bodies"><ParameterList name="block">
    <Parameter name="material" type="string" value="rubber"/></ParameterList></ParameterList>
  <ParameterList name="Initial Conditions">
    <Parameter name="velocity" type="Array(double)" value="{1, -2, 0.5}"/></ParameterList>
  <ParameterList name="Stepping"><Parameter name="end time" type="double" value="0.01"/>
    <Parameter name="steps" type="int" value="2"/></ParameterList>
  <ParameterList name="Linear Solver"><Parameter name="method" type="string" value="direct"/></ParameterList>
  <ParameterList name="Output"><Parameter name="basename" type="string" value="block"/>
    <Parameter name="field list" type="string" value="velocity displacement"/></ParameterList>
</ParameterList>
)X";
  const fs::path out = run_deck("velocity", deck);
  H5 h5(out / "block.h5");
  const std::vector<double> t = h5.times();
  ASSERT_EQ(t.size(), 3u);
  const double v0[3] = {1.0, -2.0, 0.5};
  for (int k = 0; k < 3; ++k) {
    EXPECT_EQ(h5.names(k), (std::set<std::string>{"displacement", "velocity"}));
    const auto v = h5.read("/step_" + std::to_string(k) + "/velocity"), u = h5.read("/step_" + std::to_string(k) + "/displacement");
    ASSERT_EQ(v.size(), u.size());
    ASSERT_FALSE(v.empty());
    for (std::size_t i = 0; i < v.size(); ++i) {
      EXPECT_NEAR(v[i], v0[i % 3], 1e-12) << "step " << k << " entry " << i;
      EXPECT_NEAR(u[i], v0[i % 3] * t[static_cast<std::size_t>(k)], 1e-12) << "step " << k << " entry " << i;
    }
  }
}
