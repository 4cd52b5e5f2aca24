#include "mesh/Mesh.hpp"

#include <algorithm>
#include <cmath>

namespace stentor {
namespace {
std::vector<std::string> unique_names(const std::vector<CellBlock>& blocks) {
  std::vector<std::string> names;  // first-appearance (block) order
  for (const auto& b : blocks)
    if (std::find(names.begin(), names.end(), b.name) == names.end()) names.push_back(b.name);
  return names;
}
}  // namespace

std::vector<std::string> Mesh::volume_group_names() const { return unique_names(volumes); }
std::vector<std::string> Mesh::boundary_group_names() const { return unique_names(boundaries); }

Mesh::Box Mesh::bounding_box() const {
  Box b{{1e300, 1e300, 1e300}, {-1e300, -1e300, -1e300}};
  for (std::size_t n = 0; n < num_nodes(); ++n)
    for (int c = 0; c < 3; ++c) {
      b.lo[c] = std::min(b.lo[c], x[3 * n + c]);
      b.hi[c] = std::max(b.hi[c], x[3 * n + c]);
    }
  return b;
}

double Mesh::Box::diagonal() const {
  double d = 0.0;
  for (int c = 0; c < 3; ++c) d += (hi[c] - lo[c]) * (hi[c] - lo[c]);
  return std::sqrt(d);
}

}  // namespace stentor
