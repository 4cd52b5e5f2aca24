#include "geometry/Generators.hpp"

#include <stdexcept>

#include "geometry/ArteryGenerator.hpp"
#include "geometry/BalloonGenerator.hpp"
#include "geometry/StentGenerator.hpp"

namespace stentor {

Mesh generate_mesh(const MeshConfig& cfg) {
  if (cfg.generator == "stent") {
    Mesh m = generate_stent(cfg.stent, cfg.max_cells, cfg.file + " (Mesh->Stent)");
    if (cfg.balloon.enabled) add_balloon(cfg.balloon, cfg.stent, cfg.max_cells, cfg.file + " (Mesh->Balloon)", m);
    if (cfg.artery.around_stent) add_artery(cfg.artery, cfg.stent, cfg.max_cells, cfg.file + " (Mesh->Artery)", m);
    return m;
  }
  if (cfg.generator == "artery") return generate_artery(cfg.artery, cfg.max_cells, cfg.file + " (Mesh->Artery)");
  throw std::logic_error("generate_mesh: unknown generator '" + cfg.generator + "'");
}

}  // namespace stentor
