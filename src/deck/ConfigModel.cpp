// The deck reader's sections of the model: Problem, Mesh (with the stent, balloon and
// artery generators), Materials and Bodies (deck/DeckReader.hpp).
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

void DeckReader::read_problem(const ParameterList& pl) {
  const ListSpec& ls = deck_list_spec("Problem");
  check_list(pl, "Problem", {&ls});
  cfg_.problem.title = get_string(pl, ls, "title");
  cfg_.problem.analysis = get_string(pl, ls, "analysis");
  cfg_.problem.assembly = get_string(pl, ls, "assembly");
  cfg_.problem.units = get_string(pl, ls, "units");
  cfg_.problem.kinematics = get_string(pl, ls, "kinematics");
}

void DeckReader::read_mesh(const ParameterList& pl) {
  const ListSpec& ls = deck_list_spec("Mesh");
  check_list(pl, "Mesh", {&ls});
  require(pl, "Mesh", {&ls});
  auto& m = cfg_.mesh;
  const std::string generator = get_string(pl, ls, "generator");
  m.generator = lower(generator) == "none" ? "" : lower(generator);
  if (m.generator.empty() == !pl.isParameter("file"))
    fail(m.generator.empty() ? "missing required parameter 'Mesh->file' (string, existing .msh or .geo file), or give "
                               "'Mesh->generator'"
                             : "'Mesh->file' and 'Mesh->generator' = " + generator + " exclude each other: give one");
  if (m.generator.empty() && pl.isParameter("write mesh"))
    fail("'Mesh->write mesh' applies to 'Mesh->generator', not to a mesh file");
  if (pl.isSublist("Stent") && m.generator != "stent") fail("'Mesh->Stent' needs 'Mesh->generator' = stent");
  if (pl.isSublist("Artery") && m.generator != "artery" && m.generator != "stent")
    fail("'Mesh->Artery' needs 'Mesh->generator' = artery (or stent: the artery around the stent)");
  if (pl.isSublist("Balloon") && m.generator != "stent")
    fail("'Mesh->Balloon' needs 'Mesh->generator' = stent (the balloon is mounted in the generated stent)");
  if (pl.isSublist("Parameters") && !m.generator.empty())
    fail("'Mesh->Parameters' sets the parameters of a .geo 'Mesh->file', not of 'Mesh->generator'");
  m.max_cells = get_double(pl, ls, "max cells");
  if (!m.generator.empty()) {
    for (const char* p : {"size", "order", "recombine", "dimension", "time limit"})
      if (pl.isParameter(p)) fail(quoted(std::string("Mesh->") + p) + " applies to a mesh file, not to 'Mesh->generator'");
    const std::string sub = m.generator == "stent" ? "Stent" : "Artery";
    if (!pl.isSublist(sub)) fail("missing required sublist 'Mesh->" + sub + "' ('Mesh->generator' = " + m.generator + ")");
    if (m.generator == "stent") {
      read_stent(pl.sublist("Stent"));
      if (pl.isSublist("Balloon")) read_balloon(pl.sublist("Balloon"));
      if (pl.isSublist("Artery")) read_artery(pl.sublist("Artery"), true);
    } else
      read_artery(pl.sublist("Artery"), false);
    m.write_mesh = get_bool(pl, ls, "write mesh");
    m.dimension = 3;
    m.file = cfg_.deck_path;  // messages about the mesh name the deck
    return;
  }
  const std::string file = get_string(pl, ls, "file");
  fs::path f(file);
  if (f.is_relative()) f = fs::path(cfg_.deck_path).parent_path() / f;
  f = f.lexically_normal();
  m.file = f.string();
  const std::string ext = lower(f.extension().string());
  if (ext != ".msh" && ext != ".geo")
    fail("'Mesh->file' must be a gmsh .msh or .geo file, got '" + file + "'");
  std::error_code ec;
  if (!fs::exists(f, ec)) fail("'Mesh->file': mesh file '" + m.file + "' does not exist (resolved from '" + file +
                               "' relative to the deck's folder)");
  if (!fs::is_regular_file(f, ec)) fail("'Mesh->file': '" + m.file + "' is not a regular file");
  if (pl.isSublist("Parameters")) {
    if (ext != ".geo") fail("'Mesh->Parameters' sets the DefineNumber parameters of a .geo file; '" + file + "' is a .msh");
    m.parameters = read_mesh_parameters(pl.sublist("Parameters"), file_);
  }
  m.size = get_double(pl, ls, "size");
  m.order = get_int(pl, ls, "order");
  m.recombine = get_bool(pl, ls, "recombine");
  m.dimension = get_int(pl, ls, "dimension");
  m.time_limit = get_double(pl, ls, "time limit");
  if (m.recombine && m.order == 2)
    fail("'Mesh->recombine' = true needs 'Mesh->order' = 1 (quad8/hex20 bodies are not supported)");
}

