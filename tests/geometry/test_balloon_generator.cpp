// The deformable balloon (geometry/BalloonGenerator.hpp) added to a generated stent: the
// tube's volume and surfaces against the closed forms of its polygonal cross-section
// (N/2 (ro^2 - ri^2) sin(2 pi / N) L, N 2 r sin(pi / N) L over the whole circumference;
// per sector the same with N cells over Theta), its place (centred on the stent, inside
// it), the ids after the stent's, the cut planes shared with the stent, bad input.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "deck/Config.hpp"
#include "geometry/BalloonGenerator.hpp"
#include "geometry/StentGenerator.hpp"
#include "mesh/MeshCheck.hpp"
#include "MeshMeasures.hpp"
#include "StentFixtures.hpp"

using namespace stentor;
using test::block;
using test::sector_polygon;

namespace {

const double kPi = 3.14159265358979323846;

StentConfig stent() { return test::s6_two_rings_linked(); }

BalloonConfig balloon() {
  BalloonConfig b;
  b.enabled = true;
  b.outer_diameter = 1.7;
  b.thickness = 0.05;
  b.length = 4.0;
  b.element_length = 0.1;
  return b;
}

double node_radius(const Mesh& m, GId n) { return std::hypot(m.coord(n)[0], m.coord(n)[1]); }

}  // namespace

TEST(BalloonGenerator, TubeCentredInsideTheWholeStent) {
  const StentConfig s = stent();
  const BalloonConfig b = balloon();
  Mesh m = generate_stent(s, 1e6, "test");
  const std::size_t stent_nodes = m.num_nodes(), stent_cells = m.num_volume_cells();
  const double stent_volume = test::block_volume(m, "stent");
  add_balloon(b, s, 1e6, "test", m);
  const int N = b.cells_around(s), nz = b.cells_along(s);
  EXPECT_EQ(N, static_cast<int>(std::ceil(2.0 * kPi * 0.85 / 0.1)));
  EXPECT_EQ(nz, 40);
  const CellBlock* v = block(m.volumes, "balloon");
  ASSERT_NE(v, nullptr);
  EXPECT_EQ(v->num_cells(), static_cast<std::size_t>(N * nz * b.elements_thickness));
  EXPECT_EQ(m.num_nodes() - stent_nodes, static_cast<std::size_t>(N * (nz + 1) * (b.elements_thickness + 1)));
  EXPECT_EQ(v->cell_id.front(), static_cast<GId>(stent_cells));
  EXPECT_EQ(v->cell_id.back(), static_cast<GId>(m.num_volume_cells() - 1));
  EXPECT_EQ(count_inverted_cells(m), 0u);
  EXPECT_EQ(test::duplicate_nodes(m), 0u);
  EXPECT_DOUBLE_EQ(test::block_volume(m, "stent"), stent_volume);
  EXPECT_NEAR(test::block_volume(m, "balloon"), sector_polygon(0.8, 0.85, 2.0 * kPi, N, 4.0), 1e-12);
  double area, radial;
  test::facets(m, "balloon_outer", area, radial);
  EXPECT_NEAR(area, N * 2.0 * 0.85 * std::sin(kPi / N) * 4.0, 1e-12);
  EXPECT_NEAR(radial, area, 1e-12);  // outward: each facet's normal is radial at its centre
  test::facets(m, "balloon_inner", area, radial);
  EXPECT_NEAR(area, N * 2.0 * 0.8 * std::sin(kPi / N) * 4.0, 1e-12);
  EXPECT_NEAR(radial, -area, 1e-12);  // outward from the wall: towards the axis
  // Centred on the stent (0 <= z <= 2.3), its ends 0.85 mm beyond the stent's.
  EXPECT_NEAR(s.total_length(), 2.3, 1e-12);
  double z0 = 1e9, z1 = -1e9, rmin = 1e9, rmax = 0.0;
  for (std::size_t n = stent_nodes; n < m.num_nodes(); ++n) {
    z0 = std::min(z0, m.coord(static_cast<GId>(n))[2]), z1 = std::max(z1, m.coord(static_cast<GId>(n))[2]);
    rmin = std::min(rmin, node_radius(m, static_cast<GId>(n))), rmax = std::max(rmax, node_radius(m, static_cast<GId>(n)));
  }
  EXPECT_NEAR(z0, -0.85, 1e-12);
  EXPECT_NEAR(z1, 3.15, 1e-12);
  EXPECT_NEAR(rmin, 0.8, 1e-12);
  EXPECT_NEAR(rmax, 0.85, 1e-12);
  const CellBlock* ends = block(m.boundaries, "balloon_ends");
  ASSERT_NE(ends, nullptr);
  EXPECT_EQ(ends->num_cells(), static_cast<std::size_t>(2 * N * b.elements_thickness));
  for (GId n : ends->conn) EXPECT_TRUE(m.coord(n)[2] == z0 || m.coord(n)[2] == z1);
  // Facet ids unique over all facet groups, tags unique.
  std::vector<GId> ids;
  std::vector<int> tags;
  for (const CellBlock& c : m.boundaries) ids.insert(ids.end(), c.cell_id.begin(), c.cell_id.end()), tags.push_back(c.physical_tag);
  for (const CellBlock& c : m.volumes) tags.push_back(c.physical_tag);
  std::sort(ids.begin(), ids.end());
  std::sort(tags.begin(), tags.end());
  EXPECT_EQ(std::adjacent_find(ids.begin(), ids.end()), ids.end());
  EXPECT_EQ(std::adjacent_find(tags.begin(), tags.end()), tags.end());
}

