// "Linear Solver"->"preconditioner" = "muelu" (smoothed-aggregation AMG with rigid-body
// modes, src/solver/MueLuPreconditioner.cpp): the same nonlinear solution as Schwarz, in
// fewer GMRES iterations, on the 3D and 2D uniaxial blocks (P1). See docs/solvers.md.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <Tpetra_Core.hpp>

#include "deck/Config.hpp"
#include "solver/LinearSolver.hpp"
#include "run/Simulation.hpp"

using namespace stentor;
namespace fs = std::filesystem;

namespace {

const fs::path kDir = fs::path(STENTOR_BINARY_DIR) / "system_tests" / "muelu";

// The inputs/block{2,3}d decks' problem (symmetric constraints, right face pulled 20%), P1.
std::string write_deck(int dim, double size, int steps, const std::string& muelu_xml = "") {
  fs::create_directories(kDir);
  const std::string geo = (fs::path(STENTOR_SOURCE_DIR) / "inputs" / (dim == 3 ? "block3d.geo" : "block2d.geo")).string();
  auto dirichlet = [](const char* name, const char* comp, const char* value) {
    std::string s = std::string("    <ParameterList name=\"") + name + "\">\n" +
                    "      <Parameter name=\"type\" type=\"string\" value=\"Dirichlet\"/>\n" +
                    "      <Parameter name=\"boundary\" type=\"string\" value=\"" + (std::string(name) == "pull" ? "right" : name) + "\"/>\n" +
                    "      <Parameter name=\"components\" type=\"string\" value=\"" + comp + "\"/>\n";
    if (value) s += std::string("      <Parameter name=\"values\" type=\"Array(double)\" value=\"{") + value + "}\"/>\n";
    return s + "    </ParameterList>\n";
  };
  std::string bcs = dirichlet("left", "x", nullptr) + dirichlet("bottom", dim == 3 ? "z" : "y", nullptr) + dirichlet("pull", "x", "0.2");
  if (dim == 3) bcs += dirichlet("front", "y", nullptr);
  const fs::path deck = kDir / ("block" + std::to_string(dim) + "d.xml");
  std::ofstream(deck) << R"(<ParameterList name="stentor">
  <ParameterList name="Problem"><Parameter name="title" type="string" value="MueLu vs Schwarz"/></ParameterList>
  <ParameterList name="Mesh">
    <Parameter name="file" type="string" value=")" << geo << R"("/>
    <Parameter name="size" type="double" value=")" << size << R"("/>
    <Parameter name="order" type="int" value="1"/>
  </ParameterList>
  <ParameterList name="Materials">
    <ParameterList name="rubber">
      <Parameter name="C1" type="double" value="0.5e6"/>
      <Parameter name="C2" type="double" value="0.005e6"/>
      <Parameter name="D" type="double" value="0.35e6"/>
    </ParameterList>
  </ParameterList>
  <ParameterList name="Bodies">
    <ParameterList name="block"><Parameter name="material" type="string" value="rubber"/></ParameterList>
  </ParameterList>
  <ParameterList name="Boundary Conditions">
)" << bcs << R"(  </ParameterList>
  <ParameterList name="Stepping">
    <Parameter name="end time" type="double" value="1.0"/>
    <Parameter name="steps" type="int" value=")" << steps << R"("/>
  </ParameterList>
  <ParameterList name="Newton">
    <Parameter name="relative residual tolerance" type="double" value="1e-12"/>
  </ParameterList>
  <ParameterList name="Linear Solver">
    <Parameter name="tolerance" type="double" value="1e-11"/>
)" << muelu_xml << R"(  </ParameterList>
  <ParameterList name="Output">
    <Parameter name="fields" type="bool" value="false"/>
    <Parameter name="basename" type="string" value="block"/>
  </ParameterList>
</ParameterList>
)";
  return deck.string();
}

RunResult run(const std::string& deck, const std::string& prec, const std::string& tag) {
  Config cfg = read_deck(deck);
  cfg.linear.preconditioner = prec;
  RunOptions opts;
  opts.output_dir = (kDir / ("out_" + tag)).string();
  RunResult res;
  EXPECT_EQ(run_simulation(cfg, opts, &res), 0) << tag;
  return res;
}

