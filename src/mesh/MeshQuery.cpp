#include "mesh/MeshQuery.hpp"

#include <algorithm>

#include "deck/Config.hpp"

namespace stentor {
namespace {

std::string join(const std::vector<std::string>& v) {
  if (v.empty()) return "(none)";
  std::string s;
  for (std::size_t i = 0; i < v.size(); ++i) s += (i ? ", " : "") + v[i];
  return s;
}

std::vector<const CellBlock*> blocks_named(const std::vector<CellBlock>& blocks, const std::string& g) {
  std::vector<const CellBlock*> out;
  for (const auto& b : blocks)
    if (b.name == g) out.push_back(&b);
  return out;
}

[[noreturn]] void not_found(const Mesh& m, const std::string& group, bool boundary, const std::string& prefix = "") {
  std::string msg = prefix + "physical group '" + group + "' not found in mesh " + m.source + "; available " +
                    (boundary ? "boundary" : "volume") + " groups: " +
                    join(boundary ? m.boundary_group_names() : m.volume_group_names());
  const bool other = boundary ? has_volume_group(m, group) : has_boundary_group(m, group);
  if (other) msg += std::string(" ('") + group + "' is a " + (boundary ? "body (volume) group" : "boundary group") + ")";
  throw InputError(msg);
}

std::vector<GId> nodes_of(const std::vector<const CellBlock*>& blocks) {
  std::vector<GId> n;
  for (const auto* b : blocks) n.insert(n.end(), b->conn.begin(), b->conn.end());
  std::sort(n.begin(), n.end());
  n.erase(std::unique(n.begin(), n.end()), n.end());
  return n;
}

}  // namespace

void require_group(const Mesh& m, const std::string& group, bool boundary, const std::string& parameter) {
  if (boundary ? has_boundary_group(m, group) : has_volume_group(m, group)) return;
  not_found(m, group, boundary, "'" + parameter + "' = '" + group + "': ");
}

bool has_volume_group(const Mesh& m, const std::string& group) { return !blocks_named(m.volumes, group).empty(); }
bool has_boundary_group(const Mesh& m, const std::string& group) {
  return !blocks_named(m.boundaries, group).empty();
}

std::vector<const CellBlock*> volume_blocks(const Mesh& m, const std::string& group) {
  auto b = blocks_named(m.volumes, group);
  if (b.empty()) not_found(m, group, false);
  return b;
}

std::vector<const CellBlock*> boundary_blocks(const Mesh& m, const std::string& group) {
  auto b = blocks_named(m.boundaries, group);
  if (b.empty()) not_found(m, group, true);
  return b;
}

std::vector<GId> boundary_nodes(const Mesh& m, const std::string& group) {
  return nodes_of(boundary_blocks(m, group));
}

std::vector<GId> volume_nodes(const Mesh& m, const std::string& group) { return nodes_of(volume_blocks(m, group)); }

}  // namespace stentor
