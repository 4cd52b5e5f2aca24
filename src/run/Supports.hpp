// Statics: rigid-body motions the supports leave free. A static analysis of a body that
// no Dirichlet condition holds in some direction (and that no rigid obstacle could hold)
// has a singular tangent: Newton then fails, or GMRES returns some solution of the
// singular system, with a free rigid motion in it. A cheap, conservative check of the
// deck against the mesh (no false positives on bodies held by contact):
//   - bodies that share nodes form one connected body, and so do the slave and master
//     sides of a contact pair with a master surface (contact couples, it does not hold);
//   - a connected body touched by a rigid obstacle pair is left alone: it may hold it;
//   - otherwise each direction x, y (, z) must be prescribed at some node of it, and the
//     prescribed nodes must not all be one node (which leaves the rotation free).
#pragma once
#include <string>
#include <vector>

#include "bc/Loads.hpp"
#include "deck/Config.hpp"
#include "mesh/Mesh.hpp"

namespace stentor {

// One warning line per connected body whose rigid motion is free, naming its bodies and
// the free directions; none for dynamic analyses.
std::vector<std::string> unsupported_bodies(const Config& cfg, const Mesh& mesh, const Loads& loads);

}  // namespace stentor
