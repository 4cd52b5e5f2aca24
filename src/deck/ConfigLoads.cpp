// The deck reader's sections of the procedure: ramps, Contact, Loads, Initial Conditions,
// Time Integration, Stepping, Newton, Linear Solver and Output (deck/DeckReader.hpp).
#include "deck/DeckReader.hpp"

#include <Teuchos_XMLParameterListCoreHelpers.hpp>

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

Ramp DeckReader::read_ramp(const ParameterList& pl, const std::string& path, const ListSpec& ls, const std::string& key) const {
  Ramp r;
  const std::string kt = key + " times", kf = key + " factors";
  const std::string kind = get_string(pl, ls, key);
  const bool has_t = pl.isParameter(kt), has_f = pl.isParameter(kf);
  if (kind != "table") {
    r.kind = kind == "constant" ? Ramp::Kind::Constant : Ramp::Kind::Linear;
    if (has_t || has_f)
      fail(quoted(path + "->" + (has_t ? kt : kf)) + " is only used with \"" + key + "\" = table (" + key + " is " + kind + ")");
    return r;
  }
  r.kind = Ramp::Kind::Table;
  if (!has_t) fail("missing required parameter " + quoted(path + "->" + kt) + " (Array(double)) for \"" + key + "\" = table");
  if (!has_f) fail("missing required parameter " + quoted(path + "->" + kf) + " (Array(double)) for \"" + key + "\" = table");
  r.times = get_array(pl, ls, kt);
  r.factors = get_array(pl, ls, kf);
  if (r.times.size() != r.factors.size())
    fail(quoted(path + "->" + kf) + " must have as many values as '" + kt + "' (" + std::to_string(r.times.size()) + "), got " +
         std::to_string(r.factors.size()));
  for (std::size_t i = 1; i < r.times.size(); ++i)
    if (!(r.times[i] > r.times[i - 1]))
      fail(quoted(path + "->" + kt) + " must be strictly increasing, got " + num(r.times[i - 1]) + " then " + num(r.times[i]) +
           " at positions " + std::to_string(i) + ", " + std::to_string(i + 1));
  return r;
}

// "axis" (cylinder: 3 values; capsule: one per dimension) and "length" (capsule).
void DeckReader::read_obstacle_axis(const ParameterList& sub, const std::string& path, const ListSpec& ls, ContactPairConfig& c) {
  const bool cyl = c.obstacle == "cylinder", cap = c.obstacle == "capsule";
  if (!cyl && !cap) {
    if (sub.isParameter("axis")) fail(quoted(path + "->axis") + " is only used by cylinder and capsule obstacles");
    if (sub.isParameter("length")) fail(quoted(path + "->length") + " is only used by a capsule obstacle");
    return;
  }
  if (!sub.isParameter("axis"))
    fail("missing required parameter " + quoted(path + "->axis") + " (Array(double), " + (cyl ? "3 values" : "one value per dimension") +
         ") for a " + c.obstacle + " obstacle");
  const auto a = get_array(sub, ls, "axis");
  c.axis_len = static_cast<int>(a.size());
  if (cyl && a.size() != 3) fail(quoted(path + "->axis") + " must have 3 values for a cylinder obstacle, got " + std::to_string(a.size()));
  if (cap && c.axis_len != c.point_len)
    fail(quoted(path + "->axis") + " must have as many values as 'point' (" + std::to_string(c.point_len) + ")");
  for (std::size_t k = 0; k < a.size(); ++k) c.axis[k] = a[k];
  unit_direction(c.axis, path + "->axis");
  if (cyl) {
    if (sub.isParameter("length")) fail(quoted(path + "->length") + " is only used by a capsule obstacle");
    return;
  }
  if (!sub.isParameter("length")) fail("missing required parameter " + quoted(path + "->length") + " (double, >= 0) for a capsule obstacle");
  c.length = get_double(sub, ls, "length");
}

