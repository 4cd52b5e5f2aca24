// `Linear Solver->direct solver` = mumps (src/solver/MumpsSolver.cpp), on any number of
// ranks (mpi.mumps.np2 runs the first two on 2):
//  1. an unsymmetric sparse system distributed over the ranks (a convection-diffusion
//     stencil with a zero-diagonal saddle block that needs pivoting) solved to round-off
//     against the known solution; new values on the same pattern (no new analysis) and a
//     new pattern (a new analysis) alike;
//  2. a singular matrix is a LinearSolverFailure naming MUMPS and its error code;
//  3. a whole run (the rubber block, 3D, P1) takes the same Newton path with MUMPS as with
//     KLU2 and ends at the same displacements (1 rank).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <Tpetra_Core.hpp>

#include "BlockDeck.hpp"
#include "RelDiff.hpp"
#include "deck/Config.hpp"
#include "run/Simulation.hpp"
#include "solver/LinearSolver.hpp"
#include "TestDir.hpp"

using namespace stentor;
namespace fs = std::filesystem;

#ifdef STENTOR_HAVE_MUMPS
namespace {

// Rows 0..m-1: the 1D convection-diffusion stencil (-1 - c, 2, -1 + c) times `scale`, coupled
// to a multiplier row m + i; rows m..2m-1: [I 0] (a saddle point, zero diagonal).
// `extra`: one more off-diagonal entry per stencil row (a new pattern).
la::RCP<la::CrsMatrix> saddle(const la::RCP<const la::Comm>& comm, int m, double scale, bool extra) {
  const int n = 2 * m;
  auto map = Teuchos::rcp(new la::Map(n, 0, comm));
  auto A = Teuchos::rcp(new la::CrsMatrix(map, 6));
  const double c = 0.3;
  for (std::size_t l = 0; l < map->getNodeNumElements(); ++l) {
    const la::GO i = map->getGlobalElement(static_cast<la::LO>(l));
    std::vector<la::GO> cols;
    std::vector<la::SC> v;
    if (i < m) {
      cols = {i, i + m}, v = {2.0 * scale, 1.0};
      if (i > 0) cols.push_back(i - 1), v.push_back((-1.0 - c) * scale);
      if (i < m - 1) cols.push_back(i + 1), v.push_back((-1.0 + c) * scale);
      if (extra && i + 3 < m) cols.push_back(i + 3), v.push_back(0.1 * scale);
    } else {
      cols = {i - m}, v = {1.0};
    }
    A->insertGlobalValues(i, Teuchos::ArrayView<const la::GO>(cols), Teuchos::ArrayView<const la::SC>(v));
  }
  A->fillComplete();
  return A;
}

// max |x - x*| / max |x*| after solving A x = A x*, x*_i = 1 + sin(i).
double solve_error(LinearSolver& lin, const la::RCP<la::CrsMatrix>& A) {
  const auto map = A->getRowMap();
  la::Vector xs(map), b(map), x(map);
  {
    auto h = xs.getLocalViewHost(Tpetra::Access::OverwriteAll);
    for (std::size_t l = 0; l < map->getNodeNumElements(); ++l)
      h(l, 0) = 1.0 + std::sin(static_cast<double>(map->getGlobalElement(static_cast<la::LO>(l))));
  }
  A->apply(xs, b);
  lin.setup(A);
  const LinearSolver::Result r = lin.solve(b, x);
  EXPECT_TRUE(r.converged);
  x.update(-1.0, xs, 1.0);
  return x.normInf() / xs.normInf();
}

LinearSolverConfig mumps_config() {
  LinearSolverConfig cfg;
  cfg.method = "direct";
  cfg.direct_solver = "mumps";
  return cfg;
}

}  // namespace

