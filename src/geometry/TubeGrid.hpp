// The hex8 cells' local faces, and a structured tube of hex8 cells in (theta, z, r), shared
// by the generators (geometry/StentGenerator, ArteryGenerator, BalloonGenerator).
#pragma once
#include <vector>

#include "mesh/Mesh.hpp"

namespace stentor {

// The hex8's six faces, each ordered so that its normal points out of the cell:
// zeta-, zeta+, eta-, eta+, xi-, xi+ (gmsh's node order).
inline constexpr int kHexFace[6][4] = {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4}, {3, 7, 6, 2}, {0, 4, 7, 3}, {1, 2, 6, 5}};

// cells_t x cells_z x cells_r cells around, along and through a tube; the nodes numbered
// base + (j nt + i) (cells_r + 1) + k, i around (periodic: the seam shares its nodes), j
// along, k outward. A cell's local axes (xi, eta, zeta) run along (e_theta, e_z, e_r), so it
// is positively oriented, and its faces zeta-, zeta+ are the inner and outer ones.
struct TubeGrid {
  int cells_t = 0, cells_z = 0, cells_r = 0;
  bool periodic = false;
  GId base = 0;
  int nt() const { return periodic ? cells_t : cells_t + 1; }  // node columns around
  GId node(int i, int j, int k) const {
    if (periodic) i %= cells_t;
    return base + (static_cast<GId>(j) * nt() + i) * (cells_r + 1) + k;
  }
  void hex(int i, int j, int k, GId* h) const {
    const GId v[8] = {node(i, j, k),         node(i + 1, j, k),         node(i + 1, j + 1, k),
                      node(i, j + 1, k),     node(i, j, k + 1),         node(i + 1, j, k + 1),
                      node(i + 1, j + 1, k + 1), node(i, j + 1, k + 1)};
    for (int n = 0; n < 8; ++n) h[n] = v[n];
  }
  // Appends the nodes of face `f` (kHexFace) of cell (i, j, k) to `out`.
  void face(int i, int j, int k, int f, std::vector<GId>& out) const {
    GId h[8];
    hex(i, j, k, h);
    for (int v = 0; v < 4; ++v) out.push_back(h[kHexFace[f][v]]);
  }
};

}  // namespace stentor
