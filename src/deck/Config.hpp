// The validated contents of an input deck, as plain C++ data.
// Only src/deck/ sees Teuchos; everything else reads this struct.
// docs/deck.md documents every field (names in quotes are the XML parameter names).
#pragma once
#include <array>
#include <functional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "deck/ArteryConfig.hpp"
#include "deck/BalloonConfig.hpp"
#include "deck/StentConfig.hpp"

namespace stentor {

// Every user-facing input error (deck, mesh, group names): the message names the
// file/parameter path and what was expected. main() prints it and exits with status 2.
struct InputError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// Time function multiplying a load: "linear" (t / end time), "constant" (1), or
// "table" (piecewise linear through (times[i], factors[i]), constant beyond the ends).
struct Ramp {
  enum class Kind { Linear, Constant, Table } kind = Kind::Linear;
  std::vector<double> times, factors;
  // With "Stages" (set by the deck reader): the factor in each stage (start, end] of the
  // procedure, replacing the above. Active: the stage's ramp at stage-local time
  // t - start (`linear`: (t - start) / (end - start)); Hold: `held`, the factor at the
  // end of the stage before; Off: 0.
  struct Piece {
    double start = 0.0, end = 1.0;
    enum class Mode { Active, Hold, Off } mode = Mode::Active;
    double held = 0.0;
    Kind kind = Kind::Linear;
    std::vector<double> times, factors;
  };
  std::vector<Piece> stages;
  double operator()(double t, double end_time) const;  // defined in deck/Config.cpp
  // False in a stage that switches the load off (Piece::Mode::Off); true without stages.
  bool on(double t) const;
};

struct ProblemConfig {
  std::string title;                 // "Problem"->"title"
  std::string analysis = "static";   // "Problem"->"analysis": "static" | "dynamic"
  std::string assembly = "atomic";   // "Problem"->"assembly": "atomic" | "coloring" (thread-safe sums)
  std::string units = "SI";          // "Problem"->"units": SI | mm-N-s | mm-g-ms | none (plot labels only)
  // "Problem"->"kinematics": how a 2D mesh is read, "plane strain" | "axisymmetric" ((x, y) = (r, z),
  // full-revolution forces and energies; docs/axisymmetric.md). A 3D mesh takes "plane strain" (the default).
  std::string kinematics = "plane strain";
  bool dynamic() const { return analysis == "dynamic"; }
  bool axisymmetric() const { return kinematics == "axisymmetric"; }
};

struct MeshConfig {
  std::string file;        // "Mesh"->"file", resolved relative to the deck's folder (absolute here)
  double size = 0.0;       // "Mesh"->"size": target element size when meshing a .geo (0: the .geo's own)
  int order = 1;           // "Mesh"->"order": 1 (P1/Q1) or 2 (P2), for .geo meshing
  bool recombine = false;  // "Mesh"->"recombine": quads (2D) / hexes (3D) from a .geo
  int dimension = 0;       // "Mesh"->"dimension": 2 or 3; 0 = highest dimension found in the mesh
  double max_cells = 5e6;  // "Mesh"->"max cells": refuse to mesh a .geo when the estimate is above
  double time_limit = 600; // "Mesh"->"time limit" [s]: gmsh's process (reading + meshing) is stopped after it
  std::string generator;   // "Mesh"->"generator": "" (read `file`), "stent" (from `stent`) or "artery" (from `artery`)
  StentConfig stent;       // "Mesh"->"Stent" (with generator "stent")
  BalloonConfig balloon;   // "Mesh"->"Balloon" (with generator "stent"; enabled when given)
  ArteryConfig artery;     // "Mesh"->"Artery" (with generator "artery")
  bool write_mesh = false; // "Mesh"->"write mesh": the generated mesh as <basename>_mesh.msh in the output folder
  // "Mesh"->"Parameters": (ONELAB name, value) for the .geo's DefineNumber parameters, in deck order.
  std::vector<std::pair<std::string, double>> parameters;
};

struct MaterialConfig {
  std::string name;                       // sublist name under "Materials"
  std::string model = "Ciarlet-Geymonat"; // "model"
  // "C1", "C2", "D" [Pa] of Ciarlet-Geymonat (C1, D > 0, C2 >= 0), given or from E/nu or mu/lambda;
  // Mooney-Rivlin: C1 = mu/2 - C2 > 0 and C2 (material/ElasticConstants.hpp); unused by neo-Hookean.
  double C1 = 0, C2 = 0, D = 0;
  double mu = 0, lambda = 0;              // small-strain Lame constants [Pa] of the law (every model)
  // Holzapfel-Gasser-Ogden (material/HolzapfelGasserOgden.hpp): "k1" [Pa], "k2" [-], "fibre angle" beta
  // [deg] to the circumferential direction of the frame through "axis point" along "axis" (unit).
  // "kappa": the fibre dispersion of Gasser et al. 2006, in [0, 1/3] (0: aligned fibres).
  // "anisotropy": rho of Holzapfel et al. 2005 in (0, 1] (1: the fibres alone).
  double k1 = 0, k2 = 0, fibre_angle = 0, kappa = 0, anisotropy = 1;
  std::array<double, 3> axis_point{0, 0, 0}, axis{0, 0, 1};
  // "centreline radius" (0: the straight axis) and "bend direction" (unit, normal to axis):
  // a curved vessel's fibre frame follows the arc of that radius (FibreFrame::bend).
  double centreline_radius = 0.0;
  std::array<double, 3> bend_direction{1, 0, 0};
  double density = 0;                     // "density" [kg/m^3], >= 0
  double viscosity = 0;                   // "viscosity" eta (Curnier), >= 0; unused in statics
  double yield_stress = 0;                // "yield stress" Y [Pa], > 0 (plasticity only)
  double hardening = 0;                   // "hardening" H [Pa], >= 0 (plasticity only)
  // "hardening law" (material/IsotropicHardening.hpp): linear (Y + H alpha), Voce (+ "saturation
  // stress" Y_inf >= Y [Pa] and "saturation rate" delta > 0 [-]) or table ("hardening table strains"
  // and "hardening table stresses"; then yield_stress is the first stress and hardening 0).
  std::string hardening_law = "linear";
  double saturation_stress = 0, saturation_rate = 0;
  std::vector<double> table_strains, table_stresses;
  // "plastic dynamic step": incremental potential (default), mean value or lagged
  // (docs/plasticity.md, "Dynamics").
  std::string plastic_dynamic_step = "incremental potential";
  // neo-Hookean damage (material/Damage.hpp): "saturation damage" d_inf in [0, 1) and
  // "damage energy scale" beta [Pa] > 0 of d = d_inf (1 - exp(-alpha / beta)).
  double saturation_damage = 0, damage_energy_scale = 0;
  // The multiplicative plasticity models (yield stress, hardening; plastic output fields).
  bool plastic() const { return model == "Ciarlet-Geymonat plasticity" || model == "neo-Hookean plasticity"; }
  bool damage() const { return model == "neo-Hookean damage"; }
  // A law with Gauss-point history (plasticity or damage): refused with the midpoint scheme.
  bool has_history() const { return plastic() || damage(); }
  bool ciarlet_geymonat() const { return model == "Ciarlet-Geymonat" || model == "Ciarlet-Geymonat plasticity"; }
  // The models whose elasticity is the compressible neo-Hookean law (E + nu or mu + lambda only).
  bool neo_hookean() const { return model == "neo-Hookean" || model == "neo-Hookean plasticity" || damage(); }
};

struct BodyConfig {
  std::string name;      // sublist name under "Bodies"
  std::string group;     // "physical group" (default: the sublist name)
  std::string material;  // "material": name of a sublist of "Materials"
  std::string element_technology = "full";  // "element technology": "full" | "f-bar" (hex8, statics)
  bool fbar() const { return element_technology == "f-bar"; }
  bool has_velocity = false;            // "initial velocity" given: replaces Initial Conditions' velocity
  std::array<double, 3> velocity{};     //   (and angular velocity) on this body's nodes
  bool has_angular_velocity = false;    // "initial angular velocity" (with "rotation center") given: idem
  std::array<double, 3> angular_velocity{}, center{};
  bool has_displacement = false;        // "initial displacement" given: replaces Initial Conditions' displacement
  std::array<double, 3> displacement{};
  // v0 on the body's nodes when it has its own (has_velocity or has_angular_velocity):
  // velocity + angular_velocity x (X - center).
  bool own_velocity() const { return has_velocity || has_angular_velocity; }
};

// One entry of "Boundary Conditions" (sublist name = name).
struct LoadConfig {
  enum class Type { Dirichlet, Traction, Pressure, BodyForce, FluidCavity } type = Type::Dirichlet;
  std::string name;
  std::string group;                   // "boundary" (Dirichlet/Traction/Pressure/FluidCavity) or "body" (BodyForce, "" = all)
  std::array<bool, 3> components{};    // Dirichlet: "components", e.g. "x y" or "x" or "all"
  bool all_components = false;         // Dirichlet "all": components = {x, y, z}; z is to be dropped in 2D
  bool normal = false;                 // Dirichlet "normal": the displacement along the (planar) boundary's normal; value in `value`
  std::array<double, 3> vector{};      // Dirichlet "values" / Traction "traction" / BodyForce "force": per component
  double value = 0.0;                  // Pressure "pressure" [Pa] (against the current outward normal); Dirichlet "normal": its value
  Ramp ramp;                           // "ramp" (+ "ramp times", "ramp factors" for "table")
  // FluidCavity: the cavity between `group`, its end planes normal to the axis and planes
  // through the axis, filled with a fluid of bulk modulus K whose volume at zero pressure is
  // V0 (1 + ramp(t) (volume_ratio - 1)), V0 the cavity's reference volume; its pressure is
  // p = K ln(V_fluid / V) (assembly/FluidCavity.hpp).
  double volume_ratio = 1.0;           // "volume ratio" > 0
  double bulk_modulus = 0.0;           // "bulk modulus" [stress] > 0
  std::array<double, 3> axis_point{};  // "axis point"
  std::array<double, 3> axis{0.0, 0.0, 1.0};  // "axis" (normalised)
  // Programmatic only (tests, API users; no deck syntax): when set, replaces `vector` by a
  // function of the reference position X (3 coordinates): the prescribed displacement for
  // Dirichlet, the force density for a body force. Still multiplied by the ramp.
  std::function<std::array<double, 3>(const double* X)> field;
};

struct InitialConditionsConfig {
  std::array<double, 3> displacement{};      // "Initial Conditions"->"displacement" (uniform)
  std::array<double, 3> velocity{};          // "Initial Conditions"->"velocity"
  std::array<double, 3> angular_velocity{};  // "angular velocity" (2D: z component only)
  std::array<double, 3> center{};            // "center"
};

struct TimeIntegrationConfig {
  std::string scheme = "gonzalez";  // "Time Integration"->"scheme": gonzalez | midpoint | newmark | hht
  double hht_alpha = -0.1;          // "hht alpha" in [-1/3, 0]
};

struct SteppingConfig {
  double end_time = 1.0;   // "Stepping"->"end time" > 0
  int num_steps = 1;       // "Stepping"->"steps" >= 1 (initial step = end time / steps)
  int max_cutbacks = 6;    // "Stepping"->"max cutbacks" >= 0: halvings of a failed step in a row before giving up
  double growth = 1.5;     // "Stepping"->"growth" in [1, 4]: step growth per accepted step, up to end time / steps
  int target_iterations = 0;  // "Stepping"->"target iterations": the step follows Newton's iterations (0: off, StepControl)
  double min_dt = 0.0;     // "Stepping"->"min dt": smallest step (0: 1e-6 x end time / steps, see min_step())
  int max_steps = 0;       // "Stepping"->"max steps": cap on steps tried (0: 100 x steps + 1000, see step_cap())
  std::string predictor = "auto";  // "Stepping"->"predictor": auto | none | velocity | lifting (Newton's first iterate)
  double stabilization = 0.0;  // "Stepping"->"stabilization": static steps' viscous factor xi (0: off; StepSystem)
  double contact_approach = 0.0;  // "Stepping"->"contact approach": first-touch depth per step, in slave node sizes (0: off)
  // The values in force, 0 resolved to the defaults.
  double min_step() const { return min_dt > 0.0 ? min_dt : 1e-6 * end_time / num_steps; }
  long step_cap() const { return max_steps > 0 ? max_steps : 100L * num_steps + 1000L; }
};

struct NewtonConfig {
  // The relative residual tolerance of a static or dynamic step: the deck's, or by default
  // 1e-12 in dynamics, where the energy identity holds to the Newton tolerance (S4: max
  // per-step balance 1.4e-7 J/m with 1e-10, 5.8e-9 with 1e-12, +3 % Newton iterations), and
  // 1e-10 in statics (quadratic convergence: the extra digits cost at most one iteration
  // per step, an expensive one on large 3D meshes, for no balance to keep).
  double tolerance_for(bool dynamic) const { return residual_tolerance_given ? residual_tolerance : dynamic ? 1e-12 : 1e-10; }
  int max_iterations = 25;             // "Newton"->"max iterations"
  double residual_tolerance = 1e-10;   // "relative residual tolerance": ||r|| <= tol * ref ...
  bool residual_tolerance_given = false;  // ... else the analysis' default (tolerance_for)
  double absolute_tolerance = 0.0;     // "absolute residual tolerance": ... or ||r|| <= tol (0: relative only)
  double increment_tolerance = 1e-10;  // "increment tolerance": ||du|| <= tol * ||u|| (with residual small)
  bool line_search = true;             // "line search": backtracking on ||r||
  int line_search_max = 6;             // "line search max halvings"
  int line_search_watchdog = 2;        // "line search watchdog": see newton_solve
  std::string forcing = "eisenstat-walker";  // "forcing": fixed | eisenstat-walker (linear tolerance per iteration)
  double forcing_max = 0.1;            // "forcing max": Eisenstat-Walker's upper bound (and first value)
  double max_increment = 0.0;          // "max increment": largest dof change per iteration (0: no limit)
};

struct LinearSolverConfig {
  std::string method = "gmres";          // "Linear Solver"->"method": "gmres" | "direct"
  std::string direct_solver = "auto";    // "direct solver": "auto" | "klu2" | "mumps"
  std::string preconditioner = "auto";   // "preconditioner": "auto" | "schwarz" | "muelu" | "none" (auto: muelu if built)
  double tolerance = 1e-10;              // "tolerance": relative residual of each linear solve
  int max_iterations = 1000;             // "max iterations"
  int restart = 200;                     // "restart": GMRES Krylov subspace size
  int overlap = 1;                       // "overlap": Schwarz overlap
  std::string subdomain_solver = "RILUK";// "subdomain solver": "RILUK" | "ILUT" | "KLU2"(Amesos2)
  int fill_level = 1;                    // "fill level": RILUK level of fill
  int preconditioner_reuse = 20;         // "preconditioner reuse": later setups that may keep it (gmres)
  double preconditioner_rebuild_cost = 25.0;  // "preconditioner rebuild cost": GMRES iterations a build is worth
  bool preconditioner_rebuild_on_change = true;  // "preconditioner rebuild on contact change"
  // Pass-through sublists "Belos", "Ifpack2", "MueLu", "Amesos2" as XML text ("" if absent);
  // their entries override the values above.
  std::string belos_xml, ifpack2_xml, muelu_xml, amesos2_xml;
};

struct ProbeConfig {
  std::string name;                  // sublist name under "Output"->"Probes"
  std::array<double, 3> point{};     // "point": reference coordinates; the nearest node is probed
};

// "Output"->"Stent Metrics" (enabled = the sublist is present).
struct StentMetricsConfig {
  bool enabled = false;
  std::array<double, 3> axis_point{};  // "axis point"
  std::array<double, 3> axis{};        // "axis" (normalized here)
  std::string stent, lumen, artery;    // boundary, boundary, volume group names
  double end_fraction = 0.2;           // "end fraction"
  double malapposition_threshold = 0.0;  // "malapposition threshold" [length] (0: a tenth of the strut thickness)
};

struct OutputConfig {
  std::string directory = "results/{deck}";  // "Output"->"directory" (relative to the working dir, "{deck}" replaced
                                             // by the deck's file name stem when read); --output overrides
  std::string basename = "stentor";   // "Output"->"basename": file name stem
  int every = 1;                      // "Output"->"every": write fields every N converged steps (and the last)
  bool fields = true;                 // "Output"->"fields": HDF5/XDMF output on/off
  std::string field_list = "default"; // "Output"->"field list", as given
  std::vector<std::string> field_names;  // ... resolved (deck/OutputFields.hpp); empty when fields is false
  std::vector<double> times;          // "Output"->"times": extra output times, increasing, in (0, end time]
                                      // (with "interval"'s multiples merged in by resolve_output)
  double interval = 0.0;              // "Output"->"interval": fields every `interval` of time (0: off)
  bool wants(const std::string& field) const;  // fields on and `field` in field_names
  int checkpoint_every = 0;           // "Output"->"checkpoint every": checkpoint every N accepted steps (0: none)
  std::vector<ProbeConfig> probes;    // "Output"->"Probes"
  StentMetricsConfig metrics;         // "Output"->"Stent Metrics"
};

// One node-to-rigid-obstacle contact pair: sublist of "Contact" (name = name).
// See docs/contact.md. Geometry in reference coordinates; the obstacle moves rigidly by
// translation * ramp(t) and its radius changes by radius_change * radius_ramp(t).
struct ContactPairConfig {
  std::string name;
  std::string slave;                      // "slave": boundary physical group whose nodes are the slave nodes
  std::string obstacle;                   // "obstacle": plane | circle (2D) | cylinder (3D) | sphere (3D) | capsule; empty with a master
  std::string master;                     // "master": boundary group of a deformable body (node-to-segment); empty with an obstacle
  std::array<double, 3> point{};          // "point": plane point / circle, sphere centre / cylinder axis point
  std::array<double, 3> normal{};         // "normal": plane outward normal (normalized here; the body lies on its side)
  std::array<double, 3> axis{};           // "axis": cylinder / capsule axis direction (normalized here)
  double radius = 0.0;                    // "radius" (circle, cylinder, sphere, capsule)
  double length = 0.0;                    // "length": capsule axis segment from point to point + length axis [m]
  std::string side = "outside";           // "side": outside (body outside the obstacle) | inside (body inside)
  int point_len = 0, normal_len = 0, axis_len = 0;  // lengths as given (checked against the mesh dimension at run time)
  std::array<double, 3> translation{};    // "translation" [m], times translation_ramp(t)
  Ramp translation_ramp;                  // "translation ramp" (+ "translation ramp times"/"factors")
  double radius_change = 0.0;             // "radius change" [m], times radius_ramp(t)
  Ramp radius_ramp;                       // "radius ramp" (+ times/factors)
  double c_normal = 0.0, c_tangent = 0.0; // "c normal", "c tangent": PDAS parameters (0: automatic, scale-aware)
  double friction = 0.0;                  // "friction": Coulomb coefficient mu >= 0 (0: frictionless)
  std::string formulation = "auto";       // "formulation": auto | persistence | gap (auto: persistence in dynamics, gap in statics)
  std::string discretization = "node-to-segment";  // "discretization" (master pairs): node-to-segment | mortar
  bool linearised_sets = true;            // "set update": linearised (multiplier of the last solve) | residual
};

// One entry of "Stages" (sublist name = name), in deck order: the interval (start, end]
// of the procedure, its step count, and which loads and contact pairs are active. The
// stage ramps are folded into each load's and obstacle's Ramp::stages.
struct StageConfig {
  std::string name;
  double start = 0.0, end = 1.0;     // "duration" or "end time" [s]
  int num_steps = 1;                 // "steps", or duration / "step" rounded up
  std::string analysis = "static";   // "analysis" (default Problem->analysis): static | dynamic
  std::string scheme = "gonzalez";   // "scheme" of a dynamic stage (default Time Integration->scheme)
  double stabilization = 0.0;        // "stabilization" of a static stage (default Stepping->stabilization)
  std::vector<bool> load_active;     // "loads", per Config::loads entry
  std::vector<bool> contact_active;  // "contact", per Config::contact entry
  double step() const { return (end - start) / num_steps; }
  bool dynamic() const { return analysis == "dynamic"; }
};

// A vector parameter whose number of values depends on the mesh dimension, as given in
// the deck: "Bodies->ring->initial velocity" with 2 values, expected 2 in 2D, 3 in 3D.
struct DimVector {
  std::string path;
  int given = 0;
  int in2d = 2, in3d = 3;
};

struct Config {
  std::string deck_path;  // absolute path of the deck file
  ProblemConfig problem;
  MeshConfig mesh;
  std::vector<MaterialConfig> materials;
  std::vector<BodyConfig> bodies;
  std::vector<LoadConfig> loads;
  InitialConditionsConfig initial;
  TimeIntegrationConfig time;
  SteppingConfig stepping;
  NewtonConfig newton;
  LinearSolverConfig linear;
  OutputConfig output;
  std::vector<ContactPairConfig> contact;  // "Contact": empty = no contact (costs nothing)
  std::vector<StageConfig> stages;         // "Stages": empty = one interval [0, Stepping->end time]
  // Every vector parameter given whose length depends on the dimension (checked by the deck
  // only when Mesh->dimension is set; check_vector_dimensions once the mesh is read).
  std::vector<DimVector> dim_vectors;