void DeckReader::read_contact_obstacle(const ParameterList& sub, const std::string& path, const ListSpec& ls, ContactPairConfig& c) {
  c.obstacle = get_string(sub, ls, "obstacle");
  if (c.obstacle != "plane" && c.obstacle != "circle" && c.obstacle != "cylinder" && c.obstacle != "sphere" && c.obstacle != "capsule")
    fail(quoted(path + "->obstacle") + " must be one of 'plane', 'circle', 'cylinder', 'sphere', 'capsule', got '" + c.obstacle + "'");
  const bool curved = c.obstacle != "plane";
  auto vec = [&](const std::string& key, std::array<double, 3>& out, int& len) {
    const auto v = get_array(sub, ls, key);
    check_dim_length(v, path + "->" + key);
    len = static_cast<int>(v.size());
    for (std::size_t k = 0; k < v.size(); ++k) out[k] = v[k];
  };
  if (!sub.isParameter("point")) fail("missing required parameter " + quoted(path + "->point") + " (Array(double)) for an obstacle");
  vec("point", c.point, c.point_len);
  const int dim = cfg_.mesh.dimension;
  if (c.obstacle == "plane") {
    if (!sub.isParameter("normal")) fail("missing required parameter " + quoted(path + "->normal") + " (Array(double)) for a plane obstacle");
    vec("normal", c.normal, c.normal_len);
    unit_direction(c.normal, path + "->normal");
    if (c.normal_len != c.point_len)
      fail(quoted(path + "->normal") + " must have as many values as 'point' (" + std::to_string(c.point_len) + ")");
    for (const char* k : {"radius", "radius change", "axis", "side", "length"})
      if (sub.isParameter(k)) fail(quoted(path + "->" + k) + " is not used by a plane obstacle");
  } else {
    if (!sub.isParameter("radius"))
      fail("missing required parameter " + quoted(path + "->radius") + " (double, > 0) for a " + c.obstacle + " obstacle");
    c.radius = get_double(sub, ls, "radius");
    c.side = get_string(sub, ls, "side");
    if (sub.isParameter("normal")) fail(quoted(path + "->normal") + " is only used by a plane obstacle");
    if (c.obstacle == "circle" && (dim == 3 || c.point_len == 3))
      fail(quoted(path + "->obstacle") + " = circle is 2D only; use cylinder or sphere in 3D");
    if ((c.obstacle == "cylinder" || c.obstacle == "sphere") && (dim == 2 || c.point_len == 2))
      fail(quoted(path + "->obstacle") + " = " + c.obstacle + " is 3D only; use circle in 2D" +
           (cfg_.problem.axisymmetric() ? std::string(" (in axisymmetry a cylinder about the axis is a `plane` with normal (1, 0) or "
                                                      "(-1, 0), a sphere a `circle` centred on the axis, a balloon a `capsule` along it)")
                                        : std::string("")));
    read_obstacle_axis(sub, path, ls, c);
  }
  int tl = 0;
  if (sub.isParameter("translation")) {
    vec("translation", c.translation, tl);
    if (tl != c.point_len) fail(quoted(path + "->translation") + " must have as many values as 'point' (" + std::to_string(c.point_len) + ")");
  }
  c.translation_ramp = read_ramp(sub, path, ls, "translation ramp");
  c.radius_change = get_double(sub, ls, "radius change");
  c.radius_ramp = read_ramp(sub, path, ls, "radius ramp");
  if (!curved && (sub.isParameter("radius ramp") || sub.isParameter("radius ramp times")))
    fail(quoted(path + "->radius ramp") + " is not used by a plane obstacle");
}

