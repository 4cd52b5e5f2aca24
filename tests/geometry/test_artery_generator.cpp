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
#include "MeshMeasures.hpp"

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

double volume(const Mesh& m, const std::string& layer) { return test::block_volume(m, layer); }
using test::block;
using test::duplicate_nodes;
using test::facets;
using test::hex_volume;

double polygon_layer(const ArteryConfig& a, int l) {
  const double r1 = l == 0 ? a.inner_radius() : a.layer_outer_radius(l - 1), r2 = a.layer_outer_radius(l);
  const int N = a.elements_around;
  return 0.5 * N * (r2 * r2 - r1 * r1) * std::sin(2.0 * kPi / N) * a.length;
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

namespace {

// base() with a plaque of diameter stenosis S over the middle 2 mm, nodes on its peak z = 2
// and on theta = 0, pi.
ArteryConfig stenosed(double S, const std::string& shape, int around, int along) {
  ArteryConfig a = base();
  a.plaque_stenosis = S;
  a.plaque_length = 2.0;
  a.plaque_shape = shape;
  a.elements_around = around;
  a.elements_along = along;
  return a;
}

double total_volume(const Mesh& m) {
  double v = 0.0;
  for (const auto& b : m.volumes)
    for (std::size_t c = 0; c < b.num_cells(); ++c) v += hex_volume(m, &b.conn[8 * c]);
  return v;
}

// The healthy wall's volume plus the plaque's, for the concentric profile on the circle:
// 2 pi int (Ri h - h^2 / 2) dz with h = h_max s(z), int s = Lp / 2, int s^2 = 3 Lp / 8.
double circle_volume(const ArteryConfig& a) {
  const double Ri = a.inner_radius(), Ro = a.outer_radius(), h = a.plaque_peak(), L = a.plaque_length;
  return kPi * (Ro * Ro - Ri * Ri) * a.length + 2.0 * kPi * (Ri * h * L / 2.0 - h * h * 3.0 * L / 16.0);
}

}  // namespace

// A concentric plaque of 50 % diameter stenosis: every lumen node at r = Ri - h(theta, z)
// (1e-12), the lumen's diameter at the peak 1.5 mm = (1 - S) 3 mm, the plaque cells inside
// the healthy lumen and only within the plaque's length, no inverted cell, and the whole
// volume converging at second order to the healthy wall's plus the plaque's closed form.
TEST(ArteryGenerator, ConcentricPlaqueNarrowsTheLumen) {
  const ArteryConfig a = stenosed(0.5, "concentric", 24, 16);
  const Mesh m = generate_artery(a, 1e6, "test");
  EXPECT_EQ(count_inverted_cells(m), 0u);
  EXPECT_NO_THROW(check_mesh(m));
  ASSERT_NE(block(m.volumes, "plaque"), nullptr);
  // Each block's cell ids are one consecutive range, the blocks' ranges in order (the
  // output writes a block's cells as one range; the plaque's cells, picked out of the
  // intima's columns, once had ids between the intima's).
  GId next = m.volumes.front().cell_id.front();
  for (const CellBlock& b : m.volumes)
    for (std::size_t c = 0; c < b.num_cells(); ++c) ASSERT_EQ(b.cell_id[c], next++) << b.name << " cell " << c;
  for (const CellBlock& b : m.volumes) EXPECT_EQ(locate_cell(m, b.cell_id.back()).first, static_cast<std::size_t>(&b - m.volumes.data()));
  const CellBlock* lumen = block(m.boundaries, "lumen");
  double worst = 0.0, d_min = 1e9;
  for (GId n : lumen->conn) {
    const double* X = m.coord(n);
    const double r = std::hypot(X[0], X[1]), th = std::atan2(X[1], X[0]);
    worst = std::max(worst, std::abs(r - (a.inner_radius() - a.plaque_thickness(th, X[2]))));
    if (std::abs(X[2] - 2.0) < 1e-12) d_min = std::min(d_min, 2.0 * r);
  }
  EXPECT_LT(worst, 1e-12);
  EXPECT_NEAR(d_min, 1.5, 1e-12);
  const CellBlock* p = block(m.volumes, "plaque");
  for (std::size_t c = 0; c < p->num_cells(); ++c) {
    double r = 0.0, z = 0.0;
    for (int k = 0; k < 8; ++k) r += std::hypot(m.coord(p->conn[8 * c + k])[0], m.coord(p->conn[8 * c + k])[1]) / 8, z += m.coord(p->conn[8 * c + k])[2] / 8;
    EXPECT_LT(r, a.inner_radius());
    EXPECT_LT(std::abs(z - 2.0), 1.0);
  }
  // Second order in the cell size (around and along halved together).
  const double e1 = std::abs(total_volume(m) / circle_volume(a) - 1.0);
  const ArteryConfig f = stenosed(0.5, "concentric", 48, 32);
  const double e2 = std::abs(total_volume(generate_artery(f, 1e6, "test")) / circle_volume(f) - 1.0);
  EXPECT_LT(e1, 2e-2);
  EXPECT_GT(e1 / e2, 3.5);
  std::printf("[artery] concentric 50 %% plaque: %zu plaque cells, volume error %.2e -> %.2e (ratio %.2f)\n", p->num_cells(), e1, e2,
              e1 / e2);
}

// An eccentric plaque is a crescent on the +x side: every lumen node at r = Ri - h (1e-12),
// the node at theta = pi keeps r = Ri, the diameter along x through the peak is
// (1 - S) 2 Ri, most plaque cells lie at x > 0; the half sector (y >= 0) holds half of the
// full tube's plaque cells.
TEST(ArteryGenerator, EccentricPlaqueOnOneSide) {
  const ArteryConfig a = stenosed(0.25, "eccentric", 24, 16);
  const Mesh m = generate_artery(a, 1e6, "test");
  EXPECT_EQ(count_inverted_cells(m), 0u);
  double r0 = 0.0, rpi = 0.0;
  for (GId n : block(m.boundaries, "lumen")->conn) {
    const double* X = m.coord(n);
    if (std::abs(X[2] - 2.0) > 1e-12 || std::abs(X[1]) > 1e-12) continue;
    (X[0] > 0 ? r0 : rpi) = std::abs(X[0]);
  }
  EXPECT_NEAR(rpi, a.inner_radius(), 1e-12);
  EXPECT_NEAR(r0 + rpi, 0.75 * 3.0, 1e-12);
  double worst = 0.0;
  for (GId n : block(m.boundaries, "lumen")->conn) {
    const double* X = m.coord(n);
    worst = std::max(worst, std::abs(std::hypot(X[0], X[1]) - (a.inner_radius() - a.plaque_thickness(std::atan2(X[1], X[0]), X[2]))));
  }
  EXPECT_LT(worst, 1e-12);
  const CellBlock* p = block(m.volumes, "plaque");
  ASSERT_NE(p, nullptr);
  std::size_t plus = 0;
  for (std::size_t c = 0; c < p->num_cells(); ++c) {
    double x = 0.0;
    for (int k = 0; k < 8; ++k) x += m.coord(p->conn[8 * c + k])[0] / 8;
    plus += x > 0.0;
  }
  EXPECT_GT(plus, 2 * (p->num_cells() - plus));  // a crescent, thickest on +x (measured 124 against 44)
  ArteryConfig h = a;
  h.sector = "half";
  const Mesh mh = generate_artery(h, 1e6, "test");
  EXPECT_EQ(2 * block(mh.volumes, "plaque")->num_cells(), p->num_cells());
}

TEST(ArteryGenerator, PlaqueBadInput) {
  auto why = [](ArteryConfig a) { return artery_config_error(a); };
  ArteryConfig a = stenosed(1.0, "concentric", 24, 16);
  EXPECT_NE(why(a).find("'Mesh->Artery->plaque stenosis' must be in [0, 1)"), std::string::npos) << why(a);
  a = stenosed(0.7, "concentric", 24, 16);  // h_max = 1.05 mm > the 0.82 mm wall
  EXPECT_NE(why(a).find("makes the plaque 1.05 thick, more than the wall (0.82)"), std::string::npos) << why(a);
  a = stenosed(0.3, "concentric", 24, 16);
  a.plaque_centre = 3.5;
  EXPECT_NE(why(a).find("must lie within 0 <= z <= 'Mesh->Artery->length' = 4"), std::string::npos) << why(a);
  a = stenosed(0.3, "concentric", 24, 16);
  a.plaque_length = 0.0;
  EXPECT_NE(why(a).find("'Mesh->Artery->plaque length' must be > 0"), std::string::npos) << why(a);
  a = stenosed(0.2, "eccentric", 24, 16);
  a.sector = "quarter";
  EXPECT_NE(why(a).find("'Mesh->Artery->plaque shape' = eccentric is not symmetric about x = 0"), std::string::npos) << why(a);
  a = stenosed(0.3, "concentric", 24, 16);
  a.half_length = true;
  a.plaque_centre = 1.5;
  EXPECT_NE(why(a).find("'Mesh->Artery->plaque centre' must be the middle of the tube (2)"), std::string::npos) << why(a);
  a.plaque_centre = -1.0;
  EXPECT_EQ(why(a), "");
}
