// The state a run carries from step to step: displacements, time, the step-size
// controller, the cumulative energy terms and the counters of the summary.
#pragma once
#include <algorithm>
#include <cmath>
#include <string>

#include "parallel/LinearAlgebra.hpp"

namespace stentor {

// Step size: starts at the deck's step (the target, also the upper bound); a failed step
// is retried with half the step tried, at most `max_cutbacks` times in a row and never
// below `min_dt`. After an accepted step:
//  - without a target iteration count, the step grows by `growth`, up to the target;
//  - with one (Stepping->target iterations = T > 0) the step follows the solve (Crisfield's
//    rule for load increments): a step that took n Newton iterations scales the next by
//    sqrt(T / n), between 1/2 and `growth`, up to the target; a step that changed a contact
//    node's set does not let it grow (the contact is moving: another change is likely).
//    The reason of each change is kept for the log (reason()).
class StepControl {
 public:
  StepControl(double target, int max_cutbacks, double growth, double min_dt, int target_iterations = 0)
      : target_(target), dt_(target), growth_(growth), min_dt_(min_dt), max_cutbacks_(max_cutbacks), target_iterations_(target_iterations) {}
  // The step to try next, never past the end of the interval (`remaining`).
  double propose(double remaining) {
    tried_ = std::min(dt_, remaining);
    return tried_;
  }
  double next() const { return dt_; }  // the step propose() would try (before the end of the interval)
  enum class Cut { Ok, TooManyCutbacks, BelowMinimum };
  // After a failed step: halves the step tried; says why not when it may not.
  Cut cut() {
    if (consecutive_ >= max_cutbacks_) return Cut::TooManyCutbacks;
    if (0.5 * tried_ < min_dt_) return Cut::BelowMinimum;
    ++consecutive_;
    ++total_;
    dt_ = 0.5 * tried_;
    cap_ = 0.0;  // the retried step proposes its own
    return Cut::Ok;
  }
  // A new interval (stage) with its own step and minimum; the cut-back total carries on.
  void restart(double target, double min_dt) {
    target_ = dt_ = target;
    min_dt_ = min_dt;
    consecutive_ = 0;
  }
  // An accepted step that took `iterations` Newton iterations and changed the set of
  // `events` contact nodes (entered or released).
  void accepted(int iterations = 0, long events = 0) {
    consecutive_ = 0;
    reason_.clear();
    if (cap_ > 0.0) {
      const double before = dt_;
      dt_ = std::max(min_dt_, std::min(dt_, cap_));
      cap_ = 0.0;
      if (dt_ < before) reason_ = "the contact that started in the step may deepen by its allowed depth in the next";
      return;
    }
    if (target_iterations_ <= 0) {
      dt_ = std::min(target_, growth_ * dt_);
      return;
    }
    const double before = dt_;
    const double f = std::sqrt(double(target_iterations_) / std::max(iterations, 1));
    if (f < 1.0) {
      dt_ = std::max(min_dt_, std::max(0.5, f) * std::min(dt_, tried_));
      reason_ = std::to_string(iterations) + " Newton iterations > target " + std::to_string(target_iterations_);
    } else if (f > 1.0 && events == 0) {
      dt_ = std::min(target_, std::min(growth_, f) * dt_);
      reason_ = std::to_string(iterations) + " Newton iterations < target " + std::to_string(target_iterations_);
    }
    if (dt_ == before) reason_.clear();
  }
  // The step about to be tried shortened to dt (<= the proposed one; Stepping->contact
  // approach), and the step after it, once accepted, at most `then`: it grows back from there
  // as after any step.
  void shorten(double dt, double then) {
    tried_ = dt_ = dt;
    cap_ = then;
  }
  // Why the last accepted() changed the step ("" when it did not, or without a target).
  const std::string& reason() const { return reason_; }
  // Restart: the controller's state (growth and the cut-back limit come from the deck).
  struct Saved {
    double target, dt, min_dt;
    int consecutive, total;
  };
  Saved saved() const { return {target_, dt_, min_dt_, consecutive_, total_}; }
  void restore(const Saved& v) {
    target_ = v.target, dt_ = v.dt, min_dt_ = v.min_dt;
    consecutive_ = v.consecutive, total_ = v.total;
  }
  double dt() const { return dt_; }
  double target() const { return target_; }
  double min_dt() const { return min_dt_; }
  int consecutive_cuts() const { return consecutive_; }
  int total_cuts() const { return total_; }

 private:
  double target_, dt_, tried_ = 0.0, growth_, min_dt_;
  int max_cutbacks_;
  int target_iterations_ = 0;
  double cap_ = 0.0;  // shorten(): the step after the shortened one (0: none)
  int consecutive_ = 0, total_ = 0;
  std::string reason_;
};

// Cumulative energy terms of a dynamic run (written per step to <basename>_energy.csv).
struct EnergyTotals {
  double external = 0.0, support = 0.0, dissipation = 0.0;
  double contact = 0.0, friction = 0.0;  // contact work on the bodies, frictional dissipation
  double plastic = 0.0;                  // plastic dissipation (also in `dissipation`)
  double stabilization = 0.0;            // energy absorbed by the static stabilisation (StepSystem::stabilize)
  double max_balance = 0.0;              // max |balance residual| per step
};

struct RunState {
  RunState(const la::RCP<const la::Map>& map, const StepControl& c) : u(map), u_prev(map), u_before_last(map), control(c) {}
  la::Vector u;              // current iterate; after an accepted step u_{n+1}
  la::Vector u_prev;         // u_n, the start of the step being solved
  la::Vector u_before_last;  // u_{n-1}: the static predictor extrapolates u_n - u_{n-1}
  double t = 0.0;            // time of the last accepted step
  double dt_last = 0.0;      // its step size
  int step = 0;              // accepted steps
  long attempts = 0;         // steps tried, accepted and rejected
  int stage = 0;             // index into Config::stages (0 without stages)
  StepControl control;
  EnergyTotals energy;
  int newton_iterations = 0, linear_iterations = 0;  // all attempts, failed ones included
  bool failed = false;
  std::string failure;       // why the run stopped, for the summary
  int stopped_by = 0;        // the signal that stopped the run (run/StopRequest.hpp; failed is set too)
};

}  // namespace stentor