void DeckReader::read_contact(const ParameterList& pl) {
  const ListSpec& top = deck_list_spec("Contact");
  const ListSpec& ls = deck_list_spec("Contact/*");
  check_list(pl, "Contact", {&top});
  for (auto it = pl.begin(); it != pl.end(); ++it) {
    const std::string& name = pl.name(it);
    const std::string path = "Contact->" + name;
    check_safe_name(name, path, "the contact pair name");
    const ParameterList& sub = pl.sublist(name);
    check_list(sub, path, {&ls});
    require(sub, path, {&ls});
    ContactPairConfig c;
    c.name = name;
    c.slave = get_string(sub, ls, "slave");
    if (c.slave.empty()) fail(quoted(path + "->slave") + " must name a boundary physical group");
    const bool has_obstacle = sub.isParameter("obstacle"), has_master = sub.isParameter("master");
    if (has_obstacle == has_master)
      fail(quoted(path) + " needs exactly one of 'obstacle' (a rigid analytic surface) and 'master' (a boundary group of a "
           "deformable body)" + (has_obstacle ? std::string(", not both") : std::string("")));
    if (has_master) {
      c.master = get_string(sub, ls, "master");
      if (c.master.empty()) fail(quoted(path + "->master") + " must name a boundary physical group");
      if (c.master == c.slave) fail(quoted(path + "->master") + " names the slave group '" + c.slave + "'; self-contact is not supported");
      for (const char* k : {"point", "normal", "axis", "length", "radius", "side", "translation", "translation ramp", "translation ramp times",
                            "translation ramp factors", "radius change", "radius ramp", "radius ramp times", "radius ramp factors"})
        if (sub.isParameter(k)) fail(quoted(path + "->" + k) + " describes a rigid obstacle; a pair with 'master' has none");
    } else {
      read_contact_obstacle(sub, path, ls, c);
    }
    c.friction = get_double(sub, ls, "friction");
    c.c_normal = get_double(sub, ls, "c normal");
    c.c_tangent = get_double(sub, ls, "c tangent");
    c.formulation = get_string(sub, ls, "formulation");
    c.discretization = get_string(sub, ls, "discretization");
    c.linearised_sets = get_string(sub, ls, "set update") == "linearised";
    if (c.discretization == "mortar" && !has_master)
      fail(quoted(path + "->discretization") + " = mortar couples two meshed surfaces; it needs 'master' (a rigid obstacle is "
           "exact at every slave node already)");
    cfg_.contact.push_back(c);
  }
  if (cfg_.contact.empty()) fail("'Contact' defines no contact pair; add one sublist per pair or remove 'Contact'");
}

// A fluid cavity (LoadConfig::FluidCavity): 3D only (checked with the mesh, bc/Loads.cpp) and
// static stages only (check_analysis).
void DeckReader::read_fluid_cavity(const ParameterList& sub, const ListSpec& ls, const std::string& path, LoadConfig& lc) {
  lc.type = LoadConfig::Type::FluidCavity;
  lc.group = get_string(sub, ls, "boundary");
  lc.volume_ratio = get_double(sub, ls, "volume ratio");
  lc.bulk_modulus = get_double(sub, ls, "bulk modulus");
  const auto point = get_array(sub, ls, "axis point"), axis = get_array(sub, ls, "axis");
  if (point.size() != 3) fail(quoted(path + "->axis point") + " must have 3 values (a fluid cavity is 3D), got " + std::to_string(point.size()));
  if (axis.size() != 3) fail(quoted(path + "->axis") + " must have 3 values (a fluid cavity is 3D), got " + std::to_string(axis.size()));
  for (std::size_t c = 0; c < 3; ++c) lc.axis_point[c] = point[c], lc.axis[c] = axis[c];
  unit_direction(lc.axis, path + "->axis");
}