TEST(Mumps, SolvesADistributedUnsymmetricSystem) {
  auto comm = Tpetra::getDefaultComm();
  LinearSolver lin(mumps_config(), comm);
  EXPECT_NE(lin.description().find("MUMPS, " + std::to_string(comm->getSize()) + " rank"), std::string::npos) << lin.description();
  const double e1 = solve_error(lin, saddle(comm, 3000, 1.0, false));
  const double e2 = solve_error(lin, saddle(comm, 3000, 7.0, false));  // new values, same pattern
  const double e3 = solve_error(lin, saddle(comm, 3000, 1.0, true));   // a new pattern
  if (comm->getRank() == 0)
    std::printf("[mumps] %d rank(s), 6000 rows: max error %.2e, %.2e (new values), %.2e (new pattern)\n", comm->getSize(), e1, e2, e3);
  EXPECT_LT(e1, 1e-12);
  EXPECT_LT(e2, 1e-12);
  EXPECT_LT(e3, 1e-12);
}

TEST(Mumps, SingularMatrixIsAFailureNamingMumps) {
  auto comm = Tpetra::getDefaultComm();
  auto map = Teuchos::rcp(new la::Map(40, 0, comm));
  auto A = Teuchos::rcp(new la::CrsMatrix(map, 2));
  for (std::size_t l = 0; l < map->getNodeNumElements(); ++l) {
    const la::GO i = map->getGlobalElement(static_cast<la::LO>(l));
    // Rows 10 and 11 equal: singular.
    const la::GO c = i == 11 ? 10 : i;
    const la::SC v = 1.0;
    A->insertGlobalValues(i, Teuchos::ArrayView<const la::GO>(&c, 1), Teuchos::ArrayView<const la::SC>(&v, 1));
  }
  A->fillComplete();
  LinearSolver lin(mumps_config(), comm);
  try {
    lin.setup(A);
    FAIL() << "a singular matrix was factored";
  } catch (const LinearSolverFailure& e) {
    const std::string what = e.what();
    if (comm->getRank() == 0) std::printf("[mumps] %s\n", what.c_str());
    EXPECT_NE(what.find("MUMPS"), std::string::npos) << what;
    EXPECT_NE(what.find("INFOG(1) = -10"), std::string::npos) << what;
    EXPECT_NE(what.find("singular"), std::string::npos) << what;
  }
}

TEST(Mumps, SameNewtonPathAsKlu2OnTheBlock) {
  if (Tpetra::getDefaultComm()->getSize() > 1) GTEST_SKIP() << "a whole run: 1 rank (the 2-rank runs are mpi.consistency's)";
  const fs::path dir = stentor::testing::test_dir("mumps");
  fs::create_directories(dir);
  const std::string geo = std::string(STENTOR_SOURCE_DIR) + "/inputs/block3d.geo";
  const std::string bcs = stentor::testing::dirichlet_xml("left", "left", "x") + stentor::testing::dirichlet_xml("front", "front", "y") +
                          stentor::testing::dirichlet_xml("bottom", "bottom", "z") +
                          stentor::testing::dirichlet_xml("pull", "right", "x", "{0.3}");
  std::ofstream(dir / "block.xml") << stentor::testing::block_deck_xml(geo, bcs, "block");
  RunResult r[2];
  const char* solver[2] = {"klu2", "mumps"};
  for (int k = 0; k < 2; ++k) {
    Config cfg = read_deck((dir / "block.xml").string());
    cfg.linear.direct_solver = solver[k];
    RunOptions o;
    o.output_dir = (dir / solver[k]).string();
    o.overwrite = true;
    ASSERT_EQ(run_simulation(cfg, o, &r[k]), 0) << solver[k];
  }
  const double d = stentor::testing::rel_diff(r[1].displacement, r[0].displacement);
  std::printf("[mumps] block: Newton %d (KLU2) / %d (MUMPS), |u_mumps - u_klu2| / |u_klu2| = %.2e\n", r[0].newton_iterations,
              r[1].newton_iterations, d);
  EXPECT_EQ(r[0].newton_iterations, r[1].newton_iterations);
  EXPECT_LT(d, 1e-12);
}
#endif  // STENTOR_HAVE_MUMPS
