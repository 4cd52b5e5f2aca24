// The Newton options of issue 14 (docs/performance.md, "Time to solution"):
//  - residual-only line-search trials give the same iterates as trials with the tangent,
//    with fewer tangent assemblies (a cubic algebraic system where the full step overshoots);
//  - a reused preconditioner still solves to the requested tolerance and is rebuilt when
//    a solve degrades, at once when GMRES's first cycle gains less than one digit;
//  - GMRES beyond its first cycle ends at the configured tolerance;
//  - Stepping->predictor = auto (lifting on the first static step), Newton->forcing =
//    eisenstat-walker and Linear Solver->preconditioner reuse reach the same solution as
//    the plain iteration on the 3D block (P2, 20% stretch in one step), with fewer Newton
//    or Krylov iterations.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <Tpetra_Core.hpp>

#include "RelDiff.hpp"
#include "deck/Config.hpp"
#include "run/RunState.hpp"
#include "run/Simulation.hpp"
#include "solver/LinearSolver.hpp"
#include "solver/ReusePolicy.hpp"
#include "solver/Newton.hpp"
#include "TestDir.hpp"

using namespace stentor;
using stentor::testing::rel_diff;
namespace fs = std::filesystem;

namespace {

fs::path work_dir() { return stentor::testing::test_dir("newton"); }

la::RCP<const la::Comm> comm() { return Tpetra::getDefaultComm(); }

// GMRES without a preconditioner, to 1e-13: the small algebraic systems below need no
// more, and their iterates then do not depend on a preconditioner.
LinearSolverConfig unpreconditioned() {
  LinearSolverConfig lc;
  lc.preconditioner = "none";
  lc.tolerance = 1e-13;
  return lc;
}

// Tridiagonal matrix on `map` (its graph fixed once), values set by set_values.
la::RCP<la::CrsMatrix> tridiagonal(const la::RCP<const la::Map>& map) {
  auto A = Teuchos::rcp(new la::CrsMatrix(map, 3));
  const la::GO n = static_cast<la::GO>(map->getGlobalNumElements());
  for (la::LO l = 0; l < static_cast<la::LO>(map->getNodeNumElements()); ++l) {
    const la::GO g = map->getGlobalElement(l);
    std::vector<la::GO> cols;
    std::vector<double> vals;
    for (la::GO c = std::max<la::GO>(0, g - 1); c <= std::min<la::GO>(n - 1, g + 1); ++c) {
      cols.push_back(c);
      vals.push_back(0.0);
    }
    A->insertGlobalValues(g, Teuchos::ArrayView<const la::GO>(cols), Teuchos::ArrayView<const double>(vals));
  }
  A->fillComplete();
  return A;
}

// r_i(u) = u_i^3 + u_i + k (2 u_i - u_{i-1} - u_{i+1}) - b_i: from u = 0 the full Newton
// step overshoots (the tangent there is the linear part only), so the line search halves.
class CubicSystem : public NewtonSystem {
 public:
  CubicSystem(const la::RCP<const la::Map>& map, bool needs_tangent) : map_(map), needs_(needs_tangent), A_(tridiagonal(map)) {}
  int tangents = 0, residuals = 0;
  bool evaluate(const la::Vector& u, la::Vector& r, bool tangent) override {
    ++(tangent ? tangents : residuals);
    la::Vector uu(map_);  // u with its neighbours: A's off-diagonal action via a Laplacian
    auto Lap = laplacian();
    Lap->apply(u, uu);
    auto uh = u.getLocalViewHost(Tpetra::Access::ReadOnly);
    auto lh = uu.getLocalViewHost(Tpetra::Access::ReadOnly);
    auto rh = r.getLocalViewHost(Tpetra::Access::OverwriteAll);
    for (size_t i = 0; i < u.getLocalLength(); ++i) {
      const double x = uh(i, 0);
      rh(i, 0) = x * x * x + x + k * lh(i, 0) - b(map_->getGlobalElement(static_cast<la::LO>(i)));
    }
    if (tangent) {
      A_->resumeFill();
      for (size_t i = 0; i < u.getLocalLength(); ++i) {
        const la::GO g = map_->getGlobalElement(static_cast<la::LO>(i));
        const double x = uh(i, 0);
        const la::GO n = static_cast<la::GO>(map_->getGlobalNumElements());
        for (la::GO c = std::max<la::GO>(0, g - 1); c <= std::min<la::GO>(n - 1, g + 1); ++c) {
          const double v = c == g ? 3 * x * x + 1 + 2 * k : -k;
          A_->replaceGlobalValues(g, Teuchos::tuple<la::GO>(c), Teuchos::tuple<double>(v));
        }
      }
      A_->fillComplete();
    }
    return true;
  }
  la::RCP<la::CrsMatrix> matrix() override { return A_; }
  bool residual_needs_tangent() const override { return needs_; }

