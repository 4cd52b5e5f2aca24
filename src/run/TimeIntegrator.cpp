#include "run/TimeIntegrator.hpp"

#include <Teuchos_CommHelpers.hpp>

#include <algorithm>
#include <cmath>
#include <sstream>

namespace stentor {

TimeIntegrator::TimeIntegrator(const Config& cfg, Assembler& assembler, const Distribution& dist, const Mesh& mesh)
    : cfg_(cfg), assembler_(assembler), dist_(dist), mesh_(mesh) {
  set_scheme(cfg.scheme_in(0));
  bool midpoint = false, end_point = false;
  for (int k = 0; k < cfg.interval_count(); ++k)
    if (cfg.dynamic_in(k)) (cfg.scheme_in(k) == "gonzalez" || cfg.scheme_in(k) == "midpoint" ? midpoint : end_point) = true;
  keep_mean_acceleration_ = midpoint && end_point;
  const auto& map = dist.owned_map();
  for (auto* v : {&v_, &a_, &u_tilde_, &extra_, &r_static_n_, &f_ext_n_, &du_, &Mv_}) *v = Teuchos::rcp(new la::Vector(map));
}

void TimeIntegrator::set_scheme(const std::string& scheme) {
  scheme_ = scheme;
  alpha_ = scheme_ == "hht" ? cfg_.time.hht_alpha : 0.0;
  beta_ = 0.25 * (1.0 - alpha_) * (1.0 - alpha_);
  gamma_ = 0.5 - alpha_;
}

double TimeIntegrator::assemble_state(const la::Vector& u, double t, double end_time) {
  la::Vector r(dist_.owned_map());
  const Assembler::Stats st = assembler_.assemble(u, t, end_time, r, false);
  r_static_n_->update(1.0, assembler_.static_residual(), 0.0);
  f_ext_n_->update(1.0, assembler_.external_force(), 0.0);
  return st.energy;
}

EnergyAudit TimeIntegrator::begin_stage(const la::Vector& u, double t, double end_time, const std::string& scheme, bool at_rest) {
  const bool had_end_point_state = !midpoint_family();
  set_scheme(scheme);
  double strain = 0.0;
  if (at_rest) {
    // A converged static state: f_int - f_ext balances the supports and the contact forces,
    // so a_n = 0 (to Newton's tolerance) is the acceleration, contact included, which a mass
    // solve of f_ext - f_int would miss.
    v_->putScalar(0.0);
    a_->putScalar(0.0);
    strain = assemble_state(u, t, end_time);
  } else if (!midpoint_family() && !had_end_point_state) {
    // From the midpoint family: accept() left the last step's mean acceleration in a_ and
    // its static residual (f_int,algo - f_ext)_{n+1/2} in r_static_n_. On rows without
    // contact M a_mean = -(that residual); so a_n = a_mean + M^-1 (r_{n+1/2} - r_n) is the
    // exact M a_n = f_ext(t_n) - f_int(u_n) there, and on contact rows it carries the
    // contact force of the last step over (first order).
    la::Vector r_mid(*r_static_n_, Teuchos::Copy), da(dist_.owned_map());
    assemble_state(u, t, end_time);
    r_mid.update(-1.0, *r_static_n_, 1.0);
    solve_mass(r_mid, da);
    a_->update(1.0, da, 1.0);
  }
  EnergyAudit au = audit(u);
  if (at_rest) {
    au.strain = strain;
    energy_n_ = au.kinetic + au.strain;
  } else {
    au.strain = energy_n_ - au.kinetic;
  }
  return au;
}

std::string TimeIntegrator::description() const {
  std::ostringstream os;
  if (scheme_ == "gonzalez") os << "Gonzalez energy-consistent midpoint (discrete gradient)";
  if (scheme_ == "midpoint") os << "implicit midpoint rule";
  if (scheme_ == "newmark") os << "Newmark average acceleration (beta 1/4, gamma 1/2)";
  if (scheme_ == "hht") os << "HHT-alpha (alpha " << alpha_ << ", beta " << beta_ << ", gamma " << gamma_ << ")";
  return os.str();
}

std::vector<std::pair<std::string, la::Vector*>> TimeIntegrator::carried() {
  return {{"velocity", v_.get()}, {"acceleration", a_.get()}, {"static_residual_n", r_static_n_.get()}, {"external_force_n", f_ext_n_.get()}};
}

EnergyAudit TimeIntegrator::initialize(la::Vector& u0, double end_time) {
  const int dim = dist_.dim();
  const auto& ic = cfg_.initial;
  // The body whose own initial velocity / displacement a node takes (the last listed wins
  // on shared nodes), -1: Initial Conditions'.
  // By stored node (a rank's part of the mesh has every cell around its owned nodes).
  std::vector<int> vel_of(mesh_.num_stored_nodes(), -1), disp_of(mesh_.num_stored_nodes(), -1);
  for (std::size_t b = 0; b < cfg_.bodies.size(); ++b) {
    const BodyConfig& bc = cfg_.bodies[b];
    if (!bc.own_velocity() && !bc.has_displacement) continue;
    for (const auto& vb : mesh_.volumes)
      if (vb.name == bc.group)
        for (GId g : vb.conn) {
          const auto i = static_cast<std::size_t>(mesh_.stored_index(g));
          if (bc.own_velocity()) vel_of[i] = static_cast<int>(b);
          if (bc.has_displacement) disp_of[i] = static_cast<int>(b);
        }
  }
  // v0 = v + w x (X - c) of the body, or of Initial Conditions.
  auto rigid = [](const std::array<double, 3>& v, const std::array<double, 3>& w, const std::array<double, 3>& c, const double* X,
                  double* out) {
    const double r[3] = {X[0] - c[0], X[1] - c[1], X[2] - c[2]};
    out[0] = v[0] + w[1] * r[2] - w[2] * r[1];
    out[1] = v[1] + w[2] * r[0] - w[0] * r[2];
    out[2] = v[2] + w[0] * r[1] - w[1] * r[0];
  };
  {
    auto uh = u0.getLocalViewHost(Tpetra::Access::ReadWrite);
    auto vh = v_->getLocalViewHost(Tpetra::Access::OverwriteAll);
    for (la::LO n = 0; n < dist_.num_owned_nodes(); ++n) {
      const auto i = static_cast<std::size_t>(mesh_.stored_index(dist_.global_node(n)));
      const double* X = &mesh_.x[3 * i];
      double v[3];
      if (vel_of[i] >= 0) {
        const BodyConfig& bc = cfg_.bodies[static_cast<std::size_t>(vel_of[i])];
        rigid(bc.velocity, bc.angular_velocity, bc.center, X, v);
      } else {
        rigid(ic.velocity, ic.angular_velocity, ic.center, X, v);
      }
      const auto& d = disp_of[i] >= 0 ? cfg_.bodies[static_cast<std::size_t>(disp_of[i])].displacement : ic.displacement;
      for (int c = 0; c < dim; ++c) {
        const la::LO r = n * dim + c;
        if (assembler_.is_cartesian_dirichlet(r)) {  // on `normal` planes: projected below
          vh(r, 0) = 0.0;
        } else {
          uh(r, 0) = d[static_cast<std::size_t>(c)];
          vh(r, 0) = v[c];
        }
      }
    }
  }
  // Nodes on `normal` planes: u0 on the planes (the initial displacement's normal part
  // removed, as a Cartesian Dirichlet dof keeps its prescribed value), v0 along them.
  assembler_.apply_planes(u0, 0.0, end_time);
  assembler_.project_on_planes(*v_);
  a_->putScalar(0.0);
  const double strain0 = assemble_state(u0, 0.0, end_time);
  if (!midpoint_family()) initial_acceleration();
  EnergyAudit au = audit(u0);
  au.strain = strain0;
  energy_n_ = au.kinetic + au.strain;
  return au;
}

// M a_0 = f_ext(0) - f_int(u_0) on free dofs; a_0 = 0 on constrained ones (identity rows).
void TimeIntegrator::initial_acceleration() {
  la::Vector rhs(dist_.owned_map());
  rhs.update(-1.0, assembler_.static_residual(), 0.0);
  solve_mass(rhs, *a_);
}

// x = M^-1 rhs on free dofs, 0 on constrained ones (identity rows); x = 0 for rhs = 0.
void TimeIntegrator::solve_mass(la::Vector& rhs, la::Vector& x) {
  x.putScalar(0.0);
  if (!(rhs.normInf() > 0.0)) return;
  auto Mc = Teuchos::rcp(new la::CrsMatrix(*assembler_.mass(), Teuchos::Copy));
  Mc->resumeFill();
  {
    auto rh = rhs.getLocalViewHost(Tpetra::Access::ReadWrite);
    for (la::LO i = 0; i < static_cast<la::LO>(rhs.getLocalLength()); ++i) {
      if (!assembler_.is_cartesian_dirichlet(i)) continue;  // rows on `normal` planes: constrain_planes
      rh(i, 0) = 0.0;
      la::CrsMatrix::nonconst_local_inds_host_view_type cols("cols", Mc->getNumEntriesInLocalRow(i));
      la::CrsMatrix::nonconst_values_host_view_type vals("vals", cols.extent(0));
      size_t nnz = 0;
      Mc->getLocalRowCopy(i, cols, vals, nnz);
      const la::LO diag = Mc->getColMap()->getLocalElement(dist_.owned_map()->getGlobalElement(i));
      for (size_t k = 0; k < nnz; ++k) vals(k) = (cols(k) == diag) ? 1.0 : 0.0;
      Mc->replaceLocalValues(i, cols, vals);
    }
  }
  assembler_.constrain_planes(*Mc, rhs);  // rows of nodes on `normal` planes: as the tangent's
  Mc->fillComplete(dist_.owned_map(), dist_.owned_map());
  // The deck's solver and preconditioner, with the node coordinates multigrid needs
  // (without them MueLu refused the mass matrix: "dimension must be 2 or 3 (got 0)").
  LinearSolver lin(cfg_.linear, dist_.comm());
  lin.set_node_coordinates(dist_.dim(), dist_.owned_coordinates());
  lin.setup(Mc);
  lin.solve(rhs, x);
}

Assembler::StepInput TimeIntegrator::step_input(double t_n, double dt, double end_time, const la::Vector& u_n) {
  Assembler::StepInput in;
  in.end_time = end_time;
  in.u_old = &u_n;
  in.dt = dt;
  dt_ = dt;
  if (midpoint_family()) {
    in.eval = (scheme_ == "gonzalez") ? StressEval::Gonzalez : StressEval::Midpoint;
    in.load_time = t_n + 0.5 * dt;
    in.pressure_theta = 0.5;
    in.mass_coeff = 2.0 / (dt * dt);
    u_tilde_->update(1.0, u_n, dt, *v_, 0.0);
  } else {
    in.eval = StressEval::EndPoint;
    in.load_time = t_n + dt;
    in.pressure_theta = 1.0;
    in.scale = 1.0 + alpha_;
    in.mass_coeff = 1.0 / (beta_ * dt * dt);
    u_tilde_->update(1.0, u_n, dt, *v_, 0.0);
    u_tilde_->update(dt * dt * (0.5 - beta_), *a_, 1.0);
    if (alpha_ != 0.0) {
      extra_->update(-alpha_, *r_static_n_, 0.0);
      in.extra = extra_.get();
    }
  }
  in.u_tilde = u_tilde_.get();
  return in;
}

void TimeIntegrator::predict(la::Vector& u, const la::Vector& u_n, double dt) const {
  u.update(1.0, u_n, dt, *v_, 0.0);
  if (!midpoint_family()) u.update(0.5 * dt * dt, *a_, 1.0);
}

double TimeIntegrator::kinetic_energy() const {
  assembler_.mass()->apply(*v_, *Mv_);
  return 0.5 * v_->dot(*Mv_);
}

double TimeIntegrator::momentum_norm() const {
  assembler_.mass()->apply(*v_, *Mv_);
  return Mv_->norm2();
}

EnergyAudit TimeIntegrator::accept(const la::Vector& u_n, const la::Vector& u_np1, double dt, const Assembler::Stats& last) {
  du_->update(1.0, u_np1, -1.0, u_n, 0.0);
  EnergyAudit au;
  if (midpoint_family()) {
    au.external_work = assembler_.external_force().dot(*du_);  // f_ext(t_{n+1/2}, x_{n+1/2}) . du
    if (keep_mean_acceleration_) a_->update(-1.0 / dt, *v_, 0.0);
    v_->update(2.0 / dt, *du_, -1.0);                           // v_{n+1} = 2 du/dt - v_n
    if (keep_mean_acceleration_) {
      // The step's mean acceleration (v_{n+1} - v_n)/dt = M^-1 (f_ext - f_int - contact)_{n+1/2}
      // and the static residual it balances: what newmark/hht start from when a later stage
      // switches to them (begin_stage).
      a_->update(1.0 / dt, *v_, 1.0);
      r_static_n_->update(1.0, assembler_.static_residual(), 0.0);
    }
  } else {
    // Trapezoidal work of the end-point loads.
    au.external_work = 0.5 * (assembler_.external_force().dot(*du_) + f_ext_n_->dot(*du_));
    la::Vector a_new(dist_.owned_map());
    a_new.update(1.0 / (beta_ * dt * dt), *du_, -1.0 / (beta_ * dt), *v_, 0.0);
    a_new.update(-(0.5 / beta_ - 1.0), *a_, 1.0);
    v_->update(dt * (1.0 - gamma_), *a_, dt * gamma_, a_new, 1.0);
    a_->update(1.0, a_new, 0.0);
    r_static_n_->update(1.0, assembler_.static_residual(), 0.0);
    f_ext_n_->update(1.0, assembler_.external_force(), 0.0);
  }
  au.support_work = assembler_.support_work(*du_);
  au.plastic_dissipation = last.plastic_dissipation;
  au.dissipation = last.dissipation + last.plastic_dissipation;
  const EnergyAudit state = audit(u_np1);
  au.kinetic = state.kinetic;
  au.momentum = state.momentum;
  au.angular_momentum = state.angular_momentum;
  au.strain = last.energy;
  const double e_new = au.kinetic + au.strain;
  au.balance = e_new - energy_n_ - (au.external_work + au.support_work - au.dissipation);
  energy_n_ = e_new;
  return au;
}

// Kinetic energy 1/2 v.Mv, linear momentum sum(Mv), angular momentum sum x x (Mv) with
// x = X + u (consistent mass: these are the discrete momenta the midpoint schemes conserve).
EnergyAudit TimeIntegrator::audit(const la::Vector& u) const {
  EnergyAudit au;
  au.kinetic = kinetic_energy();  // leaves M v in Mv_
  const int dim = dist_.dim();
  auto mv = Mv_->getLocalViewHost(Tpetra::Access::ReadOnly);
  auto uh = u.getLocalViewHost(Tpetra::Access::ReadOnly);
  double loc[6] = {0, 0, 0, 0, 0, 0}, glob[6];
  for (la::LO n = 0; n < dist_.num_owned_nodes(); ++n) {
    const double* X = mesh_.coord(dist_.global_node(n));
    double x[3] = {X[0], X[1], X[2]}, p[3] = {0, 0, 0};
    for (int c = 0; c < dim; ++c) {
      x[c] += uh(n * dim + c, 0);
      p[c] = mv(n * dim + c, 0);
      loc[c] += p[c];
    }
    loc[3] += x[1] * p[2] - x[2] * p[1];
    loc[4] += x[2] * p[0] - x[0] * p[2];
    loc[5] += x[0] * p[1] - x[1] * p[0];
  }
  Teuchos::reduceAll(*dist_.comm(), Teuchos::REDUCE_SUM, 6, loc, glob);
  au.momentum = {glob[0], glob[1], glob[2]};
  au.angular_momentum = {glob[3], glob[4], glob[5]};
  return au;
}

}  // namespace stentor
