// A mesh turned by 40 degrees about (1, 1, 1) / sqrt 3: oblique symmetry planes
// (components = normal) for tests that compare with the aligned mesh's Cartesian rollers.
#pragma once
#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include "geometry/MshWriter.hpp"
#include "mesh/Mesh.hpp"

namespace stentor::testing {

// The rotation (Rodrigues) applied to v; inverse: the rotation back.
inline std::array<double, 3> rotate(const std::array<double, 3>& v, bool inverse = false) {
  const double a = (inverse ? -40.0 : 40.0) * std::acos(-1.0) / 180.0, k = 1.0 / std::sqrt(3.0), c = std::cos(a), s = std::sin(a);
  const double kv = k * (v[0] + v[1] + v[2]);
  const double kx[3] = {k * (v[2] - v[1]), k * (v[0] - v[2]), k * (v[1] - v[0])};  // k x v
  std::array<double, 3> r{};
  for (int i = 0; i < 3; ++i) r[static_cast<std::size_t>(i)] = v[static_cast<std::size_t>(i)] * c + kx[i] * s + k * kv * (1.0 - c);
  return r;
}

// The mesh rotated node by node, written as `msh` (the same cells and groups).
inline std::filesystem::path rotated_msh(Mesh m, const std::filesystem::path& msh) {
  for (std::size_t i = 0; i < m.num_nodes(); ++i) {
    const auto r = rotate({m.x[3 * i], m.x[3 * i + 1], m.x[3 * i + 2]});
    for (int c = 0; c < 3; ++c) m.x[3 * i + static_cast<std::size_t>(c)] = r[static_cast<std::size_t>(c)];
  }
  std::ofstream(msh) << mesh_to_msh(m);
  return msh;
}

}  // namespace stentor::testing
