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
// Curved (`centreline radius` R > 0, not around a stent): the straight tube's nodes are then
// mapped by (x, y, z) -> (R - (R - x) cos phi, y, length / 2 + (R - x) sin phi), phi =
// (z - length / 2) / R, a rotation of each cross-section about the bend's axis (its cells
// keep their orientation; the plaque's cells are picked before the map); the end groups
// are planes through the bend's axis.
//
// Groups (Mesh::volumes / Mesh::boundaries): volumes `intima`, `media`, `adventitia`
// (hex8, physical tags 1, 2, 3); quad4 facets, oriented outward: `lumen` (r = Ri),
// `outer` (the adventitia's outer surface), `end_proximal` (z = 0), `end_distal`
// (z = length, not with `half length`), `symmetry_x` (x = 0, quarter), `symmetry_y`
// (y = 0, half and quarter), `symmetry_z` (z = length / 2, half length).
//
// Around a generated stent (add_artery: `Mesh->Artery` in a stent deck, docs/artery.md
// "Stent and artery in one model"): the same tube, its z from z0 = the stent's middle -
// length / 2 (the artery's own z = z - z0: the plaque's centre is measured from its
// proximal end), over the stent's kept sector 0 <= theta <= Theta (`elements around` /
// (2 pi / Theta) cells) and, with the stent's `half length`, up to its middle plane. Its
// nodes, cells, facets and physical tags are numbered after the mesh's. Groups: volumes
// `intima`, `media`, `adventitia` (`plaque`); facets `lumen`, `artery_outer`,
// `artery_end_proximal`, `artery_end_distal` (prefixed: the stent has `outer`,
// `end_proximal`, `end_distal`), and on the cut planes the stent's groups `symmetry_y`
// (theta = 0), `symmetry_x` (x = 0, a quarter) or `symmetry_sector` (theta = Theta, a
// period), `symmetry_z` (half length).
#pragma once
#include <string>

#include "deck/ArteryConfig.hpp"
#include "mesh/Mesh.hpp"

namespace stentor {

// Throws InputError naming the parameter when artery_config_error(a) says so, or when
// the cells would number more than max_cells ('Mesh->max cells'), before anything is
// built. `source` names the mesh in messages (Mesh::source).
Mesh generate_artery(const ArteryConfig& a, double max_cells, const std::string& source);

// Appends the artery around the stent s to m, the generated stent's mesh (with its balloon,
// if any). Throws InputError naming the parameter when artery_around_stent_error() says
// so, or when all the cells together would number more than max_cells, before the artery
// is built.
void add_artery(const ArteryConfig& a, const StentConfig& s, double max_cells, const std::string& source, Mesh& m);

}  // namespace stentor
