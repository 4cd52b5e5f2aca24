#include "run/MetricsReport.hpp"

#include <algorithm>
#include <iomanip>
#include <iterator>
#include <limits>

#include "io/Units.hpp"

namespace stentor {

MetricsReport::MetricsReport(const Model& model) : m_(model), plastic_(model.assembler && model.assembler->has_history()) {
  if (model.cfg.mesh.generator == "stent") {
    rings_ = std::make_unique<RingMetrics>(model);
    names_ = rings_->columns();
    if (ArteryMetrics::applies(model.cfg)) {
      artery_ = std::make_unique<ArteryMetrics>(model);
      const auto c = artery_->columns();
      names_.insert(names_.end(), c.begin(), c.end());
    }
  } else {
    vessel_ = std::make_unique<StentMetrics>(model);
    names_ = vessel_->columns();
  }
}

int MetricsReport::col(const std::string& name) const {
  return static_cast<int>(std::find(names_.begin(), names_.end(), name) - names_.begin());
}

void MetricsReport::open(const std::string& stem) {
  if (m_.rank != 0) return;
  std::vector<std::string> c = {"step", "time", "stage"};
  c.insert(c.end(), names_.begin(), names_.end());
  steps_csv_ = std::make_unique<CsvWriter>(stem + "_metrics.csv", c);
  std::vector<std::string> s = {"stage", "time"};
  s.insert(s.end(), names_.begin(), names_.end());
  if (vessel_)
    s.insert(s.end(), {"lumen_gain", "stent_radius_max", "radial_recoil", "stage_contact_pressure_max",
                       "stage_artery_von_mises_max", "stage_artery_hoop_stress_max"});
  s.insert(s.end(), {"stage_delta_energy", "stage_external_work", "stage_dissipation", "stage_contact_work",
                     "stage_friction_dissipation"});
  if (plastic_) s.push_back("stage_plastic_dissipation");  // also in stage_dissipation
  stages_csv_ = std::make_unique<CsvWriter>(stem + "_stages.csv", s);
}

void MetricsReport::step(const RunState& s, const la::Vector& u, double E) {
  now_ = vessel_ ? vessel_->evaluate(u) : rings_->evaluate(u, s.t);
  if (artery_) {
    const std::vector<double> a = artery_->evaluate(u);
    now_.insert(now_.end(), a.begin(), a.end());
  }
  E_ = E;
  if (!started_) {
    first_ = now_;
    stage_max_ = now_;
    stage_e0_ = s.energy;
    stage_E0_ = E;
    started_ = true;
  }
  for (std::size_t k = 0; k < now_.size(); ++k) stage_max_[k] = std::max(stage_max_[k], now_[k]);
  if (vessel_) stent_r_max_ = std::max(stent_r_max_, now_[static_cast<std::size_t>(col("stent_radius_mean"))]);
  if (!steps_csv_) return;
  std::vector<double> row = {double(s.step), s.t, double(s.stage + 1)};
  row.insert(row.end(), now_.begin(), now_.end());
  steps_csv_->row(row);
}

void MetricsReport::end_stage(const RunState& s, const std::string& name, std::ostream& log) {
  if (!started_) return;
  const auto at = [&](const std::vector<double>& v, const char* c) { return v[static_cast<std::size_t>(col(c))]; };
  const EnergyTotals& e = s.energy;
  const double dE = E_ - stage_E0_, wext = e.external + e.support - stage_e0_.external - stage_e0_.support;
  const double diss = e.dissipation - stage_e0_.dissipation, wc = e.contact - stage_e0_.contact;
  const double fric = e.friction - stage_e0_.friction, plast = e.plastic - stage_e0_.plastic;
  std::vector<double> row = {double(s.stage + 1), s.t};
  row.insert(row.end(), now_.begin(), now_.end());
  log << "  metrics at the end of '" << name << "'";
  if (vessel_) {
    const double lumen0 = at(first_, "lumen_radius_mean"), lumen = at(now_, "lumen_radius_mean");
    const double gain = lumen0 > 0.0 ? (lumen - lumen0) / lumen0 : 0.0;
    const double rs = at(now_, "stent_radius_mean");
    const double recoil = stent_r_max_ > 0.0 ? (stent_r_max_ - rs) / stent_r_max_ : 0.0;
    const double pmax = at(stage_max_, "contact_pressure_max"), vm = at(stage_max_, "artery_von_mises_max");
    const double hoop = at(stage_max_, "artery_hoop_stress_max");
    row.insert(row.end(), {gain, stent_r_max_, recoil, pmax, vm, hoop});
    log << std::scientific << std::setprecision(4) << ": lumen radius " << lumen << " (gain " << std::fixed
        << std::setprecision(2) << 100.0 * gain << "%), stent radius " << std::scientific << std::setprecision(4) << rs
        << " (max " << stent_r_max_ << ", recoil " << std::fixed << std::setprecision(2) << 100.0 * recoil << "%)";
    if (vessel_->axial())
      log << ", dogboning " << 100.0 * at(now_, "dogboning") << "%, foreshortening " << 100.0 * at(now_, "foreshortening") << "%";
    const UnitLabels u = unit_labels(m_.cfg.problem.units, m_.dim, m_.cfg.problem.axisymmetric());
    const std::string stress = u.stress.empty() ? "" : " " + u.stress;
    log << std::scientific << std::setprecision(3) << "\n  stage maxima: contact pressure " << pmax << stress << ", wall von Mises "
        << vm << stress << ", wall hoop stress " << hoop << stress;
  } else {
    log << " (t = " << s.t << "):\n";
    rings_->table(log);
    if (artery_) artery_->table(log);
    log << "  stage";
  }
  const double none = std::numeric_limits<double>::quiet_NaN();
  if (m_.dynamic)
    row.insert(row.end(), {dE, wext, diss, wc, fric});
  else
    row.insert(row.end(), {dE, none, none, none, none});
  if (plastic_) row.push_back(plast);
  if (stages_csv_) stages_csv_->row(row);
  log << std::scientific << std::setprecision(3) << (vessel_ ? "; energy: dE " : " energy: dE ") << dE;
  if (m_.dynamic)
    log << ", W_ext " << wext << ", W_contact " << wc << (plastic_ ? ", D_visc + D_plastic " : ", D_visc ") << diss << ", D_fric " << fric;
  if (plastic_) log << ", D_plastic " << plast;
  if (!m_.dynamic) log << " (static: stored energy" << (plastic_ ? " and plastic dissipation" : "") << " only, no energy audit)";
  log << "\n"
      << std::defaultfloat;
  stage_max_ = now_;
  stage_e0_ = e;
  stage_E0_ = E_;
  if (rings_) rings_->begin_stage();
}

namespace {
const char* const kEnergyKeys[] = {"external", "support", "dissipation", "contact", "friction", "plastic"};
constexpr double EnergyTotals::* kEnergyFields[] = {&EnergyTotals::external, &EnergyTotals::support, &EnergyTotals::dissipation,
                                                   &EnergyTotals::contact,  &EnergyTotals::friction, &EnergyTotals::plastic};
}  // namespace

void MetricsReport::save(std::map<std::string, double>& out) const {
  if (!started_) return;
  for (std::size_t k = 0; k < first_.size(); ++k) {
    out["metrics_first_" + std::to_string(k)] = first_[k];
    out["metrics_stage_max_" + std::to_string(k)] = stage_max_[k];
  }
  for (std::size_t i = 0; i < std::size(kEnergyKeys); ++i) out[std::string("metrics_stage_e0_") + kEnergyKeys[i]] = stage_e0_.*kEnergyFields[i];
  out["metrics_stage_E0"] = stage_E0_;
  out["metrics_stent_r_max"] = stent_r_max_;
  if (rings_) rings_->save(out, "metrics_ring_");
  if (artery_) artery_->save(out, "metrics_artery_");
}

void MetricsReport::restore(const std::map<std::string, double>& in) {
  // All or nothing: a checkpoint without the state (or with other columns) starts afresh.
  auto get = [&](const std::string& key, double& v) {
    const auto it = in.find(key);
    if (it == in.end()) return false;
    v = it->second;
    return true;
  };
  std::vector<double> first(names_.size()), stage_max(names_.size());
  EnergyTotals e0;
  double E0 = 0.0, r_max = 0.0;
  bool ok = get("metrics_stage_E0", E0) && get("metrics_stent_r_max", r_max);
  for (std::size_t k = 0; ok && k < names_.size(); ++k)
    ok = get("metrics_first_" + std::to_string(k), first[k]) && get("metrics_stage_max_" + std::to_string(k), stage_max[k]);
  for (std::size_t i = 0; ok && i < std::size(kEnergyKeys); ++i)
    ok = get(std::string("metrics_stage_e0_") + kEnergyKeys[i], e0.*kEnergyFields[i]);
  if (!ok || (rings_ && !rings_->restore(in, "metrics_ring_")) || (artery_ && !artery_->restore(in, "metrics_artery_"))) return;
  first_ = first, stage_max_ = stage_max, stage_e0_ = e0, stage_E0_ = E0, stent_r_max_ = r_max;
  started_ = true;
}

void MetricsReport::close() {
  steps_csv_.reset();
  stages_csv_.reset();
}

std::vector<std::string> MetricsReport::radius_columns() const {
  if (!vessel_) return {};
  std::vector<std::string> c = {"lumen_radius_mean", "lumen_radius_min", "stent_radius_mean"};
  if (vessel_->axial()) c.insert(c.end(), {"stent_radius_middle", "stent_radius_ends"});
  return c;
}

bool MetricsReport::wall_gaps(const la::Vector& u, std::vector<GId>& nodes, std::vector<double>& gaps) const {
  if (!artery_) return false;
  nodes = artery_->outer_nodes();
  gaps = artery_->wall_gaps(u);
  return true;
}

std::vector<std::string> MetricsReport::diameter_columns() const {
  std::vector<std::string> c = rings_ ? rings_->diameter_columns() : std::vector<std::string>{};
  if (artery_) {
    const auto a = artery_->diameter_columns();
    c.insert(c.end(), a.begin(), a.end());
  }
  return c;
}

std::vector<std::string> MetricsReport::stress_columns() const {
  if (artery_) return artery_->stress_columns();
  if (!vessel_) return {};
  return {"artery_von_mises_max", "artery_hoop_stress_max", "contact_pressure_max"};
}

}  // namespace stentor
