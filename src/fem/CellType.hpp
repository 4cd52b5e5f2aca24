// Cell (element) types Stentor understands. Node ordering is gmsh's for every type.
#pragma once
#include <Kokkos_Macros.hpp>

namespace stentor {

enum class CellType : int {
  Point1 = 0,
  Line2,
  Line3,
  Tri3,
  Tri6,
  Quad4,
  Quad8,  // serendipity, boundary of hex20 (not a volume cell here)
  Tet4,
  Tet10,
  Hex8,
  Invalid
};

KOKKOS_INLINE_FUNCTION int cell_num_nodes(CellType t) {
  switch (t) {
    case CellType::Point1: return 1;
    case CellType::Line2: return 2;
    case CellType::Line3: return 3;
    case CellType::Tri3: return 3;
    case CellType::Tri6: return 6;
    case CellType::Quad4: return 4;
    case CellType::Quad8: return 8;
    case CellType::Tet4: return 4;
    case CellType::Tet10: return 10;
    case CellType::Hex8: return 8;
    default: return 0;
  }
}

KOKKOS_INLINE_FUNCTION int cell_dim(CellType t) {
  switch (t) {
    case CellType::Point1: return 0;
    case CellType::Line2:
    case CellType::Line3: return 1;
    case CellType::Tri3:
    case CellType::Tri6:
    case CellType::Quad4:
    case CellType::Quad8: return 2;
    case CellType::Tet4:
    case CellType::Tet10:
    case CellType::Hex8: return 3;
    default: return -1;
  }
}

// Polynomial order of the geometry/field interpolation (1 = P1/Q1, 2 = P2).
KOKKOS_INLINE_FUNCTION int cell_order(CellType t) {
  switch (t) {
    case CellType::Line3:
    case CellType::Tri6:
    case CellType::Quad8:
    case CellType::Tet10: return 2;
    default: return 1;
  }
}

// Largest node count of any volume cell: sizes element scratch arrays.
constexpr int kMaxCellNodes = 10;
constexpr int kMaxCellDofs = 3 * kMaxCellNodes;

const char* cell_name(CellType t);  // "tri3", ... (defined in fem/CellType.cpp)

}  // namespace stentor
