#include "mesh/Mesh.hpp"

#include <algorithm>

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

}  // namespace stentor