void DeckReader::read_stent(const ParameterList& pl) {
  const ListSpec& ls = deck_list_spec("Mesh/Stent");
  check_list(pl, "Mesh->Stent", {&ls});
  require(pl, "Mesh->Stent", {&ls});
  StentConfig& s = cfg_.mesh.stent;
  s.rings = get_int(pl, ls, "rings");
  s.crowns = get_int(pl, ls, "crowns");
  s.outer_diameter = get_double(pl, ls, "outer diameter");
  s.thickness = get_double(pl, ls, "thickness");
  s.strut_width = get_double(pl, ls, "strut width");
  s.ring_length = get_double(pl, ls, "ring length");
  s.gap = get_double(pl, ls, "gap");
  s.links = lower(get_string(pl, ls, "links"));
  s.links_per_ring = get_int(pl, ls, "links per ring");
  s.link_width = get_double(pl, ls, "link width");
  s.elements_width = get_int(pl, ls, "elements through width");
  s.elements_thickness = get_int(pl, ls, "elements through thickness");
  s.element_length = get_double(pl, ls, "element length");
  s.sector = lower(get_string(pl, ls, "sector"));
  s.half_length = get_bool(pl, ls, "half length");
  const std::string why = stent_config_error(s);
  if (!why.empty()) fail(why);
}

void DeckReader::read_balloon(const ParameterList& pl) {
  const ListSpec& ls = deck_list_spec("Mesh/Balloon");
  check_list(pl, "Mesh->Balloon", {&ls});
  require(pl, "Mesh->Balloon", {&ls});
  BalloonConfig& b = cfg_.mesh.balloon;
  b.enabled = true;
  b.outer_diameter = get_double(pl, ls, "outer diameter");
  b.thickness = get_double(pl, ls, "thickness");
  b.length = get_double(pl, ls, "length");
  b.elements_thickness = get_int(pl, ls, "elements through thickness");
  b.element_length = get_double(pl, ls, "element length");
  const std::string why = balloon_config_error(b, cfg_.mesh.stent);
  if (!why.empty()) fail(why);
}

// around_stent: `Mesh->Artery` in a stent deck, the artery around the stent, which takes
// the stent's sector and half length (its own are refused).
void DeckReader::read_artery(const ParameterList& pl, bool around_stent) {
  const ListSpec& ls = deck_list_spec("Mesh/Artery");
  check_list(pl, "Mesh->Artery", {&ls});
  require(pl, "Mesh->Artery", {&ls});
  ArteryConfig& a = cfg_.mesh.artery;
  a.around_stent = around_stent;
  if (around_stent)
    for (const char* p : {"sector", "half length"})
      if (pl.isParameter(p))
        fail(quoted(std::string("Mesh->Artery->") + p) + " does not apply with 'Mesh->generator' = stent: the artery around "
             "the stent takes the stent's " + quoted(std::string("Mesh->Stent->") + p) + "; remove it");
  if (around_stent && pl.isParameter("centreline radius"))
    fail("'Mesh->Artery->centreline radius' (a curved artery) is for 'Mesh->generator' = artery: the artery around a "
         "generated stent is straight; remove it");
  a.inner_diameter = get_double(pl, ls, "inner diameter");
  a.length = get_double(pl, ls, "length");
  for (int l = 0; l < 3; ++l) {
    a.thickness[l] = get_double(pl, ls, std::string(kArteryLayer[l]) + " thickness");
    a.elements_layer[l] = get_int(pl, ls, std::string("elements through ") + kArteryLayer[l]);
  }
  a.elements_around = get_int(pl, ls, "elements around");
  a.elements_along = get_int(pl, ls, "elements along");
  a.sector = lower(get_string(pl, ls, "sector"));
  a.half_length = get_bool(pl, ls, "half length");
  a.plaque_stenosis = get_double(pl, ls, "plaque stenosis");
  a.plaque_length = get_double(pl, ls, "plaque length");
  a.plaque_centre = get_double(pl, ls, "plaque centre");
  a.plaque_shape = lower(get_string(pl, ls, "plaque shape"));
  a.elements_plaque = get_int(pl, ls, "elements through plaque");
  a.centreline_radius = get_double(pl, ls, "centreline radius");
  const std::string why = around_stent ? artery_around_stent_error(a, cfg_.mesh.stent) : artery_config_error(a);
  if (!why.empty()) fail(why);
}

