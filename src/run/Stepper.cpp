#include "run/Stepper.hpp"

#include <Teuchos_CommHelpers.hpp>

#include "run/Supports.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace stentor {

namespace {
constexpr int kWorstCells = 5;         // cells of smallest det F named when a step fails on inverted cells
constexpr int kWorstContactNodes = 3;  // contact nodes named when a step fails after their state changed
}  // namespace

bool StepSystem::evaluate(const la::Vector& u, la::Vector& r, bool tangent) {
  Timers::Scope s{timers_, "assembly"};
  last = a_.assemble(u, input, r, tangent);
  if (xi_ > 0.0 && last.inverted == 0) stabilize(u, r, tangent);
  if (contact) {
    Timers::Scope sc{timers_, "contact"};
    auto K = contact->apply(u, r, tangent ? a_.matrix() : la::RCP<la::CrsMatrix>());
    if (tangent) K_ = K;
    if (contact_log) *contact_log << contact->iteration_summary() << "\n";
  }
  if (last.inverted > 0) first_failed = last.first_failed;
  return last.inverted == 0;
}

void StepSystem::stabilize(const la::Vector& u, la::Vector& r, bool tangent) {
  const la::RCP<la::CrsMatrix> K = a_.matrix();
  if (damp_.is_null()) {
    if (!tangent) return;  // Newton's first evaluation of a step always assembles the tangent
    damp_ = Teuchos::rcp(new la::Vector(K->getRowMap()));
    K->getLocalDiagCopy(*damp_);
    auto d = damp_->getLocalViewHost(Tpetra::Access::ReadWrite);
    for (std::size_t i = 0; i < d.extent(0); ++i)
      d(i, 0) = a_.is_dirichlet(static_cast<la::LO>(i)) ? 0.0 : xi_ * std::abs(d(i, 0));
  }
  {
    auto d = damp_->getLocalViewHost(Tpetra::Access::ReadOnly);
    auto uh = u.getLocalViewHost(Tpetra::Access::ReadOnly);
    auto un = u_n_->getLocalViewHost(Tpetra::Access::ReadOnly);
    auto rh = r.getLocalViewHost(Tpetra::Access::ReadWrite);
    for (std::size_t i = 0; i < d.extent(0); ++i) rh(i, 0) += d(i, 0) * (uh(i, 0) - un(i, 0));
  }
  if (!tangent) return;
  auto d = damp_->getLocalViewHost(Tpetra::Access::ReadOnly);
  const auto& rows = *K->getRowMap();
  const auto& cols = *K->getColMap();
  K->resumeFill();
  for (std::size_t i = 0; i < d.extent(0); ++i) {
    if (d(i, 0) == 0.0) continue;
    const la::LO row = static_cast<la::LO>(i), col = cols.getLocalElement(rows.getGlobalElement(row));
    K->sumIntoLocalValues(row, Teuchos::ArrayView<const la::LO>(&col, 1), Teuchos::ArrayView<const double>(&d(i, 0), 1));
  }
  K->fillComplete(K->getDomainMap(), K->getRangeMap());
}

double StepSystem::stabilization_energy(const la::Vector& u) const {
  if (damp_.is_null() || u_n_ == nullptr) return 0.0;
  la::Vector du(u, Teuchos::Copy);
  du.update(-1.0, *u_n_, 1.0);
  la::Vector ddu(du.getMap());
  ddu.elementWiseMultiply(1.0, *damp_, du, 0.0);
  return ddu.dot(du);
}

Stepper::Stepper(Model& model, Timers& timers, std::ostream* newton_log, std::ostream* contact_log)
    : m_(model), timers_(timers), system_(*model.assembler, timers), newton_log_(newton_log) {
  system_.input.end_time = m_.cfg.stepping.end_time;
  system_.contact_log = contact_log;
  const std::vector<double> X = m_.dist->owned_coordinates();
  double loc = 0.0, glob = 0.0;
  for (double x : X) loc += x * x;
  Teuchos::reduceAll(*m_.comm, Teuchos::REDUCE_SUM, 1, &loc, &glob);
  system_.coordinate_scale_ = std::sqrt(glob);
}

EnergyAudit Stepper::initialize_dynamics(RunState& s) { return m_.integrator->initialize(s.u, m_.cfg.stepping.end_time); }

void Stepper::initialize_contact(RunState& s) {
  // Dynamics: the initial velocities feed the first step's leapfrog test (Contact::initialize).
  if (m_.dynamic && m_.integrator) {
    m_.contact->initialize(s.u, m_.cfg.stepping.end_time, &m_.integrator->velocity(), s.control.next());
  } else {
    m_.contact->initialize(s.u, m_.cfg.stepping.end_time);
  }
  system_.contact = m_.contact.get();
}