  const MaterialConfig& material(const std::string& name) const;  // throws InputError

  // The analysis of stage k (of the run without stages: Problem->analysis), and its scheme.
  bool dynamic_in(int stage) const {
    return stages.empty() ? problem.dynamic() : stages[static_cast<std::size_t>(stage)].dynamic();
  }
  const std::string& scheme_in(int stage) const {
    return stages.empty() ? time.scheme : stages[static_cast<std::size_t>(stage)].scheme;
  }
  // The viscous stabilisation factor of stage k's steps (0 in a dynamic stage).
  double stabilization_in(int stage) const {
    if (dynamic_in(stage)) return 0.0;
    return stages.empty() ? stepping.stabilization : stages[static_cast<std::size_t>(stage)].stabilization;
  }
  bool any_stabilization() const {
    for (int k = 0; k < interval_count(); ++k)
      if (stabilization_in(k) > 0.0) return true;
    return false;
  }
  // "static", or the time scheme of a dynamic stage.
  std::string analysis_in(int stage) const { return dynamic_in(stage) ? scheme_in(stage) : std::string("static"); }
  // The number of intervals the run steps through: its stages, or the one without stages.
  int interval_count() const { return stages.empty() ? 1 : static_cast<int>(stages.size()); }
  // Every interval has the same analysis and scheme.
  bool one_analysis() const;
  // Whether some stage (the run without stages) is dynamic / static: what is built once
  // (mass matrix, time integrator, energy output; the supports check of static bodies).
  bool any_dynamic() const;
  bool any_static() const;
  // Whether some stage activates contact pairs a and b together (without stages every pair
  // is active throughout); `stage`, if given, gets the first such stage (nullptr without
  // stages).
  bool pairs_meet(std::size_t a, std::size_t b, const StageConfig** stage = nullptr) const;
};

// Reads and validates a deck. Throws InputError naming the file, the parameter path
// (e.g. "Materials->steel->C1") and what was expected; misspelled names get the
// nearest valid name suggested.
Config read_deck(const std::string& path);

// Throws InputError for the first of cfg.dim_vectors whose number of values does not fit
// a mesh of dimension `dim` (2 or 3), naming the deck, the parameter, the expected and the
// given number. Called once the mesh is read (a run and --check alike): without it a
// 2-value velocity in a 3D deck ran as (vx, vy, 0).
void check_vector_dimensions(const Config& cfg, int dim);

}  // namespace stentor