double rel_diff(const std::vector<double>& a, const std::vector<double>& b) {
  double d2 = 0.0, n2 = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    d2 += (a[i] - b[i]) * (a[i] - b[i]);
    n2 += b[i] * b[i];
  }
  return std::sqrt(d2 / n2);
}

[[maybe_unused]] void compare(int dim, double size, int steps) {
  const std::string deck = write_deck(dim, size, steps);
  const std::string tag = std::to_string(dim) + "d";
  const RunResult s = run(deck, "schwarz", tag + "_schwarz");
  const RunResult m = run(deck, "muelu", tag + "_muelu");
  ASSERT_TRUE(s.converged && m.converged) << tag;
  ASSERT_EQ(s.displacement.size(), m.displacement.size());
  const double d = rel_diff(m.displacement, s.displacement);
  std::printf("[muelu] %s: %zu nodes; Newton %d / %d, GMRES iterations schwarz %d, muelu %d; |u_mg - u_s| / |u_s| = %.2e\n",
              tag.c_str(), s.mesh.num_nodes(), s.newton_iterations, m.newton_iterations, s.linear_iterations, m.linear_iterations,
              d);
  EXPECT_LT(d, 1e-8) << tag;
  EXPECT_NEAR(m.energy, s.energy, 1e-8 * std::abs(s.energy)) << tag;
  EXPECT_LT(m.linear_iterations, s.linear_iterations) << tag;
}

}  // namespace

// preconditioner = auto (the default): MueLu where this build has it, else Schwarz; the
// solver line of the log says which, and the run converges either way.
TEST(MueLu, AutoPicksWhatThisBuildHas) {
  LinearSolverConfig c;
  ASSERT_EQ(c.preconditioner, "auto");
  LinearSolver ls(c, Tpetra::getDefaultComm());
#ifdef STENTOR_HAVE_MUELU
  EXPECT_NE(ls.description().find("MueLu"), std::string::npos) << ls.description();
#else
  EXPECT_NE(ls.description().find("Ifpack2 Schwarz"), std::string::npos) << ls.description();
#endif
  EXPECT_NE(ls.description().find("(preconditioner = auto)"), std::string::npos) << ls.description();
  const RunResult r = run(write_deck(2, 0.1, 2), "auto", "auto");
  EXPECT_TRUE(r.converged);
}

#ifndef STENTOR_HAVE_MUELU
// This build's Trilinos has no MueLu (e.g. the OpenMP build of ci/build-trilinos-openmp.sh):
// asking for it is an input error that names the parameter and the alternative.
TEST(MueLu, UnavailableIsAnInputErrorNamingTheParameter) {
  const std::string deck = write_deck(2, 0.1, 2, "    <Parameter name=\"preconditioner\" type=\"string\" value=\"muelu\"/>\n");
  try {
    read_deck(deck);
    FAIL() << "a deck asking for MueLu was accepted by a build without MueLu";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("Linear Solver->preconditioner"), std::string::npos) << what;
    EXPECT_NE(what.find("schwarz"), std::string::npos) << what;
  }
}
#else
TEST(MueLu, Block3dP1SameSolutionFewerIterations) { compare(3, 0.1, 4); }

TEST(MueLu, Block2dP1SameSolutionFewerIterations) { compare(2, 0.03, 4); }

// A pass-through sublist replaces defaults (here the smoother, which must not inherit the
// default smoother's parameters), and a misspelt MueLu parameter is an input error.
TEST(MueLu, PassThroughSublist) {
  const std::string cheb = R"(    <ParameterList name="MueLu">
      <Parameter name="smoother: type" type="string" value="CHEBYSHEV"/>
      <ParameterList name="smoother: params"><Parameter name="chebyshev: degree" type="int" value="3"/></ParameterList>
    </ParameterList>
)";
  const RunResult r = run(write_deck(2, 0.1, 2, cheb), "muelu", "cheb");
  EXPECT_TRUE(r.converged);
  const std::string bad = R"(    <ParameterList name="MueLu"><Parameter name="smoother: tpye" type="string" value="RELAXATION"/></ParameterList>
)";
  Config cfg = read_deck(write_deck(2, 0.1, 2, bad));
  cfg.linear.preconditioner = "muelu";
  RunOptions opts;
  opts.output_dir = (kDir / "out_bad").string();
  EXPECT_THROW(run_simulation(cfg, opts), InputError);
}
#endif  // STENTOR_HAVE_MUELU