TEST(BalloonGenerator, SectorOfHalfTheLengthSharesTheStentsCutPlanes) {
  StentConfig s = stent();
  s.sector = "period";
  s.half_length = true;
  const BalloonConfig b = balloon();
  Mesh m = generate_stent(s, 1e6, "test");
  const std::size_t stent_sym[3] = {block(m.boundaries, "symmetry_y")->num_cells(),
                                    block(m.boundaries, "symmetry_sector")->num_cells(),
                                    block(m.boundaries, "symmetry_z")->num_cells()};
  add_balloon(b, s, 1e6, "test", m);
  const double th = s.sector_angle();
  const int N = b.cells_around(s), nz = b.cells_along(s), nt = b.elements_thickness;
  EXPECT_EQ(N, static_cast<int>(std::ceil(th * 0.85 / 0.1)));
  EXPECT_EQ(nz, 20);
  EXPECT_EQ(count_inverted_cells(m), 0u);
  EXPECT_NEAR(test::block_volume(m, "balloon"), sector_polygon(0.8, 0.85, th, N, 2.0), 1e-12);
  EXPECT_EQ(block(m.boundaries, "symmetry_y")->num_cells(), stent_sym[0] + nz * nt);
  EXPECT_EQ(block(m.boundaries, "symmetry_sector")->num_cells(), stent_sym[1] + nz * nt);
  EXPECT_EQ(block(m.boundaries, "symmetry_z")->num_cells(), stent_sym[2] + N * nt);
  EXPECT_EQ(block(m.boundaries, "balloon_ends")->num_cells(), static_cast<std::size_t>(N * nt));
  for (GId n : block(m.boundaries, "symmetry_y")->conn) EXPECT_EQ(m.coord(n)[1], 0.0);
  for (GId n : block(m.boundaries, "symmetry_sector")->conn)
    EXPECT_NEAR(std::sin(th) * m.coord(n)[0] - std::cos(th) * m.coord(n)[1], 0.0, 1e-14);
  for (GId n : block(m.boundaries, "symmetry_z")->conn) EXPECT_NEAR(m.coord(n)[2], 1.15, 1e-12);
  s.sector = "quarter";
  s.crowns = 8;
  Mesh q = generate_stent(s, 1e6, "test");
  add_balloon(b, s, 1e6, "test", q);
  for (GId n : block(q.boundaries, "symmetry_x")->conn) EXPECT_EQ(q.coord(n)[0], 0.0);
  EXPECT_NEAR(test::block_volume(q, "balloon"), sector_polygon(0.8, 0.85, 0.5 * kPi, b.cells_around(s), 2.0), 1e-12);
}

TEST(BalloonGenerator, RefusesABalloonThatDoesNotFit) {
  auto error = [](auto change) {
    StentConfig s = stent();
    BalloonConfig b = balloon();
    change(b);
    try {
      Mesh m = generate_stent(s, 1e6, "deck");
      add_balloon(b, s, 1e5, "deck", m);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  auto has = [](const std::string& e, const std::string& what) { return e.find(what) != std::string::npos; };
  EXPECT_TRUE(has(error([](BalloonConfig& b) { b.outer_diameter = 2.8; }), "'Mesh->Balloon->outer diameter' = 2.8"));
  EXPECT_TRUE(has(error([](BalloonConfig& b) { b.thickness = 0.9; }), "'Mesh->Balloon->thickness'"));
  EXPECT_TRUE(has(error([](BalloonConfig& b) { b.length = 2.0; }), "'Mesh->Balloon->length'"));
  EXPECT_TRUE(has(error([](BalloonConfig& b) { b.element_length = 3.0; }), "'Mesh->Balloon->element length'"));
  EXPECT_TRUE(has(error([](BalloonConfig& b) { b.element_length = 0.002; }), "'Mesh->max cells'"));
  EXPECT_EQ(error([](BalloonConfig&) {}), "");
}
