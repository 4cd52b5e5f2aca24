#include "bc/Axisymmetry.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace stentor {

namespace {

std::string refused(const Config& cfg, const std::string& what) {
  return cfg.deck_path + ": " + what + " is not supported with 'Problem->kinematics' = axisymmetric (docs/axisymmetric.md)";
}

}  // namespace

void check_axisymmetric_deck(const Config& cfg) {
  if (!cfg.problem.axisymmetric()) return;
  if (cfg.mesh.dimension == 3)
    throw InputError(cfg.deck_path + ": 'Problem->kinematics' = axisymmetric needs a 2D mesh in the (r, z) half plane; "
                     "'Mesh->dimension' is 3");
  // Contact: node-to-segment and dual mortar pairs (their integrals in the revolved measure
  // 2 pi r ds, contact/Mortar.hpp) and rigid obstacles (2D profiles: surfaces of revolution).
  if (cfg.output.metrics.enabled) {
    // The vessel axis is the axis of revolution: radii are r = x, the circumferential
    // stress is the hoop stress sigma_thth (docs/axisymmetric.md, Output).
    const auto& m = cfg.output.metrics;
    const bool along_y = std::abs(m.axis[0]) < 1e-12 && std::abs(m.axis[2]) < 1e-12;
    if (!along_y || m.axis_point[0] != 0.0)
      throw InputError(cfg.deck_path + ": 'Output->Stent Metrics->axis' and 'axis point': in an axisymmetric run the vessel "
                       "axis is the axis of revolution, the mesh's y axis: expected axis (0, 1, 0) through a point with x = 0");
  }
  const auto& w = cfg.initial.angular_velocity;
  if (w[0] != 0.0 || w[1] != 0.0 || w[2] != 0.0)
    throw InputError(refused(cfg, "a nonzero 'Initial Conditions->angular velocity' (a rotation of the section is not axisymmetric)"));
  for (const auto& b : cfg.bodies)
    if (b.has_angular_velocity) throw InputError(refused(cfg, "'Bodies->" + b.name + "->initial angular velocity'"));
  for (const auto& l : cfg.loads)
    if (l.name == axis_set_name())
      throw InputError(cfg.deck_path + ": 'Boundary Conditions->" + l.name + "': the name '" + axis_set_name() +
                       "' is taken by the axisymmetric run's u_r = 0 set of the nodes on the axis; rename the condition");
  for (const auto& m : cfg.materials) {
    if (m.model != "Holzapfel-Gasser-Ogden") continue;
    const bool along_y = std::abs(m.axis[0]) < 1e-12 && std::abs(m.axis[2]) < 1e-12;
    if (!along_y || m.axis_point[0] != 0.0)
      throw InputError(cfg.deck_path + ": 'Materials->" + m.name +
                       "->axis' and 'axis point': the fibre frame of an axisymmetric run turns about the axis of "
                       "revolution, the mesh's y axis: expected axis (0, 1, 0) through a point with x = 0");
  }
}

void prepare_axisymmetric_mesh(const Config& cfg, Mesh& mesh) {
  if (!cfg.problem.axisymmetric()) return;
  if (mesh.dim != 2)
    throw InputError(cfg.deck_path + ": 'Problem->kinematics' = axisymmetric needs a 2D mesh in the (r, z) half plane; mesh " +
                     mesh.source + " is " + std::to_string(mesh.dim) + "D");
  const std::size_t n = mesh.num_stored_nodes();
  double extent = 0.0;
  for (std::size_t i = 0; i < 3 * n; ++i) extent = std::max(extent, std::abs(mesh.x[i]));
  const double tol = 1e-12 * extent;
  std::size_t on_axis = 0, first_on_axis = 0;
  for (std::size_t i = 0; i < n; ++i) {
    double& r = mesh.x[3 * i];
    if (r < -tol) {
      std::ostringstream os;
      os.precision(17);
      os << cfg.deck_path << ": 'Problem->kinematics' = axisymmetric: node " << mesh.stored_node(i) << " of mesh " << mesh.source
         << " is at r = x = " << r << " < 0 (at (" << r << ", " << mesh.x[3 * i + 1]
         << ")); an axisymmetric mesh lies in the half plane x >= 0, the axis of revolution being x = 0";
      throw InputError(os.str());
    }
    if (std::abs(r) <= tol) {
      if (on_axis++ == 0) first_on_axis = i;
      r = 0.0;
    }
  }
  if (on_axis == 0) return;
  auto radial = [&](double v, const std::string& what) {
    if (v == 0.0) return;
    std::ostringstream os;
    os << cfg.deck_path << ": '" << what << "' has a radial (x) value " << v << ", but node " << mesh.stored_node(first_on_axis)
       << " (and " << on_axis - 1 << " more) of mesh " << mesh.source
       << " lies on the axis, where u_r = 0; a uniform radial value is not axisymmetric there";
    throw InputError(os.str());
  };
  radial(cfg.initial.displacement[0], "Initial Conditions->displacement");
  radial(cfg.initial.velocity[0], "Initial Conditions->velocity");
  for (const auto& b : cfg.bodies) {
    if (b.has_velocity) radial(b.velocity[0], "Bodies->" + b.name + "->initial velocity");
    if (b.has_displacement) radial(b.displacement[0], "Bodies->" + b.name + "->initial displacement");
  }
}

}  // namespace stentor
