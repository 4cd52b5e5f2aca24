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


std::string ordinal(int n) {
  static const char* names[] = {"zeroth", "first", "second", "third", "fourth"};
  return n >= 0 && n <= 4 ? names[n] : std::to_string(n) + "th";
}

constexpr double kCreep = 0.125;  // a step damped to this or less counts as creeping
// Beyond the first iteration a step converges only if its last correction is at most this
// fraction of everything Newton moved in the step (Abaqus' C_n = 1e-2). The relative
// residual test alone can be met against an enormous first residual: from a first guess
// that stretched an artery's end cells by 40 %, the exponential fibres' residual fell by a
// constant factor per iteration while every correction stayed 0.026 mm, and the test
// accepted, 23 iterations later, a state 0.094 mm from the equilibrium
// (ArteryInflation.StageStartLiftsItsPrescribedMotion, before the stage-start lifting).
constexpr double kCorrection = 1e-2;

struct Trial {
  bool accepted = false;
  bool admissible_seen = false;
  bool full_unsettled = false;  // the full step changed the active set
  bool has_tangent = false;     // the last evaluate() (at the accepted point) assembled the tangent
  bool settled = true;          // sys.settled() right after the accepted point's evaluate()
  bool relaxed = false;         // a forced step (creeping or set change) whose starting point Watch keeps
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
// The same holds after `line_search_watchdog` iterations in a row damped to alpha <= 1/8
// (`damped_creeping`), set change or not, when `relax` allows it: the residual along a
// Newton direction can carry a second-order term far above the first-order decrease (a
// floating body's large rotation predicted linearly: |r(alpha)| ~ |(1 - alpha) r0 +
// alpha^2 q| with |q| ~ 20 |r0| on the free struts of S4), so backtracking keeps
// alpha ~ 1/32 and Newton creeps for the rest of the step, where the full step lands in
// the quadratic basin. That step is `relaxed`: newton_solve keeps the point before it and
// returns there if it leads nowhere (Watch).
// The full step is evaluated with the tangent; halved trials are residual-only where the
// system allows it.
Trial line_search(NewtonSystem& sys, const la::Vector& u, const la::Vector& du, double rn, int damped_unsettled, int damped_creeping,
                  bool relax, const NewtonConfig& cfg, la::Vector& u_trial, la::Vector& r_trial) {
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
      const bool decrease = t.rn <= (1.0 - 1e-4 * t.alpha) * rn;
      const bool watchdog = ls == 0 && cfg.line_search_watchdog > 0;
      const bool unsettled_force = watchdog && t.full_unsettled && damped_unsettled >= cfg.line_search_watchdog;
      const bool creep_force = watchdog && relax && damped_creeping >= cfg.line_search_watchdog;
      if (std::isfinite(t.rn) && (unsettled_force || creep_force || !cfg.line_search || decrease)) {
        t.accepted = true;
        t.relaxed = relax && (creep_force || unsettled_force) && !decrease && cfg.line_search;
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

// Chamberlain's watchdog for a relaxed step (line_search): the point before it is kept;
// unless |r| falls below the kept point's within kWatchIterations iterations (or a trial
// fails on the way), Newton returns there and takes the damped step of the line search,
// and the relaxation is spent for the rest of the solve. So a relaxed step can cost
// iterations but never lose the monotone path.
constexpr int kWatchIterations = 3;

struct Watch {
  explicit Watch(const la::RCP<const la::Map>& map) : u(map), du(map) {}
  bool armed = false, spent = false;
  int left = 0;
  double rn = 0.0;
  la::Vector u, du;
  void keep(const la::Vector& u0, const la::Vector& du0, double rn0) {
    u.update(1.0, u0, 0.0);
    du.update(1.0, du0, 0.0);
    rn = rn0;
    left = kWatchIterations;
    armed = true;
  }
};

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

bool linear_solve(LinearSolver& lin, NewtonSystem& sys, const la::Vector& b, la::Vector& x, double tol,
                  LinearSolver::Result& res, std::string& failure) {
  const std::vector<NewtonSystem::RankOne> terms = sys.rank_one();
  if (!linear_solve(lin, sys.matrix(), b, x, tol, res, failure)) return false;
  if (terms.empty()) return true;
  // Woodbury with m terms: (C^-1 + R^T Y) z = R^T x0, x = x0 - Y z (m is the number of cavities).
  const std::size_t m = terms.size();
  std::vector<la::Vector> Y;
  std::vector<double> A(m * m), z(m);
  for (std::size_t i = 0; i < m; ++i) {
    Y.emplace_back(x.getMap());
    try {
      const LinearSolver::Result ri = lin.solve(*terms[i].left, Y.back(), tol);
      res.iterations += ri.iterations;
      res.converged = res.converged && ri.converged;
    } catch (const LinearSolverFailure& e) {
      failure = "the linear solver failed: " + std::string(e.what());
      return false;
    }
  }
  for (std::size_t i = 0; i < m; ++i) {
    z[i] = terms[i].right->dot(x);
    for (std::size_t j = 0; j < m; ++j) A[i * m + j] = terms[i].right->dot(Y[j]) + (i == j ? 1.0 / terms[i].c : 0.0);
  }
  // Gaussian elimination with partial pivoting on the small dense system.
  for (std::size_t k = 0; k < m; ++k) {
    std::size_t piv = k;
    for (std::size_t i = k + 1; i < m; ++i)
      if (std::abs(A[i * m + k]) > std::abs(A[piv * m + k])) piv = i;
    for (std::size_t j = 0; j < m; ++j) std::swap(A[k * m + j], A[piv * m + j]);
    std::swap(z[k], z[piv]);
    for (std::size_t i = k + 1; i < m; ++i) {
      const double f = A[i * m + k] / A[k * m + k];
      for (std::size_t j = k; j < m; ++j) A[i * m + j] -= f * A[k * m + j];
      z[i] -= f * z[k];
    }
  }
  for (std::size_t k = m; k-- > 0;) {
    for (std::size_t j = k + 1; j < m; ++j) z[k] -= A[k * m + j] * z[j];
    z[k] /= A[k * m + k];
  }
  for (std::size_t i = 0; i < m; ++i) x.update(-z[i], Y[i], 1.0);
  return true;
}

namespace {

// One iteration's update: the accepted trial and what the log prints about it.
struct Update {
  Trial t;
  LinearSolver::Result lr;
  double eta = 0.0, du_full = 0.0, scaled = 1.0;  // forcing term, |du| before damping, step-length factor
};

// The state of one newton_solve: the iterate and its residual, the line-search watchdogs'
// counters, and the point kept before a relaxed step (Watch).
class Solve {
 public:
  Solve(NewtonSystem& sys, la::Vector& u, LinearSolver& lin, const NewtonConfig& cfg, std::ostream* log, double hint)
      : sys_(sys), u_(u), lin_(lin), cfg_(cfg), log_(log), hint_(hint), r_(u.getMap()), du_(u.getMap()),
        u_trial_(u.getMap()), r_trial_(u.getMap()), u_first_(u, Teuchos::Copy), watch_(u.getMap()) {}

  NewtonResult run() {
    if (!start()) return res_;
    Forcing forcing(cfg_, lin_.tolerance(), hint_);
    // `max iterations` counts from the last revision of held contact nodes (verify_held):
    // a revision starts Newton over from a converged point with a few nodes' states changed.
    for (int it = 1; it - round_start_ <= cfg_.max_iterations; ++it) {
      Update up;
      const bool back = watch_.armed && watch_.left == 0;
      if (!(back ? back_to_kept_point(up) : newton_step(up, forcing))) return res_;
      count_damping(up.t);
      if (!up.t.accepted && watch_.armed) {  // a trial failed after a relaxed step: go back
        watch_.left = 0;
        continue;
      }
      if (!up.t.accepted && !full_step_anyway(up.t)) return res_;
      const int state = accept(it, up);
      if (state < 0) return res_;
      if (state > 0) continue;
      // A residual-only trial was accepted: the next iteration needs the tangent there (the
      // same state, so the same residual).
      if (!up.t.has_tangent && !sys_.evaluate(u_, r_, true)) {
        fail("the accepted line-search point became inadmissible", true);
        return res_;
      }
    }
    std::ostringstream os;
    os << "no convergence in " << cfg_.max_iterations << " iterations";
    if (round_start_ > 0) os << " after the " << ordinal(rounds_) << " revision of held contact nodes (" << res_.iterations << " in all)";
    os << " (|r| " << std::scientific << std::setprecision(3) << rn_ << ", target " << target_ << ")";
    res_.failure = os.str();
    return res_;
  }

 private:
  // Records why the solve failed; false, for the callers' returns.
  bool fail(const std::string& why, bool inadmissible) {
    res_.failure = why;
    res_.inadmissible = inadmissible;
    return false;
  }

  // The residual at the first guess and the target; false when nothing is left to do
  // (converged already, or a failure recorded in res_).
  bool start() {
    if (!sys_.evaluate(u_, r_, true)) return fail("inverted elements at the start of the step", true);
    rn_ = r_.norm2();
    res_.residual0 = rn_;
    res_.residual = rn_;
    ref_ = std::max(rn_, sys_.force_scale());
    target_ = std::max(cfg_.residual_tolerance * ref_, cfg_.absolute_tolerance);
    // A non-finite residual or force scale makes the target inf (or NaN): never converged.
    if (!std::isfinite(rn_) || !std::isfinite(ref_)) {
      std::ostringstream os;
      os << "the residual (" << rn_ << ") or the load scale (" << sys_.force_scale()
         << ") is not finite at the start of the step (loads or state too large?)";
      res_.failure = os.str();
      return false;
    }
    settled_ = sys_.settled();
    if (rn_ <= target_ && settled_) {  // nothing is held before the first solve
      res_.converged = true;
      return false;
    }
    return true;
  }

  // Newton's correction from the tangent at u and its line search; false: failed.
  bool newton_step(Update& up, Forcing& forcing) {
    up.eta = forcing.next(rn_, target_);
    // A tangent whose discrete part changed (contact rows of nodes that entered, left or
    // changed stick/slip) gets a preconditioner built for it: one kept from the old rows
    // loses more than a build is worth there (docs/performance.md, "Rebuilding a stale
    // preconditioner").
    if (!settled_) lin_.tangent_changed();
    r_.scale(-1.0);
    if (!linear_solve(lin_, sys_, r_, du_, up.eta, up.lr, res_.failure)) return false;
    r_.scale(-1.0);
    res_.linear_iterations += up.lr.iterations;
    if (!std::isfinite(du_.norm2())) return fail("linear solve produced a non-finite increment", false);
    up.du_full = du_.norm2();  // Newton's correction, before damping
    up.scaled = limit_increment(du_, cfg_.max_increment);
    sys_.linearised_step(du_);
    const bool relax = !watch_.armed && !watch_.spent;
    up.t = line_search(sys_, u_, du_, rn_, damped_unsettled_, damped_creeping_, relax, cfg_, u_trial_, r_trial_);
    return true;
  }

  // The relaxed step led nowhere: back to the point before it (its tangent and contact
  // state again), and the damped step along the same direction.
  bool back_to_kept_point(Update& up) {
    watch_.armed = false;
    watch_.spent = true;
    u_.update(1.0, watch_.u, 0.0);
    du_.update(1.0, watch_.du, 0.0);
    if (!sys_.evaluate(u_, r_, true)) return fail("the point before a relaxed Newton step became inadmissible", true);
    rn_ = watch_.rn;
    up.du_full = du_.norm2();
    if (log_)
      *log_ << "    watchdog: the relaxed step led nowhere; back to |r| " << std::scientific << std::setprecision(3) << rn_
            << std::defaultfloat << "\n";
    sys_.linearised_step(du_);
    up.t = line_search(sys_, u_, du_, rn_, 0, 0, false, cfg_, u_trial_, r_trial_);
    return true;
  }

  void count_damping(const Trial& t) {
    damped_creeping_ = t.accepted && t.alpha <= kCreep ? damped_creeping_ + 1 : 0;
    damped_unsettled_ = t.accepted && t.alpha < 1.0 && t.full_unsettled ? damped_unsettled_ + 1 : 0;
  }

  // No decrease along du: take the full step anyway if it is admissible (the residual can
  // rise before Newton's quadratic phase), else fail.
  bool full_step_anyway(Trial& t) {
    if (!t.admissible_seen) return fail("every line-search trial inverted elements", true);
    t.alpha = 1.0;
    u_trial_.update(1.0, u_, t.alpha, du_, 0.0);
    sys_.step_length(1.0);
    const bool admissible = sys_.evaluate(u_trial_, r_trial_, true);
    if (!admissible || !std::isfinite(t.rn = r_trial_.norm2())) return fail("line search found no admissible decrease", !admissible);
    t.has_tangent = true;
    t.settled = sys_.settled();
    return true;
  }

  // Moves to the accepted trial and tests convergence: -1 return res_ (converged or
  // failed), 1 next iteration at once, 0 go on.
  int accept(int it, const Update& up) {
    const Trial& t = up.t;
    if (t.relaxed) watch_.keep(u_, du_, rn_);
    u_.update(1.0, u_trial_, 0.0);
    r_.update(1.0, r_trial_, 0.0);
    settled_ = t.settled;
    const double step = t.alpha * up.scaled * up.du_full;  // |alpha du| of the (limited) update
    const double un = u_.norm2();
    if (it == 1 && rn_ > 0.0) res_.first_ratio = t.rn / rn_;
    rn_ = t.rn;
    res_.iterations = it;
    res_.residual = rn_;
    if (log_) log_iteration(*log_, it, rn_, step, t.alpha, up.lr, up.eta, up.scaled);
    if (!std::isfinite(rn_)) {
      if (!watch_.armed) {
        fail("residual is not finite", false);
        return -1;
      }
      watch_.left = 0;
      return 1;
    }
    // The correction below the round-off of the coordinates: machine precision reached.
    // (An increment test too: off with `increment tolerance` = 0, as the other one.)
    const bool roundoff = cfg_.increment_tolerance > 0.0 &&
                          up.du_full <= 8.0 * std::numeric_limits<double>::epsilon() * (sys_.coordinate_scale() + un);
    const bool small = (rn_ <= target_ && correction_small(it, step)) || roundoff ||
                       (step <= cfg_.increment_tolerance * std::max(un, 1e-300) && rn_ <= std::sqrt(cfg_.residual_tolerance) * ref_);
    if (small && t.settled) return verify_held();
    if (watch_.armed && !t.relaxed) {
      if (rn_ < (1.0 - 1e-4) * watch_.rn) watch_.armed = false;  // the relaxed step paid off
      else --watch_.left;
    }
    return 0;
  }

  // The residual test's second half (kCorrection): beyond the first iteration, the last
  // correction |alpha du| = step is small against what Newton moved in the step. Called
  // only once the residual is below its target (the same on every rank: collective).
  bool correction_small(int it, double step) {
    if (it == 1) return true;
    u_trial_.update(1.0, u_, -1.0, u_first_, 0.0);  // a scratch vector until the next line search
    return step <= kCorrection * u_trial_.norm2();
  }

  // Converged with the sets settled: the conditions the iteration held fixed are checked
  // (NewtonSystem::verify_held); revised holds make Newton go on from here.
  int verify_held() {
    const int held = sys_.verify_held(res_.failure);
    if (held != 1) {
      res_.converged = held == 0;
      return -1;
    }
    if (++rounds_ > kMaxHeldRevisions) {
      fail("held contact nodes still fail their conditions after " + std::to_string(kMaxHeldRevisions) + " revisions", false);
      return -1;
    }
    round_start_ = res_.iterations;
    if (log_) *log_ << "    held contact nodes revised: Newton goes on\n";
    if (!sys_.evaluate(u_, r_, true)) {
      fail("the converged point became inadmissible", true);
      return -1;
    }
    rn_ = r_.norm2();
    settled_ = false;
    watch_.armed = false;  // the revised holds change the residual: no comparison across them
    return 1;
  }

  NewtonSystem& sys_;
  la::Vector& u_;
  LinearSolver& lin_;
  const NewtonConfig& cfg_;
  std::ostream* log_;
  double hint_;
  NewtonResult res_;
  la::Vector r_, du_, u_trial_, r_trial_;
  la::Vector u_first_;  // the first guess: |u - u_first| is what Newton moved in the step
  Watch watch_;
  double rn_ = 0.0, ref_ = 0.0, target_ = 0.0;
  bool settled_ = true;        // at the point whose tangent the next solve uses
  int damped_unsettled_ = 0;   // consecutive iterations whose full step changed the active set and was damped
  int damped_creeping_ = 0;    // consecutive iterations damped to alpha <= kCreep
  int rounds_ = 0;             // revisions of held contact nodes so far
  int round_start_ = 0;        // the iteration of the last revision
};

}  // namespace

NewtonResult newton_solve(NewtonSystem& sys, la::Vector& u, LinearSolver& lin, const NewtonConfig& cfg, std::ostream* log,
                          double first_ratio_hint) {
  return Solve(sys, u, lin, cfg, log, first_ratio_hint).run();
}

}  // namespace stentor