 private:
  static constexpr double k = 0.5;
  static double b(la::GO g) { return 20.0 + static_cast<double>(g % 5); }
  la::RCP<la::CrsMatrix> laplacian() {
    if (L_.is_null()) {
      L_ = tridiagonal(map_);
      L_->resumeFill();
      const la::GO n = static_cast<la::GO>(map_->getGlobalNumElements());
      for (la::LO l = 0; l < static_cast<la::LO>(map_->getNodeNumElements()); ++l) {
        const la::GO g = map_->getGlobalElement(l);
        for (la::GO c = std::max<la::GO>(0, g - 1); c <= std::min<la::GO>(n - 1, g + 1); ++c)
          L_->replaceGlobalValues(g, Teuchos::tuple<la::GO>(c), Teuchos::tuple<double>(c == g ? 2.0 : -1.0));
      }
      L_->fillComplete();
    }
    return L_;
  }
  la::RCP<const la::Map> map_;
  bool needs_;
  la::RCP<la::CrsMatrix> A_, L_;
};

struct CubicRun {
  NewtonResult res;
  std::vector<double> u;
  int tangents = 0, residuals = 0;
};

CubicRun solve_cubic(bool needs_tangent) {
  auto map = Teuchos::rcp(new la::Map(40, 0, comm()));
  CubicSystem sys(map, needs_tangent);
  LinearSolver lin(unpreconditioned(), comm());
  NewtonConfig nc;
  nc.residual_tolerance = 1e-12;
  la::Vector u(map);
  CubicRun out;
  out.res = newton_solve(sys, u, lin, nc, nullptr);
  auto uh = u.getLocalViewHost(Tpetra::Access::ReadOnly);
  for (size_t i = 0; i < u.getLocalLength(); ++i) out.u.push_back(uh(i, 0));
  out.tangents = sys.tangents;
  out.residuals = sys.residuals;
  return out;
}

// r_i(u) = atan(u_i - c_i), diagonal: plain Newton (no line search) from u = 0 diverges where
// |c_i| > 1.39 (each update overshoots the root further), the classic case for step-length
// control. Records the largest change of any component between consecutive tangents.
class AtanSystem : public NewtonSystem {
 public:
  explicit AtanSystem(const la::RCP<const la::Map>& map) : map_(map), A_(tridiagonal(map)), last_(map) {}
  double largest_update = 0.0;
  bool evaluate(const la::Vector& u, la::Vector& r, bool tangent) override {
    auto uh = u.getLocalViewHost(Tpetra::Access::ReadOnly);
    auto rh = r.getLocalViewHost(Tpetra::Access::OverwriteAll);
    for (size_t i = 0; i < u.getLocalLength(); ++i) rh(i, 0) = std::atan(uh(i, 0) - c(i));
    if (!tangent) return true;
    la::Vector d(u, Teuchos::Copy);
    d.update(-1.0, last_, 1.0);
    largest_update = std::max(largest_update, d.normInf());
    last_.update(1.0, u, 0.0);
    A_->resumeFill();
    for (size_t i = 0; i < u.getLocalLength(); ++i) {
      const double x = uh(i, 0) - c(i);
      A_->replaceLocalValues(static_cast<la::LO>(i), Teuchos::tuple<la::LO>(A_->getColMap()->getLocalElement(map_->getGlobalElement(static_cast<la::LO>(i)))),
                             Teuchos::tuple<double>(1.0 / (1.0 + x * x)));
    }
    A_->fillComplete();
    return true;
  }
  la::RCP<la::CrsMatrix> matrix() override { return A_; }
  double c(size_t i) const { return 3.0 + 0.1 * static_cast<double>(map_->getGlobalElement(static_cast<la::LO>(i)) % 4); }

 private:
  la::RCP<const la::Map> map_;
  la::RCP<la::CrsMatrix> A_;
  la::Vector last_;
};

// Tridiagonal matrix with `diag` on the diagonal, `lower` left of it and `upper` right of it.
void set_tridiagonal(la::CrsMatrix& A, double diag, double lower, double upper) {
  const auto map = A.getRowMap();
  const la::GO n = static_cast<la::GO>(map->getGlobalNumElements());
  A.resumeFill();
  for (la::LO l = 0; l < static_cast<la::LO>(map->getNodeNumElements()); ++l) {
    const la::GO g = map->getGlobalElement(l);
    for (la::GO c = std::max<la::GO>(0, g - 1); c <= std::min<la::GO>(n - 1, g + 1); ++c)
      A.replaceGlobalValues(g, Teuchos::tuple<la::GO>(c), Teuchos::tuple<double>(c == g ? diag : c < g ? lower : upper));
  }
  A.fillComplete();
}

// r(u) = A u - b with A = tridiag(-1, 2.5, -1): one exact linear solve converges Newton.
class LinearTridiagonalSystem : public NewtonSystem {
 public:
  explicit LinearTridiagonalSystem(const la::RCP<const la::Map>& map) : A_(tridiagonal(map)), b_(map) {
    set_tridiagonal(*A_, 2.5, -1.0, -1.0);
    b_.putScalar(1.0);
  }
  bool evaluate(const la::Vector& u, la::Vector& r, bool) override {
    A_->apply(u, r);
    r.update(-1.0, b_, 1.0);
    return true;
  }
  la::RCP<la::CrsMatrix> matrix() override { return A_; }

 private:
  la::RCP<la::CrsMatrix> A_;
  la::Vector b_;
};

// r = (a - theta, K (b - a^2)): a stiff "strain" b that must follow a^2, as a floating body's
// elastic energy follows its rotation. From (0, 0) the tangent sees only the linear part,
// so the full step's residual carries K (a - a_k)^2: |r(alpha)| ~ |(1 - alpha) r0 +
// alpha^2 q| with |q| >> |r0|, and backtracking accepts only alpha ~ 1/32, again at every
// iterate (Newton creeps); the full step lands where one more iteration converges
// (b is linear at fixed a). With `wrong` > 1 the tangent's b column is scaled by it where
// |b - a^2| > 1 (a model whose tangent is poor far from the path): there the full step
// converges only linearly, at rate 1 - 1/wrong, so it leads nowhere within the watchdog's
// 3 iterations. One rank holds both unknowns (the test runs on one).
class StiffQuadraticSystem : public NewtonSystem {
 public:
  StiffQuadraticSystem(const la::RCP<const la::Map>& map, double theta, double wrong)
      : theta_(theta), wrong_(wrong), A_(tridiagonal(map)) {}
  bool evaluate(const la::Vector& u, la::Vector& r, bool tangent) override {
    const auto uh = u.getLocalViewHost(Tpetra::Access::ReadOnly);
    auto rh = r.getLocalViewHost(Tpetra::Access::OverwriteAll);
    const double a = uh(0, 0), b = uh(1, 0);
    rh(0, 0) = a - theta_;
    rh(1, 0) = kK * (b - a * a);
    if (tangent) {
      const double f = std::abs(b - a * a) > 1.0 ? wrong_ : 1.0;
      A_->resumeFill();
      A_->replaceGlobalValues(0, Teuchos::tuple<la::GO>(0, 1), Teuchos::tuple<double>(1.0, 0.0));
      A_->replaceGlobalValues(1, Teuchos::tuple<la::GO>(0, 1), Teuchos::tuple<double>(-2.0 * kK * a, kK * f));
      A_->fillComplete();
    }
    return true;
  }
  la::RCP<la::CrsMatrix> matrix() override { return A_; }
  static constexpr double kK = 100.0;

