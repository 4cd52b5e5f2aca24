#include "run/ResultPlots.hpp"

#include <algorithm>
#include <cmath>
#include <iostream>
#include <limits>
#include <map>

#include "io/Plot.hpp"
#include "io/Units.hpp"
#include "run/Model.hpp"
#include "run/RingMetrics.hpp"

namespace stentor {

namespace {

const char* kAxes[3] = {"x", "y", "z"};
const double kNaN = std::numeric_limits<double>::quiet_NaN();

// A name as part of a file name: spaces become '_' (load names may hold spaces).
std::string file_part(std::string s) {
  for (char& c : s)
    if (c == ' ') c = '_';
  return s;
}

// A dashed line where each stage but the last ends, for every plot against time.
std::vector<PlotMark> stage_marks(const Config& cfg) {
  std::vector<PlotMark> marks;
  for (std::size_t k = 0; k + 1 < cfg.stages.size(); ++k) marks.push_back({cfg.stages[k].end, "end of " + cfg.stages[k].name});
  return marks;
}

// The history table with the initial state as row 0 (t = 0): probe displacements when
// known, reactions and contact forces 0 when at rest and unloaded, else NaN (no point).
void prepend_initial_row(PlotTable& h, const Model& m, const InitialState& init) {
  if (h.rows() == 0 || h.find("time") < 0 || h.columns[static_cast<std::size_t>(h.find("time"))].front() <= 0.0) return;
  std::vector<double> row(h.names.size(), kNaN);
  for (std::size_t c = 0; c < h.names.size(); ++c) {
    const std::string& n = h.names[c];
    if (n == "time" || n == "step") row[c] = 0.0;
    const bool force = n.rfind("reaction_", 0) == 0 ||
                       (n.rfind("contact_", 0) == 0 && (n.find("_force_") != std::string::npos || n.find("_normal_force") != std::string::npos));
    if (force && init.known && init.at_rest_unloaded) row[c] = 0.0;
  }
  for (const LoadConfig& l : m.cfg.loads) {  // a pressure's value at t = 0 is the deck's
    const int c = h.find("pressure_" + l.name);
    if (l.type == LoadConfig::Type::Pressure && c >= 0) row[static_cast<std::size_t>(c)] = l.value * l.ramp(0.0, m.cfg.stepping.end_time);
    if (l.type == LoadConfig::Type::FluidCavity && c >= 0) row[static_cast<std::size_t>(c)] = 0.0;  // the mesh's volume: no pressure
    const int v = h.find("volume_ratio_" + l.name);
    if (l.type == LoadConfig::Type::FluidCavity && v >= 0) row[static_cast<std::size_t>(v)] = 1.0;
  }
  for (std::size_t p = 0; init.known && p < m.cfg.output.probes.size() && 3 * p + 2 < init.probes.size(); ++p)
    for (int k = 0; k < m.dim; ++k) {
      const int c = h.find("u_" + m.cfg.output.probes[p].name + "_" + kAxes[k]);
      if (c >= 0) row[static_cast<std::size_t>(c)] = init.probes[3 * p + static_cast<std::size_t>(k)];
    }
  for (std::size_t c = 0; c < h.names.size(); ++c) h.columns[c].insert(h.columns[c].begin(), row[c]);
}

// Reactions vs time, and vs the prescribed displacement of each set that moves.
void reaction_plots(const Model& m, PlotTable& h, const std::string& stem, const UnitLabels& u, std::vector<std::string>& made) {
  PlotSpec vs_time{"Reaction forces of the Dirichlet sets", with_unit("time", u.time), with_unit("reaction force", u.force), "time", {}, true};
  // A copy: h.add() below grows h.columns, which would leave a reference dangling (it did:
  // with two moving Dirichlet sets the second set's loop read a freed vector, and the run
  // ended with "cannot create std::vector larger than max_size()" or garbage plots,
  // depending on the heap; found on inputs/ironing.xml when launched from another python).
  const std::vector<double> t = h.columns[static_cast<std::size_t>(h.find("time"))];
  const double T = m.cfg.stepping.end_time;
  for (const DirichletSet& d : m.assembler->dirichlet_sets()) {
    PlotSpec vs_u{"Reaction of '" + d.name + "' versus its prescribed displacement", with_unit("prescribed displacement", u.length),
                  with_unit("reaction force", u.force), "", {}, false};
    for (int k = 0; k < m.dim; ++k) {
      const std::string col = "reaction_" + d.name + "_" + kAxes[k];
      if (h.find(col) < 0) continue;
      const std::string comp = std::string(kAxes[k]);
      vs_time.curves.push_back({col, d.name + ": reaction " + comp, ""});
      if (d.field || !d.components[static_cast<std::size_t>(k)] || d.values[static_cast<std::size_t>(k)] == 0.0) continue;
      std::vector<double> ud(t.size());
      for (std::size_t r = 0; r < t.size(); ++r) ud[r] = d.values[static_cast<std::size_t>(k)] * d.ramp(t[r], T);
      const std::string ucol = "prescribed_" + d.name + "_" + comp;
      h.add(ucol, std::move(ud));
      vs_u.curves.push_back({col, d.name + ": reaction " + comp + " vs prescribed u_" + comp, ucol});
    }
    if (!vs_u.curves.empty()) {
      const std::string png = stem + "_reaction_" + file_part(d.name) + ".png";
      if (plot_png(h, png, vs_u)) made.push_back(png);
    }
  }
  if (!vs_time.curves.empty() && plot_png(h, stem + "_reactions.png", vs_time, stage_marks(m.cfg))) made.push_back(stem + "_reactions.png");
}

// Probe displacements and contact forces vs time.
void history_plots(const Model& m, const PlotTable& h, const std::string& stem, const UnitLabels& u, std::vector<std::string>& made) {
  PlotSpec probes{"Displacement at the probes", with_unit("time", u.time), with_unit("displacement", u.length), "time", {}, true};
  for (const auto& p : m.cfg.output.probes)
    for (int k = 0; k < m.dim; ++k) {
      const std::string col = "u_" + p.name + "_" + kAxes[k];
      if (h.find(col) >= 0) probes.curves.push_back({col, p.name + ": u_" + kAxes[k], ""});
    }
  if (!probes.curves.empty() && plot_png(h, stem + "_probes.png", probes, stage_marks(m.cfg))) made.push_back(stem + "_probes.png");
  // The normal force of each pair (the sum of its nodes' normal forces: the radial force
  // against a cylinder or a balloon), not the vector sum, in which opposite walls cancel.
  PlotSpec contact{"Normal contact force of each pair (compression > 0)", with_unit("time", u.time), with_unit("normal force", u.force), "time", {}, true};
  // In dynamics also its mean over two steps, without the step-to-step alternation of the
  // midpoint rule's multipliers in sustained contact (docs/contact.md, "Sustained contact").
  for (const auto& c : m.cfg.contact) {
    const std::string col = "contact_" + c.name + "_normal_force";
    if (h.find(col) >= 0) contact.curves.push_back({col, c.name, ""});
    const std::string mean = "contact_" + c.name + "_two_step_mean_normal_force";
    if (m.cfg.any_dynamic() && h.find(mean) >= 0) contact.curves.push_back({mean, c.name + ", two-step mean", ""});
  }
  if (m.contact && !contact.curves.empty() && plot_png(h, stem + "_contact.png", contact, stage_marks(m.cfg))) made.push_back(stem + "_contact.png");
  // A balloon (a rigid round obstacle whose radius changes): its force-diameter curve.
  for (const auto& c : m.cfg.contact) {
    const std::string d = "contact_" + c.name + "_obstacle_diameter", f = "contact_" + c.name + "_normal_force";
    if (c.radius_change == 0.0 || h.find(d) < 0 || h.find(f) < 0) continue;
    PlotSpec fd{"Force-diameter curve of '" + c.name + "': normal contact force against the obstacle's diameter",
                with_unit("diameter", u.length), with_unit("normal force", u.force), d, {{f, c.name, ""}}, false};
    const std::string png = stem + "_force_diameter_" + file_part(c.name) + ".png";
    if (plot_png(h, png, fd)) made.push_back(png);
  }
}

// What the `plastic_dissipation` column holds: the dissipation of the deck's laws with
// Gauss-point history (plasticity, damage).
std::string history_dissipation_label(const Config& cfg) {
  bool plastic = false, damage = false;
  for (const auto& mat : cfg.materials) plastic |= mat.plastic(), damage |= mat.damage();
  return plastic && damage ? "plastic + damage dissipation" : damage ? "damage dissipation" : "plastic dissipation";
}

// Dynamics: every term of the energy balance, and the balance per step.
void energy_plots(const Model& m, const std::string& stem, const UnitLabels& u, std::vector<std::string>& made) {
  PlotTable e;
  if (!read_csv_table(stem + "_energy.csv", e) || e.rows() == 0) return;
  auto col = [&](const std::string& n) -> const std::vector<double>* {
    const int i = e.find(n);
    return i < 0 ? nullptr : &e.columns[static_cast<std::size_t>(i)];
  };
  const auto *total = col("total"), *ext = col("external_work"), *sup = col("support_work"), *dis = col("dissipation");
  if (!total || !ext || !sup || !dis || !col("time")) return;
  const auto *plastic = col("plastic_dissipation"), *wc = col("contact_work"), *fric = col("friction_dissipation");
  const std::size_t n = e.rows();
  std::vector<double> viscous(n), error(n);
  for (std::size_t r = 0; r < n; ++r) {
    viscous[r] = (*dis)[r] - (plastic ? (*plastic)[r] : 0.0);  // "dissipation" is viscous + plastic
    const double contact = (wc ? (*wc)[r] : 0.0) - (fric ? (*fric)[r] : 0.0);
    error[r] = (*total)[r] - (*total)[0] - ((*ext)[r] + (*sup)[r] - (*dis)[r] + contact);
  }
  e.add("viscous_dissipation", std::move(viscous));
  e.add("balance_error", std::move(error));
  const bool c = wc != nullptr;
  const std::string balance = std::string("E - E_0 - (W_ext + W_sup") + (c ? " + W_contact" : "") + " - D" + (c ? " - D_friction" : "") + ")";
  std::string schemes;  // of the dynamic stages (the run's without stages)
  for (int k = 0; k < m.cfg.interval_count(); ++k)
    if (m.cfg.dynamic_in(k) && schemes.find(m.cfg.scheme_in(k)) == std::string::npos)
      schemes += (schemes.empty() ? "" : ", ") + m.cfg.scheme_in(k);
  const std::string law_dissipation = history_dissipation_label(m.cfg);
  PlotSpec s{"Energy balance (" + schemes + "): E = kinetic + strain, D = viscous + " +
                 (plastic ? law_dissipation : std::string("plastic dissipation")),
             with_unit("time", u.time), with_unit("energy", u.energy), "time", {}, true};
  s.curves = {{"kinetic", "kinetic energy", ""},
              {"strain", "strain energy", ""},
              {"total", "total energy E (kinetic + strain)", ""},
              {"external_work", "external work W_ext", ""},
              {"support_work", "support work W_sup (Dirichlet reactions)", ""},
              {"viscous_dissipation", "viscous dissipation", ""}};
  if (plastic) s.curves.push_back({"plastic_dissipation", law_dissipation, ""});
  if (wc) s.curves.push_back({"contact_work", "contact work W_contact", ""});
  if (fric) s.curves.push_back({"friction_dissipation", "frictional dissipation D_friction", ""});
  s.curves.push_back({"balance_error", "balance error " + balance, ""});
  if (plot_png(e, stem + "_energy.png", s, stage_marks(m.cfg))) made.push_back(stem + "_energy.png");
  const std::string per_step = std::string("E_{n+1} - E_n - (W_ext + W_sup") + (c ? " + W_contact" : "") + " - D" +
                               (c ? " - D_friction" : "") + ") of the step";
  PlotSpec b{"Energy balance residual per step (" + m.cfg.time.scheme + ")", with_unit("time", u.time),
             with_unit("balance residual", u.energy), "time", {{"balance_residual", per_step, ""}}, true};
  if (plot_png(e, stem + "_balance.png", b, stage_marks(m.cfg))) made.push_back(stem + "_balance.png");
}

// A metrics column as a legend: "lumen_radius_mean" -> "lumen radius, mean".
std::string metric_legend(const std::string& c) {
  static const std::pair<const char*, const char*> names[] = {
      {"lumen_radius_mean", "lumen radius, mean"}, {"lumen_radius_min", "lumen radius, minimum"},
      {"stent_radius_mean", "stent radius, mean"}, {"stent_radius_middle", "stent radius, middle"},
      {"stent_radius_ends", "stent radius, ends"}, {"artery_von_mises_max", "artery von Mises stress, maximum"},
      {"artery_hoop_stress_max", "artery hoop (circumferential) stress, maximum"},
      {"contact_pressure_max", "contact pressure, maximum"}, {"plaque_sigma1_max", "plaque, maximum"},
      {"plaque_sigma1_p99", "plaque, 99th percentile"}, {"intima_sigma1_max", "intima, maximum"},
      {"intima_sigma1_p99", "intima, 99th percentile"}, {"media_sigma1_max", "media, maximum"},
      {"media_sigma1_p99", "media, 99th percentile"}, {"adventitia_sigma1_max", "adventitia, maximum"},
      {"adventitia_sigma1_p99", "adventitia, 99th percentile"}};
  for (const auto& p : names)
    if (c == p.first) return p.second;
  std::string s = c;
  for (char& ch : s)
    if (ch == '_') ch = ' ';
  return s;
}

void metrics_plots(const Model& m, const std::string& stem, const UnitLabels& u, const std::vector<std::string>& radii,
                   const std::vector<std::string>& stresses, std::vector<std::string>& made) {
  PlotTable t;
  if ((radii.empty() && stresses.empty()) || !read_csv_table(stem + "_metrics.csv", t)) return;
  if (!radii.empty()) {
    PlotSpec r{"Lumen and stent radii", with_unit("time", u.time), with_unit("radius", u.length), "time", {}, true};
    for (const auto& c : radii) r.curves.push_back({c, metric_legend(c), ""});
    if (plot_png(t, stem + "_radii.png", r, stage_marks(m.cfg))) made.push_back(stem + "_radii.png");
  }
  if (stresses.empty()) return;
  // A stent deck with the artery around it: the layers' largest principal stresses.
  const bool layers = m.cfg.mesh.generator == "stent";
  PlotSpec s{layers ? "Artery wall: largest principal Cauchy stress per layer (maximum and 99th percentile of the cells)"
                    : "Artery wall stress, contact pressure",
             with_unit("time", u.time), with_unit("stress", u.stress), "time", {}, true};
  for (const auto& c : stresses) s.curves.push_back({c, metric_legend(c.substr(0, c.find(" ["))), ""});
  if (plot_png(t, stem + "_stresses.png", s, stage_marks(m.cfg))) made.push_back(stem + "_stresses.png");
}

// A generated stent's outer diameters against time, a dashed line where each stage ends.
void diameter_plot(const Model& m, const std::string& stem, const UnitLabels& u, const std::vector<std::string>& cols,
                   std::vector<std::string>& made) {
  PlotTable t;
  if (cols.empty() || !read_csv_table(stem + "_metrics.csv", t)) return;
  const bool lumen = std::any_of(cols.begin(), cols.end(), [](const std::string& c) { return c.rfind("lumen_", 0) == 0; });
  PlotSpec d{lumen ? "Stent outer and lumen diameters (stent: mean over the nodes, crowns: the crown sections; lumen: "
                     "over the stented segment)"
                   : "Stent outer diameters (mean over the nodes; crowns: the crown sections)",
             with_unit("time", u.time), with_unit(lumen ? "diameter" : "outer diameter", u.length), "time", {}, true};
  for (const auto& c : cols) {
    std::string legend = c.substr(0, c.find(" ["));
    for (char& ch : legend)
      if (ch == '_') ch = ' ';
    d.curves.push_back({c, legend, ""});
  }
  std::vector<PlotMark> marks = stage_marks(m.cfg);
  // The peak of the expansion as the metrics take it (RingMetrics): the largest mean
  // diameter since the smallest one so far; a stage's end at the same time gets the words.
  const int dm = t.find(cols.front()), tc = t.find("time");
  if (dm >= 0 && tc >= 0 && t.rows() > 0) {
    const auto& D = t.columns[static_cast<std::size_t>(dm)];
    std::size_t peak = 0, low = 0;
    for (std::size_t i = 1; i < D.size(); ++i) {
      if (RingMetrics::new_smallest(D[i], D[low])) low = peak = i;
      else if (D[i] > D[peak]) peak = i;
    }
    const auto& time = t.columns[static_cast<std::size_t>(tc)];
    const double tp = time[peak], tol = 1e-9 * std::max(1.0, std::fabs(time.back()));
    auto at = std::find_if(marks.begin(), marks.end(), [&](const PlotMark& k) { return std::fabs(k.x - tp) <= tol; });
    if (at != marks.end())
      at->label += ", peak of the expansion";
    else
      marks.push_back({tp, "peak of the expansion"});
  }
  if (plot_png(t, stem + "_diameters.png", d, marks)) made.push_back(stem + "_diameters.png");
}

// A generated stent expanded by a pressure load (a deformable balloon's inflation): its
// outer diameters against the pressure (history column pressure_<load>, matched by step;
// `h` with its t = 0 row), loading and unloading (the compliance chart), over the stages
// where the load is on.
void pressure_diameter_plots(const Model& m, const PlotTable& h, const std::string& stem, const UnitLabels& u,
                             const std::vector<std::string>& cols, std::vector<std::string>& made) {
  PlotTable metrics;
  if (cols.empty() || h.find("step") < 0 || !read_csv_table(stem + "_metrics.csv", metrics) || metrics.find("step") < 0) return;
  const auto& hs = h.columns[static_cast<std::size_t>(h.find("step"))];
  for (const LoadConfig& l : m.cfg.loads) {
    const int pc = h.find("pressure_" + l.name);
    if ((l.type != LoadConfig::Type::Pressure && l.type != LoadConfig::Type::FluidCavity) || pc < 0) continue;
    std::map<long, double> at_step;
    for (std::size_t r = 0; r < hs.size(); ++r) at_step[std::lround(hs[r])] = h.columns[static_cast<std::size_t>(pc)][r];
    PlotTable t = metrics;
    std::vector<double> p;
    const auto& steps = t.columns[static_cast<std::size_t>(t.find("step"))];
    const int tc = t.find("time");
    for (std::size_t r = 0; r < steps.size(); ++r) {
      const auto it = at_step.find(std::lround(steps[r]));
      // Not in a stage that switches the load off (a crimp before it, a release after it).
      const bool on = tc < 0 || l.ramp.on(t.columns[static_cast<std::size_t>(tc)][r]);
      p.push_back(it == at_step.end() || !on ? std::nan("") : it->second);
    }
    t.add("pressure", std::move(p));
    PlotSpec d{"Pressure-diameter curve of '" + l.name + "': stent outer diameters against the pressure",
               with_unit("pressure", u.stress), with_unit("outer diameter", u.length), "pressure", {}, true};
    for (const auto& c : cols) d.curves.push_back({c, metric_legend(c), ""});
    const std::string png = stem + "_pressure_diameter_" + file_part(l.name) + ".png";
    if (plot_png(t, png, d)) made.push_back(png);
  }
}

}  // namespace

bool deck_at_rest_unloaded(const Model& m) {
  const Config& c = m.cfg;
  const double T = c.stepping.end_time;
  const bool dynamic0 = c.dynamic_in(0);  // initial conditions belong to a dynamic first stage
  if (dynamic0)
    for (int k = 0; k < 3; ++k)
      if (c.initial.displacement[k] != 0.0 || c.initial.velocity[k] != 0.0 || c.initial.angular_velocity[k] != 0.0) return false;
  for (const BodyConfig& b : c.bodies)
    if (dynamic0)
      for (int k = 0; k < 3; ++k)
        if (b.velocity[k] != 0.0 || b.angular_velocity[k] != 0.0 || b.displacement[k] != 0.0) return false;
  for (const LoadConfig& l : c.loads) {
    if (l.ramp(0.0, T) == 0.0) continue;
    if (l.field) return false;
    if (l.value != 0.0) return false;
    for (double v : l.vector)
      if (v != 0.0) return false;
  }
  return true;
}

std::vector<std::string> write_result_plots(const Model& m, const std::string& stem, const InitialState& init,
                                            const std::vector<std::string>& radius_columns,
                                            const std::vector<std::string>& stress_columns,
                                            const std::vector<std::string>& diameter_columns) {
  std::vector<std::string> made;
  const auto& systems = unit_systems();  // a Config built in code may hold any string
  const bool known = std::find(systems.begin(), systems.end(), m.cfg.problem.units) != systems.end();
  if (!known) std::cerr << "plots: unknown Problem->units '" << m.cfg.problem.units << "', plots without units\n";
  const UnitLabels u = unit_labels(known ? m.cfg.problem.units : "none", m.dim, m.cfg.problem.axisymmetric());
  PlotTable h;
  if (read_csv_table(stem + "_history.csv", h) && h.find("time") >= 0 && h.rows() > 0) {
    prepend_initial_row(h, m, init);
    reaction_plots(m, h, stem, u, made);
    history_plots(m, h, stem, u, made);
  }
  if (m.any_dynamic) energy_plots(m, stem, u, made);
  metrics_plots(m, stem, u, radius_columns, stress_columns, made);
  diameter_plot(m, stem, u, diameter_columns, made);
  pressure_diameter_plots(m, h, stem, u, diameter_columns, made);
  return made;
}

}  // namespace stentor
