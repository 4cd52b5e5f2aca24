// The parametric artery mesh (deck `Mesh->Artery`, docs/artery.md): hex8 cells,
// structured in (theta, z, r) and built directly from deck/ArteryConfig.hpp.
//
// Nodes: r on the layer interfaces Ri, Ri + t_intima, ... and uniformly in between
// (`elements through <layer>` cells per layer), theta uniformly (`elements around` over
// the whole circumference; the seam theta = 0 shares its nodes around a full tube),
// z uniformly (`elements along` over the whole length); (theta, z, r) -> (r cos theta,
// r sin theta, z), with x = 0 / y = 0 put exactly on the cut planes. Each cell has its
// local axes (xi, eta, zeta) along (e_theta, e_z, e_r), so the cells are positively
// oriented. The cross-section is the polygon of the nodes: a layer between radii r1, r2
// has the volume N/2 (r2^2 - r1^2) sin(2 pi / N) L (N = `elements around`) over the
// whole tube, the lumen's facets the area N 2 Ri sin(pi / N) L.
//
// Reductions: `sector` half keeps 0 <= theta <= pi (y >= 0), quarter 0 <= theta <= pi/2;
// `half length` keeps 0 <= z <= length / 2.
//
// Groups (Mesh::volumes / Mesh::boundaries): volumes `intima`, `media`, `adventitia`
// (hex8, physical tags 1, 2, 3); quad4 facets, oriented outward: `lumen` (r = Ri),
// `outer` (the adventitia's outer surface), `end_proximal` (z = 0), `end_distal`
// (z = length, not with `half length`), `symmetry_x` (x = 0, quarter), `symmetry_y`
// (y = 0, half and quarter), `symmetry_z` (z = length / 2, half length).
#pragma once
#include <string>

#include "deck/ArteryConfig.hpp"
#include "mesh/Mesh.hpp"

namespace stentor {

// Throws InputError naming the parameter when artery_config_error(a) says so, or when
// the cells would number more than max_cells ('Mesh->max cells'), before anything is
// built. `source` names the mesh in messages (Mesh::source).
Mesh generate_artery(const ArteryConfig& a, double max_cells, const std::string& source);

}  // namespace stentor