void Stepper::attach_contact(const RunState& s) {
  m_.contact->initialize(s.u, m_.cfg.stepping.end_time);
  system_.contact = m_.contact.get();
}

NewtonResult Stepper::newton(la::Vector& u) {
  Timers::Scope s{timers_, "newton"};
  NewtonConfig nc = m_.cfg.newton;
  nc.residual_tolerance = nc.tolerance_for(m_.dynamic);
  // Dynamics: Eisenstat-Walker starts from the last dynamic step's first residual ratio
  // (one tight solve nearly converges a dynamic step; statics keep `forcing max`, which
  // measured faster there: docs/performance.md).
  NewtonResult nr = newton_solve(system_, u, *m_.linear, nc, newton_log_, m_.dynamic ? first_ratio_ : 0.0);
  if (m_.dynamic && nr.converged && nr.first_ratio > 0.0) first_ratio_ = nr.first_ratio;
  return nr;
}

// The initial guess (Stepping->predictor). auto, statics: extrapolate the last converged
// increment, so that a prescribed boundary motion is spread into the interior instead of
// squeezing the boundary layer of cells (which can invert them); where there is no
// increment yet (the first step, and a stage's first step: run_stages), lift; extrapolate:
// the same without the lifting. Dynamics, auto / none:
// u_n; velocity: the scheme's constant-velocity (acceleration) guess. lifting: lift every
// step. none: u_n.
void Stepper::predict(RunState& s, double dt, double t_new, bool& predicted, NewtonResult& lifted) {
  predicted = false;
  const std::string& p = m_.cfg.stepping.predictor;
  const bool statics_auto = !m_.dynamic && (p == "auto" || p == "velocity");
  const bool extrapolate = !m_.dynamic && (statics_auto || p == "extrapolate");
  if (extrapolate && s.step > 0 && s.dt_last > 0.0) {
    s.u.update(dt / s.dt_last, s.u_prev, -dt / s.dt_last, s.u_before_last, 1.0);
    predicted = true;
  } else if (m_.dynamic && p == "velocity") {
    m_.integrator->predict(s.u, s.u_prev, dt);
    system_.inertia_scale = 2.0 * m_.integrator->momentum_norm() / dt;
    predicted = true;
  } else if (statics_auto || p == "lifting") {
    predicted = lift(s, t_new, lifted);
  }
  m_.assembler->apply_dirichlet(s.u, t_new, m_.cfg.stepping.end_time);
}

// One Newton-like solve from u_n with the tangent K(u_n): the rows of prescribed dofs are
// identity rows whose right-hand side is the increment of the prescribed values, the
// others carry -r(u_n) of the new step, so
//   K_ff du_f = -r_f(u_n) - K_fp (g_{n+1} - g_n),   du_p = g_{n+1} - g_n:
// the increment enters the interior as the linearised problem spreads it (for a linear
// material, the whole step's solution). Counted as one Newton iteration.
bool Stepper::lift(RunState& s, double t_new, NewtonResult& lifted) {
  Timers::Scope sc{timers_, "newton"};
  const auto map = s.u.getMap();
  la::Vector inc(s.u, Teuchos::Copy), r(map), du(map);
  m_.assembler->apply_dirichlet(inc, t_new, m_.cfg.stepping.end_time);
  inc.update(-1.0, s.u, 1.0);
  if (inc.normInf() == 0.0) return false;  // nothing prescribed moves: Newton's first iteration is the lifting
  if (!system_.evaluate(s.u, r, true)) return false;
  r.update(1.0, inc, -1.0);  // prescribed rows of r are zero: inc there, -r elsewhere
  LinearSolver::Result lr;
  const NewtonConfig& nc = m_.cfg.newton;
  std::string failure;  // a failed lifting only falls back to u_n
  if (!linear_solve(*m_.linear, system_, r, du, nc.forcing == "eisenstat-walker" ? nc.forcing_max : 0.0, lr, failure))
    return false;
  if (!std::isfinite(du.norm2())) return false;
  s.u.update(1.0, du, 1.0);
  lifted.iterations = 1;
  lifted.linear_iterations = lr.iterations;
  const double inc_norm = inc.norm2();  // collective: on every rank, though only rank 0 logs
  if (newton_log_) *newton_log_ << "    lifting  |g_{n+1} - g_n| " << inc_norm << "  linear " << lr.iterations << "\n";
  return true;
}

