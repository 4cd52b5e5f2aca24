// The deck reader's Stages: a procedure of consecutive intervals, each load's and
// obstacle's ramp one Ramp::Piece per stage (deck/DeckReader.hpp).
#include "deck/DeckReader.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <sstream>

#include "deck/InputLimits.hpp"
#include "deck/MeshParameters.hpp"
#include "deck/OutputFields.hpp"
#include "material/ElasticConstants.hpp"
#include "stentor/format.hpp"

namespace stentor::deck_reader {

// ------------------------------------------------------------------------------------
// Stages: a procedure of consecutive intervals. Each load's and obstacle's ramp becomes
// one Ramp::Piece per stage (stage-local time; held or off where not active).

std::vector<bool> DeckReader::read_active(const ParameterList& sub, const std::string& path, const std::string& key,
                                          const std::vector<std::string>& names, const std::string& what) const {
  const ListSpec& ls = deck_list_spec("Stages/*");
  const std::string text = get_string(sub, ls, key), kpath = path + "->" + key;
  if (lower(trim(text)) == "all") return std::vector<bool>(names.size(), true);
  std::vector<bool> active(names.size(), false);
  if (lower(trim(text)) == "none") return active;
  std::stringstream ss(text);
  std::string item;
  while (std::getline(ss, item, ',')) {
    const std::string n = trim(item);
    if (n.empty()) fail(quoted(kpath) + " must be 'all', 'none' or names separated by commas; got '" + text + "'");
    const auto it = std::find(names.begin(), names.end(), n);
    if (it == names.end()) {
      std::string msg = quoted(kpath) + " names undefined " + what + " '" + n + "'; defined: " + (names.empty() ? "(none)" : join(names));
      const std::string near = nearest_name(n, names);
      if (!near.empty()) msg += "; did you mean '" + near + "'?";
      fail(msg);
    }
    const auto i = static_cast<std::size_t>(it - names.begin());
    if (active[i]) fail(quoted(kpath) + " lists '" + n + "' twice");
    active[i] = true;
  }
  return active;
}

namespace {
Ramp::Piece piece_of(const Ramp& r, const StageConfig& st) {
  Ramp::Piece p;
  p.start = st.start;
  p.end = st.end;
  p.kind = r.kind;
  p.times = r.times;
  p.factors = r.factors;
  return p;
}
// The factor at the end of a piece.
double end_value(const Ramp::Piece& p) {
  Ramp r;
  r.stages = {p};
  return r(p.end, p.end);
}
}  // namespace

// "Ramps" of stage k: ramp overrides (stage-local time) of active loads and obstacles,
// written into the k-th piece of their ramps.
void DeckReader::read_stage_ramps(const ParameterList& sub, const std::string& path, std::size_t k) {
  const ListSpec& ls = deck_list_spec("Stages/*/Ramps/*");
  const StageConfig& st = cfg_.stages[k];
  check_list(sub, path, {&deck_list_spec("Stages/*/Ramps")});
  for (auto it = sub.begin(); it != sub.end(); ++it) {
    const std::string& name = sub.name(it);
    const std::string p = path + "->" + name;
    const ParameterList& r = sub.sublist(name);
    check_list(r, p, {&ls});
    int load = -1, pair = -1;
    for (std::size_t i = 0; i < cfg_.loads.size(); ++i)
      if (cfg_.loads[i].name == name) load = static_cast<int>(i);
    for (std::size_t i = 0; i < cfg_.contact.size(); ++i)
      if (cfg_.contact[i].name == name) pair = static_cast<int>(i);
    if (load < 0 && pair < 0) fail(quoted(p) + ": no load ('Boundary Conditions') or contact pair ('Contact') is named '" + name + "'");
    if (load >= 0 && pair >= 0) fail(quoted(p) + ": '" + name + "' names both a load and a contact pair; rename one");
    auto uses = [&](const std::vector<std::string>& keys) {
      for (const auto& key : keys)
        if (r.isParameter(key)) return key;
      return std::string();
    };
    const std::vector<std::string> load_keys = {"ramp", "ramp times", "ramp factors"};
    const std::vector<std::string> obstacle_keys = {"translation ramp", "translation ramp times", "translation ramp factors",
                                                    "radius ramp", "radius ramp times", "radius ramp factors"};
    if (load >= 0) {
      if (!st.load_active[static_cast<std::size_t>(load)])
        fail(quoted(p) + ": load '" + name + "' is not active in this stage (see 'Stages->" + st.name + "->loads')");
      if (const std::string bad = uses(obstacle_keys); !bad.empty()) fail(quoted(p + "->" + bad) + " belongs to a contact obstacle, '" + name + "' is a load");
      if (uses(load_keys).empty()) continue;
      Ramp& ramp = cfg_.loads[static_cast<std::size_t>(load)].ramp;
      const Ramp over = read_ramp(r, p, ls, "ramp");
      ramp.stages[k] = piece_of(over, st);
    } else {
      ContactPairConfig& c = cfg_.contact[static_cast<std::size_t>(pair)];
      if (!st.contact_active[static_cast<std::size_t>(pair)])
        fail(quoted(p) + ": contact pair '" + name + "' is not active in this stage (see 'Stages->" + st.name + "->contact')");
      if (const std::string bad = uses(load_keys); !bad.empty()) fail(quoted(p + "->" + bad) + " belongs to a load, '" + name + "' is a contact pair (use 'translation ramp' or 'radius ramp')");
      if (c.obstacle.empty()) fail(quoted(p) + ": contact pair '" + name + "' has a deformable master and no obstacle to program");
      if (r.isParameter("translation ramp") || r.isParameter("translation ramp times") || r.isParameter("translation ramp factors"))
        c.translation_ramp.stages[k] = piece_of(read_ramp(r, p, ls, "translation ramp"), st);
      if (r.isParameter("radius ramp") || r.isParameter("radius ramp times") || r.isParameter("radius ramp factors")) {
        if (c.obstacle == "plane") fail(quoted(p + "->radius ramp") + " is not used by a plane obstacle");
        c.radius_ramp.stages[k] = piece_of(read_ramp(r, p, ls, "radius ramp"), st);
      }
    }
  }
}

// A stage's analysis and scheme (defaults: Problem->analysis, Time Integration->scheme),
// and the contact pairs that need a dynamic stage.
void DeckReader::read_stage_analysis(const ParameterList& sub, const std::string& path, StageConfig& st) {
  const ListSpec& ls = deck_list_spec("Stages/*");
  st.analysis = sub.isParameter("analysis") ? get_string(sub, ls, "analysis") : cfg_.problem.analysis;
  st.scheme = cfg_.time.scheme;
  if (sub.isParameter("scheme")) {
    if (!st.dynamic())
      fail(quoted(path + "->scheme") + " is the time scheme of a dynamic stage, and the stage is static; set " +
           quoted(path + "->analysis") + " = dynamic or remove 'scheme'");
    st.scheme = get_string(sub, ls, "scheme");
  }
  st.stabilization = st.dynamic() ? 0.0 : cfg_.stepping.stabilization;
  if (sub.isParameter("stabilization")) {
    if (st.dynamic())
      fail(quoted(path + "->stabilization") + " stabilises static steps, and the stage is dynamic (inertia already "
           "holds its bodies); remove it or set " + quoted(path + "->analysis") + " = static");
    st.stabilization = get_double(sub, ls, "stabilization");
  }
  if (st.dynamic()) return;
  for (std::size_t i = 0; i < cfg_.contact.size(); ++i)
    if (st.contact_active[i] && cfg_.contact[i].formulation == "persistence")
      fail(quoted("Contact->" + cfg_.contact[i].name + "->formulation") + " = persistence needs a dynamic analysis, and the pair is active in the static stage " +
           quoted(path) + "; use gap or auto (gap in static stages), or leave the pair out of the stage's 'contact'");
}

// What the analysis asks of the rest of the deck, once the stages (each with its own
// analysis and scheme) are known.
void DeckReader::check_analysis(bool initial_conditions, bool time_integration) {
  const bool staged = !cfg_.stages.empty();
  // Two pairs may share a slave group (a stent's outer surface: the crimper's, then the
  // lumen's) only when no stage activates both.
  for (std::size_t i = 0; i < cfg_.contact.size(); ++i)
    for (std::size_t j = 0; j < i; ++j) {
      const ContactPairConfig &a = cfg_.contact[j], &b = cfg_.contact[i];
      const StageConfig* st = nullptr;
      if (a.slave == b.slave && cfg_.pairs_meet(i, j, &st))
        fail("'Contact->" + a.name + "' and 'Contact->" + b.name + "' both use slave group '" + a.slave + "' and " +
             (st ? "stage 'Stages->" + st->name + "' activates both" : std::string("without 'Stages' every pair is active throughout")) +
             "; a node may be a slave of two pairs only when no stage activates both");
    }
  for (int k = 0; k < cfg_.interval_count(); ++k) {
    if (cfg_.analysis_in(k) != "midpoint") continue;
    for (const auto& m : cfg_.materials)
      if (m.has_history())  // the element kernels have no midpoint evaluation of a law with history
        fail("'Materials->" + m.name + "->model' = " + m.model + " needs " +
             (staged ? quoted("Stages->" + cfg_.stages[static_cast<std::size_t>(k)].name + "->scheme") : std::string("'Time Integration->scheme'")) +
             " = gonzalez (energy-dissipative), newmark or hht, not midpoint");
  }
  if (cfg_.any_dynamic()) {
    for (const auto& b : cfg_.bodies)
      if (b.fbar())  // the energy-consistent schemes need Delta C linear in the step's displacement increment
        fail(quoted("Bodies->" + b.name + "->element technology") + " = f-bar is for static analysis only; " +
             (staged ? std::string("a stage has 'analysis' = dynamic") : std::string("'Problem->analysis' = dynamic")) +
             " (use 'full')");
    for (const auto& m : cfg_.materials)
      if (!(m.density > 0.0))
        fail("'Materials->" + m.name + "->density' must be > 0 in a dynamic analysis (" +
             (staged ? std::string("a stage has 'analysis' = dynamic") : std::string("'Problem->analysis' = dynamic")) + ")");
  }
  for (int k = 0; k < cfg_.interval_count(); ++k) {
    if (!cfg_.dynamic_in(k)) continue;
    for (std::size_t i = 0; i < cfg_.loads.size(); ++i)
      if (cfg_.loads[i].type == LoadConfig::Type::FluidCavity && (!staged || cfg_.stages[static_cast<std::size_t>(k)].load_active[i]))
        fail(quoted("Boundary Conditions->" + cfg_.loads[i].name) + ": a fluid cavity is for static analysis only, and " +
             (staged ? "the dynamic stage " + quoted("Stages->" + cfg_.stages[static_cast<std::size_t>(k)].name) + " activates it"
                     : std::string("'Problem->analysis' = dynamic")) +
             " (its work is not in the energy audit); use a `pressure` load there, or a static stage");
  }
  if (!cfg_.dynamic_in(0))
    for (const auto& b : cfg_.bodies)
      if (b.own_velocity() || b.has_displacement)
        fail(quoted("Bodies->" + b.name + (b.has_velocity ? "->initial velocity" : b.has_angular_velocity ? "->initial angular velocity" : "->initial displacement")) +
             " needs " + (staged ? "the first stage " + quoted("Stages->" + cfg_.stages.front().name) + " to be dynamic (a static stage starts at rest)"
                                 : std::string("'Problem->analysis' = dynamic (a static analysis has no initial state)")));
  if (initial_conditions && !cfg_.dynamic_in(0))
    fail(staged ? "'Initial Conditions' needs the first stage " + quoted("Stages->" + cfg_.stages.front().name) +
                      " to be dynamic (a static stage starts at rest)"
                : std::string("'Initial Conditions' needs 'Problem->analysis' = dynamic (a static analysis has no velocity)"));
  if (time_integration && !cfg_.any_dynamic())
    fail(staged ? std::string("'Time Integration' needs a dynamic stage ('analysis' = dynamic in a stage or in 'Problem')")
                : std::string("'Time Integration' needs 'Problem->analysis' = dynamic"));
}

void DeckReader::read_stages(const ParameterList& pl, const ParameterList* stepping) {
  const ListSpec& ls = deck_list_spec("Stages/*");
  check_list(pl, "Stages", {&deck_list_spec("Stages")});
  if (stepping)
    for (const char* k : {"end time", "steps"})
      if (stepping->isParameter(k))
        fail(std::string("'Stepping->") + k + "' is not used with 'Stages' (each stage has its own duration and steps); remove it");
  std::vector<std::string> load_names, pair_names;
  for (const auto& l : cfg_.loads) load_names.push_back(l.name);
  for (const auto& c : cfg_.contact) pair_names.push_back(c.name);
  double t = 0.0;
  long long total = 0;
  for (auto it = pl.begin(); it != pl.end(); ++it) {
    const std::string& name = pl.name(it);
    const std::string path = "Stages->" + name;
    check_safe_name(name, path, "the stage name");
    const ParameterList& sub = pl.sublist(name);
    check_list(sub, path, {&ls});
    StageConfig st;
    st.name = name;
    st.start = t;
    const bool has_d = sub.isParameter("duration"), has_e = sub.isParameter("end time");
    if (has_d == has_e) fail(quoted(path) + " needs exactly one of 'duration' and 'end time'" + (has_d ? ", not both" : ""));
    st.end = has_d ? t + get_double(sub, ls, "duration") : get_double(sub, ls, "end time");
    if (!(st.end > t)) fail(quoted(path + "->end time") + " must be after the previous stage's end " + num(t) + ", got " + num(st.end));
    if (!std::isfinite(st.end) || st.end > 1e300)
      fail(quoted(path) + ": the stage ends at " + num(st.end) + " (the previous end " + num(t) + " plus its duration); the procedure's "
           "times must stay finite, at most 1e300 s");
    if (sub.isParameter("steps") && sub.isParameter("step")) fail(quoted(path) + " takes 'steps' or 'step', not both");
    st.num_steps = get_int(sub, ls, "steps");
    if (sub.isParameter("step")) {
      const double n = std::ceil((st.end - st.start) / get_double(sub, ls, "step") * (1.0 - 1e-12));
      if (n > 1e7) fail(quoted(path + "->step") + " gives more than 1e7 steps");
      st.num_steps = std::max(1, static_cast<int>(n));
    }
    check_step(st.step(), st.end, "the step of stage " + quoted(path));
    if (cfg_.stepping.min_dt > st.step())
      fail("'Stepping->min dt' = " + num(cfg_.stepping.min_dt) + " exceeds the step " + num(st.step()) + " of stage " + quoted(path));
    st.load_active = read_active(sub, path, "loads", load_names, "load");
    st.contact_active = read_active(sub, path, "contact", pair_names, "contact pair");
    read_stage_analysis(sub, path, st);
    cfg_.stages.push_back(st);
    const std::size_t k = cfg_.stages.size() - 1;
    // Default pieces: the deck's ramp in stage-local time where active, else held
    // (Dirichlet values, obstacle motion) or off (forces).
    for (std::size_t i = 0; i < cfg_.loads.size(); ++i) {
      Ramp& r = cfg_.loads[i].ramp;
      Ramp::Piece p = piece_of(r, st);
      if (!st.load_active[i]) p.mode = cfg_.loads[i].type == LoadConfig::Type::Dirichlet ? Ramp::Piece::Mode::Hold : Ramp::Piece::Mode::Off;
      r.stages.push_back(p);
    }
    for (auto& c : cfg_.contact) {
      c.translation_ramp.stages.push_back(piece_of(c.translation_ramp, st));
      c.radius_ramp.stages.push_back(piece_of(c.radius_ramp, st));
      if (!st.contact_active[static_cast<std::size_t>(&c - cfg_.contact.data())]) {
        c.translation_ramp.stages.back().mode = Ramp::Piece::Mode::Hold;
        c.radius_ramp.stages.back().mode = Ramp::Piece::Mode::Hold;
      }
    }
    if (sub.isSublist("Ramps")) read_stage_ramps(sub.sublist("Ramps"), path + "->Ramps", k);
    t = st.end;
    total += st.num_steps;
    if (total > kMaxTotalSteps)
      fail("the stages up to " + quoted(path) + " take " + std::to_string(total) + " steps in all; at most " +
           std::to_string(kMaxTotalSteps) + " (the step counter's range): use fewer steps or larger 'step's");
  }
  if (cfg_.stages.empty()) fail("'Stages' defines no stage; add one sublist per stage or remove 'Stages'");
  // Held values: the factor at the end of the stage before (0 before the first).
  auto fill_held = [](Ramp& r) {
    double prev = 0.0;
    for (auto& p : r.stages) {
      if (p.mode == Ramp::Piece::Mode::Hold) p.held = prev;
      prev = p.mode == Ramp::Piece::Mode::Off ? 0.0 : end_value(p);
    }
  };
  for (auto& l : cfg_.loads) fill_held(l.ramp);
  for (auto& c : cfg_.contact) {
    fill_held(c.translation_ramp);
    fill_held(c.radius_ramp);
  }
  cfg_.stepping.end_time = t;
  cfg_.stepping.num_steps = static_cast<int>(total);
}

}  // namespace stentor::deck_reader
