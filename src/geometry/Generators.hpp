// The mesh generators of `Mesh->generator`, behind one function that mesh/GmshReader's
// read_mesh() calls (install it with set_mesh_generator(&generate_mesh)).
#pragma once
#include "deck/Config.hpp"
#include "mesh/Mesh.hpp"

namespace stentor {

// cfg.generator: "stent" (geometry/StentGenerator.hpp; then the balloon of
// geometry/BalloonGenerator.hpp and the artery of geometry/ArteryGenerator.hpp's
// add_artery(), when the deck has them) or "artery" (geometry/ArteryGenerator.hpp). Throws
// InputError on bad parameters, std::logic_error for an unknown generator.
Mesh generate_mesh(const MeshConfig& cfg);

}  // namespace stentor