NewtonResult Stepper::solve(RunState& s, double dt) {
  const double T = m_.cfg.stepping.end_time;
  const double t_new = s.t + dt;
  s.u_prev.update(1.0, s.u, 0.0);
  if (m_.dynamic) {
    system_.input = m_.integrator->step_input(s.t, dt, T, s.u_prev);
  } else {
    system_.input = Assembler::StepInput{};
    system_.input.load_time = t_new;
    system_.input.end_time = T;
  }
  // What an attempt at the step starts from: the contact history of u_n, no held nodes, the
  // stabilisation's increments from u_n (Model::stabilization is 0 in dynamic stages).
  auto begin_attempt = [&] {
    if (m_.contact) m_.contact->begin_step(s.t, dt, s.u_prev);
    system_.begin_step(m_.stabilization, &s.u_prev);
    system_.first_failed.clear();
  };
  begin_attempt();
  bool predicted = false;
  NewtonResult lifted;
  system_.inertia_scale = 0.0;
  predict(s, dt, t_new, predicted, lifted);
  NewtonResult nr = newton(s.u);
  // A guess that Newton could not converge from (inadmissible, or wrong: the static
  // extrapolation of the last increment points the wrong way where the load reverses, as
  // an obstacle that stops growing and shrinks back): once more from u_n, before the step
  // is cut. The iterations of both attempts count.
  if (predicted && !nr.converged) {
    const int first = nr.iterations, first_linear = nr.linear_iterations;
    s.u.update(1.0, s.u_prev, 0.0);
    m_.assembler->apply_dirichlet(s.u, t_new, T);
    begin_attempt();
    nr = newton(s.u);
    nr.iterations += first;
    nr.linear_iterations += first_linear;
  }
  nr.iterations += lifted.iterations;
  nr.linear_iterations += lifted.linear_iterations;
  // Where: the last inadmissible evaluation's first failed cell, and the cells of smallest
  // det F there (Newton's last evaluation is the inadmissible one when it fails on it).
  if (!nr.converged && nr.inadmissible && !system_.first_failed.empty())
    nr.failure += "; where: " + system_.first_failed + "; smallest det F: " + m_.assembler->smallest_det_f(kWorstCells);
  // The contact nodes whose state changed most often in the attempt (none: nothing added).
  if (!nr.converged && m_.contact) {
    const std::string changed = m_.contact->most_changed_nodes(kWorstContactNodes);
    if (!changed.empty()) nr.failure += "; contact nodes that changed state most: " + changed;
  }
  s.newton_iterations += nr.iterations;
  s.linear_iterations += nr.linear_iterations;
  return nr;
}

double Stepper::approach_limit(const RunState& s, double dt, double min_dt, std::string& why, double& then) {
  why.clear();
  then = 0.0;
  const double depth = m_.cfg.stepping.contact_approach;
  if (!m_.contact || !(depth > 0.0)) return dt;
  Timers::Scope sc{timers_, "contact"};
  la::Vector u_pred(s.u, Teuchos::Copy);
  if (m_.dynamic)
    u_pred.update(dt, m_.integrator->velocity(), 1.0);
  else if (s.step > 0 && s.dt_last > 0.0)
    u_pred.update(dt / s.dt_last, s.u, -dt / s.dt_last, s.u_before_last, 1.0);
  m_.assembler->apply_dirichlet(u_pred, s.t + dt, m_.cfg.stepping.end_time);
  const Contact::Approach a = m_.contact->approach(s.u, u_pred, s.t, dt, depth);
  if (!(a.fraction < 1.0)) return dt;
  const double shorter = std::max(min_dt, a.fraction * dt);
  if (!(shorter < dt)) return dt;
  then = dt * a.allowed / (std::max(a.gap, 0.0) - a.predicted);
  std::ostringstream os;
  os.precision(3);
  os << "node " << a.node << " of 'Contact->" << m_.contact->pair_name(static_cast<std::size_t>(a.pair)) << "' would go from gap "
     << a.gap << " to " << a.predicted << " (first touch of its part; allowed depth " << a.allowed << ")";
  why = os.str();
  return shorter;
}

double StepSystem::current_scale() const { return std::max(a_.external_force().norm2(), a_.static_residual().norm2()); }

double StepSystem::force_scale() const {
  return std::max({current_scale(), accepted_ ? scale_sum_ / accepted_ : 0.0, inertia_scale});
}

void StepSystem::record_scale() {
  const double s = current_scale();
  if (!(s > 0.0) || !std::isfinite(s)) return;
  scale_sum_ += s;
  ++accepted_;
}

