#include "solver/Newton.hpp"

#include "solver/SolverParams.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <iomanip>
#include <sstream>

namespace stentor {

namespace {

// The relative tolerance of each iteration's linear solve. Fixed: the linear solver's
// own. Eisenstat-Walker (SIAM J. Sci. Comput. 17 (1996) 16-32, choice 2 with gamma = 0.9,
// alpha = 2): eta_k = gamma (|r_k| / |r_k-1|)^alpha, kept at least gamma eta_k-1^alpha
// when that exceeds 0.1 (so eta cannot collapse after one lucky iteration), at most
// eta_max and at least the fixed tolerance; eta_1 = eta_max, or 0.9 hint^2 given the first
// ratio |r_1| / |r_0| expected from a similar solve (newton_solve's hint). The last iteration is solved to the fixed
// tolerance: where eta_k |r_k| would already be below half the convergence target (the
// iteration is expected to converge Newton), eta_k is the fixed tolerance instead, so the
// final iterate lies as far inside the target as with `fixed` (quadratic convergence from
// a nearby iterate) and results on different rank counts agree to round-off, not to the
// target (before: eta_k >= 0.5 target / |r_k|, Kelley's "no over-solving", left the last
// iterate just inside the target: 4.5e-10 between 1 and 2 ranks in S1's contact force).
class Forcing {
 public:
  Forcing(const NewtonConfig& cfg, double eta_min, double first_ratio_hint)
      : adaptive_(cfg.forcing == "eisenstat-walker" && eta_min > 0.0),
        eta_max_(std::max(cfg.forcing_max, eta_min)),
        eta_min_(eta_min),
        hint_(first_ratio_hint) {}
  bool adaptive() const { return adaptive_; }
  // 0 (the solver's own tolerance) or this iteration's eta, given |r_k| and the target.
  double next(double rn, double target) {
    if (!adaptive_) return 0.0;
    constexpr double gamma = 0.9;
    double eta = hint_ > 0.0 ? gamma * hint_ * hint_ : eta_max_;
    if (rn_prev_ > 0.0) {
      eta = gamma * (rn / rn_prev_) * (rn / rn_prev_);
      const double floor = gamma * eta_prev_ * eta_prev_;
      if (floor > 0.1) eta = std::max(eta, floor);
    }
    eta = std::min(eta, eta_max_);
    if (eta * rn < 0.5 * target) eta = eta_min_;  // the last iteration: solved tightly
    eta = std::max(eta, eta_min_);
    rn_prev_ = rn;
    eta_prev_ = eta;
    return eta;
  }

