// The deformable balloon of `Mesh->Balloon` (deck/BalloonConfig.hpp, docs/stent.md "The
// deformable balloon"), added to a generated stent's mesh: a tube of hex8 cells structured
// in (theta, z, r), on the stent's axis (z) and centred on the stent, over the stent's kept
// sector and length.
//
// Nodes: theta uniformly over the kept sector (periodic around a full tube), z uniformly
// over the modelled length, r uniformly through the thickness; (theta, z, r) -> (r cos
// theta, r sin theta, z), with y = 0 and x = 0 put exactly on the cut planes. Each cell's
// local axes (xi, eta, zeta) run along (e_theta, e_z, e_r), so the cells are positively
// oriented.
//
// Groups: volume `balloon` (hex8); quad4 facets, oriented outward: `balloon_inner` (where
// the inflation pressure acts), `balloon_outer` (the surface the stent lies on),
// `balloon_ends` (the balloon's end rings at z = z_begin and, without `half length`,
// z_end: where it is bonded to the catheter). Its facets on the stent's cut planes join
// the stent's groups of the same name (`symmetry_y`, `symmetry_x`, `symmetry_sector`,
// `symmetry_z`), so one Dirichlet set holds both bodies on a plane.
#pragma once
#include "deck/BalloonConfig.hpp"
#include "mesh/Mesh.hpp"

namespace stentor {

// Appends the balloon to `m`, the generated stent's mesh (its nodes after the stent's, its
// volume and facet ids after theirs). Throws InputError naming the parameter when
// balloon_config_error() says so, or when the stent's and the balloon's cells together
// would number more than max_cells ('Mesh->max cells'), before the balloon is built.
void add_balloon(const BalloonConfig& b, const StentConfig& s, double max_cells, const std::string& source, Mesh& m);

}  // namespace stentor
