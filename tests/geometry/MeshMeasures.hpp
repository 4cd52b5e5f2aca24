// Measures of generated hex8 meshes for the generator tests: cell and block volumes,
// facet areas and their radial orientation, duplicate nodes.
#pragma once
#include <cmath>
#include <set>
#include <string>
#include <tuple>
#include <vector>

#include "mesh/Mesh.hpp"

namespace stentor::test {

// Trilinear hex volume, 2x2x2 Gauss (exact for the trilinear map's det J).
inline double hex_volume(const Mesh& m, const GId* c) {
  const double sx[8] = {-1, 1, 1, -1, -1, 1, 1, -1}, sy[8] = {-1, -1, 1, 1, -1, -1, 1, 1},
               sz[8] = {-1, -1, -1, -1, 1, 1, 1, 1};
  const double g = 1.0 / std::sqrt(3.0);
  double v = 0.0;
  for (int a = 0; a < 8; ++a) {
    const double xi = sx[a] * g, eta = sy[a] * g, zeta = sz[a] * g;
    double J[3][3] = {};
    for (int n = 0; n < 8; ++n) {
      const double d[3] = {sx[n] * (1 + sy[n] * eta) * (1 + sz[n] * zeta) / 8, sy[n] * (1 + sx[n] * xi) * (1 + sz[n] * zeta) / 8,
                           sz[n] * (1 + sx[n] * xi) * (1 + sy[n] * eta) / 8};
      const double* X = m.coord(c[n]);
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) J[i][j] += X[i] * d[j];
    }
    v += J[0][0] * (J[1][1] * J[2][2] - J[1][2] * J[2][1]) - J[0][1] * (J[1][0] * J[2][2] - J[1][2] * J[2][0]) +
         J[0][2] * (J[1][0] * J[2][1] - J[1][1] * J[2][0]);
  }
  return v;
}

// n cells over the angle theta: the area of the polygonal annulus between r1 and r2, times
// the length (the tube generators' cross-sections over a sector).
inline double sector_polygon(double r1, double r2, double theta, int n, double length) {
  return 0.5 * n * (r2 * r2 - r1 * r1) * std::sin(theta / n) * length;
}

inline const CellBlock* block(const std::vector<CellBlock>& bs, const std::string& name) {
  for (const auto& b : bs)
    if (b.name == name) return &b;
  return nullptr;
}

inline double block_volume(const Mesh& m, const std::string& name) {
  const CellBlock* b = block(m.volumes, name);
  double v = 0.0;
  for (std::size_t c = 0; c < b->num_cells(); ++c) v += hex_volume(m, &b->conn[8 * c]);
  return v;
}

// Area of a quad facet group and the sum of its facets' normals dotted with the radial
// direction at their centres (sign: outward from the body); planar facets: the area is half
// the cross product of the diagonals.
inline void facets(const Mesh& m, const std::string& name, double& area, double& radial) {
  const CellBlock* b = block(m.boundaries, name);
  area = radial = 0.0;
  for (std::size_t c = 0; c < b->num_cells(); ++c) {
    const double *p0 = m.coord(b->conn[4 * c]), *p1 = m.coord(b->conn[4 * c + 1]), *p2 = m.coord(b->conn[4 * c + 2]),
                 *p3 = m.coord(b->conn[4 * c + 3]);
    const double u[3] = {p2[0] - p0[0], p2[1] - p0[1], p2[2] - p0[2]}, v[3] = {p3[0] - p1[0], p3[1] - p1[1], p3[2] - p1[2]};
    const double n[3] = {0.5 * (u[1] * v[2] - u[2] * v[1]), 0.5 * (u[2] * v[0] - u[0] * v[2]), 0.5 * (u[0] * v[1] - u[1] * v[0])};
    double cx = 0.0, cy = 0.0;
    for (int k = 0; k < 4; ++k) cx += 0.25 * m.coord(b->conn[4 * c + k])[0], cy += 0.25 * m.coord(b->conn[4 * c + k])[1];
    area += std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    radial += (n[0] * cx + n[1] * cy) / std::hypot(cx, cy);
  }
}

// Nodes at the same place (to 1e-7) as an earlier one.
inline std::size_t duplicate_nodes(const Mesh& m) {
  std::set<std::tuple<long long, long long, long long>> seen;
  for (std::size_t n = 0; n < m.num_nodes(); ++n) {
    const double* X = m.coord(static_cast<GId>(n));
    seen.insert({std::llround(X[0] * 1e7), std::llround(X[1] * 1e7), std::llround(X[2] * 1e7)});
  }
  return m.num_nodes() - seen.size();
}

}  // namespace stentor::test