void DeckReader::read_loads(const ParameterList& pl) {
  const ListSpec& top = deck_list_spec("Boundary Conditions");
  const ListSpec& common = deck_list_spec("Boundary Conditions/*");
  const std::vector<std::string> types = spec(common, "type").choices;
  check_list(pl, "Boundary Conditions", {&top});
  for (auto it = pl.begin(); it != pl.end(); ++it) {
    const std::string& name = pl.name(it);
    const std::string path = "Boundary Conditions->" + name;
    check_safe_name(name, path, "the load name");
    const ParameterList& sub = pl.sublist(name);
    if (!sub.isParameter("type"))
      fail("missing required parameter " + quoted(path + "->type") + " (string, one of " + join(types) + ")");
    check_param(sub.getEntry("type"), path + "->type", spec(common, "type"));
    const std::string type = get_string(sub, common, "type");
    const ListSpec& typed = deck_list_spec("Boundary Conditions/*/" + type);
    // A parameter of another load type gets a specific message.
    for (auto jt = sub.begin(); jt != sub.end(); ++jt) {
      const std::string& pn = sub.name(jt);
      if (common.find(pn) || typed.find(pn)) continue;
      for (const auto& other : types)
        if (other != type && deck_list_spec("Boundary Conditions/*/" + other).find(pn)) {
          std::vector<std::string> valid;
          for (const auto& p : typed.params) valid.push_back(p.name);
          for (const auto& p : common.params) valid.push_back(p.name);
          fail("unknown parameter " + quoted(path + "->" + pn) + " for a load of type '" + type + "' ('" + pn +
               "' belongs to type '" + other + "'); a " + type + " load takes: " + join(valid));
        }
    }
    check_list(sub, path, {&common, &typed});
    require(sub, path, {&common, &typed});

    LoadConfig lc;
    lc.name = name;
    lc.ramp = read_ramp(sub, path, common);
    if (type == "Dirichlet") {
      lc.type = LoadConfig::Type::Dirichlet;
      lc.group = get_string(sub, typed, "boundary");
      const std::string comp = get_string(sub, typed, "components");
      const std::string cpath = path + "->components";
      std::string tokens = comp;
      std::replace(tokens.begin(), tokens.end(), ',', ' ');
      std::istringstream is(tokens);
      std::string tok;
      std::vector<int> listed;
      bool all = false;
      const std::string expect = " must list components x, y, z (separated by spaces or commas) or be 'all' or 'normal'";
      bool normal = false;
      while (is >> tok) {
        const std::string t = lower(tok);
        if (t == "all") {
          all = true;
          continue;
        }
        if (t == "normal") {
          normal = true;
          continue;
        }
        if (t != "x" && t != "y" && t != "z") fail(quoted(cpath) + expect + "; got '" + comp + "' ('" + tok + "' is not a component)");
        const int c = t[0] - 'x';
        if (std::find(listed.begin(), listed.end(), c) != listed.end())
          fail(quoted(cpath) + " lists '" + tok + "' twice; got '" + comp + "'");
        listed.push_back(c);
      }
      if (all && !listed.empty()) fail(quoted(cpath) + ": 'all' cannot be combined with other components; got '" + comp + "'");
      if (normal && (all || !listed.empty()))
        fail(quoted(cpath) + ": 'normal' cannot be combined with other components; got '" + comp + "'");
      if (normal) {
        // The displacement along the boundary's unit outward normal (Loads: the group must be planar).
        lc.normal = true;
        if (sub.isParameter("values")) {
          const auto v = get_array(sub, typed, "values");
          if (v.size() != 1)
            fail(quoted(path + "->values") + " must have one value (the displacement along the normal) for components 'normal', got " +
                 std::to_string(v.size()));
          lc.value = v[0];
        }
        cfg_.loads.push_back(lc);
        continue;
      }
      if (!all && listed.empty()) fail(quoted(cpath) + expect + "; got '" + comp + "'");
      const int dim = cfg_.mesh.dimension;
      if (dim == 2 && std::find(listed.begin(), listed.end(), 2) != listed.end())
        fail(quoted(cpath) + ": 'z' is not a component of a 2D problem ('Mesh->dimension' = 2)");
      lc.all_components = all;
      if (all) {
        lc.components = {true, true, dim != 2};
      } else {
        for (int c : listed) lc.components[static_cast<std::size_t>(c)] = true;
      }
      if (sub.isParameter("values")) {
        const auto v = get_array(sub, typed, "values");
        const std::string vpath = path + "->values";
        if (all) {
          if (v.size() < 2 || v.size() > 3)
            fail(quoted(vpath) + " must have one value per dimension (2 or 3) for components 'all', got " + std::to_string(v.size()));
          check_dim_length(v, vpath);
          for (std::size_t c = 0; c < v.size(); ++c) lc.vector[c] = v[c];
        } else {
          if (v.size() != listed.size())
            fail(quoted(vpath) + " must have one value per listed component (" + std::to_string(listed.size()) + " for '" +
                 comp + "'), got " + std::to_string(v.size()));
          for (std::size_t k = 0; k < listed.size(); ++k) lc.vector[static_cast<std::size_t>(listed[k])] = v[k];
        }
      }
    } else if (type == "traction") {
      lc.type = LoadConfig::Type::Traction;
      lc.group = get_string(sub, typed, "boundary");
      const auto v = get_array(sub, typed, "traction");
      check_dim_length(v, path + "->traction");
      for (std::size_t c = 0; c < v.size(); ++c) lc.vector[c] = v[c];
    } else if (type == "pressure") {
      lc.type = LoadConfig::Type::Pressure;
      lc.group = get_string(sub, typed, "boundary");
      lc.value = get_double(sub, typed, "pressure");
    } else if (type == "fluid cavity") {
      read_fluid_cavity(sub, typed, path, lc);
    } else {  // body force
      lc.type = LoadConfig::Type::BodyForce;
      const auto v = get_array(sub, typed, "force");
      check_dim_length(v, path + "->force");
      for (std::size_t c = 0; c < v.size(); ++c) lc.vector[c] = v[c];
      const std::string body = get_string(sub, typed, "body");
      if (!body.empty()) {
        // A body's name or its physical group; stored as the physical group.
        std::vector<std::string> names;
        for (const auto& b : cfg_.bodies) {
          if (b.name == body || b.group == body) lc.group = b.group;
          names.push_back(b.name);
        }
        if (lc.group.empty()) {
          std::string msg = quoted(path + "->body") + " names undefined body '" + body + "'; defined bodies: " + join(names);
          const std::string near = nearest_name(body, names);
          if (!near.empty()) msg += "; did you mean '" + near + "'?";
          fail(msg);
        }
      }
    }
    cfg_.loads.push_back(lc);
  }
}

