#include "run/CheckpointCheck.hpp"

#include <climits>
#include <cmath>
#include <limits>
#include <sstream>
#include <vector>

#include "contact/MasterSurface.hpp"
#include "contact/NodeLaw.hpp"
#include "run/Model.hpp"
#include "stentor/format.hpp"

namespace stentor {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// A scalar's range: /ints/<name> or /reals/<name> within [lo, hi]; `required`: a
// checkpoint without it is incomplete (optional ones are checked when present).
struct Rule {
  const char* name;
  bool integer, required;
  double lo, hi;
};

std::vector<Rule> scalar_rules(const Model& m) {
  const double end = m.cfg.stepping.end_time, pos = std::numeric_limits<double>::denorm_min();
  const double big = static_cast<double>(INT_MAX);  // counters the run keeps in int
  return {
      {"dim", true, true, 1, 3},
      {"num_nodes", true, true, 0, 1e15},
      {"num_cells", true, true, 0, 1e15},
      {"num_stages", true, true, 0, 1e7},
      {"ranks", true, true, 1, big},
      {"step", true, true, 0, big - 1},
      {"attempts", true, true, 0, 9e15},
      {"stage", true, true, 0, static_cast<double>(m.cfg.interval_count() - 1)},
      {"cuts_in_a_row", true, true, 0, big},
      {"cuts_total", true, true, 0, big},
      {"newton_iterations", true, true, 0, big},
      {"linear_iterations", true, true, 0, big},
      {"force_scale_count", true, true, 0, 9e15},
      {"time", false, true, 0, end * (1 + 1e-9)},
      {"dt_last", false, true, 0, end},
      {"dt_target", false, true, pos, end},
      {"dt_next", false, true, pos, kInf},
      {"dt_min", false, true, pos, kInf},
      {"energy_max_balance", false, true, 0, kInf},
      {"contact_dt_last", false, false, 0, kInf},
  };
}

std::string num(double v) { return format_number(v, 10); }

std::string check_scalars(const Model& m, const CheckpointData& d, const std::string& path) {
  for (const Rule& r : scalar_rules(m)) {
    const std::string where = path + ": /" + (r.integer ? "ints/" : "reals/") + r.name;
    double v = 0.0;
    if (r.integer) {
      const auto it = d.ints.find(r.name);
      if (it == d.ints.end()) { if (r.required) return where + " is missing"; continue; }
      v = static_cast<double>(it->second);
    } else {
      const auto it = d.reals.find(r.name);
      if (it == d.reals.end()) { if (r.required) return where + " is missing"; continue; }
      v = it->second;
    }
    if (!(v >= r.lo && v <= r.hi))
      return where + " = " + num(v) + " is out of range: expected " +
             (r.lo > 0 && r.lo < 1e-300 ? "more than 0" : num(r.lo)) + (r.hi == kInf ? "" : " to " + num(r.hi));
  }
  if (d.ints.at("attempts") < d.ints.at("step"))
    return path + ": /ints/attempts = " + std::to_string(d.ints.at("attempts")) + " is less than /ints/step = " +
           std::to_string(d.ints.at("step"));
  if (!m.cfg.stages.empty()) {  // the time lies in the stage's interval [start, end]
    const StageConfig& st = m.cfg.stages[static_cast<std::size_t>(d.ints.at("stage"))];
    const double t = d.reals.at("time"), tol = 1e-9 * std::max(1.0, std::abs(st.end));
    if (t < st.start - tol || t > st.end + tol)
      return path + ": /reals/time = " + num(t) + " is not in stage " + std::to_string(d.ints.at("stage")) + " ('" + st.name +
             "', " + num(st.start) + " to " + num(st.end) + ")";
  }
  for (const auto& [name, v] : d.reals)  // the stent metrics' state (Reporter::metrics_state)
    if (name.rfind("metrics_", 0) == 0 && !std::isfinite(v)) return path + ": /reals/" + name + " = " + num(v) + " is not finite";
  return "";
}

// The id range of a table's rows and its column count (0: any).
struct TableKind {
  long long ids = 0;
  int cols = 0;
};

TableKind table_kind(const Model& m, const std::string& name) {
  const auto nodes = static_cast<long long>(m.mesh.num_nodes());
  if (name.rfind("gauss_points_", 0) == 0) return {static_cast<long long>(m.mesh.num_volume_cells()), 0};
  if (name.rfind("contact_", 0) == 0) return {nodes, Contact::kHistoryValues};
  return {nodes, m.dim};  // u, u_before_last and the time scheme's vectors
}

// Contact history rows (Contact::restore_step_history): the state a contact state, the two
// master facets -1 (none) or a facet of the pair's master surface (rigid: -1 or 0), the
// flags 0 or 1.
std::string check_contact_rows(const Model& m, const std::string& name, const CheckpointTable& t, const std::string& path) {
  const std::string pair = name.substr(8);
  long long facets = 1;
  for (const ContactPairConfig& c : m.cfg.contact)
    if (c.name == pair && !c.master.empty()) facets = static_cast<long long>(MasterSurface(m.mesh, c.master, "'Contact->" + c.name + "->master'").facets().size());
  const auto whole = [](double v, double lo, double hi) { return v == std::floor(v) && v >= lo && v <= hi; };
  for (std::size_t i = 0; i < t.ids.size(); ++i) {
    const double* v = &t.values[i * Contact::kHistoryValues];
    const char* bad = !whole(v[2], 0, 1) ? "column 2 (active) is not 0 or 1"
                      : !whole(v[3], contact::NotSlave, contact::Slip) ? "column 3 (state) is not a contact state"
                      : !whole(v[4], -1, static_cast<double>(facets - 1)) ? "column 4 (previous master facet) is not a facet of the master"
                      : !(v[5] >= 0) ? "column 5 (stiffness scale) is negative"
                      : !whole(v[6], -1, static_cast<double>(facets - 1)) ? "column 6 (master facet) is not a facet of the master"
                      : !whole(v[7], 0, 1) ? "column 7 (inside) is not 0 or 1" : nullptr;
    if (bad) return path + ": /tables/" + name + "/values, node " + std::to_string(t.ids[i]) + ": " + bad;
  }
  return "";
}

std::string check_tables(const Model& m, const CheckpointData& d, const std::string& path) {
  for (const auto& [name, t] : d.tables) {
    const TableKind k = table_kind(m, name);
    if (k.cols > 0 && t.ncols != k.cols)
      return path + ": /tables/" + name + "/values has " + std::to_string(t.ncols) + " columns, expected " + std::to_string(k.cols);
    if (!t.ids.empty() && t.ids.back() >= k.ids)
      return path + ": /tables/" + name + "/ids: id " + std::to_string(t.ids.back()) + " is not below " + std::to_string(k.ids) +
             (name.rfind("gauss_points_", 0) == 0 ? ", the mesh's cell count" : ", the mesh's node count");
    if (name.rfind("contact_", 0) == 0) {
      const std::string bad = check_contact_rows(m, name, t, path);
      if (!bad.empty()) return bad;
    }
  }
  return "";
}

}  // namespace

std::string checkpoint_problem(const Model& m, const CheckpointData& d, const std::string& path) {
  const std::string bad = check_scalars(m, d, path);
  return bad.empty() ? check_tables(m, d, path) : bad;
}

}  // namespace stentor