 private:
  double theta_, wrong_;
  la::RCP<la::CrsMatrix> A_;
};

struct StiffRun {
  NewtonResult res;
  double a = 0.0, b = 0.0;
  std::string log;
};

StiffRun solve_stiff(double theta, double wrong, int watchdog) {
  auto map = Teuchos::rcp(new la::Map(2, 0, comm()));
  StiffQuadraticSystem sys(map, theta, wrong);
  LinearSolverConfig lc;
  lc.method = "direct";
  LinearSolver lin(lc, comm());
  NewtonConfig nc;
  nc.residual_tolerance = 1e-12;
  nc.max_iterations = 200;
  nc.line_search_watchdog = watchdog;
  la::Vector u(map);
  std::ostringstream log;
  StiffRun out;
  out.res = newton_solve(sys, u, lin, nc, &log);
  const auto uh = u.getLocalViewHost(Tpetra::Access::ReadOnly);
  out.a = uh(0, 0);
  out.b = uh(1, 0);
  out.log = log.str();
  return out;
}

// r_i = u_i^3 + u_i - b with b = 2 + (the revisions so far): verify_held() reports revised
// holds `revisions` times (each one moves b, as a revised contact node moves the
// equilibrium), then passes. Diagonal, so any number of ranks.
class RevisedHoldsSystem : public NewtonSystem {
 public:
  RevisedHoldsSystem(const la::RCP<const la::Map>& map, int revisions) : revisions_(revisions), A_(tridiagonal(map)) {}
  bool evaluate(const la::Vector& u, la::Vector& r, bool tangent) override {
    const auto uh = u.getLocalViewHost(Tpetra::Access::ReadOnly);
    auto rh = r.getLocalViewHost(Tpetra::Access::OverwriteAll);
    for (size_t i = 0; i < u.getLocalLength(); ++i) rh(i, 0) = uh(i, 0) * uh(i, 0) * uh(i, 0) + uh(i, 0) - (2.0 + done_);
    if (tangent) {
      const auto map = A_->getRowMap();
      A_->resumeFill();
      for (size_t i = 0; i < u.getLocalLength(); ++i) {
        const la::GO g = map->getGlobalElement(static_cast<la::LO>(i));
        const la::GO n = static_cast<la::GO>(map->getGlobalNumElements());
        for (la::GO c = std::max<la::GO>(0, g - 1); c <= std::min<la::GO>(n - 1, g + 1); ++c)
          A_->replaceGlobalValues(g, Teuchos::tuple<la::GO>(c), Teuchos::tuple<double>(c == g ? 3 * uh(i, 0) * uh(i, 0) + 1 : 0.0));
      }
      A_->fillComplete();
    }
    return true;
  }
  la::RCP<la::CrsMatrix> matrix() override { return A_; }
  int verify_held(std::string&) override { return done_ < revisions_ ? (++done_, 1) : 0; }

 private:
  int revisions_, done_ = 0;
  la::RCP<la::CrsMatrix> A_;
};

}  // namespace

// Newton->max increment: without it plain Newton diverges on atan (and fails); with a limit
// of 0.5 no update moves a component by more than 0.5 and Newton converges, first with
// limited steps towards the root, then quadratically.
TEST(Newton, MaxIncrementTamesAnOvershootingNewton) {
  auto map = Teuchos::rcp(new la::Map(12, 0, comm()));
  LinearSolver lin(unpreconditioned(), comm());
  NewtonConfig nc;
  nc.line_search = false;
  nc.max_iterations = 30;
  {
    AtanSystem sys(map);
    la::Vector u(map);
    const NewtonResult plain = newton_solve(sys, u, lin, nc, nullptr);
    EXPECT_FALSE(plain.converged);
    EXPECT_GT(sys.largest_update, 10.0);  // the iterates ran away
  }
  nc.max_increment = 0.5;
  AtanSystem sys(map);
  la::Vector u(map);
  const NewtonResult res = newton_solve(sys, u, lin, nc, nullptr);
  ASSERT_TRUE(res.converged) << res.failure;
  EXPECT_LE(sys.largest_update, 0.5 * (1.0 + 1e-12));
  EXPECT_GE(res.iterations, 6);   // at least 3 / 0.5 limited steps ...
  EXPECT_LE(res.iterations, 12);  // ... then a few quadratic ones
  auto uh = u.getLocalViewHost(Tpetra::Access::ReadOnly);
  for (size_t i = 0; i < u.getLocalLength(); ++i) EXPECT_NEAR(uh(i, 0), sys.c(i), 1e-9) << i;
  std::printf("[newton] atan: diverges without a limit; %d iterations with max increment 0.5\n", res.iterations);
}

TEST(Newton, ResidualOnlyTrialsSameIteratesFewerTangents) {
  const CubicRun cheap = solve_cubic(false), full = solve_cubic(true);
  ASSERT_TRUE(cheap.res.converged) << cheap.res.failure;
  ASSERT_TRUE(full.res.converged) << full.res.failure;
  EXPECT_EQ(cheap.res.iterations, full.res.iterations);
  ASSERT_EQ(cheap.u.size(), full.u.size());
  for (std::size_t i = 0; i < cheap.u.size(); ++i) EXPECT_EQ(cheap.u[i], full.u[i]) << i;  // bitwise
  EXPECT_EQ(full.residuals, 0);
  EXPECT_GT(cheap.residuals, 0);  // the line search halved at least once
  // Every residual-only trial replaces a tangent assembly; an accepted halved step costs
  // one tangent assembly afterwards (unless Newton stopped there).
  EXPECT_LT(cheap.tangents, full.tangents);
  EXPECT_LE(cheap.tangents + cheap.residuals, full.tangents + cheap.res.iterations);
  std::printf("[newton] cubic: %d iterations; tangent assemblies %d (residual-only trials %d) vs %d\n", cheap.res.iterations,
              cheap.tangents, cheap.residuals, full.tangents);
}

// A tangent whose discrete part changed at the point it was assembled at (settled() false:
// e.g. contact rows of nodes that entered the active set) gets a preconditioner built for
// it, whatever the reuse count; once settled, the kept one serves again. The iterates do
// not depend on it (GMRES to the same tolerance).
class UnsettledCubic : public CubicSystem {
 public:
  UnsettledCubic(const la::RCP<const la::Map>& map, int unsettled) : CubicSystem(map, false), left_(unsettled) {}
  bool evaluate(const la::Vector& u, la::Vector& r, bool tangent) override {
    settled_ = left_-- <= 0;
    return CubicSystem::evaluate(u, r, tangent);
  }
  bool settled() const override { return settled_; }

 private:
  int left_;
  bool settled_ = true;
};

