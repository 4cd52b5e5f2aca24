// Stent and artery metrics of Output->Stent Metrics (docs/deck.md): lumen radius (and
// area for a 2D cross-section), stent radius, dogboning and foreshortening (axis in the
// model), the artery wall's largest von Mises and circumferential stress, and the largest
// contact pressure. Radii are distances of the current node positions from the vessel
// axis. Every rank computes the same values (the group nodes' displacements are summed
// over ranks, each node from its owner only; maxima are reduced), so they do not depend
// on the number of ranks. In an axisymmetric run (the axis the axis of revolution, x = 0,
// checked by check_axisymmetric_deck) the radii are r = x of the section's nodes and the
// circumferential stress is the hoop stress sigma_thth, the output's third component.
#pragma once
#include <string>
#include <vector>

#include "run/Model.hpp"

namespace stentor {

class StentMetrics {
 public:
  // Resolves the groups; throws InputError naming the parameter.
  explicit StentMetrics(const Model& model);

  // The axis lies in the model (2D axial section or 3D): dogboning, foreshortening.
  bool axial() const { return axial_; }
  std::vector<std::string> columns() const;
  // One value per column at displacement u (collective). The first call fixes the
  // reference (lumen radius, stent length) of the gains and of the foreshortening.
  std::vector<double> evaluate(const la::Vector& u);

 private:
  struct Group {
    std::vector<GId> nodes;        // sorted global ids
    std::vector<double> z0;        // reference axial coordinate of each node
  };
  double radius(const double* x) const;
  double axial_coordinate(const double* x) const;
  void stresses(const la::Vector& u, double& von_mises, double& hoop) const;  // collective
  double lumen_area(const std::vector<double>& x) const;

  const Model& m_;
  const StentMetricsConfig& c_;
  bool axisymmetric_ = false;  // Problem->kinematics = axisymmetric
  bool axial_ = true;
  Group stent_, lumen_;
  std::vector<int> artery_blocks_;  // Mesh::volumes indices of the artery group
  std::vector<std::vector<GId>> lumen_facets_;  // cross-section: the lumen's segments (node pairs, indices into lumen_.nodes)
  double z_lo_ = 0.0, z_hi_ = 0.0;  // the stent's reference axial span
};

}  // namespace stentor