// A plastic body on a generated stent needs 3 cells through the width and the thickness
// (fewer cannot carry the bending of a crown's plastic hinge).
void DeckReader::check_stent_plastic() const {
  const StentConfig& s = cfg_.mesh.stent;
  if (cfg_.mesh.generator != "stent" || (s.elements_width >= 3 && s.elements_thickness >= 3)) return;
  for (const BodyConfig& b : cfg_.bodies)
    for (const MaterialConfig& m : cfg_.materials)
      if (m.name == b.material && m.model.find("plasticity") != std::string::npos)
        fail("'Mesh->Stent->" + std::string(s.elements_width < 3 ? "elements through width" : "elements through thickness") +
             "' = " + std::to_string(std::min(s.elements_width, s.elements_thickness)) + ": body '" + b.name +
             "' is plastic ('" + m.model + "'), which needs at least 3 cells through the strut's width and thickness");
}

// Exactly one of the sets C1 + D (+ C2), E + nu, mu + lambda (material/ElasticConstants.hpp).
void DeckReader::read_elastic_constants(const ParameterList& sub, const ListSpec& ls, const std::string& path,
                                        MaterialConfig& m) const {
  struct Set {
    const char* a;
    const char* b;
  };
  const Set sets[] = {{"C1", "D"}, {"E", "nu"}, {"mu", "lambda"}};
  const Set* given = nullptr;
  for (const Set& s : sets) {
    const bool ha = sub.isParameter(s.a), hb = sub.isParameter(s.b);
    if (!ha && !hb) continue;
    if (given)
      fail(quoted(path) + ": give exactly one set of elastic constants (C1 + D, E + nu, or mu + lambda), got both " +
           given->a + "/" + given->b + " and " + s.a + "/" + s.b);
    if (ha != hb) {
      const ParamSpec& missing = spec(ls, ha ? s.b : s.a);
      fail("missing required parameter " + quoted(path + "->" + missing.name) + " (double, " + missing.allowed_text() +
           "): '" + s.a + "' and '" + s.b + "' are given together");
    }
    given = &s;
  }
  const bool cg = m.ciarlet_geymonat();
  if (!given)
    fail(quoted(path) + " needs one set of elastic constants: " +
         (cg ? "C1 + D (+ C2), E + nu, or mu + lambda [stress]" : "E + nu or mu + lambda [stress]"));
  if (!cg && given == &sets[0])
    fail(quoted(path + "->" + (sub.isParameter("C1") ? "C1" : "D")) + " is a Ciarlet-Geymonat parameter; 'model' = " +
         m.model + " takes E + nu or mu + lambda");
  if ((m.neo_hookean() || m.model == "Holzapfel-Gasser-Ogden") && sub.isParameter("C2"))
    fail(quoted(path + "->C2") + " needs 'model' = Ciarlet-Geymonat or Mooney-Rivlin (" + m.model + " has no I2 term)");
  m.C2 = get_double(sub, ls, "C2");
  if (given == &sets[0]) {
    m.C1 = get_double(sub, ls, "C1");
    m.D = get_double(sub, ls, "D");
    m.mu = 2.0 * (m.C1 + m.C2);
    m.lambda = 4.0 * (m.C2 + m.D);
    return;
  }
  const Lame l = given == &sets[1] ? lame_from_young(get_double(sub, ls, "E"), get_double(sub, ls, "nu"))
                                   : Lame{get_double(sub, ls, "mu"), get_double(sub, ls, "lambda")};
  m.mu = l.mu;
  m.lambda = l.lambda;
  const std::string from = std::string(given->a) + "/" + given->b;
  if (m.model == "Mooney-Rivlin") {
    const MooneyRivlinCoefficients c = mooney_rivlin_from_lame(l, m.C2);
    m.C1 = c.C1;
    if (!(c.C1 > 0.0))
      fail(quoted(path) + ": C1 = mu/2 - C2 = " + num(c.C1) + " from " + from + " and 'C2' = " + num(m.C2) +
           "; Mooney-Rivlin needs C1 > 0 (lower 'C2' below mu/2 = " + num(0.5 * l.mu) + ")");
    if (!(c.lam >= 0.0))
      fail(quoted(path) + ": the volumetric coefficient lambda - 4 C2 = " + num(c.lam) + " from " + from + " and 'C2' = " +
           num(m.C2) + "; Mooney-Rivlin needs it >= 0 (lower 'C2' to at most lambda/4 = " + num(0.25 * l.lambda) + ")");
  }
  if (!cg) return;
  const CiarletGeymonatCoefficients c = ciarlet_geymonat_from_lame(l, m.C2);
  m.C1 = c.C1;
  m.D = c.D;
  if (!(m.C1 > 0.0))
    fail(quoted(path) + ": C1 = mu/2 - C2 = " + num(m.C1) + " from " + from + " and 'C2' = " + num(m.C2) +
         "; Ciarlet-Geymonat needs C1 > 0 (lower 'C2' below mu/2 = " + num(0.5 * l.mu) + ")");
  if (!(m.D > 0.0))
    fail(quoted(path) + ": D = lambda/4 - C2 = " + num(m.D) + " from " + from + " and 'C2' = " + num(m.C2) +
         "; Ciarlet-Geymonat needs D > 0 (nu > 0, and 'C2' below lambda/4 = " + num(0.25 * l.lambda) + ")");
}