TEST(Newton, ChangedActiveSetRebuildsTheKeptPreconditioner) {
  auto run = [](int unsettled, int& iterations, bool on_change = true) {
    auto map = Teuchos::rcp(new la::Map(40, 0, comm()));
    UnsettledCubic sys(map, unsettled);
    LinearSolverConfig lc;
    lc.preconditioner = "schwarz";
    lc.tolerance = 1e-13;
    lc.preconditioner_reuse = 20;
    lc.preconditioner_rebuild_cost = 1e9;  // only the active set (and the age) rebuild
    lc.preconditioner_rebuild_on_change = on_change;
    LinearSolver lin(lc, comm());
    NewtonConfig nc;
    nc.residual_tolerance = 1e-12;
    nc.line_search = false;  // one evaluate per iteration: the k-th solve uses the k-th point
    la::Vector u(map);
    const NewtonResult res = newton_solve(sys, u, lin, nc, nullptr);
    EXPECT_TRUE(res.converged) << res.failure;
    iterations = res.iterations;
    return lin.times().builds;
  };
  int its_settled = 0, its_changed = 0;
  EXPECT_EQ(run(0, its_settled), 1);  // built once, kept to the end
  // The start and the first two iterates are unsettled: the first three solves each get a
  // preconditioner of their own (the first one is the first build anyway).
  EXPECT_EQ(run(3, its_changed), 3);
  int its_off = 0;
  EXPECT_EQ(run(3, its_off, false), 1);  // preconditioner rebuild on contact change = false
  EXPECT_EQ(its_off, its_changed);
  EXPECT_GE(its_settled, 4);
  EXPECT_GE(its_changed, 4);
}

// Eisenstat-Walker's first forcing term from a hint (the last dynamic step's first residual
// ratio, passed by the Stepper): a step that one tight solve converges (here a linear
// system) is solved tightly at once, in one Newton iteration, instead of loosely first
// (forcing max = 0.1) and then again; both reach the same solution, and first_ratio
// reports |r_1| / |r_0|.
TEST(Newton, EisenstatWalkerStartsFromTheFirstRatioHint) {
  auto map = Teuchos::rcp(new la::Map(60, 0, comm()));
  LinearSolverConfig lc;
  lc.preconditioner = "none";
  lc.tolerance = 1e-12;
  NewtonConfig nc;
  nc.residual_tolerance = 1e-10;
  nc.forcing = "eisenstat-walker";
  auto run = [&](double hint, std::vector<double>& x) {
    LinearTridiagonalSystem sys(map);
    LinearSolver lin(lc, comm());
    la::Vector u(map);
    const NewtonResult r = newton_solve(sys, u, lin, nc, nullptr, hint);
    auto uh = u.getLocalViewHost(Tpetra::Access::ReadOnly);
    for (size_t i = 0; i < u.getLocalLength(); ++i) x.push_back(uh(i, 0));
    return r;
  };
  std::vector<double> x_plain, x_hint;
  const NewtonResult plain = run(0.0, x_plain), hinted = run(1e-8, x_hint);
  ASSERT_TRUE(plain.converged);
  ASSERT_TRUE(hinted.converged);
  EXPECT_GE(plain.iterations, 2);
  EXPECT_NEAR(plain.first_ratio, 0.1, 0.05);  // the first solve stopped at eta = forcing max
  EXPECT_EQ(hinted.iterations, 1);
  EXPECT_LT(hinted.first_ratio, 1e-10);
  EXPECT_LT(rel_diff(x_plain, x_hint), 1e-9);
}

// A preconditioner kept from an earlier matrix (Linear Solver->preconditioner reuse)
// still gives solves to the requested tolerance; the counters say how often it was built.
TEST(LinearSolverReuse, StalePreconditionerStillSolvesToTolerance) {
  auto map = Teuchos::rcp(new la::Map(200, 0, comm()));
  auto A = tridiagonal(map);
  auto set = [&](double shift) {
    A->resumeFill();
    const la::GO n = 200;
    for (la::LO l = 0; l < static_cast<la::LO>(map->getNodeNumElements()); ++l) {
      const la::GO g = map->getGlobalElement(l);
      for (la::GO c = std::max<la::GO>(0, g - 1); c <= std::min<la::GO>(n - 1, g + 1); ++c)
        A->replaceGlobalValues(g, Teuchos::tuple<la::GO>(c), Teuchos::tuple<double>(c == g ? 2.0 + shift * (1 + g % 7) : -1.0));
    }
    A->fillComplete();
  };
  LinearSolverConfig lc;
  lc.preconditioner = "schwarz";
  lc.fill_level = 0;
  lc.tolerance = 1e-10;
  lc.preconditioner_reuse = 3;
  LinearSolver lin(lc, comm());
  la::Vector b(map), x(map), res(map);
  b.putScalar(1.0);
  for (int k = 0; k < 5; ++k) {
    set(0.01 * (k + 1));
    lin.setup(A);
    const LinearSolver::Result r = lin.solve(b, x);
    ASSERT_TRUE(r.converged) << k;
    A->apply(x, res);
    res.update(1.0, b, -1.0);
    EXPECT_LE(res.norm2(), 1.01e-10 * b.norm2()) << k;
  }
  EXPECT_EQ(lin.times().setups, 5);
  EXPECT_EQ(lin.times().builds, 2);  // built, kept 3 times, rebuilt
  // A forcing-term tolerance for one solve overrides the configured one.
  const LinearSolver::Result loose = lin.solve(b, x, 1e-3);
  A->apply(x, res);
  res.update(1.0, b, -1.0);
  EXPECT_LE(res.norm2(), 1.01e-3 * b.norm2());
  EXPECT_GT(res.norm2(), 1e-10 * b.norm2());
  EXPECT_TRUE(loose.converged);
  EXPECT_DOUBLE_EQ(lin.tolerance(), 1e-10);
}


double true_residual(const la::CrsMatrix& A, const la::Vector& b, const la::Vector& x) {
  la::Vector r(b.getMap());
  A.apply(x, r);
  r.update(1.0, b, -1.0);
  return r.norm2() / b.norm2();
}

// GMRES that needs several cycles (restart 10) goes on after its first cycle from that
// cycle's iterate and ends at the configured tolerance, relative to |b| as in one run.
TEST(LinearSolver, GmresBeyondOneCycleSolvesToTolerance) {
  auto map = Teuchos::rcp(new la::Map(200, 0, comm()));
  auto A = tridiagonal(map);
  set_tridiagonal(*A, 2.3, -1.0, -1.0);
  LinearSolverConfig lc;
  lc.preconditioner = "none";
  lc.restart = 10;
  lc.max_iterations = 1000;
  lc.tolerance = 1e-10;
  LinearSolver lin(lc, comm());
  la::Vector b(map), x(map);
  b.randomize();
  lin.setup(A);
  const LinearSolver::Result r = lin.solve(b, x);
  ASSERT_TRUE(r.converged);
  EXPECT_GT(r.iterations, 2 * lc.restart);
  EXPECT_LE(r.residual, 1e-10);
  EXPECT_LE(true_residual(*A, b, x), 1.01e-10);
}

