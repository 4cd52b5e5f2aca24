#include "geometry/MshWriter.hpp"

#include <map>
#include <sstream>
#include <stdexcept>

namespace stentor {
namespace {

int gmsh_type(CellType t) {
  switch (t) {
    case CellType::Point1: return 15;
    case CellType::Line2: return 1;
    case CellType::Tri3: return 2;
    case CellType::Quad4: return 3;
    case CellType::Tet4: return 4;
    case CellType::Hex8: return 5;
    default: throw std::logic_error("mesh_to_msh: a cell type without a gmsh 2.2 number here");
  }
}

int type_dim(CellType t) {
  switch (t) {
    case CellType::Point1: return 0;
    case CellType::Line2: return 1;
    case CellType::Tri3:
    case CellType::Quad4: return 2;
    default: return 3;
  }
}

}  // namespace

std::string mesh_to_msh(const Mesh& m) {
  if (m.partial) throw std::logic_error("mesh_to_msh: needs the whole mesh");
  std::ostringstream os;
  os.precision(17);
  os << "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n";
  std::map<std::pair<int, int>, std::string> names;  // (dim, tag) -> name
  std::size_t cells = 0;
  for (const auto* list : {&m.volumes, &m.boundaries})
    for (const CellBlock& b : *list) {
      names[{type_dim(b.type), b.physical_tag}] = b.name;
      cells += b.num_cells();
    }
  os << "$PhysicalNames\n" << names.size() << "\n";
  for (const auto& [key, name] : names) os << key.first << " " << key.second << " \"" << name << "\"\n";
  os << "$EndPhysicalNames\n$Nodes\n" << m.num_nodes() << "\n";
  for (std::size_t n = 0; n < m.num_nodes(); ++n)
    os << n + 1 << " " << m.x[3 * n] << " " << m.x[3 * n + 1] << " " << m.x[3 * n + 2] << "\n";
  os << "$EndNodes\n$Elements\n" << cells << "\n";
  std::size_t id = 0;
  for (const auto* list : {&m.volumes, &m.boundaries})
    for (const CellBlock& b : *list) {
      const int type = gmsh_type(b.type);
      for (std::size_t c = 0; c < b.num_cells(); ++c) {
        os << ++id << " " << type << " 2 " << b.physical_tag << " " << b.physical_tag;
        for (int k = 0; k < b.nodes_per_cell; ++k) os << " " << b.conn[c * b.nodes_per_cell + k] + 1;
        os << "\n";
      }
    }
  os << "$EndElements\n";
  return os.str();
}

}  // namespace stentor
