// Everything a run tells the user: the header, one progress line per step, the result
// files (CSV histories, HDF5/XDMF fields, PNG plots, staged in <dir>.partial and moved
// into place only when the run succeeds) and the summary with the timers.
// Rank 0 writes the text files; every rank writes its rows of the HDF5 fields (parallel
// HDF5, run/OutputRows.hpp); the collective parts (field output, probes) run on every rank.
#pragma once
#include <chrono>
#include <map>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "io/Csv.hpp"
#include "io/Obstacles.hpp"
#include "io/OutputDir.hpp"
#include "io/XdmfWriter.hpp"
#include "mesh/SurfaceProjection.hpp"
#include "run/MetricsReport.hpp"
#include "run/OutputRows.hpp"
#include "run/Model.hpp"
#include "run/ResultPlots.hpp"
#include "run/RunState.hpp"
#include "run/Stepper.hpp"

namespace stentor {

class Reporter {
 public:
  // `start`: when the run began (the summary's wall time).
  Reporter(const Model& model, const RunOptions& opts, Timers& timers, std::chrono::steady_clock::time_point start);
  ~Reporter();

  // The log: std::cout on rank 0, a sink elsewhere.
  std::ostream& out() { return out_; }

  void print_model();    // deck, mesh, parallel layout
  void print_solvers();  // dofs, analysis, solver, contact (collective)

  // Checks and locks the output folder, creates <dir>.partial, the result files, a copy
  // of the deck and of the log (collective; io/OutputDir.hpp). Throws InputError when the
  // folder may not be used or a file cannot be created.
  void open();
  // Removes <dir>.partial and the lock (an input error before the first step: nothing
  // worth keeping).
  void discard();

  void write_fields(double t, const la::Vector& u);  // collective
  // The last iterate u of a step that failed for good (at the time t it aimed for), as
  // <basename>_failed.xdmf/.h5 in the staging folder: one frame of the deck's fields, to
  // see in ParaView where and how the solve went wrong (collective; nothing when the deck
  // writes no fields).
  void write_failed_state(double t, const la::Vector& u);
  void energy_row(int step, double t, const EnergyAudit& au, const EnergyTotals& e);
  // One row of <basename>_history.csv (collective: probes).
  void history_row(const RunState& s, const StepRecord& rec, double energy);
  // The stent metrics (Output->Stent Metrics) at t = 0 (collective; nothing without them),
  // and, at step 0, the initial state the plots start from (probes; collective).
  void initial_metrics(const RunState& s);
  // The stent metrics' state for a checkpoint, and back after --restart (MetricsReport).
  std::map<std::string, double> metrics_state() const;
  void restore_metrics(const std::map<std::string, double>& state);
  // Stage k of Config::stages begins: its header line.
  void begin_stage(std::size_t k);
  // A stage (or, without stages, the run) ended at s: its stent metrics row and lines.
  void end_stage(const RunState& s, const std::string& name);
  // The stepping of [t0, t1] begins: the reference of the time-left estimate.
  void begin_interval(double t0, double t1);
  // The progress line of an accepted step (flushed): without energy terms when they are
  // not finite; then the wall time so far and an estimate of the time left.
  void step_line(const RunState& s, const StepRecord& rec, double energy);
  void cutback_line(const RunState& s, double t_new, const NewtonResult& nr, double dt_new);
  // The step controller changed the step after an accepted step (Stepping->target iterations).
  void step_size_line(double dt_old, double dt_new, const std::string& why);

  // Every rank: the displacement, 3 per mesh node (collective).
  std::vector<double> displacement(const la::Vector& u);
  // Rank 0: a vector of the dof map (displacement, velocity), 3 per mesh node; zeros
  // elsewhere (collective; the end of a run only: not used by the field output).
  std::vector<double> displacement_on_root(const la::Vector& u);
  // Energy balance, summary line, timers.
  void summary(const RunState& s);
  // Success: plots, then <dir>.partial -> <dir>. Failure: says where the partial results are.
  void finish(bool failed);

  // After open(): rank 0's staging folder, on every rank ("" without one).
  const std::string& staging_path() const { return staging_dir_; }
  // Restart (run/Restart.cpp), rank 0 after open(): the CSV files (null elsewhere; the
  // energy file in dynamics only).
  const std::string& basename() const { return cfg_.output.basename; }
  CsvWriter* history_csv() { return history_.get(); }
  CsvWriter* energy_csv() { return energy_csv_.get(); }

 private:
  std::string analysis_text() const;
  std::vector<double> probe_values(const la::Vector& u) const;  // collective
  std::vector<std::string> history_columns() const;
  // reaction_<set>_<axis> for the components each Dirichlet set constrains (deck order).
  std::vector<std::string> reaction_columns() const;
  std::vector<std::string> energy_columns() const;
  void plots();

  const Model& m_;
  const Config& cfg_;
  Timers& timers_;
  double strain_energy_ = 0.0;  // the last accepted step's (history_row): the summary's stabilisation check
  std::ostringstream null_stream_;
  std::ostream& out_;
  std::string out_dir_;
  bool overwrite_ = false;  // RunOptions::overwrite
  std::string version_;     // RunOptions::version: the run header's `version` line
  // The deck's linear solver is KLU2 (method = direct, direct solver auto or klu2).
  bool klu2() const { return cfg_.linear.method == "direct" && cfg_.linear.direct_solver != "mumps"; }
  std::chrono::steady_clock::time_point start_;
  std::chrono::steady_clock::time_point interval_start_;  // begin_interval()
  double interval_t0_ = 0.0, interval_t1_ = 1.0;
  std::unique_ptr<OutputDir> staging_;
  std::string staging_dir_;  // staging_'s path, on every rank (open())
  std::unique_ptr<XdmfWriter> xdmf_;
  std::unique_ptr<CsvWriter> history_, energy_csv_;
  std::unique_ptr<MetricsReport> metrics_;  // null without Output->Stent Metrics
  std::unique_ptr<ObstacleWriter> obstacles_;  // rank 0, fields on and rigid obstacles present
  std::unique_ptr<SurfaceProjection> master_surface_;  // rank 0, fields on and master surfaces present
  void write_obstacles(double t);
  void open_fields();  // collective
  std::unique_ptr<XdmfWriter> make_writer(const std::string& basename);  // collective
  void write_frame(XdmfWriter& w, double t, const la::Vector& u, bool obstacles);  // collective
  void write_node_fields(XdmfWriter& w, const la::Vector& u, const std::vector<std::vector<double>>& nodal);
  void write_contact(XdmfWriter& w, MPI_Comm comm);  // collective
  std::unique_ptr<NodeRows> node_rows_;  // the dof vectors on the writer's node rows
  bool master_traction_ = false;        // a contact pair with a master surface
  double total_energy_ = 0.0;               // kinetic + strain of the last energy_row
  InitialState initial_;                    // t = 0 for the plots (initial_metrics)
  // Gather of every used dof on rank 0, in mesh node order (displacement_on_root).
  std::vector<la::GO> all_dofs_;
  la::RCP<const la::Map> gather_map_;
  la::RCP<la::Import> gather_;
  la::RCP<la::Vector> u_all_;
};

}  // namespace stentor