// A reused preconditioner that no longer fits the matrix (the exact inverse of a discrete
// Laplacian, applied to a strongly unsymmetric tridiagonal matrix) stalls in GMRES's first
// cycle: it is rebuilt
// for the new matrix at once, and the system solved to tolerance in one more solve,
// instead of spending the 1000 allowed iterations first.
TEST(LinearSolverReuse, StalledReusedPreconditionerIsRebuiltAfterOneCycle) {
  auto map = Teuchos::rcp(new la::Map(200, 0, comm()));
  auto A = tridiagonal(map);
  LinearSolverConfig lc;
  lc.preconditioner = "schwarz";  // ILU(0) of a tridiagonal matrix: its exact LU on one rank
  lc.fill_level = 0;
  lc.restart = 10;
  lc.max_iterations = 1000;
  lc.tolerance = 1e-10;
  lc.preconditioner_reuse = 20;
  LinearSolver lin(lc, comm());
  la::Vector b(map), x(map);
  b.putScalar(1.0);
  set_tridiagonal(*A, 2.01, -1.0, -1.0);
  lin.setup(A);
  ASSERT_TRUE(lin.solve(b, x).converged);
  set_tridiagonal(*A, 2.01, -30.0, 30.0);
  lin.setup(A);  // reuses the preconditioner of the first matrix
  EXPECT_EQ(lin.times().builds, 1);
  const LinearSolver::Result r = lin.solve(b, x);
  ASSERT_TRUE(r.converged);
  EXPECT_LE(true_residual(*A, b, x), 1.01e-10);
  EXPECT_EQ(lin.times().stale_rebuilds, 1);
  EXPECT_EQ(lin.times().builds, 2);
  EXPECT_EQ(lin.times().fallbacks, 0);
  EXPECT_LE(r.iterations, 5);  // the rebuilt (exact on one rank) preconditioner's solve
}

// The rebuild policy in GMRES iterations: solves at a fresh preconditioner's rate never
// force a rebuild (only the age limit does); solves that need more iterations per digit add
// up their excess, a faster solve pays some back, and a rebuild comes once the excess
// reaches the build's worth; a solve that did not converge forces one at once.
TEST(ReusePolicy, RebuildsWhenLostIterationsReachTheBuildCost) {
  ReusePolicy p;
  p.max_age = 5;
  p.build_cost = 25.0;
  p.built();
  p.solved(20, 1e-10, true);  // fresh: 2 iterations per digit
  for (int k = 0; k < 5; ++k) {
    ASSERT_TRUE(p.keep()) << k;
    p.solved(24, 1e-10, true);  // 20 % slower: within the allowance (25 %)
    EXPECT_DOUBLE_EQ(p.excess, 0.0);
  }
  EXPECT_FALSE(p.keep());  // served max_age set-ups
  p.built();
  p.solved(8, 1e-4, true);    // fresh: 2 per digit, from a loose solve
  ASSERT_TRUE(p.keep());
  p.solved(40, 1e-10, true);  // 4 per digit: 40 - 1.25 * 2 * 10 = 15 lost
  EXPECT_DOUBLE_EQ(p.excess, 15.0);
  ASSERT_TRUE(p.keep());
  p.solved(10, 1e-10, true);  // faster than the allowance: pays back 15
  EXPECT_DOUBLE_EQ(p.excess, 0.0);
  ASSERT_TRUE(p.keep());
  p.solved(40, 1e-10, true);
  ASSERT_TRUE(p.keep());      // 15 < 25
  p.solved(40, 1e-10, true);  // 30 >= 25
  EXPECT_DOUBLE_EQ(p.excess, 30.0);
  EXPECT_FALSE(p.keep());
  p.built();
  EXPECT_DOUBLE_EQ(p.excess, 0.0);
  p.solved(3, 0.5, true);     // gained less than a digit: no rate from it
  EXPECT_LT(p.rate0, 0.0);
  p.solved(10, 1e-5, true);
  EXPECT_DOUBLE_EQ(p.rate0, 2.0);
  ASSERT_TRUE(p.keep());
  p.solved(200, 1e-3, false);  // not converged
  EXPECT_FALSE(p.keep());
}

// A preconditioner kept while the matrix drifts away from the one it was built for (the
// exact LU of a symmetric tridiagonal matrix, then ever more unsymmetric ones) costs GMRES
// iterations; with the default rebuild cost it is rebuilt before its age limit, and the
// run needs fewer iterations than one that keeps it (rebuild cost "infinite"), every solve
// to tolerance either way.
TEST(LinearSolverReuse, DriftingMatrixRebuildsWhenItPays) {
  auto run = [](double cost, long& builds) {
    auto map = Teuchos::rcp(new la::Map(200, 0, comm()));
    auto A = tridiagonal(map);
    LinearSolverConfig lc;
    lc.preconditioner = "schwarz";  // ILU(0) of a tridiagonal matrix: its exact LU on one rank
    lc.fill_level = 0;
    lc.tolerance = 1e-10;
    lc.preconditioner_reuse = 20;
    lc.preconditioner_rebuild_cost = cost;
    LinearSolver lin(lc, comm());
    la::Vector b(map), x(map);
    b.putScalar(1.0);
    int iterations = 0;
    for (int k = 0; k < 12; ++k) {
      const double s = 0.15 * k;
      set_tridiagonal(*A, 2.5, -1.0 - s, -1.0 + s);
      lin.setup(A);
      const LinearSolver::Result r = lin.solve(b, x);
      EXPECT_TRUE(r.converged) << k;
      EXPECT_LE(true_residual(*A, b, x), 1.01e-10) << k;
      iterations += r.iterations;
    }
    builds = lin.times().builds;
    return iterations;
  };
  long kept_builds = 0, policy_builds = 0;
  const int kept = run(1e9, kept_builds);
  const int policy = run(25.0, policy_builds);
  EXPECT_EQ(kept_builds, 1);
  EXPECT_GT(policy_builds, 1);
  EXPECT_LT(policy_builds, 12);
  EXPECT_LT(policy, kept);
  std::printf("drift: kept %d iterations, 1 build; policy %d iterations, %ld builds\n", kept, policy, policy_builds);
}

