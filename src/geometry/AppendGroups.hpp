// A generated body appended to a mesh (geometry/BalloonGenerator, ArteryGenerator): the
// next free ids and physical tag, and quad4 facet groups that join the mesh's groups of
// the same name (a symmetry plane that cuts several bodies) or start new ones.
#pragma once
#include <string>
#include <utility>
#include <vector>

#include "mesh/Mesh.hpp"

namespace stentor {

GId next_facet_id(const Mesh& m);   // after the largest facet id in m (0: none)
GId next_cell_id(const Mesh& m);    // the number of volume cells in m
int next_tag(const Mesh& m);        // after the largest physical tag in m (1: none)

// Appends each (name, quad4 connectivity) in order: to m's quad4 group of that name, or to
// a new group with the next tag from first_tag on. The facet ids continue from
// next_facet_id(m).
void append_quads(std::vector<std::pair<std::string, std::vector<GId>>> groups, int first_tag, Mesh& m);

}  // namespace stentor