// Holzapfel-Gasser-Ogden: k1, k2, fibre angle required, frame, kappa and anisotropy optional (not kappa > 0
// with anisotropy < 1: two different ways of spreading the fibres' stiffness); none of them with other models.
void DeckReader::read_fibres(const ParameterList& sub, const ListSpec& ls, const std::string& path, MaterialConfig& m) {
  const char* keys[] = {"k1", "k2", "fibre angle", "axis point", "axis", "kappa", "anisotropy", "centreline radius", "bend direction"};
  const bool hgo = m.model == "Holzapfel-Gasser-Ogden";
  for (const char* k : keys) {
    const std::string key(k);
    if (!hgo && sub.isParameter(k)) fail(quoted(path + "->" + k) + " needs 'model' = Holzapfel-Gasser-Ogden");
    const bool optional = key == "axis point" || key == "axis" || key == "kappa" || key == "anisotropy" || key == "centreline radius" ||
                          key == "bend direction";
    if (hgo && !optional && !sub.isParameter(k)) {
      const ParamSpec& p = spec(ls, k);
      fail("missing required parameter " + quoted(path + "->" + k) + " (double, " + p.allowed_text() +
           ") for model = Holzapfel-Gasser-Ogden: " + p.doc);
    }
  }
  if (!hgo) return;
  m.k1 = get_double(sub, ls, "k1");
  m.k2 = get_double(sub, ls, "k2");
  m.fibre_angle = get_double(sub, ls, "fibre angle");
  if (sub.isParameter("kappa")) m.kappa = get_double(sub, ls, "kappa");
  if (sub.isParameter("anisotropy")) m.anisotropy = get_double(sub, ls, "anisotropy");
  if (m.kappa > 0.0 && m.anisotropy < 1.0)
    fail(quoted(path + "->anisotropy") + " = " + num(m.anisotropy) + " with " + quoted(path + "->kappa") + " = " + num(m.kappa) +
         ": give one of them (the dispersion kappa of Gasser et al. 2006 or the anisotropy rho of Holzapfel et al. 2005)");
  if (sub.isParameter("axis point")) {
    const auto p = get_array(sub, ls, "axis point");
    check_dim_length(p, path + "->axis point");
    for (std::size_t c = 0; c < p.size(); ++c) m.axis_point[c] = p[c];
  }
  if (sub.isParameter("axis")) {
    const auto a = get_array(sub, ls, "axis");
    for (std::size_t c = 0; c < 3; ++c) m.axis[c] = a[c];
    unit_direction(m.axis, path + "->axis");
  }
  if (sub.isParameter("centreline radius")) m.centreline_radius = get_double(sub, ls, "centreline radius");
  if (sub.isParameter("bend direction")) {
    if (!(m.centreline_radius > 0.0))
      fail(quoted(path + "->bend direction") + " needs " + quoted(path + "->centreline radius") + " > 0 (a curved vessel)");
    const auto b = get_array(sub, ls, "bend direction");
    for (std::size_t c = 0; c < 3; ++c) m.bend_direction[c] = b[c];
    unit_direction(m.bend_direction, path + "->bend direction");
  }
  if (m.centreline_radius > 0.0) {
    const auto& a = m.axis;
    auto& b = m.bend_direction;
    const double ab = a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    if (std::abs(ab) > 1e-6)
      fail(quoted(path + "->bend direction") + " must be normal to " + quoted(path + "->axis") + " (the centreline's tangent at " +
           quoted(path + "->axis point") + "), got a cosine of " + num(ab) + " between them");
  }
}

