// One time (or load) step: predictor, Newton on the step's residual, and on success the
// updates that make the step part of the history (contact history, velocities, the
// energy audit). Cut-back and output are the driver's and the reporter's business.
#pragma once
#include <ostream>
#include <string>
#include <utility>
#include <vector>

#include "run/Model.hpp"
#include "run/RunState.hpp"
#include "solver/Newton.hpp"

namespace stentor {

// The residual of one step (static equilibrium, or a time scheme's), for Newton.
class StepSystem : public NewtonSystem {
 public:
  StepSystem(Assembler& a, Timers& timers) : a_(a), timers_(timers) {}
  Assembler::StepInput input;
  Assembler::Stats last;
  Contact* contact = nullptr;           // null without a "Contact" sublist
  std::ostream* contact_log = nullptr;  // --verbose: active/stick/slip sets per evaluation
  bool evaluate(const la::Vector& u, la::Vector& r, bool tangent) override;
  std::string first_failed;  // Assembler::Stats::first_failed of the last inadmissible evaluation in this step
  // The assembler's tangent, or with contact on master surfaces the coupled one.
  la::RCP<la::CrsMatrix> matrix() override { return K_.is_null() ? a_.matrix() : K_; }
  // Newton may stop only once the contact active set did not change in the last evaluation.
  bool settled() const override { return contact == nullptr || !contact->active_set_changed(); }
  // Contact rows are scaled by the tangent's diagonal (Contact::read_scales).
  bool residual_needs_tangent() const override { return contact != nullptr; }
  double coordinate_scale() const override { return coordinate_scale_; }
  void linearised_step(const la::Vector& du) override {
    if (contact) contact->linearised_step(du);
  }
  void step_length(double alpha) override {
    if (contact) contact->set_step_length(alpha);
  }
  int verify_held(std::string& why) override { return contact ? contact->verify_held(why) : 0; }
  // Fluid cavities' pressure-volume coupling (Assembler::Cavity).
  std::vector<RankOne> rank_one() const override {
    std::vector<RankOne> terms;
    for (const auto& c : a_.cavities())
      if (c.tangent_c > 0.0) terms.push_back({c.left.get(), c.right.get(), c.tangent_c});
    return terms;
  }
  // Static stabilisation (Stepping->stabilization): with xi > 0 each free dof i gets the
  // force D_i (u_i - u_n,i), D_i = xi |K_ii| from the bulk tangent of the step's first
  // evaluation (fixed for the step, so the tangent D is exact), before contact reads the
  // residual. A backward-Euler dashpot with coefficient D_i dt: it absorbs D_i du_i^2 >= 0
  // over the step (stabilization_energy) and vanishes for a body at rest, so it regularises
  // the tangent of a body that floats until contact holds it (a strut before the balloon
  // touches it) without moving an equilibrium that the step reaches with du = 0.
  void begin_step(double xi, const la::Vector* u_n) {
    xi_ = xi;
    u_n_ = u_n;
    damp_.reset();
  }
  double stabilization_energy(const la::Vector& u) const;  // sum_i D_i (u_i - u_n,i)^2 (collective)
  double coordinate_scale_ = 0.0;  // |X| over the dofs (Stepper's constructor)
  // |f_ext| and |f_int - f_ext| over all rows (reactions included): the forces in play.
  // After unloading (a deflated balloon, a body at rest) both are round-off, and so would
  // be the target: the mean force scale of the accepted steps so far is kept as a floor
  // (Abaqus' time-averaged force plays the same role).
  double force_scale() const override;
  // With a dynamic predictor, the inertia scale 2 |M v_n| / dt (the residual at u_n would
  // be about that): a guess that is already nearly exact (free flight) leaves only
  // round-off in |r|, which a relative target of |r_0| could never reach.
  double inertia_scale = 0.0;
  // After an accepted step: its force scale joins the mean.
  void record_scale();
  // Restart: the sum and count behind that mean.
  std::pair<double, long> scale_history() const { return {scale_sum_, accepted_}; }
  void restore_scale_history(double sum, long count) { scale_sum_ = sum, accepted_ = count; }