void Stepper::reject(RunState& s) {
  s.u.update(1.0, s.u_prev, 0.0);
  m_.assembler->rollback_history();  // Gauss-point state: back to the last accepted step
}

StepRecord Stepper::accept(RunState& s, double dt, const NewtonResult& nr) {
  StepRecord rec;
  rec.newton = nr;
  rec.dt = dt;
  s.t += dt;
  ++s.step;
  s.u_before_last.update(1.0, s.u_prev, 0.0);
  s.dt_last = dt;
  system_.record_scale();
  rec.plastic_dissipation = system_.last.plastic_dissipation;
  rec.stabilization_energy = system_.stabilization_energy(s.u);
  s.energy.stabilization += rec.stabilization_energy;
  m_.assembler->commit_history();  // Newton's last assemble() was at the accepted u
  if (m_.contact) rec.contact = m_.contact->accept(s.u);
  if (!m_.dynamic) {
    s.energy.plastic += rec.plastic_dissipation;  // the one energy term a static step has besides the stored energy
    rec.nonfinite = nonfinite(s, nullptr);
    if (rec.nonfinite.empty() && nr.iterations > 0) rec.free_motion = free_translation();  // 0 iterations: nothing solved
    return rec;
  }
  EnergyAudit& au = rec.audit;
  au = m_.integrator->accept(s.u_prev, s.u, dt, system_.last);
  EnergyTotals& e = s.energy;
  e.external += au.external_work;
  e.support += au.support_work;
  e.dissipation += au.dissipation;
  e.plastic += au.plastic_dissipation;
  if (m_.contact) {
    // E_{n+1} - E_n = W_ext + W_sup - D + W_contact - D_friction.
    au.balance -= rec.contact.work - rec.contact.friction_dissipation;
    e.contact += rec.contact.work;
    e.friction += rec.contact.friction_dissipation;
  }
  rec.nonfinite = nonfinite(s, &au);
  if (rec.nonfinite.empty()) e.max_balance = std::max(e.max_balance, std::abs(au.balance));
  return rec;
}

std::string Stepper::nonfinite(const RunState& s, const EnergyAudit* au) const {
  if (!std::isfinite(s.u.norm1())) return "displacement";
  if (!std::isfinite(system_.last.energy)) return "stored energy";
  for (const auto& rf : m_.assembler->reactions())
    for (double v : rf)
      if (!std::isfinite(v)) return "reaction force";
  if (!au) return "";
  const EnergyTotals& e = s.energy;
  const double vals[] = {au->kinetic, au->strain, au->external_work, au->support_work, au->dissipation, au->balance,
                         au->momentum[0], au->momentum[1], au->momentum[2], au->angular_momentum[0],
                         au->angular_momentum[1], au->angular_momentum[2], e.external, e.support, e.dissipation};
  for (double v : vals)
    if (!std::isfinite(v)) return "energy or momentum";
  return "";
}

std::string Stepper::free_translation() {
  const Distribution& dist = *m_.dist;
  const ConnectedBodies& cb = m_.bodies;
  if (!translations_built_) {
    translations_built_ = true;
    for (std::size_t k = 0; k < cb.names.size(); ++k)
      for (int c = 0; c < m_.dim; ++c) {
        if (cb.names[k].empty() || cb.held[k][static_cast<std::size_t>(c)]) continue;
        auto z = Teuchos::rcp(new la::Vector(dist.owned_map()));
        {
          auto zh = z->getLocalViewHost(Tpetra::Access::ReadWrite);  // a new Vector is zero
          for (la::LO n = 0; n < dist.num_owned_nodes(); ++n)
            zh(n * m_.dim + c, 0) = cb.body(m_.mesh, dist.global_node(n)) == static_cast<int>(k) ? 1.0 : 0.0;
        }
        translations_.push_back({k, c, z});
      }
  }
  if (translations_.empty()) return "";
  const la::RCP<la::CrsMatrix> K = system_.matrix();
  la::Vector diag(K->getRowMap()), Kz(dist.owned_map()), dz(dist.owned_map());
  K->getLocalDiagCopy(diag);
  std::string out;
  std::size_t body = cb.names.size();
  for (const Translation& t : translations_) {
    K->apply(*t.z, Kz);
    dz.elementWiseMultiply(1.0, diag, *t.z, 0.0);
    const double scale = dz.normInf();
    if (!(scale > 0.0) || Kz.normInf() > 1e-8 * scale) continue;
    out += std::string(t.body == body ? ", " : out.empty() ? "" : "; ") + (t.body == body ? "" : cb.who(t.body) + " in ") + "xyz"[t.dir];
    body = t.body;
  }
  return out;
}

}  // namespace stentor