// The parameters of the laws with Gauss-point history: `yield stress` (required, > 0) and
// `hardening` and `plastic dynamic step` of the plasticity models, `saturation damage` and `damage energy scale`
// (both required) of neo-Hookean damage; none of them with another model.
void DeckReader::read_inelastic(const ParameterList& sub, const ListSpec& ls, const std::string& path, MaterialConfig& m) const {
  const auto needs = [&](const char* key, bool ok, const char* models) {
    if (!ok && sub.isParameter(key)) fail(quoted(path + "->" + key) + " needs 'model' = " + models);
  };
  const auto require_for_model = [&](const char* key) {
    if (sub.isParameter(key)) return;
    const ParamSpec& p = spec(ls, key);
    fail("missing required parameter " + quoted(path + "->" + key) + " (double, " + p.allowed_text() + ") for model = " +
         m.model);
  };
  needs("yield stress", m.plastic(), "Ciarlet-Geymonat plasticity or neo-Hookean plasticity");
  needs("hardening", m.plastic(), "Ciarlet-Geymonat plasticity or neo-Hookean plasticity");
  needs("plastic dynamic step", m.plastic(), "Ciarlet-Geymonat plasticity or neo-Hookean plasticity");
  needs("saturation damage", m.damage(), "neo-Hookean damage");
  needs("damage energy scale", m.damage(), "neo-Hookean damage");
  if (m.plastic()) {
    read_hardening(sub, ls, path, m);
    m.plastic_dynamic_step = get_string(sub, ls, "plastic dynamic step");
  } else {
    for (const char* k : {"hardening law", "saturation stress", "saturation rate", "hardening table strains",
                          "hardening table stresses"})
      needs(k, false, "Ciarlet-Geymonat plasticity or neo-Hookean plasticity");
  }
  if (m.damage()) {
    require_for_model("saturation damage");
    require_for_model("damage energy scale");
    m.saturation_damage = get_double(sub, ls, "saturation damage");
    m.damage_energy_scale = get_double(sub, ls, "damage energy scale");
  }
}