 private:
  Assembler& a_;
  Timers& timers_;
  la::RCP<la::CrsMatrix> K_;
  double xi_ = 0.0;
  const la::Vector* u_n_ = nullptr;
  la::RCP<la::Vector> damp_;  // D_i of the step (null until its first tangent)
  void stabilize(const la::Vector& u, la::Vector& r, bool tangent);
  double current_scale() const;  // max(|f_ext|, |f_int - f_ext|) of the last evaluate()
  double scale_sum_ = 0.0;
  long accepted_ = 0;
};

// What an accepted step produced, for the progress line and the result files.
struct StepRecord {
  NewtonResult newton;
  double dt = 0.0;
  Contact::StepStats contact;   // contact runs only
  EnergyAudit audit;            // dynamics only
  double plastic_dissipation = 0.0;  // of the step (plastic blocks only)
  double stabilization_energy = 0.0; // of the step (static stabilisation only)
  std::string nonfinite;        // the first non-finite quantity, or "" (then nothing may be written)
  std::string free_motion;      // statics: a rigid translation nothing holds (free_translation), or ""
};

class Stepper {
 public:
  // `newton_log`, `contact_log`: --verbose lines (null: none).
  Stepper(Model& model, Timers& timers, std::ostream* newton_log, std::ostream* contact_log);

  // u_0 (and v_0) from the initial conditions; the audit of the state at t = 0 (dynamics).
  EnergyAudit initialize_dynamics(RunState& s);
  // The contact history at t = 0 (d_{-1} = d_0).
  void initialize_contact(RunState& s);

  // Solves the step s.t -> s.t + dt from u_n = s.u: on return s.u_prev = u_n and s.u holds
  // Newton's last iterate (u_{n+1} when converged).
  NewtonResult solve(RunState& s, double dt);
  // Stepping->contact approach: the step dt from s.t shortened (never below `min_dt`) so that
  // no slave node of a part of its surface that touches nothing is predicted to end it
  // deeper than the deck's depth inside its obstacle or master surface (Contact::approach;
  // the prediction: statics, u_n plus the last increment scaled to dt; dynamics, u_n + dt
  // v_n; prescribed dofs at their values at s.t + dt). `why` says why when it shortened it,
  // and `then` is the step in which that node's predicted approach is the allowed depth (the
  // contact's own pace, for the step after it).
  double approach_limit(const RunState& s, double dt, double min_dt, std::string& why, double& then);
  // A failed step: back to u_n.
  void reject(RunState& s);
  // A converged step becomes u_{n+1}: time, contact history, velocities, energy totals.
  StepRecord accept(RunState& s, double dt, const NewtonResult& nr);

  // The name of the first non-finite quantity of the state (displacement, stored energy,
  // reactions, then the audit and the energy totals when given), or "". Global: every
  // rank gets the same answer.
  std::string nonfinite(const RunState& s, const EnergyAudit* au) const;

  // Statics, after a converged step: the connected bodies (Model::bodies) that no Dirichlet
  // condition holds in some direction and whose unit translation z in it the step's tangent
  // K (contact constraints included) leaves free, |K z|_inf <= 1e-8 max |K_ii| over z's
  // dofs, as "Bodies->'a' in x, y; ..."; "" when none. Such an equilibrium is not unique: the
  // linear solver may add any amount of that translation (a body pushed by a rigid circle
  // and held by nothing else ended 1.5e9 m away with exit 0). Collective.
  std::string free_translation();

  const Assembler::Stats& last() const { return system_.last; }
  // Restart: Newton's force-scale history (see StepSystem::force_scale).
  std::pair<double, long> scale_history() const { return system_.scale_history(); }
  void restore_scale_history(double sum, long count) { system_.restore_scale_history(sum, count); }
  // Restart: contact takes part from now on, its history set by the caller (initialize()
  // at u, instead of initialize_contact's t = 0 history).
  void attach_contact(const RunState& s);

 private:
  // The first iterate of the step (Stepping->predictor); `lifted` counts a lifting solve.
  void predict(RunState& s, double dt, double t_new, bool& predicted, NewtonResult& lifted);
  // Linearised lifting of the prescribed increment from u_n = s.u; false (s.u untouched)
  // when nothing prescribed moves, u_n is inadmissible or the linear solve fails.
  bool lift(RunState& s, double t_new, NewtonResult& lifted);
  NewtonResult newton(la::Vector& u);

  Model& m_;
  Timers& timers_;
  StepSystem system_;
  std::ostream* newton_log_;
  double first_ratio_ = 0.0;  // the last converged dynamic step's first |r_1| / |r_0| (Eisenstat-Walker's start)
  // free_translation's unit translations: connected body, direction, z (built at first use).
  struct Translation {
    std::size_t body;
    int dir;
    la::RCP<la::Vector> z;
  };
  std::vector<Translation> translations_;
  bool translations_built_ = false;
};

}  // namespace stentor
