// When a kept (reused) preconditioner is rebuilt: Linear Solver->preconditioner reuse and
// ->preconditioner rebuild cost.
//
// A preconditioner built for one Newton tangent serves later tangents of the same graph
// until it is rebuilt. Keeping it saves its build; the price is the GMRES iterations it
// loses as the matrix moves away from the one it was built for (a contact active set that
// grows, plastic zones that spread). The policy weighs the two in GMRES iterations, so the
// decision depends only on iteration counts and residuals, never on timings: the same run
// makes the same decisions every time, and a restart the same as the uninterrupted run.
//
//   rate0   = iterations per digit gained (-log10 of the achieved relative residual) of
//             the first solve after the build that gained at least one digit: the rate of
//             a fresh preconditioner;
//   excess <- max(0, excess + its - kAllowance * rate0 * digits) after every later solve:
//             the iterations lost to staleness, summed (a CUSUM test: solves a little
//             faster than rate0 pay back earlier losses, and kAllowance absorbs the spread
//             of a fresh preconditioner's rate between loose and tight solves);
//   rebuild at the next set-up when excess >= build_cost (a build is worth that many
//             iterations), or when the kept one has served max_age set-ups, or when the
//             last solve did not converge.
//
// Newton adds one more rule (solver/Newton.cpp): a tangent whose contact active set changed
// at its point gets a fresh preconditioner (LinearSolver::tangent_changed()).
//
// Measured (docs/performance.md, "Rebuilding a stale preconditioner"): a MueLu build is
// worth about 25 GMRES iterations both on the 30k-DOF S2 case on 2 ranks here and on the
// 200k-DOF one on 16 ranks. The per-digit rate undercounts the loss of long solves (GMRES
// iterations get dearer as the Krylov basis grows, and loose solves start with a plateau),
// so the CUSUM alone rebuilt too rarely on 16 ranks; with the active-set rule the 200k
// case's Newton solves took 46 s instead of 51 s (the fixed count of 20 before), 2064
// instead of 2985 GMRES iterations.
#pragma once
#include <algorithm>
#include <cmath>

namespace stentor {

struct ReusePolicy {
  static constexpr double kAllowance = 1.25;

  int max_age = 20;          // set-ups a build may serve after its own (0: rebuild every time)
  double build_cost = 25.0;  // GMRES iterations a build is worth (0: rebuild after any loss)

  int age = 0;               // set-ups served since the last build
  double rate0 = -1.0;       // iterations per digit of a fresh preconditioner (-1: not yet known)
  double excess = 0.0;       // iterations lost to staleness since the build
  bool last_converged = true;

  // The preconditioner was (re)built for the current matrix.
  void built() {
    age = 0;
    rate0 = -1.0;
    excess = 0.0;
    last_converged = true;
  }

  // May the next set-up keep the preconditioner? (Counts the set-up as served when it may.)
  bool keep() {
    if (age >= max_age || !last_converged || excess >= build_cost) return false;
    ++age;
    return true;
  }

  // A GMRES solve ended: its iterations and achieved relative residual.
  void solved(int iterations, double residual, bool converged) {
    last_converged = converged;
    if (!(residual > 0.0) || !std::isfinite(residual)) return;  // b = 0 or a breakdown (judged elsewhere)
    const double digits = -std::log10(residual);
    if (rate0 < 0.0) {
      if (digits >= 1.0) rate0 = iterations / digits;
      return;
    }
    excess = std::max(0.0, excess + iterations - kAllowance * rate0 * std::max(0.0, digits));
  }
};

}  // namespace stentor