namespace {

// The 3D block (inputs/block3d.geo, symmetry constraints, right face pulled 20%) in P2,
// in `steps` load steps, with the given Stepping/Newton/Linear Solver parameters.
std::string write_block(const std::string& tag, int steps, const std::string& stepping, const std::string& newton,
                        const std::string& linear) {
  fs::create_directories(work_dir());
  const std::string geo = (fs::path(STENTOR_SOURCE_DIR) / "inputs" / "block3d.geo").string();
  auto dirichlet = [](const char* name, const char* boundary, const char* comp, const char* value) {
    std::string s = std::string("    <ParameterList name=\"") + name + "\">\n" +
                    "      <Parameter name=\"type\" type=\"string\" value=\"Dirichlet\"/>\n" +
                    "      <Parameter name=\"boundary\" type=\"string\" value=\"" + boundary + "\"/>\n" +
                    "      <Parameter name=\"components\" type=\"string\" value=\"" + comp + "\"/>\n";
    if (value) s += std::string("      <Parameter name=\"values\" type=\"Array(double)\" value=\"{") + value + "}\"/>\n";
    return s + "    </ParameterList>\n";
  };
  const fs::path deck = work_dir() / (tag + ".xml");
  std::ofstream(deck) << R"(<ParameterList name="stentor">
  <ParameterList name="Mesh">
    <Parameter name="file" type="string" value=")" << geo << R"("/>
    <Parameter name="size" type="double" value="0.34"/>
    <Parameter name="order" type="int" value="2"/>
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
)" << dirichlet("left", "left", "x", nullptr)
                      << dirichlet("front", "front", "y", nullptr) << dirichlet("bottom", "bottom", "z", nullptr)
                      << dirichlet("pull", "right", "x", "0.2") << R"(  </ParameterList>
  <ParameterList name="Stepping">
    <Parameter name="end time" type="double" value="1.0"/>
    <Parameter name="steps" type="int" value=")" << steps << R"("/>
)" << stepping << R"(  </ParameterList>
  <ParameterList name="Newton">
)" << newton << R"(  </ParameterList>
  <ParameterList name="Linear Solver">
)" << linear << R"(  </ParameterList>
  <ParameterList name="Output">
    <Parameter name="fields" type="bool" value="false"/>
    <Parameter name="basename" type="string" value="block"/>
  </ParameterList>
</ParameterList>
)";
  return deck.string();
}

RunResult run_block(const std::string& tag, int steps, const std::string& stepping, const std::string& newton = "",
                    const std::string& linear = "") {
  const Config cfg = read_deck(write_block(tag, steps, stepping, newton, linear));
  RunOptions opts;
  opts.output_dir = (work_dir() / ("out_" + tag)).string();
  RunResult res;
  EXPECT_EQ(run_simulation(cfg, opts, &res), 0) << tag;
  return res;
}

std::string param(const char* name, const char* type, const char* value) {
  return std::string("    <Parameter name=\"") + name + "\" type=\"" + type + "\" value=\"" + value + "\"/>\n";
}

}  // namespace

// 20% stretch in one step: moving only the pulled face squeezes the increment into one
// layer of cells; the lifting spreads it (one linear solve) and Newton needs fewer
// iterations (each counted, the lifting included) to the same solution.
TEST(Newton, LiftingSameSolutionFewerIterations) {
  const RunResult none = run_block("lift_none", 1, param("predictor", "string", "none"));
  const RunResult lift = run_block("lift_auto", 1, "");  // auto: lifting on the first static step
  ASSERT_TRUE(none.converged && lift.converged);
  EXPECT_EQ(none.cutbacks, lift.cutbacks);
  const double d = rel_diff(lift.displacement, none.displacement);
  std::printf("[newton] lifting: Newton %d -> %d (lifting counted), GMRES %d -> %d, |du|/|u| = %.2e\n", none.newton_iterations,
              lift.newton_iterations, none.linear_iterations, lift.linear_iterations, d);
  EXPECT_LT(d, 1e-8);
  EXPECT_NEAR(lift.reactions[3][0], none.reactions[3][0], 1e-8 * std::abs(none.reactions[3][0]));
  EXPECT_LT(lift.newton_iterations, none.newton_iterations);
}

// Inexact Newton (Eisenstat-Walker) and a reused MueLu preconditioner (the default): the
// same solution to the Newton tolerance as exact solves with a fresh preconditioner per
// iteration, in fewer Krylov iterations.
TEST(Newton, EisenstatWalkerAndReuseSameSolution) {
  const std::string fresh = param("preconditioner reuse", "int", "0");
  const RunResult fixed = run_block("ew_fixed", 2, "", param("forcing", "string", "fixed"), fresh);
  const RunResult ew = run_block("ew_on", 2, "", param("forcing", "string", "eisenstat-walker"), fresh);
  const RunResult reuse = run_block("ew_reuse", 2, "", param("forcing", "string", "eisenstat-walker"));  // reuse 20 (default)
  ASSERT_TRUE(fixed.converged && ew.converged && reuse.converged);
  const double d_ew = rel_diff(ew.displacement, fixed.displacement), d_re = rel_diff(reuse.displacement, fixed.displacement);
  std::printf("[newton] forcing: Newton %d / %d / %d, GMRES %d / %d / %d (fixed / eisenstat-walker / + reuse); |du|/|u| %.2e, %.2e\n",
              fixed.newton_iterations, ew.newton_iterations, reuse.newton_iterations, fixed.linear_iterations,
              ew.linear_iterations, reuse.linear_iterations, d_ew, d_re);
  EXPECT_LT(d_ew, 1e-7);
  EXPECT_LT(d_re, 1e-7);
  EXPECT_NEAR(ew.energy, fixed.energy, 1e-8 * fixed.energy);
  EXPECT_NEAR(reuse.energy, fixed.energy, 1e-8 * fixed.energy);
  EXPECT_LT(ew.linear_iterations, fixed.linear_iterations);
}

