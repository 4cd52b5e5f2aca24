// Problem->kinematics = axisymmetric (docs/axisymmetric.md): what the deck and the mesh must
// be, and the constraint u_r = 0 on the axis. Trilinos-free.
#pragma once
#include "deck/Config.hpp"
#include "mesh/Mesh.hpp"

namespace stentor {

// Name of the Dirichlet set an axisymmetric run adds for the nodes on the axis (u_r = 0);
// its reaction is reported as reaction_axis_x.
inline const char* axis_set_name() { return "axis"; }

// What axisymmetric runs do not support (yet), refused with an InputError naming the
// parameter: mortar contact, stent metrics, initial angular velocities,
// Holzapfel-Gasser-Ogden fibres about another axis than the mesh's y axis, a boundary
// condition named like the axis set, a 3D Mesh->dimension. No-op for other kinematics.
void check_axisymmetric_deck(const Config& cfg);

// The whole mesh of an axisymmetric run (on one rank, before it is distributed): 2D, every
// node at r = x >= -tol (tol = 1e-12 times the mesh's extent; refused naming the first node
// below); nodes within tol of the axis are put on it (x = 0 exactly), and a uniform initial
// radial displacement or velocity is refused when nodes lie on the axis. No-op for other
// kinematics.
void prepare_axisymmetric_mesh(const Config& cfg, Mesh& mesh);

}  // namespace stentor
