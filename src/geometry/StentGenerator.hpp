// The parametric stent mesh (deck `Mesh->Stent`, docs/stent.md): hex8 cells, structured
// through the strut's width and thickness, built directly from the pattern of
// deck/StentConfig.hpp and wrapped onto the cylinder.
//
// Construction, in the unrolled mid-surface plane (u = Rm theta, z):
//  * each ring's centreline is cut at every crown (apex, u = multiples of lambda / 2), and
//    where a link's side edge meets the strut's edge; each piece is divided uniformly in
//    arc length into cells of about `element length` (a link's half width gets exactly
//    ceil(link width / (2 h)) cells, the same on both rings it joins);
//  * across the width the nodes are c(u) + d n(u), d in [-w/2, w/2] (n the centreline's
//    unit normal in the plane): the strut's edges are the exact offset curves;
//  * a link's nodes are the attached edge nodes of the two rings, and between them
//    straight lines (an even number of cells along it, so its middle is a node plane);
//  * radially the layers are at r = Ri + t l / n_t; (u, z, r) -> (r cos(u/Rm),
//    r sin(u/Rm), z). Around the full ring the u-index is periodic: the seam theta = 0
//    shares its nodes (no duplicates by construction).
//  * A reduction keeps the cells whose centroid has 0 < theta < pi/2 (quarter) and/or
//    z < total length / 2 (half length); the cut planes are node planes of the pattern
//    (crowns, link middles), and nodes on x = 0 / y = 0 are put there exactly.
// The metal's volume is then (centreline length x w + link areas) x t, up to the chords
// of the straight-edged cells: the u scale is that of the mid-surface.
//
// Groups (Mesh::volumes / Mesh::boundaries):
//   volume `stent` (hex8); quad4 facets, oriented outward: `inner` (r = Ri), `outer`
//   (r = Ro), `end_proximal` (the free edge of ring 0 facing -z), `end_distal` (that of
//   the last ring, not with `half length`), `symmetry_x` / `symmetry_y` (on x = 0 /
//   y = 0, quarter only), `symmetry_z` (on z = total length / 2, half length only),
//   `ring_<k>` (the outer facets of ring k) and `links` (the outer facets of the links,
//   when there are links), `sides` (the rings' side faces (their free edges too), through the
//   thickness, off the cut planes) and `inner_and_sides` (`inner` and `sides`: the surface a
//   balloon wraps, to name as a contact master; its outer edges are nodes of `outer`, so a
//   crimper on `outer` and the balloon may not be active in the same stage); point `anchor`: the inner node of ring 0's strut edge at
//   theta = 0, z = 0 side (one node: the place to hold the axial rigid motion).
#pragma once
#include <string>

#include "deck/StentConfig.hpp"
#include "mesh/Mesh.hpp"

namespace stentor {

// Throws InputError naming the parameter when stent_config_error(s) says so, when the
// cells would number more than max_cells (naming 'Mesh->max cells'; an upper estimate
// counted before anything is built), or when a cell
// came out inverted (a link too wide for its crown: naming 'Mesh->Stent->link width').
// `source` names the mesh in messages (Mesh::source).
Mesh generate_stent(const StentConfig& s, double max_cells, const std::string& source);

}  // namespace stentor