void DeckReader::read_initial(const ParameterList& pl) {
  const ListSpec& ls = deck_list_spec("Initial Conditions");
  check_list(pl, "Initial Conditions", {&ls});
  auto& ic = cfg_.initial;
  if (pl.isParameter("displacement")) {
    const auto d = get_array(pl, ls, "displacement");
    check_dim_length(d, "Initial Conditions->displacement");
    for (std::size_t c = 0; c < d.size(); ++c) ic.displacement[c] = d[c];
  }
  if (pl.isParameter("velocity")) {
    const auto v = get_array(pl, ls, "velocity");
    check_dim_length(v, "Initial Conditions->velocity");
    for (std::size_t c = 0; c < v.size(); ++c) ic.velocity[c] = v[c];
  }
  if (pl.isParameter("angular velocity")) {
    const auto w = get_array(pl, ls, "angular velocity");
    if (w.size() != 1 && w.size() != 3)
      fail("'Initial Conditions->angular velocity' must have 1 value (2D, about z) or 3 values (3D), got " +
           std::to_string(w.size()));
    check_dim_length(w, "Initial Conditions->angular velocity", 1, 3);
    if (w.size() == 1) {
      ic.angular_velocity[2] = w[0];
    } else {
      for (std::size_t c = 0; c < 3; ++c) ic.angular_velocity[c] = w[c];
    }
  }
  if (pl.isParameter("center")) {
    const auto c = get_array(pl, ls, "center");
    check_dim_length(c, "Initial Conditions->center");
    for (std::size_t k = 0; k < c.size(); ++k) ic.center[k] = c[k];
  }
}

void DeckReader::read_time(const ParameterList& pl) {
  const ListSpec& ls = deck_list_spec("Time Integration");
  check_list(pl, "Time Integration", {&ls});
  cfg_.time.scheme = get_string(pl, ls, "scheme");
  cfg_.time.hht_alpha = get_double(pl, ls, "hht alpha");
}

