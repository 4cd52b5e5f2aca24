#include "fem/CellType.hpp"

namespace stentor {

const char* cell_name(CellType t) {
  switch (t) {
    case CellType::Point1: return "point1";
    case CellType::Line2: return "line2";
    case CellType::Line3: return "line3";
    case CellType::Tri3: return "tri3";
    case CellType::Tri6: return "tri6";
    case CellType::Quad4: return "quad4";
    case CellType::Quad8: return "quad8";
    case CellType::Tet4: return "tet4";
    case CellType::Tet10: return "tet10";
    case CellType::Hex8: return "hex8";
    default: return "invalid";
  }
}

}  // namespace stentor
