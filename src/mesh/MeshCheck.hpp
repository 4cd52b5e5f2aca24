// Sanity checks of a Mesh before anything is assembled on it.
#pragma once
#include "mesh/Mesh.hpp"

namespace stentor {

// Throws InputError (message starting with m.source) when
//  * a volume cell has det J <= 0 (relative to its size: det J <= 1e-12 h^dim)
//    at one of its reference nodes or at its centroid: "<file>: 3 inverted or
//    degenerate elements (det J <= 0) in group 'ring', e.g. cell 17 at (x, y, z)"
//    (cell = global volume cell id, point = the cell's node average); in 2D a
//    group whose cells are all inverted gets a hint that the surface is
//    oriented clockwise (reverse its curve loop);
//  * a boundary group has nodes that belong to no volume (body) cell.
void check_mesh(const Mesh& m);

// Number of volume cells with det J <= 0 somewhere (the test check_mesh uses).
std::size_t count_inverted_cells(const Mesh& m);

}  // namespace stentor
