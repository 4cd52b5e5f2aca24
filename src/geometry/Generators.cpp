#include "geometry/Generators.hpp"

#include <stdexcept>

#include "geometry/ArteryGenerator.hpp"
#include "geometry/StentGenerator.hpp"

namespace stentor {

Mesh generate_mesh(const MeshConfig& cfg) {
  if (cfg.generator == "stent") return generate_stent(cfg.stent, cfg.max_cells, cfg.file + " (Mesh->Stent)");
  if (cfg.generator == "artery") return generate_artery(cfg.artery, cfg.max_cells, cfg.file + " (Mesh->Artery)");
  throw std::logic_error("generate_mesh: unknown generator '" + cfg.generator + "'");
}

}  // namespace stentor
