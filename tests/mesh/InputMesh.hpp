// The mesh settings of a file in inputs/ for tests: file, Mesh->size, Mesh->order.
#pragma once
#include <string>

#include "deck/Config.hpp"

inline stentor::MeshConfig input_mesh(const std::string& name, double size, int order) {
  stentor::MeshConfig c;
  c.file = std::string(STENTOR_SOURCE_DIR) + "/inputs/" + name;
  c.size = size;
  c.order = order;
  return c;
}