 private:
  bool adaptive_;
  double eta_max_, eta_min_;
  double hint_;  // the first iteration's expected |r_1| / |r_0| (0: unknown)
  double rn_prev_ = 0.0, eta_prev_ = 0.0;
};

struct Trial {
  bool accepted = false;
  bool admissible_seen = false;
  bool full_unsettled = false;  // the full step changed the active set
  bool has_tangent = false;     // the last evaluate() (at the accepted point) assembled the tangent
  bool settled = true;          // sys.settled() right after the accepted point's evaluate()
  double alpha = 1.0;
  double rn = 0.0;
};

// Backtracking: halve the step until the residual decreases (Armijo, c = 1e-4). The
// residual jumps where a contact active set changes, so a full step into the right new
// set can look worse than a halved one in the old set, and Newton then creeps at
// alpha = 1/2 (the residual halves per iteration) while the set flips back and forth
// between the trials. After `line_search_watchdog` such damped iterations in a row
// (`damped_unsettled`), a full step that changes the set is taken unconditionally
// (non-monotone watchdog); if it leads nowhere, the iteration limit cuts the step back.
// The full step is evaluated with the tangent; halved trials are residual-only where the
// system allows it.
Trial line_search(NewtonSystem& sys, const la::Vector& u, const la::Vector& du, double rn, int damped_unsettled,
                  const NewtonConfig& cfg, la::Vector& u_trial, la::Vector& r_trial) {
  Trial t;
  const int max_halvings = cfg.line_search ? cfg.line_search_max : 0;
  const bool cheap_trials = !sys.residual_needs_tangent();
  for (int ls = 0; ls <= max_halvings; ++ls) {
    u_trial.update(1.0, u, t.alpha, du, 0.0);
    sys.step_length(t.alpha);
    const bool with_tangent = ls == 0 || !cheap_trials;
    if (sys.evaluate(u_trial, r_trial, with_tangent)) {
      t.admissible_seen = true;
      t.rn = r_trial.norm2();
      t.settled = sys.settled();
      if (ls == 0) t.full_unsettled = !t.settled;
      const bool force = ls == 0 && t.full_unsettled && cfg.line_search_watchdog > 0 &&
                         damped_unsettled >= cfg.line_search_watchdog;
      if (std::isfinite(t.rn) && (force || !cfg.line_search || t.rn <= (1.0 - 1e-4 * t.alpha) * rn)) {
        t.accepted = true;
        t.has_tangent = with_tangent;
        return t;
      }
    }
    t.alpha *= 0.5;
  }
  return t;
}

// Step-length control (Newton->max increment): du scaled so that no component exceeds
// `limit` (0: none), before the line search. Returns the factor (1: untouched).
double limit_increment(la::Vector& du, double limit) {
  if (!(limit > 0.0)) return 1.0;
  const double largest = du.normInf();
  if (largest <= limit) return 1.0;
  du.scale(limit / largest);
  return limit / largest;
}

void log_iteration(std::ostream& log, int it, double rn, double step, double alpha, const LinearSolver::Result& lr, double eta,
                   double scaled) {
  std::ostringstream os;
  os << "    newton " << std::setw(2) << it << "  |r| " << std::scientific << std::setprecision(3) << rn << "  |du| " << step
     << "  alpha " << std::defaultfloat << alpha << "  linear " << lr.iterations << (lr.converged ? "" : " (not converged)");
  if (scaled < 1.0) os << "  limited x" << std::setprecision(3) << scaled;
  if (eta > 0.0) os << "  eta " << std::setprecision(2) << eta;
  log << os.str() << "\n";
}

}  // namespace

bool linear_solve(LinearSolver& lin, const la::RCP<la::CrsMatrix>& K, const la::Vector& b, la::Vector& x, double tol,
                  LinearSolver::Result& res, std::string& failure) {
  try {
    lin.setup(K);
    res = lin.solve(b, x, tol);
    return true;
  } catch (const LinearSolverFailure& e) {
    // Every link of the fallback chain failed (e.g. MueLu "damping factor needs to be
    // finite", then Belos "residual norms is NaN", then KLU2 on a singular matrix), on
    // every rank alike.
    failure = "the linear solver failed: " + std::string(e.what());
    return false;
  }
}

NewtonResult newton_solve(NewtonSystem& sys, la::Vector& u, LinearSolver& lin, const NewtonConfig& cfg, std::ostream* log,
                          double first_ratio_hint) {
  NewtonResult res;
  la::Vector r(u.getMap()), du(u.getMap()), u_trial(u.getMap()), r_trial(u.getMap());
  if (!sys.evaluate(u, r, true)) {
    res.failure = "inverted elements at the start of the step";
    res.inadmissible = true;
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
  if (rn <= target && sys.settled()) {  // nothing is held before the first solve
    res.converged = true;
    return res;
  }
  Forcing forcing(cfg, lin.tolerance(), first_ratio_hint);
  int damped_unsettled = 0;  // consecutive iterations whose full step changed the active set and was damped
  bool settled = sys.settled();  // at the point whose tangent the next solve uses
  for (int it = 1; it <= cfg.max_iterations; ++it) {
    LinearSolver::Result lr;
    const double eta = forcing.next(rn, target);
    // A tangent whose discrete part changed (contact rows of nodes that entered, left or
    // changed stick/slip) gets a preconditioner built for it: one kept from the old rows
    // loses more than a build is worth there (docs/performance.md, "Rebuilding a stale
    // preconditioner").
    if (!settled) lin.tangent_changed();
    r.scale(-1.0);
    if (!linear_solve(lin, sys.matrix(), r, du, eta, lr, res.failure)) return res;
    r.scale(-1.0);
    res.linear_iterations += lr.iterations;
    if (!std::isfinite(du.norm2())) {
      res.failure = "linear solve produced a non-finite increment";
      return res;
    }
    const double du_full = du.norm2();  // Newton's correction, before damping
    const double scaled = limit_increment(du, cfg.max_increment);
    sys.linearised_step(du);
    Trial t = line_search(sys, u, du, rn, damped_unsettled, cfg, u_trial, r_trial);
    if (t.accepted && t.alpha < 1.0 && t.full_unsettled) ++damped_unsettled;
    else damped_unsettled = 0;
    if (!t.accepted) {
      if (!t.admissible_seen) {
        res.failure = "every line-search trial inverted elements";
        res.inadmissible = true;
        return res;
      }
      // No decrease along du: take the full step anyway if it is admissible (the residual
      // can rise before Newton's quadratic phase), else fail.
      t.alpha = 1.0;
      u_trial.update(1.0, u, t.alpha, du, 0.0);
      sys.step_length(1.0);
      const bool admissible = sys.evaluate(u_trial, r_trial, true);
      if (!admissible || !std::isfinite(t.rn = r_trial.norm2())) {
        res.failure = "line search found no admissible decrease";
        res.inadmissible = !admissible;
        return res;
      }
      t.has_tangent = true;
      t.settled = sys.settled();
    }
    u.update(1.0, u_trial, 0.0);
    r.update(1.0, r_trial, 0.0);
    settled = t.settled;
    const double step = t.alpha * scaled * du_full;  // |alpha du| of the (limited) update
    const double un = u.norm2();
    if (it == 1 && rn > 0.0) res.first_ratio = t.rn / rn;
    rn = t.rn;
    res.iterations = it;
    res.residual = rn;
    if (log) log_iteration(*log, it, rn, step, t.alpha, lr, eta, scaled);
    if (!std::isfinite(rn)) {
      res.failure = "residual is not finite";
      return res;
    }
    // The correction below the round-off of the coordinates: machine precision reached.
    // (An increment test too: off with `increment tolerance` = 0, as the other one.)
    const bool roundoff =
        cfg.increment_tolerance > 0.0 && du_full <= 8.0 * std::numeric_limits<double>::epsilon() * (sys.coordinate_scale() + un);
    const bool small = rn <= target || roundoff ||
                       (step <= cfg.increment_tolerance * std::max(un, 1e-300) && rn <= std::sqrt(cfg.residual_tolerance) * ref);
    if (small && t.settled) {
      const int held = sys.verify_held(res.failure);
      if (held != 1) {
        res.converged = held == 0;
        return res;
      }
      if (log) *log << "    held contact nodes revised: Newton goes on\n";
      if (!sys.evaluate(u, r, true)) {
        res.failure = "the converged point became inadmissible";
        res.inadmissible = true;
        return res;
      }
      rn = r.norm2();
      settled = false;
      continue;
    }
    // A residual-only trial was accepted: the next iteration needs the tangent there (the
    // same state, so the same residual).
    if (!t.has_tangent && !sys.evaluate(u, r, true)) {
      res.failure = "the accepted line-search point became inadmissible";
      res.inadmissible = true;
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
