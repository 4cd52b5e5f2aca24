// The run, as the procedure reads (cf. deal.II step-44 run()):
//   run_simulation   build the model, open the output, set the initial state, step the
//                    interval, report;
//   run_stages       with "Stages": each stage's step and contact pairs, then its interval;
//   run_interval     the time loop: try a step, cut it back on failure, accept it;
//   accept_step      make a converged step part of the history and write it out
//                    (and, every Output->checkpoint every steps, a checkpoint);
//   resume           with --restart: the state from a checkpoint instead of t = 0.
// The pieces live in their own files: Model (mesh, loads, assembler, solvers), RunState
// (u, time, step control, energy totals), Stepper (predictor, Newton, accept) and
// Reporter (progress lines, CSV/HDF5/XDMF, summary, plots).
#include "run/Simulation.hpp"

#include <algorithm>
#include <chrono>
#include <csignal>
#include <iostream>
#include <memory>
#include <sstream>

#include "deck/InputLimits.hpp"
#include "run/Model.hpp"
#include "run/Reporter.hpp"
#include "run/Restart.hpp"
#include "run/RunState.hpp"
#include "run/StentMetrics.hpp"
#include "run/Stepper.hpp"
#include "run/StopRequest.hpp"

namespace stentor {

namespace {

struct Run {
  Model& model;
  Stepper& stepper;
  Reporter& reporter;
  RunState& state;
  Timers& timers;
  std::string checkpoint;  // the checkpoint file (the same on every rank)
  int fields_step = -1;      // the last accepted step whose fields were written
  int checkpoint_step = -1;  // the last accepted step checkpointed
};

void checkpoint(Run& r) {
  Timers::Scope t{r.timers, "checkpoint"};
  write_checkpoint(r.model, r.stepper, r.state, r.checkpoint, r.reporter.out(), r.reporter.metrics_state());
  r.checkpoint_step = r.state.step;
  r.model.linear->rebuild_preconditioner();  // as a run restarted from here will
}

void write_fields(Run& r) {
  r.reporter.write_fields(r.state.t, r.state.u);
  r.fields_step = r.state.step;
}

// A stop signal (run/StopRequest.hpp) reached every rank between two steps: the last
// accepted step's fields and checkpoint are written (unless they already are) and the run
// ends, its results in the .partial folder, with the command that continues it.
void stop_on_signal(Run& r, int sig) {
  RunState& s = r.state;
  if (r.model.cfg.output.fields && r.fields_step != s.step) write_fields(r);
  const bool ckpt = !r.checkpoint.empty();
  if (ckpt && r.checkpoint_step != s.step) checkpoint(r);
  std::ostringstream os;
  os << (sig == SIGINT ? "SIGINT" : sig == SIGTERM ? "SIGTERM" : "signal " + std::to_string(sig))
     << " received: the run stopped after step " << s.step << " (t = " << s.t << ")";
  if (ckpt)
    os << "; checkpoint " << r.checkpoint << "; continue with: stentor --restart " << r.checkpoint << " "
       << r.model.cfg.deck_path;
  s.failure = os.str();
  s.failed = true;
  s.stopped_by = sig;
}

// --restart: the state of the checkpoint, the interrupted run's CSV rows up to it, the
// fields at its time (the first frame of the new XDMF file), and at once a checkpoint in
// the new output folder.
void resume(Run& r, const Restart& rs) {
  RunState& s = r.state;
  try {
    restore(rs, r.model, r.stepper, s);
  } catch (const InputError&) {
    r.reporter.discard();  // nothing of this run was written yet
    throw;
  }
  r.reporter.out() << "  restart  from " << rs.path << ": step " << s.step << ", t = " << s.t
                   << (r.model.cfg.stages.empty() ? std::string() : ", stage " + r.model.cfg.stages[static_cast<std::size_t>(s.stage)].name)
                   << ", next dt " << s.control.dt() << "\n";
  if (r.model.rank == 0) carry_rows(rs, r.reporter, r.reporter.out());
  r.reporter.restore_metrics(rs.data.reals);  // the metrics' reference, peak and stage start
  r.reporter.initial_metrics(s);
  if (r.model.cfg.output.fields) write_fields(r);
  if (r.model.cfg.output.checkpoint_every > 0) checkpoint(r);
}

// The error for a non-finite initial state ("" when it is finite).
std::string nonfinite_initial_state(const Model& m, const Stepper& stepper, const RunState& s, const EnergyAudit& au0) {
  const std::string bad = stepper.nonfinite(s, &au0);
  if (bad.empty()) return "";
  std::ostringstream kinetic;
  kinetic << std::scientific;
  kinetic.precision(3);
  kinetic << au0.kinetic;
  return m.cfg.deck_path + ": 'Initial Conditions' give a non-finite initial " + bad + " (kinetic energy " + kinetic.str() +
         "); use smaller initial values";
}

// u_0, v_0 and the contact history at t = 0; the fields at t = 0.
void initialize(Run& r) {
  const Model& m = r.model;
  if (m.dynamic) {
    const EnergyAudit au0 = r.stepper.initialize_dynamics(r.state);
    const std::string bad = nonfinite_initial_state(m, r.stepper, r.state, au0);
    if (!bad.empty()) {
      r.reporter.discard();  // an input error: nothing worth keeping was written
      throw InputError(bad);
    }
    r.reporter.energy_row(0, 0.0, au0, r.state.energy);
  }
  if (m.contact) {
    r.stepper.initialize_contact(r.state);
    for (const std::string& w : m.contact->initial_penetrations()) r.reporter.out() << "  " << w << "\n";
  }
  r.reporter.initial_metrics(r.state);
  if (m.cfg.output.fields) write_fields(r);
}

// The step the numeric range is checked with: the run's, or the smallest of the dynamic
// stages' (the mass term grows as 1/dt^2), else the first stage's.
double check_step(const Config& cfg) {
  if (cfg.stages.empty()) return cfg.stepping.end_time / cfg.stepping.num_steps;
  double dt = 0.0;
  for (const StageConfig& st : cfg.stages)
    if (st.dynamic() && (dt == 0.0 || st.step() < dt)) dt = st.step();
  return dt > 0.0 ? dt : cfg.stages.front().step();
}

// The state at t = 0 before the initial conditions: u = 0, the deck's step control (each
// stage restarts it with its own step).
RunState fresh_state(const Model& model) {
  const SteppingConfig& st = model.cfg.stepping;
  return RunState(model.dist->owned_map(), StepControl(st.end_time / st.num_steps, st.max_cutbacks, st.growth, st.min_step(), st.target_iterations));
}

// --check: every check a run makes before its first step, and nothing written: the names
// in the mesh (done by Model), the stent metrics' groups, the contact pairs and the time
// scheme (discretise: slave sets, facet types, persistence in statics), the initial state
// (finite energy; the initial acceleration with Newmark/HHT) and initial penetrations.
void check_before_first_step(Model& model, Reporter& reporter, Timers& timers) {
  const Config& cfg = model.cfg;
  if (cfg.output.metrics.enabled && cfg.mesh.generator != "stent") StentMetrics groups(model);  // throws InputError
  model.discretise(timers);
  model.check_numeric_range(check_step(cfg));
  Stepper stepper(model, timers, nullptr, nullptr);
  RunState state = fresh_state(model);
  if (model.dynamic) {
    const std::string bad = nonfinite_initial_state(model, stepper, state, stepper.initialize_dynamics(state));
    if (!bad.empty()) throw InputError(bad);
  }
  if (model.contact) {
    stepper.initialize_contact(state);
    for (const std::string& w : model.contact->initial_penetrations()) reporter.out() << "  " << w << "\n";
  }
}

// Output->times: a time counts as reached by a step ending within round-off of it.
double output_time_tolerance(const Config& cfg) { return 1e-10 * cfg.stepping.end_time; }

// The turning points of a `table` ramp, shifted by `start`: its first and last points and
// the interior ones where the factor stops rising or falling (a peak, a trough, the start
// or end of a hold). A dense monotone table (a measured curve) adds only its ends.
void add_turning_points(const std::vector<double>& times, const std::vector<double>& f, double start, std::vector<double>& out) {
  const std::size_t n = std::min(times.size(), f.size());
  for (std::size_t i = 0; i < n; ++i)
    if (i == 0 || i + 1 == n || (f[i] - f[i - 1]) * (f[i + 1] - f[i]) <= 0.0) out.push_back(start + times[i]);
}

// The same on the run's clock (with stages: in the stages where the table is active).
void add_knots(const Ramp& r, std::vector<double>& out) {
  if (r.stages.empty()) {
    if (r.kind == Ramp::Kind::Table) add_turning_points(r.times, r.factors, 0.0, out);
    return;
  }
  for (const Ramp::Piece& p : r.stages)
    if (p.mode == Ramp::Piece::Mode::Active && p.kind == Ramp::Kind::Table) add_turning_points(p.times, p.factors, p.start, out);
}

// Where the loads' and the obstacles' table ramps turn, sorted.
std::vector<double> ramp_knots(const Config& cfg) {
  std::vector<double> k;
  for (const LoadConfig& l : cfg.loads) add_knots(l.ramp, k);
  for (const ContactPairConfig& c : cfg.contact) {
    add_knots(c.translation_ramp, k);
    add_knots(c.radius_ramp, k);
  }
  std::sort(k.begin(), k.end());
  return k;
}

// Where the step from t must end at the latest: the first Output->times entry after t (not
// reached at t), in a static interval the first turning point of a table ramp after t (time
// is the load parameter there: a table's extreme values, the peak of an expansion or of a
// load cycle, are reached exactly; a dynamic interval keeps its time grid), or `end`.
double next_stop(const Config& cfg, double t, double end, bool dynamic) {
  const double tol = output_time_tolerance(cfg);
  double stop = end;
  for (double tau : cfg.output.times)
    if (tau > t + tol) {
      stop = std::min(stop, tau);
      break;
    }
  if (!dynamic)
    for (double tau : ramp_knots(cfg))
      if (tau > t + tol) {
        stop = std::min(stop, tau);
        break;
      }
  return stop;
}

// Whether a step from t0 to t1 reached an Output->times entry.
bool output_time_reached(const Config& cfg, double t0, double t1) {
  const double tol = output_time_tolerance(cfg);
  for (double tau : cfg.output.times)
    if (tau > t0 + tol && tau <= t1 + tol) return true;
  return false;
}

// A converged step: history, progress line, result rows and fields. False when the new
// state is not finite (the run stops before writing it). Fields: every Output->every
// steps, at Output->times, at the end of the interval (the run, or a stage).
bool accept_step(Run& r, double dt, const NewtonResult& nr, double end) {
  RunState& s = r.state;
  const double t0 = s.t;
  const StepRecord rec = r.stepper.accept(s, dt, nr);
  const double energy = r.stepper.last().energy;
  r.reporter.step_line(s, rec, energy);
  if (!rec.nonfinite.empty()) {
    std::ostringstream os;
    os.precision(6);
    os << std::scientific << s.t;
    s.failure = "non-finite " + rec.nonfinite + " at t = " + os.str() +
                (r.model.dynamic ? " (loads, velocities or material constants too large?)" : " (loads or material constants too large?)");
    s.failed = true;
    return false;
  }
  if (!rec.free_motion.empty()) {
    std::ostringstream os;
    os << "static analysis: at t = " << s.t << " nothing holds " << rec.free_motion
       << " (no Dirichlet condition and no active contact constraint acts in that direction): the tangent is singular, so "
          "the equilibrium is not unique and the solver may add any rigid translation in it; add a support in 'Boundary "
          "Conditions' (or friction), or use Problem->analysis = dynamic";
    s.failure = os.str();
    s.failed = true;
    return false;
  }
  if (r.model.dynamic) r.reporter.energy_row(s.step, s.t, rec.audit, s.energy);
  r.reporter.history_row(s, rec, energy);
  const bool last = s.t >= end * (1.0 - 1e-12);
  const auto& out = r.model.cfg.output;
  if (out.fields && (s.step % out.every == 0 || last || output_time_reached(r.model.cfg, t0, s.t))) write_fields(r);
  const double dt_before = s.control.next();
  s.control.accepted(rec.newton.iterations, rec.contact.events);
  if (!s.control.reason().empty()) r.reporter.step_size_line(dt_before, s.control.next(), s.control.reason());
  if (out.checkpoint_every > 0 && (s.step % out.checkpoint_every == 0 || last)) checkpoint(r);
  return true;
}

// Why the run stops at a failed step that may not be cut back again.
std::string cutback_failure(const RunState& s, double dt, const NewtonResult& nr, StepControl::Cut why) {
  std::ostringstream os;
  os << "Newton failed at t = " << s.t + dt << " (" << nr.failure << ")";
  if (why == StepControl::Cut::BelowMinimum)
    os << " with dt = " << dt << "; half of it is below Stepping->min dt = " << s.control.min_dt()
       << " (see Stepping->min dt, Newton->max iterations)";
  else
    os << " after " << s.control.consecutive_cuts() << " step halvings (dt = " << dt
       << "); see Stepping->max cutbacks, Newton->max iterations";
  return os.str();
}

// Steps from the current time to `end`: each step is tried with the controller's size; a
// failed Newton solve is retried from the last converged state with half the step.
// False when the run must stop (cut-backs or steps used up, or a non-finite state).
bool run_interval(Run& r, double end) {
  RunState& s = r.state;
  const long cap = r.model.cfg.stepping.step_cap();
  while (s.t < end * (1.0 - 1e-12)) {
    if (const int sig = agreed_stop_signal(*r.model.comm)) {
      stop_on_signal(r, sig);
      return false;
    }
    if (s.attempts >= cap) {
      std::ostringstream os;
      os << "reached Stepping->max steps = " << cap << " (" << s.step << " accepted, " << s.attempts - s.step
         << " rejected) at t = " << s.t << " of " << end << "; raise it, or see why steps are cut back";
      s.failure = os.str();
      s.failed = true;
      return false;
    }
    ++s.attempts;
    double dt = s.control.propose(next_stop(r.model.cfg, s.t, end, r.model.dynamic) - s.t);  // to an output time or a table's point
    std::string landing_why;
    double then = 0.0;
    const double landing = r.stepper.approach_limit(s, dt, s.control.min_dt(), landing_why, then);
    if (landing < dt) {
      r.reporter.step_size_line(dt, landing, landing_why);
      s.control.shorten(dt = landing, then);
    }
    const NewtonResult nr = r.stepper.solve(s, dt);
    if (nr.converged) {
      if (!accept_step(r, dt, nr, end)) return false;
      test_signal_hook(s.step, r.model.rank);
      continue;
    }
    const StepControl::Cut why = s.control.cut();
    if (why != StepControl::Cut::Ok) {
      r.reporter.write_failed_state(s.t + dt, s.u);  // before reject() puts u_n back
      r.stepper.reject(s);
      s.failure = cutback_failure(s, dt, nr, why);
      s.failed = true;
      return false;
    }
    r.stepper.reject(s);
    r.reporter.cutback_line(s, s.t + dt, nr, s.control.dt());
  }
  return true;
}

// Stage k is about to run: its analysis (Model::set_stage: `auto` contact pairs follow it)
// and what changes where the analysis or the scheme does. A static stage after a dynamic one starts at
// rest (v = 0; its first guess is lifted, not extrapolated from the last dynamic increment);
// a dynamic stage after a static one starts at rest from the static state, with an energy
// row at its start (the energy CSV holds the dynamic stages); newmark/hht after the midpoint
// family read f_int and f_ext at t (TimeIntegrator::begin_stage).
void change_analysis(Run& r, std::size_t k) {
  Model& m = r.model;
  RunState& s = r.state;
  const bool was_dynamic = m.dynamic;
  m.set_stage(static_cast<int>(k));
  if (was_dynamic && !m.dynamic) {
    const double kinetic = m.integrator->kinetic_energy();
    m.integrator->stop();
    s.dt_last = 0.0;
    std::ostringstream os;
    os.precision(4);
    os << kinetic;
    r.reporter.out() << "  static stage: starts at rest (kinetic energy " << os.str() << " of the stage before is not carried)\n";
  } else if (m.dynamic && (!was_dynamic || m.cfg.scheme_in(static_cast<int>(k)) != m.integrator->scheme())) {
    const EnergyAudit au = m.integrator->begin_stage(s.u, s.t, m.cfg.stepping.end_time, m.cfg.scheme_in(static_cast<int>(k)), !was_dynamic);
    if (!was_dynamic) r.reporter.energy_row(s.step, s.t, au, s.energy);
  }
}

// The stages in order, each with its own step, contact pairs and analysis; the state
// carries over. `resumed`: from the checkpoint's stage, whose step control the checkpoint
// holds. False when a stage fails.
bool run_stages(Run& r, bool resumed) {
  const SteppingConfig& st = r.model.cfg.stepping;
  const auto& stages = r.model.cfg.stages;
  for (std::size_t k = resumed ? static_cast<std::size_t>(r.state.stage) : 0; k < stages.size(); ++k) {
    const StageConfig& stage = stages[k];
    RunState& s = r.state;
    if (resumed && static_cast<int>(k) == s.stage) {
      r.model.set_stage(s.stage);  // the checkpoint holds the stage's state
      if (r.model.dynamic) r.model.integrator->set_scheme(r.model.cfg.scheme_in(s.stage));
    } else {
      s.control.restart(stage.step(), st.min_dt > 0.0 ? st.min_dt : 1e-6 * stage.step());
      change_analysis(r, k);
      // The stage before moved other boundaries (a crimper's release, say): its last
      // increment is no guess for this stage's first step, whose own prescribed motion is
      // lifted into the body instead (Stepper::predict). Extrapolated, that motion landed on
      // the boundary's layer of cells alone: an artery's end moved by 0.0575 mm over cells
      // 0.125 mm long stretched them by 46 %, where the coronary intima's exponential law
      // (k2 = 171) gave a residual of 1e72 (inputs/s7_stent_coronary.xml).
      if (k > 0) s.dt_last = 0.0;
    }
    s.stage = static_cast<int>(k);
    if (r.model.contact) r.model.contact->set_active_pairs(stage.contact_active);
    r.reporter.begin_stage(k);
    if (!run_interval(r, stage.end)) return false;
    r.reporter.end_stage(s, stage.name);
  }
  return true;
}

void fill_result(Run& r, RunResult& result) {
  const RunState& s = r.state;
  result.displacement = r.reporter.displacement(s.u);
  result.reactions = r.model.assembler->reactions();
  result.energy = r.stepper.last().energy;
  result.steps = s.step;
  result.cutbacks = s.control.total_cuts();
  result.newton_iterations = s.newton_iterations;
  result.linear_iterations = s.linear_iterations;
  result.converged = !s.failed;
  result.mesh = r.model.mesh;
}

}  // namespace

int run_simulation(const Config& cfg, const RunOptions& opts, RunResult* result) {
  const auto start = std::chrono::steady_clock::now();
  Timers timers;
  Model model(cfg, opts, timers);
  Reporter reporter(model, opts, timers, start);
  reporter.print_model();
  if (opts.check_only) {
    check_before_first_step(model, reporter, timers);
    reporter.out() << "deck and mesh are valid: " << cfg.bodies.size() << " bodies, " << cfg.materials.size() << " materials, "
                   << cfg.loads.size() << " boundary conditions\n";
    return 0;
  }
  model.discretise(timers);
  reporter.print_solvers();
  model.check_numeric_range(check_step(cfg));
  const bool restarting = !opts.restart_file.empty();
  Restart restart;
  if (restarting) restart = read_restart(opts.restart_file, model, opts, reporter.out());  // before open(): it may move <dir>.partial
  reporter.open();

  const bool verbose0 = opts.verbose && model.rank == 0;
  std::ostringstream sink;
  std::ostream* contact_log = opts.verbose ? (verbose0 ? static_cast<std::ostream*>(&std::cout) : &sink) : nullptr;
  Stepper stepper(model, timers, verbose0 ? &std::cout : nullptr, contact_log);
  RunState state = fresh_state(model);
  Run run{model, stepper, reporter, state, timers, checkpoint_path(reporter, model)};

  if (restarting)
    resume(run, restart);
  else
    initialize(run);
  current_phase() = "time stepping (solving the steps and writing their results)";
  reporter.begin_interval(state.t, cfg.stepping.end_time);
  if (cfg.stages.empty()) {
    if (run_interval(run, cfg.stepping.end_time)) reporter.end_stage(state, "the run");
  } else {
    run_stages(run, restarting);
  }

  if (result) fill_result(run, *result);
  reporter.summary(state);
  reporter.finish(state.failed);
  if (state.stopped_by) return 128 + state.stopped_by;
  return state.failed ? 3 : 0;
}

}  // namespace stentor