void DeckReader::read_stepping(const ParameterList& pl) {
  const ListSpec& ls = deck_list_spec("Stepping");
  check_list(pl, "Stepping", {&ls});
  cfg_.stepping.end_time = get_double(pl, ls, "end time");
  cfg_.stepping.num_steps = get_int(pl, ls, "steps");
  cfg_.stepping.max_cutbacks = get_int(pl, ls, "max cutbacks");
  cfg_.stepping.growth = get_double(pl, ls, "growth");
  cfg_.stepping.target_iterations = get_int(pl, ls, "target iterations");
  if (cfg_.stepping.target_iterations > 0 && cfg_.stepping.target_iterations < 4)
    fail("'Stepping->target iterations' = " + std::to_string(cfg_.stepping.target_iterations) +
         ": must be 0 (off) or at least 4 (a Newton solve to the tolerances takes 2 to 3 iterations, so a smaller target "
         "would shrink every step)");
  cfg_.stepping.predictor = get_string(pl, ls, "predictor");
  cfg_.stepping.stabilization = get_double(pl, ls, "stabilization");
  cfg_.stepping.contact_approach = get_double(pl, ls, "contact approach");
  cfg_.stepping.min_dt = get_double(pl, ls, "min dt");
  cfg_.stepping.max_steps = get_int(pl, ls, "max steps");
}

void DeckReader::read_newton(const ParameterList& pl) {
  const ListSpec& ls = deck_list_spec("Newton");
  check_list(pl, "Newton", {&ls});
  auto& n = cfg_.newton;
  n.max_iterations = get_int(pl, ls, "max iterations");
  n.residual_tolerance = get_double(pl, ls, "relative residual tolerance");
  n.residual_tolerance_given = pl.isParameter("relative residual tolerance");
  n.absolute_tolerance = get_double(pl, ls, "absolute residual tolerance");
  n.increment_tolerance = get_double(pl, ls, "increment tolerance");
  n.line_search = get_bool(pl, ls, "line search");
  n.line_search_max = get_int(pl, ls, "line search max halvings");
  n.line_search_watchdog = get_int(pl, ls, "line search watchdog");
  n.forcing = get_string(pl, ls, "forcing");
  n.forcing_max = get_double(pl, ls, "forcing max");
  n.max_increment = get_double(pl, ls, "max increment");
}

void DeckReader::read_linear(const ParameterList& pl) {
  const ListSpec& ls = deck_list_spec("Linear Solver");
  check_list(pl, "Linear Solver", {&ls});
  auto& l = cfg_.linear;
  l.method = get_string(pl, ls, "method");
  l.direct_solver = get_string(pl, ls, "direct solver");
  l.preconditioner = get_string(pl, ls, "preconditioner");
  l.tolerance = get_double(pl, ls, "tolerance");
  l.max_iterations = get_int(pl, ls, "max iterations");
  l.restart = get_int(pl, ls, "restart");
  l.overlap = get_int(pl, ls, "overlap");
  l.subdomain_solver = get_string(pl, ls, "subdomain solver");
  l.fill_level = get_int(pl, ls, "fill level");
  l.preconditioner_reuse = get_int(pl, ls, "preconditioner reuse");
  l.preconditioner_rebuild_cost = get_double(pl, ls, "preconditioner rebuild cost");
  l.preconditioner_rebuild_on_change = get_bool(pl, ls, "preconditioner rebuild on contact change");
#ifndef STENTOR_HAVE_MUELU
  if (l.preconditioner == "muelu")
    fail("'Linear Solver->preconditioner' = muelu needs Trilinos with MueLu, which this build lacks; use schwarz");
#endif
#ifndef STENTOR_HAVE_AMESOS2
  if (l.method == "direct" && l.direct_solver != "mumps")
    fail("'Linear Solver->method' = direct needs Trilinos with Amesos2 for KLU2, which this build lacks; use gmres, or "
         "'direct solver' = mumps");
  if (l.subdomain_solver == "KLU2")
    fail("'Linear Solver->subdomain solver' = KLU2 needs Trilinos with Amesos2, which this build lacks; use RILUK or ILUT");
#endif
  auto xml_of = [&](const char* name) -> std::string {
    if (!pl.isSublist(name)) return "";
    ParameterList copy = pl.sublist(name);
    copy.setName(name);
    std::ostringstream os;
    Teuchos::writeParameterListToXmlOStream(copy, os);
    return os.str();
  };
  l.belos_xml = xml_of("Belos");
  l.ifpack2_xml = xml_of("Ifpack2");
  l.muelu_xml = xml_of("MueLu");
  l.amesos2_xml = xml_of("Amesos2");
}

