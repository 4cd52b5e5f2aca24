// Time schemes of a dynamic analysis, and the energy audit that checks them.
//
// Every scheme is written as "static residual + inertia" so one Newton loop and one
// assembler serve all of them (Assembler::StepInput):
//   midpoint family (gonzalez, midpoint):  v_{n+1} = 2 (u_{n+1} - u_n)/dt - v_n,
//     r = M (v_{n+1} - v_n)/dt + f_int,algo + f_visc - f_ext(t_{n+1/2})
//       = (2/dt^2) M (u_{n+1} - u_n - dt v_n) + ...
//   newmark (beta = 1/4, gamma = 1/2) and hht (alpha in [-1/3, 0], beta = (1-alpha)^2/4,
//   gamma = 1/2 - alpha):
//     r = M a_{n+1} + (1+alpha) (f_int - f_ext)_{n+1} - alpha (f_int - f_ext)_n.
// The audit computes each energy term independently (kinetic from v and M, stored from
// the strain-energy integral, dissipation from the viscous integral, external work from
// f_ext . du, support work from the reactions) so that the balance residual
//   E_{n+1} - E_n - (W_ext + W_support - D)
// is a real check of the scheme, not an identity.
#pragma once
#include <array>
#include <string>
#include <utility>
#include <vector>

#include "assembly/Assembler.hpp"
#include "deck/Config.hpp"
#include "solver/LinearSolver.hpp"

namespace stentor {

struct EnergyAudit {
  double kinetic = 0, strain = 0;                      // at t_{n+1}
  double external_work = 0, support_work = 0, dissipation = 0;  // over the step (dissipation: viscous + plastic)
  double plastic_dissipation = 0;                      // over the step (laws with Gauss-point history)
  double balance = 0;                                  // E_{n+1} - E_n - (W_ext + W_sup - D)
  std::array<double, 3> momentum{}, angular_momentum{};
};

class TimeIntegrator {
 public:
  TimeIntegrator(const Config& cfg, Assembler& assembler, const Distribution& dist, const Mesh& mesh);

  // Sets u_0 and v_0 from the deck's initial conditions (constrained dofs keep u = 0,
  // v = 0) and, for newmark/hht, a_0 = M^{-1} (f_ext(0) - f_int(u_0)). Returns the audit
  // of the state at t = 0.
  EnergyAudit initialize(la::Vector& u0, double end_time);

  // Stages: the scheme from now on (gonzalez | midpoint | newmark | hht; alpha from the deck).
  void set_scheme(const std::string& scheme);
  // The first step of a dynamic stage is about to start from the state u at time t:
  //   after a static stage (at_rest): v = 0 and a = 0 (a converged static state is at rest;
  //     the kinetic energy of a dynamic stage before it is not carried), E_n = the stored
  //     energy at u, f_int and f_ext at t;
  //   newmark/hht after a midpoint-family stage: f_int and f_ext at t, and a_n from
  //     M a_n = f_ext(t) - f_int(u) plus the last step's contact force (accept() keeps the
  //     mean acceleration and static residual of each midpoint step for this, in decks
  //     with such a switch).
  // Otherwise nothing changes. Returns the audit of the state (the energy row that opens a
  // dynamic stage after a static one).
  EnergyAudit begin_stage(const la::Vector& u, double t, double end_time, const std::string& scheme, bool at_rest);
  // A static stage starts: v = 0 (the velocity field of its output).
  void stop() { v_->putScalar(0.0); }

  // Assembler input for the step t_n -> t_n + dt from u_n.
  Assembler::StepInput step_input(double t_n, double dt, double end_time, const la::Vector& u_n);

  // Stepping->predictor = velocity: u <- u_n + dt v_n (midpoint family; v_{n+1} = v_n),
  // + dt^2/2 a_n for newmark/hht (a_{n+1} = a_n). Dirichlet values are the caller's.
  void predict(la::Vector& u, const la::Vector& u_n, double dt) const;
  // |M v_n| (2-norm over all ranks; collective).
  double momentum_norm() const;

  // After a converged step (u_n -> u_{n+1}): velocities, accelerations, history; the audit.
  EnergyAudit accept(const la::Vector& u_n, const la::Vector& u_np1, double dt, const Assembler::Stats& last);

  const la::Vector& velocity() const { return *v_; }
  // Restart: the vectors the scheme carries from step to step (v_n; a_n, the static
  // residual and external force at t_n for newmark/hht), by name, and E_n. Restoring them
  // replaces initialize().
  std::vector<std::pair<std::string, la::Vector*>> carried();
  double energy_n() const { return energy_n_; }
  void set_energy_n(double e) { energy_n_ = e; }
  bool midpoint_family() const { return scheme_ == "gonzalez" || scheme_ == "midpoint"; }
  const std::string& scheme() const { return scheme_; }
  // 1/2 v_n . M v_n, with M v_n left in Mv_ (collective).
  double kinetic_energy() const;
  std::string description() const;

 private:
  EnergyAudit audit(const la::Vector& u) const;
  // a_0 of newmark/hht from the residual of the state just assembled at t = 0, solved with
  // the deck's linear solver (a second instance, with the node coordinates).
  void initial_acceleration();
  // x = M^-1 rhs on free dofs, 0 on constrained ones (rhs is modified), with the deck's solver.
  void solve_mass(la::Vector& rhs, la::Vector& x);
  // f_int, f_ext and the stored energy at (u, t): the values of t_n the next step reads.
  double assemble_state(const la::Vector& u, double t, double end_time);

  std::string scheme_;
  double alpha_ = 0.0, beta_ = 0.25, gamma_ = 0.5;
  const Config& cfg_;
  Assembler& assembler_;
  const Distribution& dist_;
  const Mesh& mesh_;
  la::RCP<la::Vector> v_, a_, u_tilde_, extra_, r_static_n_, f_ext_n_, du_, Mv_;
  double energy_n_ = 0.0;  // total mechanical energy at t_n
  // Stages switch from the midpoint family to newmark/hht: the midpoint steps keep their
  // mean acceleration and static residual for the switch (a deck pays only for what it asks).
  bool keep_mean_acceleration_ = false;
  double dt_ = 0.0;
};

}  // namespace stentor
