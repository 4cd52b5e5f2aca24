#include "io/Units.hpp"

#include <stdexcept>

namespace stentor {

const std::vector<std::string>& unit_systems() {
  static const std::vector<std::string> names = {"SI", "mm-N-s", "mm-g-ms", "none"};
  return names;
}

UnitLabels unit_labels(const std::string& system, int dim, bool axisymmetric) {
  UnitLabels u;
  if (system == "SI") {
    u = {"m", "kg", "s", "N", "Pa", "J", "m/s"};
  } else if (system == "mm-N-s") {
    u = {"mm", "t", "s", "N", "MPa", "mJ", "mm/s"};
  } else if (system == "mm-g-ms") {
    u = {"mm", "g", "ms", "N", "MPa", "mJ", "mm/ms"};
  } else if (system == "none") {
    return u;
  } else {
    throw std::invalid_argument("unknown unit system '" + system + "'");
  }
  if (dim == 2 && !axisymmetric) {  // plane strain: per unit thickness
    u.force += "/" + u.length;
    u.energy += "/" + u.length;
  }
  return u;
}

std::string with_unit(const std::string& quantity, const std::string& unit) {
  return unit.empty() ? quantity : quantity + " [" + unit + "]";
}

}  // namespace stentor