// Tiny loads: at strains of 1e-9 and below, C - I keeps few digits and the residual's
// round-off floor (4e-10 N here) lies above every relative target, so Newton iterated
// without progress and the step failed after 6 cut-backs (a 1e-3 Pa traction on a 0.5 MPa
// block; the former 1e-12 N absolute floor did not help). Newton now stops once its
// correction is below the round-off of the coordinates (NewtonSystem::coordinate_scale):
// the same block converges in 2 iterations for 1e-3 and 1e-6 Pa, and the displacement is
// the 1 Pa solution scaled (linear elasticity at these strains) to the precision left.
TEST(Newton, TinyLoadsConvergeToMachinePrecision) {
  fs::create_directories(work_dir());
  auto run = [](const std::string& load) {
    const fs::path deck = work_dir() / ("tiny_" + load + ".xml");
    std::ofstream(deck) << R"X(<ParameterList name="stentor">
  <ParameterList name="Mesh"><Parameter name="file" type="string" value=")X"
                        << STENTOR_SOURCE_DIR << R"X(/inputs/block2d.geo"/><Parameter name="size" type="double" value="0.25"/></ParameterList>
  <ParameterList name="Materials"><ParameterList name="rubber"><Parameter name="C1" type="double" value="0.5e6"/><Parameter name="D" type="double" value="0.35e6"/></ParameterList></ParameterList>
  <ParameterList name="Bodies"><ParameterList name="block"><Parameter name="material" type="string" value="rubber"/></ParameterList></ParameterList>
  <ParameterList name="Boundary Conditions">
    <ParameterList name="clamp"><Parameter name="type" type="string" value="Dirichlet"/><Parameter name="boundary" type="string" value="bottom"/></ParameterList>
    <ParameterList name="push"><Parameter name="type" type="string" value="traction"/><Parameter name="boundary" type="string" value="right"/>
      <Parameter name="traction" type="Array(double)" value="{)X" << load << R"X(, 0}"/></ParameterList>
  </ParameterList>
  <ParameterList name="Linear Solver"><Parameter name="method" type="string" value="direct"/></ParameterList>
  <ParameterList name="Output"><Parameter name="fields" type="bool" value="false"/></ParameterList>
</ParameterList>
)X";
    RunOptions opts;
    opts.output_dir = (work_dir() / ("out_tiny_" + load)).string();
    RunResult res;
    EXPECT_EQ(run_simulation(read_deck(deck.string()), opts, &res), 0) << load;
    return res;
  };
  const RunResult unit = run("1");
  for (const char* load : {"1e-3", "1e-6"}) {
    const double f = std::stod(load);
    const RunResult r = run(load);
    EXPECT_EQ(r.cutbacks, 0) << load;
    EXPECT_LE(r.newton_iterations, 3) << load;
    ASSERT_EQ(r.displacement.size(), unit.displacement.size());
    double diff = 0.0, scale = 0.0;
    for (std::size_t i = 0; i < r.displacement.size(); ++i) {
      diff = std::max(diff, std::abs(r.displacement[i] / f - unit.displacement[i]));
      scale = std::max(scale, std::abs(unit.displacement[i]));
    }
    std::printf("[newton] traction %s Pa: %d iterations, max |u/f - u(1 Pa)| = %.2e of %.2e\n", load, r.newton_iterations, diff, scale);
    // Measured: 7.0e-7 (1e-3 Pa: the 1 Pa solution's own nonlinearity, strain 2e-6) and
    // 1.2e-5 (1e-6 Pa: round-off at strain 2e-12) of |u(1 Pa)|.
    EXPECT_LT(diff, (f > 1e-4 ? 3e-6 : 1e-4) * scale) << load;
    EXPECT_NEAR(r.reactions.front()[0], -f, (f > 1e-4 ? 1e-6 : 1e-3) * f) << load;
  }
}

// Stepping->target iterations: the step follows Newton's iteration count (Crisfield's rule).
// A step that took n iterations scales the next by sqrt(T / n), between 1/2 and `growth`,
// up to the deck's step, and not up when the contact set changed in it; each change says
// why. Without a target the step grows after every step.
TEST(StepControl, FollowsNewtonIterations) {
  StepControl c(0.1, 6, 1.5, 1e-6, 6);
  EXPECT_DOUBLE_EQ(c.propose(1.0), 0.1);
  c.accepted(12, 0);  // sqrt(6 / 12)
  double dt = 0.1 * std::sqrt(0.5);
  EXPECT_DOUBLE_EQ(c.next(), dt);
  EXPECT_NE(c.reason().find("12 Newton iterations > target 6"), std::string::npos) << c.reason();
  c.propose(1.0);
  c.accepted(30, 0);  // sqrt(6 / 30) = 0.45, limited to 1/2
  dt *= 0.5;
  EXPECT_DOUBLE_EQ(c.next(), dt);
  c.propose(1.0);
  c.accepted(6, 0);  // on target: kept, nothing to say
  EXPECT_DOUBLE_EQ(c.next(), dt);
  EXPECT_TRUE(c.reason().empty());
  c.propose(1.0);
  c.accepted(3, 4);  // easy, but the contact set changed: kept
  EXPECT_DOUBLE_EQ(c.next(), dt);
  EXPECT_TRUE(c.reason().empty());
  c.propose(1.0);
  c.accepted(4, 0);  // sqrt(6 / 4)
  dt *= std::sqrt(1.5);
  EXPECT_DOUBLE_EQ(c.next(), dt);
  EXPECT_NE(c.reason().find("4 Newton iterations < target 6"), std::string::npos) << c.reason();
  c.propose(1.0);
  c.accepted(1, 0);  // sqrt(6), limited to growth = 1.5
  EXPECT_DOUBLE_EQ(c.next(), 1.5 * dt);
  for (int k = 0; k < 10; ++k) {  // easy steps grow it back to the deck's step, never past it
    c.propose(1.0);
    c.accepted(2, 0);
  }
  EXPECT_DOUBLE_EQ(c.next(), 0.1);
  // A step shortened by the end of the interval that was hard shrinks from what was tried.
  EXPECT_DOUBLE_EQ(c.propose(0.04), 0.04);
  c.accepted(24, 0);
  EXPECT_DOUBLE_EQ(c.next(), 0.02);
  // Never below the minimum.
  StepControl floor(0.1, 6, 1.5, 0.08, 6);
  floor.propose(1.0);
  floor.accepted(25, 0);
  EXPECT_DOUBLE_EQ(floor.next(), 0.08);
  // Without a target: growth after every accepted step, whatever it took.
  StepControl plain(0.1, 6, 1.5, 1e-6);
  plain.propose(1.0);
  ASSERT_EQ(plain.cut(), StepControl::Cut::Ok);
  plain.propose(1.0);
  plain.accepted(25, 3);
  EXPECT_DOUBLE_EQ(plain.next(), 0.075);
  EXPECT_TRUE(plain.reason().empty());
}

// A step shortened before it is tried (Stepping->contact approach) is the step tried; once
// accepted, the next is at most the given cap (the contact's pace), and grows from there; a
// cut-back of the shortened step drops the cap (the retried step proposes its own).
TEST(StepControl, ShortenedStepCapsTheNext) {
  StepControl c(0.1, 6, 1.5, 1e-6);
  EXPECT_DOUBLE_EQ(c.propose(1.0), 0.1);
  c.shorten(0.06, 0.004);
  c.accepted(3, 8);
  EXPECT_DOUBLE_EQ(c.next(), 0.004);
  EXPECT_NE(c.reason().find("allowed depth"), std::string::npos) << c.reason();
  c.propose(1.0);
  c.accepted(3, 0);
  EXPECT_DOUBLE_EQ(c.next(), 0.006);
  EXPECT_TRUE(c.reason().empty());
  // A cap above the grown step changes nothing.
  c.propose(1.0);
  c.shorten(0.005, 0.5);
  c.accepted(3, 0);
  EXPECT_DOUBLE_EQ(c.next(), 0.005);
  // Cut back: the cap is gone.
  c.propose(1.0);
  c.shorten(0.004, 1e-5);
  ASSERT_EQ(c.cut(), StepControl::Cut::Ok);
  EXPECT_DOUBLE_EQ(c.propose(1.0), 0.002);
  c.accepted(3, 0);
  EXPECT_DOUBLE_EQ(c.next(), 0.003);
}

