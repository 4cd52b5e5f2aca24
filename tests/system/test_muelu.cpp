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

#include "RelDiff.hpp"
#include "deck/Config.hpp"
#include "solver/LinearSolver.hpp"
#include "solver/SolverParams.hpp"
#include "run/Simulation.hpp"
#include "TestDir.hpp"

using namespace stentor;
using stentor::testing::rel_diff;
namespace fs = std::filesystem;

namespace {

fs::path work_dir() { return stentor::testing::test_dir("muelu"); }

// The inputs/block{2,3}d decks' problem (symmetric constraints, right face pulled 20%), P1.
std::string write_deck(int dim, double size, int steps, const std::string& muelu_xml = "") {
  fs::create_directories(work_dir());
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
  const fs::path deck = work_dir() / ("block" + std::to_string(dim) + "d.xml");
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
  opts.output_dir = (work_dir() / ("out_" + tag)).string();
  RunResult res;
  EXPECT_EQ(run_simulation(cfg, opts, &res), 0) << tag;
  return res;
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

// Pass-through lists are validated by the packages before a run: each bad entry is an
// InputError naming "Linear Solver-><package>-><parameter>" (issue 16; each of these was
// exit 1 with raw Trilinos text, MueLu "max levels" = 0 a SIGSEGV).
TEST(SolverParams, BadPassThroughEntriesNameTheParameter) {
  struct Case {
    const char* method;
    const char* prec;
    const char* belos;
    const char* ifpack2;
    const char* muelu;
    const char* amesos2;
    std::vector<std::string> expect;
  };
  auto pl = [](const char* name, const std::string& body) {
    return std::string("<ParameterList name=\"") + name + "\">" + body + "</ParameterList>";
  };
  const std::vector<Case> cases = {
      {"gmres", "none", "<Parameter name=\"Num Blocks\" type=\"int\" value=\"0\"/>", "", "", "", {"Linear Solver->Belos", "Num Blocks", "strictly positive"}},
      {"gmres", "none", "<Parameter name=\"Convergence Tolerance\" type=\"string\" value=\"tiny\"/>", "", "", "",
       {"Linear Solver->Belos->Convergence Tolerance", "wrong type", "double"}},
      {"gmres", "none", "<Parameter name=\"Convergence Tolerance\" type=\"double\" value=\"-1\"/>", "", "", "",
       {"Linear Solver->Belos->Convergence Tolerance", "finite number > 0"}},
      {"gmres", "none", "<Parameter name=\"Orthogonalization\" type=\"string\" value=\"QR\"/>", "", "", "",
       {"Linear Solver->Belos", "orthogonalization manager name"}},
      {"gmres", "none", "<Parameter name=\"Num Blockz\" type=\"int\" value=\"5\"/>", "", "", "", {"Linear Solver->Belos->Num Blockz", "not found", "did you mean 'Num Blocks'"}},
      {"gmres", "schwarz", "", "<Parameter name=\"schwarz: overlap levl\" type=\"int\" value=\"1\"/>", "", "",
       {"Linear Solver->Ifpack2->schwarz: overlap levl", "not found"}},
      {"gmres", "schwarz", "", "<Parameter name=\"schwarz: overlap level\" type=\"string\" value=\"one\"/>", "", "",
       {"Linear Solver->Ifpack2->schwarz: overlap level", "int"}},
      {"gmres", "schwarz", "", "<Parameter name=\"inner preconditioner name\" type=\"string\" value=\"NOPE\"/>", "", "",
       {"Linear Solver->Ifpack2", "Ifpack2 refused"}},
#ifdef STENTOR_HAVE_MUELU
      {"gmres", "muelu", "", "", "<Parameter name=\"smoother: type\" type=\"string\" value=\"NOPE\"/>", "",
       {"Linear Solver->MueLu->smoother: type = 'NOPE'", "MueLu cannot build"}},
      {"gmres", "auto", "", "", "<Parameter name=\"max levels\" type=\"int\" value=\"0\"/>", "", {"Linear Solver->MueLu->max levels = 0", ">= 1"}},
      {"gmres", "muelu", "", "", "<Parameter name=\"max levelz\" type=\"int\" value=\"3\"/>", "", {"Linear Solver->MueLu->max levelz", "max levels"}},
      {"gmres", "muelu", "", "", "<ParameterList name=\"level 1\"><Parameter name=\"coarse: type\" type=\"string\" value=\"NOPE\"/></ParameterList>", "",
       {"Linear Solver->MueLu->level 1->coarse: type = 'NOPE'"}},
#endif
#ifdef STENTOR_HAVE_AMESOS2
      {"direct", "auto", "", "", "", "<Parameter name=\"Foo\" type=\"int\" value=\"1\"/>", {"Linear Solver->Amesos2->Foo", "not found"}},
#endif
  };
  for (const Case& c : cases) {
    LinearSolverConfig cfg;
    cfg.method = c.method;
    cfg.preconditioner = c.prec;
    if (*c.belos) cfg.belos_xml = pl("Belos", c.belos);
    if (*c.ifpack2) cfg.ifpack2_xml = pl("Ifpack2", c.ifpack2);
    if (*c.muelu) cfg.muelu_xml = pl("MueLu", c.muelu);
    if (*c.amesos2) cfg.amesos2_xml = pl("Amesos2", c.amesos2);
    try {
      validate_linear_solver(cfg);
      ADD_FAILURE() << "accepted: " << c.expect[0];
    } catch (const InputError& e) {
      const std::string what = e.what();
      for (const auto& f : c.expect) EXPECT_NE(what.find(f), std::string::npos) << "'" << f << "' not in: " << what;
    }
  }
  // Valid lists pass (the shipped decks' and the documented combinations).
  LinearSolverConfig ok;
  ok.belos_xml = pl("Belos", "<Parameter name=\"Num Blocks\" type=\"int\" value=\"30\"/><Parameter name=\"Orthogonalization\" type=\"string\" value=\"ICGS\"/>");
  ok.muelu_xml = pl("MueLu", "<Parameter name=\"smoother: type\" type=\"string\" value=\"CHEBYSHEV\"/><Parameter name=\"max levels\" type=\"int\" value=\"3\"/>");
  EXPECT_NO_THROW(validate_linear_solver(ok));
  for (const char* sub : {"RILUK", "ILUT", "KLU2"}) {
    LinearSolverConfig s;
    s.preconditioner = "schwarz";
    s.subdomain_solver = sub;
    s.ifpack2_xml = pl("Ifpack2", "<Parameter name=\"schwarz: overlap level\" type=\"int\" value=\"2\"/>");
    EXPECT_NO_THROW(validate_linear_solver(s)) << sub;
  }
}

#ifdef STENTOR_HAVE_AMESOS2
// Schwarz with KLU2 subdomain solves (documented; was exit 1, "The ParameterList passed to
// Amesos2 must be called Amesos2"): the same solution as RILUK subdomains.
TEST(SolverParams, SchwarzKlu2SameSolutionAsRiluk) {
  const std::string deck = write_deck(2, 0.1, 2);
  Config cfg = read_deck(deck);
  cfg.linear.preconditioner = "schwarz";
  RunOptions opts;
  opts.output_dir = (work_dir() / "out_riluk").string();
  RunResult a, b;
  ASSERT_EQ(run_simulation(cfg, opts, &a), 0);
  cfg.linear.subdomain_solver = "KLU2";
  opts.output_dir = (work_dir() / "out_klu2").string();
  ASSERT_EQ(run_simulation(cfg, opts, &b), 0);
  EXPECT_LT(rel_diff(b.displacement, a.displacement), 1e-8);
  EXPECT_LE(b.linear_iterations, a.linear_iterations);
}
#endif

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
  opts.output_dir = (work_dir() / "out_bad").string();
  EXPECT_THROW(run_simulation(cfg, opts), InputError);
}
#endif  // STENTOR_HAVE_MUELU

#if defined(STENTOR_HAVE_MUELU) && defined(STENTOR_HAVE_AMESOS2)
// The fallback chain (LinearSolver.hpp): a nonsingular system with zero diagonal entries,
// the saddle point [[K, I], [I, 0]] (K the 1D Laplacian tridiag(-1, 2, -1)): MueLu's
// prolongator damping divides by the diagonal ("Prolongator damping factor needs to be
// finite", the set-up throws), Schwarz/RILUK(1) leaves GMRES at a relative residual of 0.2
// after 40 iterations. The solver steps down twice, to KLU2, which solves it. On 2 ranks
// too (mpi.fallback_chain.np2): there RILUK breaks down and Belos throws ("implicit
// residual norms is NaN"); the ranks vote on each failure and fall back together (both
// throws ended a 2-rank run with exit 1 before the vote).
TEST(LinearSolver, FallbackChainSolvesWhatMueLuAndIluCannot) {
  auto comm = Tpetra::getDefaultComm();
  const int m = 2000, n = 2 * m;  // above MueLu's coarse size (2000 rows), so it builds a hierarchy
  auto map = Teuchos::rcp(new la::Map(n, 0, comm));
  auto A = Teuchos::rcp(new la::CrsMatrix(map, 4));
  for (std::size_t l = 0; l < map->getNodeNumElements(); ++l) {  // the owned rows
    const la::GO i = map->getGlobalElement(static_cast<la::LO>(l));
    std::vector<la::GO> c;
    std::vector<la::SC> v;
    if (i < m) {
      c = {i, i + m}, v = {2.0, 1.0};
      if (i > 0) c.push_back(i - 1), v.push_back(-1.0);
      if (i < m - 1) c.push_back(i + 1), v.push_back(-1.0);
    } else {
      c = {i - m, i}, v = {1.0, 0.0};  // the zero diagonal stored: Ifpack2 13.2's overlap needs one
    }
    A->insertGlobalValues(i, Teuchos::ArrayView<const la::GO>(c), Teuchos::ArrayView<const la::SC>(v));
  }
  A->fillComplete();
  // x* = (1, 2, ..., n); b = A x*.
  la::Vector xs(map), b(map), x(map);
  {
    auto h = xs.getLocalViewHost(Tpetra::Access::OverwriteAll);
    for (std::size_t l = 0; l < map->getNodeNumElements(); ++l)
      h(l, 0) = static_cast<double>(map->getGlobalElement(static_cast<la::LO>(l))) + 1.0;
  }
  A->apply(xs, b);
  LinearSolverConfig cfg;
  cfg.method = "gmres";
  cfg.preconditioner = "muelu";
  cfg.max_iterations = 40;
  cfg.restart = 40;
  LinearSolver lin(cfg, comm);
  // 2D: n rows = m "nodes" of 2 dofs each (rows 2k, 2k + 1); coordinates of the owned ones.
  const std::size_t owned_nodes = map->getNodeNumElements() / 2;
  std::vector<double> xyz(3 * owned_nodes, 0.0);
  for (std::size_t k = 0; k < owned_nodes; ++k) {
    const la::GO node = map->getGlobalElement(static_cast<la::LO>(2 * k)) / 2;
    xyz[3 * k] = static_cast<double>(node), xyz[3 * k + 1] = static_cast<double>(node % 2);
  }
  lin.set_node_coordinates(2, xyz);
  lin.setup(A);
  const LinearSolver::Result r = lin.solve(b, x);
  x.update(-1.0, xs, 1.0);
  EXPECT_LT(x.normInf(), 1e-10 * n) << lin.description();
  EXPECT_TRUE(r.converged) << r.residual;
  EXPECT_GE(lin.times().fallbacks, 1) << "the system was solved without a fallback: the test no longer exercises it";
  EXPECT_NE(lin.description().find("direct"), std::string::npos) << lin.description();
}
#endif