// The hardening of a plasticity model: `hardening law` linear (`yield stress`, `hardening`), Voce
// (+ `saturation stress` >= `yield stress`, `saturation rate`) or table (`hardening table strains`
// from 0, strictly increasing, and as many non-decreasing `hardening table stresses`, the first of
// which is the yield stress: `yield stress` and `hardening` are refused with it).
void DeckReader::read_hardening(const ParameterList& sub, const ListSpec& ls, const std::string& path,
                                MaterialConfig& m) const {
  m.hardening_law = get_string(sub, ls, "hardening law");
  const bool voce = m.hardening_law == "Voce", table = m.hardening_law == "table";
  const auto only = [&](const char* key, bool ok, const char* law) {
    if (!ok && sub.isParameter(key))
      fail(quoted(path + "->" + key) + " needs 'hardening law' = " + law + ", got " + m.hardening_law);
  };
  const auto required = [&](const char* key, bool with) {
    if (!with || sub.isParameter(key)) return;
    const ParamSpec& p = spec(ls, key);
    fail("missing required parameter " + quoted(path + "->" + key) + " (" + p.allowed_text() + ") for 'hardening law' = " +
         m.hardening_law);
  };
  only("saturation stress", voce, "Voce");
  only("saturation rate", voce, "Voce");
  only("hardening table strains", table, "table");
  only("hardening table stresses", table, "table");
  only("hardening", !table, "linear or Voce");
  if (table && sub.isParameter("yield stress"))
    fail(quoted(path + "->yield stress") + " is not allowed with 'hardening law' = table: the first of " +
         quoted(path + "->hardening table stresses") + " is the initial yield stress");
  for (const char* k : {"saturation stress", "saturation rate"}) required(k, voce);
  for (const char* k : {"hardening table strains", "hardening table stresses"}) required(k, table);
  if (!table) {
    if (!sub.isParameter("yield stress")) {
      const ParamSpec& p = spec(ls, "yield stress");
      fail("missing required parameter " + quoted(path + "->yield stress") + " (double, " + p.allowed_text() +
           ") for model = " + m.model);
    }
    m.yield_stress = get_double(sub, ls, "yield stress");
    m.hardening = get_double(sub, ls, "hardening");
  }
  if (voce) {
    m.saturation_stress = get_double(sub, ls, "saturation stress");
    m.saturation_rate = get_double(sub, ls, "saturation rate");
    if (m.saturation_stress < m.yield_stress)
      fail(quoted(path + "->saturation stress") + " = " + num(m.saturation_stress) + " is below " +
           quoted(path + "->yield stress") + " = " + num(m.yield_stress) +
           "; expected >= the yield stress (softening is not supported)");
  }
  if (table) {
    const std::string se = quoted(path + "->hardening table strains"), ss = quoted(path + "->hardening table stresses");
    m.table_strains = get_array(sub, ls, "hardening table strains");
    m.table_stresses = get_array(sub, ls, "hardening table stresses");
    if (m.table_strains.size() != m.table_stresses.size())
      fail(ss + " has " + std::to_string(m.table_stresses.size()) + " values and " + se + " " +
           std::to_string(m.table_strains.size()) + "; expected one stress per strain");
    if (m.table_strains[0] != 0.0) fail(se + " must start at 0, got " + num(m.table_strains[0]));
    for (std::size_t i = 1; i < m.table_strains.size(); ++i) {
      if (!(m.table_strains[i] > m.table_strains[i - 1]))
        fail(se + " must be strictly increasing, got " + num(m.table_strains[i]) + " after " + num(m.table_strains[i - 1]));
      if (m.table_stresses[i] < m.table_stresses[i - 1])
        fail(ss + " must be non-decreasing (softening is not supported), got " + num(m.table_stresses[i]) + " after " +
             num(m.table_stresses[i - 1]) + " at strain " + num(m.table_strains[i]));
    }
    m.yield_stress = m.table_stresses[0];
    m.hardening = 0.0;
  }
}

void DeckReader::read_materials(const ParameterList& pl) {
  const ListSpec& top = deck_list_spec("Materials");
  const ListSpec& ls = deck_list_spec("Materials/*");
  check_list(pl, "Materials", {&top});
  for (auto it = pl.begin(); it != pl.end(); ++it) {
    const std::string& name = pl.name(it);
    const std::string path = "Materials->" + name;
    const ParameterList& sub = pl.sublist(name);
    check_list(sub, path, {&ls});
    require(sub, path, {&ls});
    MaterialConfig m;
    m.name = name;
    m.model = get_string(sub, ls, "model");
    read_elastic_constants(sub, ls, path, m);
    // 1e308 is a double, but the law's moduli from it are not (the run checks the stiffness
    // itself; this names it here, under --check too).
    if (!std::isfinite(m.mu) || !std::isfinite(m.lambda))
      fail(quoted(path) + ": the elastic constants overflow double precision (small-strain mu = " + num(m.mu) + ", lambda = " +
           num(m.lambda) + "); expected smaller values (a deck in smaller units, e.g. mm-N-s with moduli in MPa, helps)");
    read_fibres(sub, ls, path, m);
    m.density = get_double(sub, ls, "density");
    m.viscosity = get_double(sub, ls, "viscosity");
    read_inelastic(sub, ls, path, m);
    cfg_.materials.push_back(m);
  }
  if (cfg_.materials.empty()) fail("'Materials' defines no material; add one sublist per material");
}

