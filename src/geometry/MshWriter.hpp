// A whole Mesh as a gmsh ASCII file (format 2.2), for inspecting a generated mesh in gmsh
// or ParaView: nodes with tags 1..N in Stentor's numbering, every block's cells with the
// block's physical tag as physical and elementary tag, $PhysicalNames with the blocks'
// names. gmsh reads it back (mesh/GmshReader.hpp) to the same nodes, cells and groups.
#pragma once
#include <string>

#include "mesh/Mesh.hpp"

namespace stentor {

// Throws std::logic_error for a part of a mesh (Mesh::partial) or a cell type gmsh's
// 2.2 format is not given here (Point1, Quad4, Hex8 and the other first-order types are).
std::string mesh_to_msh(const Mesh& m);

}  // namespace stentor
