// Unit labels of a deck's unit system (Problem->units). Units are labels only: Stentor
// converts nothing, a deck is solved in whatever consistent units its values are in.
//
//   system    length  mass  time  force  stress  energy  (derived: N = mass length / time^2)
//   SI        m       kg    s     N      Pa      J
//   mm-N-s    mm      t     s     N      MPa     mJ      (1 t mm / s^2 = 1 N)
//   mm-g-ms   mm      g     ms    N      MPa     mJ      (1 g mm / ms^2 = 1 N)
//   none      (a dimensionless deck: no labels)
//
// A 2D model is a plane-strain slice of unit thickness: its forces and energies are per
// unit thickness (force/length, energy/length: N/m and J/m in SI, N/mm and mJ/mm in mm).
// An axisymmetric 2D model is the full revolution of its section: forces and energies as in 3D.
#pragma once
#include <string>
#include <vector>

namespace stentor {

struct UnitLabels {
  std::string length, mass, time, force, stress, energy, velocity;  // "" for `none`
};

// The labels of `system` (one of unit_systems(), case as in the schema) for a model of
// dimension `dim` (2: force and energy per unit thickness, unless `axisymmetric`). Throws
// std::invalid_argument for an unknown system (the deck reader has already checked it).
UnitLabels unit_labels(const std::string& system, int dim, bool axisymmetric = false);

// The names accepted by unit_labels, in the schema's order.
const std::vector<std::string>& unit_systems();

// An axis label: "force [N]", or "force" when the unit is "" (Problem->units = none).
std::string with_unit(const std::string& quantity, const std::string& unit);

}  // namespace stentor