// A body's own initial rotation and displacement (its "initial velocity" is read above).
void DeckReader::read_body_initial_state(const ParameterList& sub, const std::string& path, BodyConfig& b) {
  const ListSpec& ls = deck_list_spec("Bodies/*");
  const bool w = sub.isParameter("initial angular velocity"), c = sub.isParameter("rotation center");
  if (w != c)
    fail(quoted(path + (w ? "->rotation center" : "->initial angular velocity")) + " is required with " +
         quoted(path + (w ? "->initial angular velocity" : "->rotation center")));
  if (w) {
    const auto a = get_array(sub, ls, "initial angular velocity");
    if (a.size() != 1 && a.size() != 3)
      fail(quoted(path + "->initial angular velocity") + " must have 1 value (2D, about z) or 3 values (3D), got " + std::to_string(a.size()));
    check_dim_length(a, path + "->initial angular velocity", 1, 3);
    if (a.size() == 1)
      b.angular_velocity[2] = a[0];
    else
      for (std::size_t k = 0; k < 3; ++k) b.angular_velocity[k] = a[k];
    const auto x = get_array(sub, ls, "rotation center");
    check_dim_length(x, path + "->rotation center");
    for (std::size_t k = 0; k < x.size() && k < 3; ++k) b.center[k] = x[k];
    b.has_angular_velocity = true;
  }
  if (sub.isParameter("initial displacement")) {
    const auto d = get_array(sub, ls, "initial displacement");
    check_dim_length(d, path + "->initial displacement");
    for (std::size_t k = 0; k < d.size() && k < 3; ++k) b.displacement[k] = d[k];
    b.has_displacement = true;
  }
}

void DeckReader::read_bodies(const ParameterList& pl) {
  const ListSpec& top = deck_list_spec("Bodies");
  const ListSpec& ls = deck_list_spec("Bodies/*");
  check_list(pl, "Bodies", {&top});
  std::vector<std::string> defined;
  for (const auto& m : cfg_.materials) defined.push_back(m.name);
  std::map<std::string, std::string> group_owner;
  for (auto it = pl.begin(); it != pl.end(); ++it) {
    const std::string& name = pl.name(it);
    const std::string path = "Bodies->" + name;
    const ParameterList& sub = pl.sublist(name);
    check_list(sub, path, {&ls});
    require(sub, path, {&ls});
    BodyConfig b;
    b.name = name;
    b.group = sub.isParameter("physical group") ? get_string(sub, ls, "physical group") : name;
    if (b.group.empty()) fail(quoted(path + "->physical group") + " must not be empty");
    b.material = get_string(sub, ls, "material");
    b.element_technology = get_string(sub, ls, "element technology");
    if (sub.isParameter("initial velocity")) {
      const auto v = get_array(sub, ls, "initial velocity");
      check_dim_length(v, path + "->initial velocity");
      b.has_velocity = true;
      for (std::size_t k = 0; k < v.size() && k < 3; ++k) b.velocity[k] = v[k];
    }
    read_body_initial_state(sub, path, b);
    if (std::find(defined.begin(), defined.end(), b.material) == defined.end()) {
      std::string msg = quoted(path + "->material") + " names undefined material '" + b.material +
                        "'; defined materials: " + join(defined);
      const std::string near = nearest_name(b.material, defined);
      if (!near.empty()) msg += "; did you mean '" + near + "'?";
      fail(msg);
    }
    const auto [pos, fresh] = group_owner.emplace(b.group, name);
    if (!fresh)
      fail("'Bodies->" + pos->second + "' and " + quoted(path) + " both use physical group '" + b.group +
           "'; a physical group belongs to one body");
    cfg_.bodies.push_back(b);
  }
  if (cfg_.bodies.empty()) fail("'Bodies' defines no body; add one sublist per body");
}

}  // namespace stentor::deck_reader
