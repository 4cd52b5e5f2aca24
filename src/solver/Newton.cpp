#include "solver/Newton.hpp"

#include "solver/SolverParams.hpp"

#include <cmath>
#include <iomanip>
#include <sstream>

namespace stentor {

NewtonResult newton_solve(NewtonSystem& sys, la::Vector& u, LinearSolver& lin, const NewtonConfig& cfg, std::ostream* log) {
  NewtonResult res;
  la::Vector r(u.getMap()), du(u.getMap()), u_trial(u.getMap()), r_trial(u.getMap());
  if (!sys.evaluate(u, r, true)) {
    res.failure = "inverted elements at the start of the step";
    return res;
  }
  double rn = r.norm2();
  res.residual0 = rn;
  res.residual = rn;
  const double ref = std::max(rn, sys.force_scale());
  const double target = std::max(cfg.residual_tolerance * ref, cfg.absolute_tolerance);
  // A non-finite residual or force scale makes the target inf (or NaN): never converged.
  if (!std::isfinite(rn) || !std::isfinite(ref)) {
    std::ostringstream os;
    os << "the residual (" << rn << ") or the load scale (" << sys.force_scale()
       << ") is not finite at the start of the step (loads or state too large?)";
    res.failure = os.str();
    return res;
  }
  if (rn <= target && sys.settled()) {
    res.converged = true;
    return res;
  }
  int damped_unsettled = 0;  // consecutive iterations whose full step changed the active set and was damped
  for (int it = 1; it <= cfg.max_iterations; ++it) {
    LinearSolver::Result lr;
    r.scale(-1.0);
    try {
      lin.setup(sys.matrix());
      lr = lin.solve(r, du);
    } catch (const InputError&) {
      throw;
    } catch (const std::exception& e) {
      // A preconditioner or Krylov breakdown (MueLu "damping factor needs to be finite",
      // Belos "residual norms is NaN"): a failed iteration, so the step is cut back. On
      // several ranks the error may be one rank's alone while the others wait in a
      // collective: there it ends the run on every rank (main's fail_all_ranks).
      if (u.getMap()->getComm()->getSize() > 1) throw;
      res.failure = "the linear solver failed: " + teuchos_short_message(e.what());
      return res;
    }
    r.scale(-1.0);
    res.linear_iterations += lr.iterations;
    if (!std::isfinite(du.norm2())) {
      res.failure = "linear solve produced a non-finite increment";
      return res;
    }
    // Backtracking: halve the step until the residual decreases (Armijo, c = 1e-4). The
    // residual jumps where a contact active set changes, so a full step into the right
    // new set can look worse than a halved one in the old set, and Newton then creeps at
    // alpha = 1/2 (the residual halves per iteration) while the set flips back and forth
    // between the trials. After `line_search_watchdog` such damped iterations in a row, a
    // full step that changes the set is taken unconditionally (non-monotone watchdog); if
    // it leads nowhere, the iteration limit cuts the step back as before.
    double alpha = 1.0, rn_trial = 0.0;
    bool accepted = false, admissible_seen = false;
    const int max_halvings = cfg.line_search ? cfg.line_search_max : 0;
    bool full_unsettled = false;
    for (int ls = 0; ls <= max_halvings; ++ls) {
      u_trial.update(1.0, u, alpha, du, 0.0);
      if (sys.evaluate(u_trial, r_trial, true)) {
        admissible_seen = true;
        rn_trial = r_trial.norm2();
        if (ls == 0) full_unsettled = !sys.settled();
        const bool force = ls == 0 && full_unsettled && cfg.line_search_watchdog > 0 &&
                           damped_unsettled >= cfg.line_search_watchdog;
        if (std::isfinite(rn_trial) && (force || !cfg.line_search || rn_trial <= (1.0 - 1e-4 * alpha) * rn)) {
          accepted = true;
          break;
        }
      }
      alpha *= 0.5;
    }
    if (accepted && alpha < 1.0 && full_unsettled) ++damped_unsettled;
    else damped_unsettled = 0;
    if (!accepted) {
      if (!admissible_seen) {
        res.failure = "every line-search trial inverted elements";
        return res;
      }
      // No decrease along du: take the full step anyway if it is admissible (the residual
      // can rise before Newton's quadratic phase), else fail.
      alpha = 1.0;
      u_trial.update(1.0, u, alpha, du, 0.0);
      if (!sys.evaluate(u_trial, r_trial, true) || !std::isfinite(rn_trial = r_trial.norm2())) {
        res.failure = "line search found no admissible decrease";
        return res;
      }
    }
    u.update(1.0, u_trial, 0.0);
    r.update(1.0, r_trial, 0.0);
    const double step = alpha * du.norm2();
    const double un = u.norm2();
    rn = rn_trial;
    res.iterations = it;
    res.residual = rn;
    if (log) {
      std::ostringstream os;
      os << "    newton " << std::setw(2) << it << "  |r| " << std::scientific << std::setprecision(3) << rn << "  |du| " << step
         << "  alpha " << std::defaultfloat << alpha << "  linear " << lr.iterations << (lr.converged ? "" : " (not converged)") << "\n";
      *log << os.str();
    }
    if (!std::isfinite(rn)) {
      res.failure = "residual is not finite";
      return res;
    }
    const bool small = rn <= target || (step <= cfg.increment_tolerance * std::max(un, 1e-300) && rn <= std::sqrt(cfg.residual_tolerance) * ref);
    if (small && sys.settled()) {
      res.converged = true;
      return res;
    }
  }
  std::ostringstream os;
  os << "no convergence in " << cfg.max_iterations << " iterations (|r| " << std::scientific << std::setprecision(3) << rn << ", target "
     << target << ")";
  res.failure = os.str();
  return res;
}

}  // namespace stentor
