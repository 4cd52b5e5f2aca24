// The state a run carries from step to step: displacements, time, the step-size
// controller, the cumulative energy terms and the counters of the summary.
#pragma once
#include <algorithm>
#include <string>

#include "parallel/LinearAlgebra.hpp"

namespace stentor {

// Step size: starts at the deck's step (the target); a failed step is retried with half
// the step tried, at most `max_cutbacks` times in a row and never below `min_dt`; each
// accepted step lets the step grow by `growth` again, up to the target.
class StepControl {
 public:
  StepControl(double target, int max_cutbacks, double growth, double min_dt)
      : target_(target), dt_(target), growth_(growth), min_dt_(min_dt), max_cutbacks_(max_cutbacks) {}
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
    return Cut::Ok;
  }
  // A new interval (stage) with its own step and minimum; the cut-back total carries on.
  void restart(double target, double min_dt) {
    target_ = dt_ = target;
    min_dt_ = min_dt;
    consecutive_ = 0;
  }
  void accepted() {
    dt_ = std::min(target_, growth_ * dt_);
    consecutive_ = 0;
  }
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
  int consecutive_ = 0, total_ = 0;
};

// Cumulative energy terms of a dynamic run (written per step to <basename>_energy.csv).
struct EnergyTotals {
  double external = 0.0, support = 0.0, dissipation = 0.0;
  double contact = 0.0, friction = 0.0;  // contact work on the bodies, frictional dissipation
  double plastic = 0.0;                  // plastic dissipation (also in `dissipation`)
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
};

}  // namespace stentor
