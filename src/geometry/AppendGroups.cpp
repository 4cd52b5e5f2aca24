#include "geometry/AppendGroups.hpp"

#include <algorithm>

namespace stentor {

GId next_facet_id(const Mesh& m) {
  GId next = 0;
  for (const CellBlock& c : m.boundaries)
    for (GId id : c.cell_id) next = std::max(next, id + 1);
  return next;
}

GId next_cell_id(const Mesh& m) {
  GId n = 0;
  for (const CellBlock& c : m.volumes) n += static_cast<GId>(c.num_cells());
  return n;
}

int next_tag(const Mesh& m) {
  int tag = 0;
  for (const CellBlock& c : m.volumes) tag = std::max(tag, c.physical_tag);
  for (const CellBlock& c : m.boundaries) tag = std::max(tag, c.physical_tag);
  return tag + 1;
}

void append_quads(std::vector<std::pair<std::string, std::vector<GId>>> groups, int first_tag, Mesh& m) {
  GId id = next_facet_id(m);
  int tag = first_tag;
  for (auto& [name, conn] : groups) {
    auto it = std::find_if(m.boundaries.begin(), m.boundaries.end(),
                           [&](const CellBlock& c) { return c.name == name && c.type == CellType::Quad4; });
    if (it == m.boundaries.end()) {
      CellBlock c;
      c.name = name;
      c.physical_tag = tag++;
      c.type = CellType::Quad4;
      c.nodes_per_cell = 4;
      m.boundaries.push_back(std::move(c));
      it = m.boundaries.end() - 1;
    }
    for (std::size_t q = 0; q < conn.size() / 4; ++q) it->cell_id.push_back(id++);
    it->conn.insert(it->conn.end(), conn.begin(), conn.end());
  }
}

}  // namespace stentor