void DeckReader::read_output(const ParameterList& pl) {
  const ListSpec& ls = deck_list_spec("Output");
  check_list(pl, "Output", {&ls});
  auto& o = cfg_.output;
  o.directory = get_string(pl, ls, "directory");
  o.basename = get_string(pl, ls, "basename");
  o.every = get_int(pl, ls, "every");
  o.fields = get_bool(pl, ls, "fields");
  o.field_list = get_string(pl, ls, "field list");
  o.times = get_array(pl, ls, "times");
  o.interval = get_double(pl, ls, "interval");
  for (const char* p : {"field list", "times", "interval"})
    if (!o.fields && pl.isParameter(p))
      fail("'Output->" + std::string(p) + "' is given but 'Output->fields' is false (no fields are written)");
  o.checkpoint_every = get_int(pl, ls, "checkpoint every");
  if (o.directory.empty()) fail("'Output->directory' must not be empty");
  if (o.basename.empty()) fail("'Output->basename' must not be empty");
  if (o.basename.find('/') != std::string::npos)
    fail("'Output->basename' must be a file name stem without '/', got '" + o.basename + "'");
  check_safe_name(o.basename, "Output->basename", "the file name stem");
  if (pl.isSublist("Probes")) {
    const ParameterList& probes = pl.sublist("Probes");
    const ListSpec& pls = deck_list_spec("Output/Probes/*");
    check_list(probes, "Output->Probes", {&deck_list_spec("Output/Probes")});
    for (auto it = probes.begin(); it != probes.end(); ++it) {
      const std::string& name = probes.name(it);
      const std::string path = "Output->Probes->" + name;
      check_safe_name(name, path, "the probe name");
      const ParameterList& sub = probes.sublist(name);
      check_list(sub, path, {&pls});
      require(sub, path, {&pls});
      ProbeConfig p;
      p.name = name;
      const auto v = get_array(sub, pls, "point");
      check_dim_length(v, path + "->point");
      for (std::size_t c = 0; c < v.size(); ++c) p.point[c] = v[c];
      o.probes.push_back(p);
    }
  }
  if (pl.isSublist("Stent Metrics")) read_stent_metrics(pl.sublist("Stent Metrics"));
}

void DeckReader::resolve_output() {
  OutputConfig& o = cfg_.output;
  OutputDeckTraits traits;
  traits.dynamic = cfg_.any_dynamic();
  traits.contact = !cfg_.contact.empty();
  for (const auto& c : cfg_.contact) traits.master_surface |= !c.master.empty();
  traits.stent_in_artery = cfg_.mesh.generator == "stent" && cfg_.mesh.artery.around_stent && o.metrics.enabled;
  for (const auto& b : cfg_.bodies)
    for (const auto& m : cfg_.materials)
      if (m.name == b.material) {
        traits.plastic |= m.plastic();
        traits.damage |= m.damage();
      }
  try {
    o.field_names = o.fields ? resolve_output_fields(o.field_list, traits) : std::vector<std::string>{};
  } catch (const std::invalid_argument& e) {
    fail("'Output->field list' " + std::string(e.what()) + "; got '" + o.field_list + "'");
  }
  const double end = cfg_.stepping.end_time;
  for (std::size_t i = 0; i < o.times.size(); ++i) {
    const double t = o.times[i];
    if (!(t > 0.0) || t > end * (1.0 + 1e-12))
      fail("'Output->times' must lie in (0, end time = " + num(end) + "], got " + num(t) + " at position " + std::to_string(i + 1));
    if (i > 0 && !(t > o.times[i - 1]))
      fail("'Output->times' must be strictly increasing, got " + num(o.times[i - 1]) + " then " + num(t) + " at positions " +
           std::to_string(i) + ", " + std::to_string(i + 1));
  }
  merge_output_interval(o, end);
}

