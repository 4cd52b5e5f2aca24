// The stent metrics of a run (Output->Stent Metrics) as files: one row per accepted step
// in <basename>_metrics.csv, one row per stage in <basename>_stages.csv (the metrics at
// the stage's end, the lumen gain and radial recoil so far, the stage's largest stresses
// and contact pressure, and its energy terms), and a paragraph in the log per stage.
// A stent in an artery: StentMetrics; a generated stent: RingMetrics (with its per-ring
// table in each stage's paragraph), and ArteryMetrics when the artery is generated around
// it (Mesh->Artery).
#pragma once
#include <map>
#include <memory>
#include <ostream>
#include <string>
#include <vector>

#include "io/Csv.hpp"
#include "run/RunState.hpp"
#include "run/ArteryMetrics.hpp"
#include "run/RingMetrics.hpp"
#include "run/StentMetrics.hpp"

namespace stentor {

class MetricsReport {
 public:
  explicit MetricsReport(const Model& model);  // throws InputError (groups)
  // Rank 0: creates <stem>_metrics.csv and <stem>_stages.csv.
  void open(const std::string& stem);
  // After step s (and at t = 0): the metrics at u; E = kinetic + strain energy (collective).
  void step(const RunState& s, const la::Vector& u, double E);
  // The stage (or the whole run) that ends at s: its row and log paragraph (rank 0). A
  // static stage has no energy audit: its row carries the change of stored energy and the
  // plastic dissipation, NaN for the works and the other dissipations, and its log line
  // names only those two.
  void end_stage(const RunState& s, const std::string& name, std::ostream& log);
  void close();
  // The state the report carries between steps (the t = 0 metrics, the stage's start and
  // maxima, the largest stent radius; a generated stent's peak and reference), as named
  // values for a checkpoint ("metrics_..."), and back after a restart (before the first
  // step(); a checkpoint without them leaves the report to start afresh).
  void save(std::map<std::string, double>& out) const;
  void restore(const std::map<std::string, double>& in);
  // Columns of <stem>_metrics.csv worth a plot: radii; stresses and pressure.
  std::vector<std::string> radius_columns() const;
  std::vector<std::string> stress_columns() const;
  std::vector<std::string> diameter_columns() const;  // a generated stent's outer diameters
  // A generated stent in a generated artery: its outer nodes and their signed distances to
  // the lumen at u (collective, the same on every rank); false (nothing) otherwise.
  bool wall_gaps(const la::Vector& u, std::vector<GId>& nodes, std::vector<double>& gaps) const;

 private:
  int col(const std::string& name) const;

  const Model& m_;
  std::unique_ptr<StentMetrics> vessel_;  // a stent in an artery (the deck names the groups)
  std::unique_ptr<RingMetrics> rings_;    // a generated stent
  std::unique_ptr<ArteryMetrics> artery_; // ... in a generated artery
  std::vector<std::string> names_;
  std::unique_ptr<CsvWriter> steps_csv_, stages_csv_;
  std::vector<double> now_, first_;      // the last row's metrics, the t = 0 ones
  std::vector<double> stage_max_;        // this stage's maxima of each metric
  bool plastic_ = false;                 // Gauss-point history: a stage_plastic_dissipation column
  double stent_r_max_ = 0.0;             // largest stent radius so far
  EnergyTotals stage_e0_;                // totals when the stage began
  double stage_E0_ = 0.0, E_ = 0.0;      // energy when the stage began, now
  bool started_ = false;
};

}  // namespace stentor