// The deck's target reaches the run: the 20% stretch in 2 static steps from u_n (predictor
// none: the first takes 6 iterations) at T = 4 takes more, smaller steps and ends at the
// same equilibrium (hyperelastic statics do not depend on the path).
TEST(StepControl, TargetIterationsRefinesTheRunToTheSameSolution) {
  const std::string none = param("predictor", "string", "none");
  const RunResult plain = run_block("follow_off", 2, none);
  const RunResult follow = run_block("follow_on", 2, none + param("target iterations", "int", "4"));
  ASSERT_TRUE(plain.converged && follow.converged);
  std::printf("[stepping] target iterations 4: %d steps (%d Newton) against %d steps (%d Newton) without\n", follow.steps,
              follow.newton_iterations, plain.steps, plain.newton_iterations);
  EXPECT_EQ(plain.steps, 2);
  EXPECT_GT(follow.steps, plain.steps);
  EXPECT_EQ(follow.cutbacks, 0);
  EXPECT_LT(rel_diff(follow.displacement, plain.displacement), 1e-8);
}

// Newton->line search watchdog on a creeping line search (StiffQuadraticSystem): strictly
// monotone (0), Newton creeps at alpha = 1/32 for tens of iterations; with the default (2),
// after two creeping iterations the full step is taken and Newton converges in 2 more, to
// the same root. Measured: 58 iterations against 4.
TEST(Newton, WatchdogEndsACreepingLineSearch) {
  if (comm()->getSize() > 1) GTEST_SKIP() << "one rank holds both unknowns";
  const StiffRun monotone = solve_stiff(1.0, 1.0, 0), watched = solve_stiff(1.0, 1.0, 2);
  ASSERT_TRUE(monotone.res.converged) << monotone.res.failure;
  ASSERT_TRUE(watched.res.converged) << watched.res.failure;
  EXPECT_GE(monotone.res.iterations, 40);
  EXPECT_LE(watched.res.iterations, 6);
  EXPECT_NEAR(watched.a, 1.0, 1e-12);
  EXPECT_NEAR(watched.b, 1.0, 1e-12);
  EXPECT_NEAR(monotone.a, 1.0, 1e-12);
  EXPECT_EQ(watched.log.find("watchdog:"), std::string::npos);  // the relaxed step paid off
  std::printf("[newton] creeping line search: %d iterations strictly monotone, %d with the watchdog\n",
              monotone.res.iterations, watched.res.iterations);
}

// A relaxed step that leads nowhere (the tangent is poor where it lands: the residual falls
// only linearly, 198 -> 144 in the 3 iterations the watchdog allows, never below the 1.47
// of the point before it): Newton returns to that point, says so, and converges along the
// damped path to the same root, at most the watchdog's 4 iterations behind the strictly
// monotone iteration (measured: 83 against 79).
TEST(Newton, WatchdogReturnsWhenTheRelaxedStepLeadsNowhere) {
  if (comm()->getSize() > 1) GTEST_SKIP() << "one rank holds both unknowns";
  const StiffRun monotone = solve_stiff(1.5, 10.0, 0), watched = solve_stiff(1.5, 10.0, 2);
  ASSERT_TRUE(monotone.res.converged) << monotone.res.failure;
  ASSERT_TRUE(watched.res.converged) << watched.res.failure;
  EXPECT_NE(watched.log.find("watchdog: the relaxed step led nowhere; back to |r| 1.46"), std::string::npos) << watched.log;
  EXPECT_LE(watched.res.iterations, monotone.res.iterations + 4);
  EXPECT_NEAR(watched.a, 1.5, 1e-12);
  EXPECT_NEAR(watched.b, 2.25, 1e-11);
  std::printf("[newton] relaxed step that leads nowhere: back after it, %d iterations (strictly monotone %d)\n",
              watched.res.iterations, monotone.res.iterations);
}

// Revised holds start Newton over from a converged point: `max iterations` counts from the
// last revision, so a step that converged, had its held contact nodes revised and converges
// again is not cut back for the iterations of the rounds before (S4: 9 -> 5 cut-backs, each
// of the 4 saved had converged 2-3 times). After kMaxHeldRevisions revisions the solve fails
// and says so.
TEST(Newton, RevisedHoldsGetTheirOwnIterationBudget) {
  auto map = Teuchos::rcp(new la::Map(8, 0, comm()));
  LinearSolver lin(unpreconditioned(), comm());
  NewtonConfig nc;
  nc.residual_tolerance = 1e-12;
  nc.max_iterations = 8;
  {
    RevisedHoldsSystem sys(map, 3);
    la::Vector u(map);
    std::ostringstream log;
    const NewtonResult res = newton_solve(sys, u, lin, nc, &log);
    ASSERT_TRUE(res.converged) << res.failure;
    EXPECT_GT(res.iterations, nc.max_iterations);  // more than one budget in all
    std::size_t rounds = 0;
    for (auto k = log.str().find("held contact nodes revised"); k != std::string::npos; k = log.str().find("held contact nodes revised", k + 1)) ++rounds;
    EXPECT_EQ(rounds, 3u);
    const auto uh = u.getLocalViewHost(Tpetra::Access::ReadOnly);
    for (size_t i = 0; i < u.getLocalLength(); ++i) EXPECT_NEAR(uh(i, 0) * uh(i, 0) * uh(i, 0) + uh(i, 0), 5.0, 1e-11);
    std::printf("[newton] 3 revisions of held nodes: converged in %d iterations with max iterations %d\n", res.iterations,
                nc.max_iterations);
  }
  RevisedHoldsSystem sys(map, kMaxHeldRevisions + 1);
  la::Vector u(map);
  const NewtonResult res = newton_solve(sys, u, lin, nc, nullptr);
  EXPECT_FALSE(res.converged);
  EXPECT_EQ(res.failure, "held contact nodes still fail their conditions after " + std::to_string(kMaxHeldRevisions) + " revisions");
}