// Output->interval: its multiples in (0, end] merged into Output->times (sorted; a multiple
// within 1e-10 end time of a given time is the same output).
void DeckReader::merge_output_interval(OutputConfig& o, double end) const {
  if (!(o.interval > 0.0)) return;
  const double count = std::floor(end / o.interval * (1.0 + 1e-12));
  if (count > 100000.0)
    fail("'Output->interval' = " + num(o.interval) + " would write " + num(count) + " field outputs over the end time " + num(end) +
         " (at most 100,000); raise it");
  std::vector<double> all = o.times;
  for (long k = 1; k <= static_cast<long>(count); ++k) all.push_back(std::min(end, static_cast<double>(k) * o.interval));
  std::sort(all.begin(), all.end());
  const double tol = 1e-10 * end;
  o.times.clear();
  for (double t : all)
    if (o.times.empty() || t > o.times.back() + tol) o.times.push_back(t);
}

void DeckReader::read_stent_metrics(const ParameterList& sub) {
  const std::string path = "Output->Stent Metrics";
  const ListSpec& ls = deck_list_spec("Output/Stent Metrics");
  check_list(sub, path, {&ls});
  require(sub, path, {&ls});
  StentMetricsConfig& m = cfg_.output.metrics;
  m.enabled = true;
  m.end_fraction = get_double(sub, ls, "end fraction");
  m.malapposition_threshold = get_double(sub, ls, "malapposition threshold");
  if (sub.isParameter("malapposition threshold") && !(cfg_.mesh.generator == "stent" && cfg_.mesh.artery.around_stent))
    fail(quoted(path + "->malapposition threshold") + " applies to a generated stent in a generated artery ('Mesh->generator' = "
         "stent with 'Mesh->Artery'); this deck has none: remove it");
  const char* named[] = {"axis point", "axis", "stent", "lumen", "artery"};
  if (cfg_.mesh.generator == "stent") {
    // The generated stent's axis is z through the origin and its groups are the generator's.
    for (const char* n : named)
      if (sub.isParameter(n))
        fail(quoted(path + "->" + n) + ": not with 'Mesh->generator' = stent (the metrics take the generated "
             "stent's axis, the z axis through the origin, and its groups); remove it");
    m.axis = {0.0, 0.0, 1.0};
    return;
  }
  for (const char* n : named)
    if (!sub.isParameter(n))
      fail("missing required parameter " + quoted(path + "->" + n) + " (required unless 'Mesh->generator' = stent: "
           "the metrics of a mesh file name the vessel axis and the groups 'stent', 'lumen', 'artery')");
  const auto p = get_array(sub, ls, "axis point");
  check_dim_length(p, path + "->axis point");
  for (std::size_t c = 0; c < p.size(); ++c) m.axis_point[c] = p[c];
  const auto a = get_array(sub, ls, "axis");
  for (std::size_t c = 0; c < 3; ++c) m.axis[c] = a[c];
  unit_direction(m.axis, path + "->axis");
  m.stent = get_string(sub, ls, "stent");
  m.lumen = get_string(sub, ls, "lumen");
  m.artery = get_string(sub, ls, "artery");
  for (const std::string* g : {&m.stent, &m.lumen, &m.artery})
    if (g->empty()) fail(quoted(path) + ": 'stent', 'lumen' and 'artery' must name physical groups");
}

}  // namespace stentor::deck_reader
