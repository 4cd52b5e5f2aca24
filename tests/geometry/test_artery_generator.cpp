// The parametric artery (geometry/ArteryGenerator.hpp) against closed forms: the layers'
// volumes and the lumen's area of the polygonal cross-section (N/2 (r2^2 - r1^2)
// sin(2 pi / N) L, N 2 Ri sin(pi / N) L), their second-order approach to the circle's
// pi (r2^2 - r1^2) L and 2 pi Ri L, the reductions, the groups, bad input.
#include <gtest/gtest.h>

#include <cmath>
#include <set>
#include <string>
#include <tuple>

#include "deck/Config.hpp"
#include "geometry/ArteryGenerator.hpp"
#include "mesh/MeshCheck.hpp"

using namespace stentor;

namespace {

const double kPi = 3.14159265358979323846;

// A coronary artery in mm (Holzapfel et al. 2005 thicknesses): lumen 3 mm, intima 0.27,
// media 0.21, adventitia 0.34.
ArteryConfig base() {
  ArteryConfig a;
  a.inner_diameter = 3.0;
  a.length = 4.0;
  a.thickness[0] = 0.27;
  a.thickness[1] = 0.21;
  a.thickness[2] = 0.34;
  a.elements_around = 24;
  a.elements_along = 4;
  return a;
}

// Trilinear hex volume, 2x2x2 Gauss (exact for the trilinear map's det J).
double hex_volume(const Mesh& m, const GId* c) {
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

const CellBlock* block(const std::vector<CellBlock>& bs, const std::string& name) {
  for (const auto& b : bs)
    if (b.name == name) return &b;
  return nullptr;
}

double volume(const Mesh& m, const std::string& layer) {
  const CellBlock* b = block(m.volumes, layer);
  double v = 0.0;
  for (std::size_t c = 0; c < b->num_cells(); ++c) v += hex_volume(m, &b->conn[8 * c]);
  return v;
}

// Area of a facet group and the sum of its facets' normals dotted with the radial
// direction at their centres (sign: outward from the body); planar facets: the area is half
// the cross product of the diagonals.
void facets(const Mesh& m, const std::string& name, double& area, double& radial) {
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

double polygon_layer(const ArteryConfig& a, int l) {
  const double r1 = l == 0 ? a.inner_radius() : a.layer_outer_radius(l - 1), r2 = a.layer_outer_radius(l);
  const int N = a.elements_around;
  return 0.5 * N * (r2 * r2 - r1 * r1) * std::sin(2.0 * kPi / N) * a.length;
}

std::size_t duplicate_nodes(const Mesh& m) {
  std::set<std::tuple<long long, long long, long long>> seen;
  for (std::size_t n = 0; n < m.num_nodes(); ++n) {
    const double* X = m.coord(static_cast<GId>(n));
    seen.insert({std::llround(X[0] * 1e7), std::llround(X[1] * 1e7), std::llround(X[2] * 1e7)});
  }
  return m.num_nodes() - seen.size();
}

}  // namespace

TEST(ArteryGenerator, LayerVolumesLumenAreaAndGroups) {
  const ArteryConfig a = base();
  const Mesh m = generate_artery(a, 1e6, "test");
  EXPECT_EQ(count_inverted_cells(m), 0u);
  EXPECT_NO_THROW(check_mesh(m));
  EXPECT_EQ(duplicate_nodes(m), 0u);
  EXPECT_EQ(m.num_nodes(), 24u * 5u * 5u);
  EXPECT_EQ(m.num_volume_cells(), 24u * 4u * 4u);
  for (const char* g : {"lumen", "outer", "end_proximal", "end_distal"}) EXPECT_NE(block(m.boundaries, g), nullptr) << g;
  for (const char* g : {"symmetry_x", "symmetry_y", "symmetry_z"}) EXPECT_EQ(block(m.boundaries, g), nullptr) << g;
  for (int l = 0; l < 3; ++l) {
    const double v = volume(m, kArteryLayer[l]);
    EXPECT_NEAR(v / polygon_layer(a, l), 1.0, 1e-12) << kArteryLayer[l];
    const double r1 = l == 0 ? a.inner_radius() : a.layer_outer_radius(l - 1), r2 = a.layer_outer_radius(l);
    const double circle = kPi * (r2 * r2 - r1 * r1) * a.length, chord = std::sin(2.0 * kPi / 24) / (2.0 * kPi / 24);
    EXPECT_NEAR(v / circle, chord, 1e-12);
  }
  double area, radial;
  facets(m, "lumen", area, radial);
  EXPECT_NEAR(area / (24 * 2.0 * a.inner_radius() * std::sin(kPi / 24) * a.length), 1.0, 1e-12);
  EXPECT_NEAR(radial / area, -std::cos(0.0), 1e-12);  // pointing into the lumen: out of the wall
  facets(m, "outer", area, radial);
  EXPECT_NEAR(area / (24 * 2.0 * a.outer_radius() * std::sin(kPi / 24) * a.length), 1.0, 1e-12);
  EXPECT_NEAR(radial / area, 1.0, 1e-12);
  facets(m, "end_proximal", area, radial);
  const double ring = 12 * (a.outer_radius() * a.outer_radius() - a.inner_radius() * a.inner_radius()) * std::sin(2 * kPi / 24);
  EXPECT_NEAR(area / ring, 1.0, 1e-12);
  // The cross-section's lumen area, from the lumen nodes of z = 0: the polygon's.
  for (GId n : block(m.boundaries, "lumen")->conn)
    EXPECT_NEAR(std::hypot(m.coord(n)[0], m.coord(n)[1]), a.inner_radius(), 1e-13);
  // The polygon tends to the circle at second order: the volume defect 1 - sin(x)/x = x^2/6.
  ArteryConfig fine = a;
  fine.elements_around = 48;
  const Mesh mf = generate_artery(fine, 1e6, "test");
  const double d1 = 1.0 - volume(m, "media") / (kPi * (std::pow(a.layer_outer_radius(1), 2) - std::pow(a.layer_outer_radius(0), 2)) * a.length);
  const double d2 = 1.0 - volume(mf, "media") / (kPi * (std::pow(a.layer_outer_radius(1), 2) - std::pow(a.layer_outer_radius(0), 2)) * a.length);
  std::printf("[artery] media volume defect vs circle: 24 cells around %.3e, 48: %.3e (ratio %.3f)\n", d1, d2, d1 / d2);
  const double x1 = 2.0 * kPi / 24, x2 = 2.0 * kPi / 48;
  EXPECT_NEAR(d1, 1.0 - std::sin(x1) / x1, 1e-12);
  EXPECT_NEAR(d2, 1.0 - std::sin(x2) / x2, 1e-12);
  EXPECT_GT(d1 / d2, 3.9);  // x^2/6: a quarter of the defect with twice the cells
}

TEST(ArteryGenerator, Reductions) {
  for (const char* sector : {"half", "quarter"})
    for (bool half_length : {false, true}) {
      ArteryConfig a = base();
      a.sector = sector;
      a.half_length = half_length;
      const Mesh m = generate_artery(a, 1e6, "test");
      EXPECT_EQ(count_inverted_cells(m), 0u);
      EXPECT_NO_THROW(check_mesh(m));
      const double f = a.sector_fraction() * (half_length ? 0.5 : 1.0);
      for (int l = 0; l < 3; ++l) EXPECT_NEAR(volume(m, kArteryLayer[l]) / (f * polygon_layer(a, l)), 1.0, 1e-12);
      const bool quarter = std::string(sector) == "quarter";
      EXPECT_EQ(block(m.boundaries, "symmetry_x") != nullptr, quarter);
      EXPECT_EQ(block(m.boundaries, "end_distal") != nullptr, !half_length);
      EXPECT_EQ(block(m.boundaries, "symmetry_z") != nullptr, half_length);
      for (GId n : block(m.boundaries, "symmetry_y")->conn) EXPECT_EQ(m.coord(n)[1], 0.0);
      if (quarter)
        for (GId n : block(m.boundaries, "symmetry_x")->conn) EXPECT_EQ(m.coord(n)[0], 0.0);
      if (half_length)
        for (GId n : block(m.boundaries, "symmetry_z")->conn) EXPECT_EQ(m.coord(n)[2], 2.0);
      // The cut planes' facets: the wall's rectangle (r from Ri to Ro, z over the modelled length), twice.
      double area, radial;
      facets(m, "symmetry_y", area, radial);
      const double rect = (a.outer_radius() - a.inner_radius()) * a.modelled_length();
      EXPECT_NEAR(area / ((quarter ? 1 : 2) * rect), 1.0, 1e-12);
    }
}

TEST(ArteryGenerator, BadInputNamesTheParameter) {
  auto message = [](const ArteryConfig& a, double max_cells = 1e6) {
    try {
      generate_artery(a, max_cells, "deck.xml");
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  ArteryConfig a = base();
  a.thickness[1] = 0.0;
  EXPECT_NE(message(a).find("'Mesh->Artery->media thickness' must be > 0"), std::string::npos) << message(a);
  a = base();
  a.thickness[2] = -0.1;
  EXPECT_NE(message(a).find("'Mesh->Artery->adventitia thickness'"), std::string::npos) << message(a);
  a = base();
  a.sector = "quarter";
  a.elements_around = 22;
  EXPECT_NE(message(a).find("'Mesh->Artery->elements around' = 22 must be >= 4 and divisible by 4"), std::string::npos)
      << message(a);
  a = base();
  a.half_length = true;
  a.elements_along = 3;
  EXPECT_NE(message(a).find("'Mesh->Artery->elements along' = 3"), std::string::npos) << message(a);
  EXPECT_NE(message(base(), 100.0).find("more than 'Mesh->max cells' = 100"), std::string::npos) << message(base(), 100.0);
}
