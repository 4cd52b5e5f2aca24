// The artery around a generated stent (geometry/ArteryGenerator.hpp's add_artery(): a
// stent deck with `Mesh->Artery`): the layers' volumes against the closed form of the
// polygonal cross-section over the stent's sector (n cells over Theta: n/2 (r2^2 - r1^2)
// sin(Theta / n) L), its place (centred on the stent, around it, not touching it), the
// node ranges and ids after the stent's (and the balloon's), the group names, the cut
// planes shared with the stent, bad input.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>
#include <string>

#include "deck/Config.hpp"
#include "geometry/ArteryGenerator.hpp"
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

// A coronary artery around it: lumen 3.4 mm (0.2 mm clear of the stent), 4 mm long.
ArteryConfig artery() {
  ArteryConfig a;
  a.around_stent = true;
  a.inner_diameter = 3.4;
  a.length = 4.0;
  a.thickness[0] = 0.27;
  a.thickness[1] = 0.21;
  a.thickness[2] = 0.34;
  a.elements_around = 32;
  a.elements_along = 8;
  return a;
}

BalloonConfig balloon() {
  BalloonConfig b;
  b.enabled = true;
  b.outer_diameter = 2.7;
  b.thickness = 0.05;
  b.length = 3.0;
  b.element_length = 0.2;
  return b;
}

double layer_inner(const ArteryConfig& a, int l) { return l == 0 ? a.inner_radius() : a.layer_outer_radius(l - 1); }

// The nodes of the volume group `name`.
std::set<GId> body_nodes(const Mesh& m, const std::string& name) {
  const CellBlock* b = block(m.volumes, name);
  return b ? std::set<GId>(b->conn.begin(), b->conn.end()) : std::set<GId>();
}

std::set<GId> nodes_of(const Mesh& m, std::initializer_list<const char*> names) {
  std::set<GId> out;
  for (const char* n : names) {
    const std::set<GId> b = body_nodes(m, n);
    out.insert(b.begin(), b.end());
  }
  return out;
}

bool disjoint(const std::set<GId>& a, const std::set<GId>& b) {
  for (GId n : a)
    if (b.count(n)) return false;
  return true;
}

// Facet ids unique over all facet groups, physical tags and group names unique over all groups.
void expect_unique_ids_tags_names(const Mesh& m) {
  std::vector<GId> ids;
  std::vector<int> tags;
  std::vector<std::string> names;
  for (const auto* blocks : {&m.volumes, &m.boundaries})
    for (const CellBlock& c : *blocks) tags.push_back(c.physical_tag), names.push_back(c.name);
  for (const CellBlock& c : m.boundaries) ids.insert(ids.end(), c.cell_id.begin(), c.cell_id.end());
  std::sort(ids.begin(), ids.end());
  std::sort(tags.begin(), tags.end());
  std::sort(names.begin(), names.end());
  EXPECT_EQ(std::adjacent_find(ids.begin(), ids.end()), ids.end());
  EXPECT_EQ(std::adjacent_find(tags.begin(), tags.end()), tags.end());
  EXPECT_EQ(std::adjacent_find(names.begin(), names.end()), names.end());
}

}  // namespace

TEST(StentArteryGenerator, WholeArteryCentredAroundTheWholeStent) {
  const StentConfig s = stent();
  const ArteryConfig a = artery();
  Mesh m = generate_stent(s, 1e6, "test");
  const std::size_t stent_nodes = m.num_nodes(), stent_cells = m.num_volume_cells(), stent_groups = m.boundaries.size();
  const std::size_t stent_outer = block(m.boundaries, "outer")->num_cells();
  add_artery(a, s, 1e6, "test", m);
  EXPECT_EQ(count_inverted_cells(m), 0u);
  EXPECT_NO_THROW(check_mesh(m));
  EXPECT_EQ(test::duplicate_nodes(m), 0u);
  // Nodes: the artery's 32 x 9 x 5 after the stent's; cells after the stent's.
  const int N = 32, nz = 8, nr = 4;
  EXPECT_EQ(m.num_nodes() - stent_nodes, static_cast<std::size_t>(N * (nz + 1) * (nr + 1)));
  EXPECT_EQ(m.num_volume_cells() - stent_cells, static_cast<std::size_t>(N * nz * nr));
  EXPECT_EQ(block(m.volumes, "intima")->cell_id.front(), static_cast<GId>(stent_cells));
  const std::set<GId> metal = body_nodes(m, "stent"), wall = nodes_of(m, {"intima", "media", "adventitia"});
  EXPECT_TRUE(disjoint(metal, wall));
  EXPECT_LT(*metal.rbegin(), static_cast<GId>(stent_nodes));
  EXPECT_EQ(*wall.begin(), static_cast<GId>(stent_nodes));
  EXPECT_EQ(*wall.rbegin(), static_cast<GId>(m.num_nodes() - 1));
  // Volumes: the polygon of 32 cells around the whole circumference, 4 mm long.
  for (int l = 0; l < 3; ++l)
    EXPECT_NEAR(test::block_volume(m, kArteryLayer[l]) / sector_polygon(layer_inner(a, l), a.layer_outer_radius(l), 2.0 * kPi, N, 4.0),
                1.0, 1e-12)
        << kArteryLayer[l];
  // Groups: the artery's prefixed where the stent has the name; the stent's unchanged.
  for (const char* g : {"lumen", "artery_outer", "artery_end_proximal", "artery_end_distal"})
    EXPECT_NE(block(m.boundaries, g), nullptr) << g;
  for (const char* g : {"symmetry_x", "symmetry_y", "symmetry_sector", "symmetry_z", "artery_symmetry_y"})
    EXPECT_EQ(block(m.boundaries, g), nullptr) << g;
  EXPECT_EQ(m.boundaries.size(), stent_groups + 4);
  EXPECT_EQ(block(m.boundaries, "outer")->num_cells(), stent_outer);
  for (GId n : block(m.boundaries, "outer")->conn) EXPECT_LT(n, static_cast<GId>(stent_nodes));
  expect_unique_ids_tags_names(m);
  double area, radial;
  test::facets(m, "lumen", area, radial);
  EXPECT_NEAR(area / (N * 2.0 * 1.7 * std::sin(kPi / N) * 4.0), 1.0, 1e-12);
  EXPECT_NEAR(radial / area, -1.0, 1e-12);  // out of the wall: towards the axis (and the stent)
  test::facets(m, "artery_outer", area, radial);
  EXPECT_NEAR(radial / area, 1.0, 1e-12);
  // Centred on the stent (0 <= z <= 2.3): -0.85 <= z <= 3.15; the lumen outside the stent.
  double z0 = 1e9, z1 = -1e9, rmin = 1e9;
  for (GId n : wall) {
    z0 = std::min(z0, m.coord(n)[2]), z1 = std::max(z1, m.coord(n)[2]);
    rmin = std::min(rmin, std::hypot(m.coord(n)[0], m.coord(n)[1]));
  }
  EXPECT_NEAR(z0, -0.85, 1e-12);
  EXPECT_NEAR(z1, 3.15, 1e-12);
  EXPECT_NEAR(rmin, 1.7, 1e-12);
  for (GId n : block(m.boundaries, "artery_end_proximal")->conn) EXPECT_EQ(m.coord(n)[2], z0);
  for (GId n : block(m.boundaries, "artery_end_distal")->conn) EXPECT_EQ(m.coord(n)[2], z1);
}

// The stent's `period` sector of half its length, with a balloon inside: the artery's cut
// faces join the stent's (and the balloon's) symmetry_y, symmetry_sector and symmetry_z, on
// their planes; three bodies, three disjoint node ranges.
TEST(StentArteryGenerator, PeriodSectorOfHalfTheLengthSharesTheCutPlanes) {
  StentConfig s = stent();
  s.sector = "period";
  s.half_length = true;
  const ArteryConfig a = artery();
  Mesh m = generate_stent(s, 1e6, "test");
  add_balloon(balloon(), s, 1e6, "test", m);
  const std::size_t before = m.num_nodes();
  std::size_t sym[3];
  const char* planes[3] = {"symmetry_y", "symmetry_sector", "symmetry_z"};
  for (int p = 0; p < 3; ++p) sym[p] = block(m.boundaries, planes[p])->num_cells();
  add_artery(a, s, 1e6, "test", m);
  const double th = s.sector_angle();
  const int copies = 2 * s.crowns / s.sector_half_pitches();  // the sector's copies around
  const int n = cells_around_stent(a, s), nz = 4, nr = 4;
  EXPECT_EQ(n * copies, 32);
  EXPECT_NEAR(n * 2.0 * kPi / 32, th, 1e-12);  // n cells of the whole tube's 32 make up the sector
  EXPECT_EQ(count_inverted_cells(m), 0u);
  EXPECT_NO_THROW(check_mesh(m));
  EXPECT_EQ(test::duplicate_nodes(m), 0u);
  EXPECT_EQ(m.num_nodes() - before, static_cast<std::size_t>((n + 1) * (nz + 1) * (nr + 1)));
  for (int l = 0; l < 3; ++l)
    EXPECT_NEAR(test::block_volume(m, kArteryLayer[l]) / sector_polygon(layer_inner(a, l), a.layer_outer_radius(l), th, n, 2.0), 1.0,
                1e-12)
        << kArteryLayer[l];
  EXPECT_EQ(block(m.boundaries, "symmetry_y")->num_cells(), sym[0] + nz * nr);
  EXPECT_EQ(block(m.boundaries, "symmetry_sector")->num_cells(), sym[1] + nz * nr);
  EXPECT_EQ(block(m.boundaries, "symmetry_z")->num_cells(), sym[2] + n * nr);
  EXPECT_EQ(block(m.boundaries, "artery_end_distal"), nullptr);
  for (GId q : block(m.boundaries, "symmetry_y")->conn) EXPECT_EQ(m.coord(q)[1], 0.0);
  for (GId q : block(m.boundaries, "symmetry_sector")->conn)
    EXPECT_NEAR(std::sin(th) * m.coord(q)[0] - std::cos(th) * m.coord(q)[1], 0.0, 1e-14);
  for (GId q : block(m.boundaries, "symmetry_z")->conn) EXPECT_NEAR(m.coord(q)[2], 1.15, 1e-12);
  for (GId q : block(m.boundaries, "artery_end_proximal")->conn) EXPECT_NEAR(m.coord(q)[2], -0.85, 1e-12);
  // The cut planes' artery facets: the wall's rectangle (Ri .. Ro by the modelled 2 mm).
  double area = 0.0, radial;
  const std::set<GId> metal = body_nodes(m, "stent"), rubber = body_nodes(m, "balloon"),
                      wall = nodes_of(m, {"intima", "media", "adventitia"});
  EXPECT_TRUE(disjoint(metal, wall));
  EXPECT_TRUE(disjoint(rubber, wall));
  EXPECT_TRUE(disjoint(metal, rubber));
  EXPECT_LT(*rubber.rbegin(), *wall.begin());
  test::facets(m, "symmetry_sector", area, radial);
  Mesh alone = generate_stent(s, 1e6, "test");
  add_balloon(balloon(), s, 1e6, "test", alone);
  double area0;
  test::facets(alone, "symmetry_sector", area0, radial);
  EXPECT_NEAR(area - area0, (a.outer_radius() - a.inner_radius()) * 2.0, 1e-12);
  expect_unique_ids_tags_names(m);
  // A quarter: the plane x = 0 is `symmetry_x`, exactly.
  s.sector = "quarter";
  Mesh q = generate_stent(s, 1e6, "test");
  add_artery(a, s, 1e6, "test", q);
  EXPECT_EQ(cells_around_stent(a, s), 8);
  for (GId k : block(q.boundaries, "symmetry_x")->conn) EXPECT_EQ(q.coord(k)[0], 0.0);
  EXPECT_EQ(block(q.boundaries, "symmetry_sector"), nullptr);
  for (int l = 0; l < 3; ++l)
    EXPECT_NEAR(test::block_volume(q, kArteryLayer[l]) / sector_polygon(layer_inner(a, l), a.layer_outer_radius(l), 0.5 * kPi, 8, 2.0),
                1.0, 1e-12);
}

// A concentric plaque around the stent: measured from the artery's proximal end (its
// centre the stent's middle by default), the lumen at its peak Ri - h_max, still outside
// the stent.
TEST(StentArteryGenerator, PlaqueAroundTheStent) {
  const StentConfig s = stent();
  ArteryConfig a = artery();
  a.inner_diameter = 4.0;
  a.plaque_stenosis = 0.2;  // h_max = 0.4: the lumen's radius 1.6 at the peak
  a.plaque_length = 2.0;
  Mesh m = generate_stent(s, 1e6, "test");
  add_artery(a, s, 1e6, "test", m);
  ASSERT_NE(block(m.volumes, "plaque"), nullptr);
  EXPECT_EQ(count_inverted_cells(m), 0u);
  double rmin = 1e9, zmin = 0.0;
  for (GId n : block(m.boundaries, "lumen")->conn) {
    const double r = std::hypot(m.coord(n)[0], m.coord(n)[1]);
    if (r < rmin) rmin = r, zmin = m.coord(n)[2];
  }
  EXPECT_NEAR(rmin, 1.6, 1e-12);
  EXPECT_NEAR(zmin, 1.15, 1e-12);
  expect_unique_ids_tags_names(m);
}

TEST(StentArteryGenerator, RefusesAnArteryThatDoesNotFit) {
  auto error = [](auto change, const std::string& sector = "full", bool half = false) {
    StentConfig s = stent();
    s.sector = sector;
    s.half_length = half;
    ArteryConfig a = artery();
    change(a);
    try {
      Mesh m = generate_stent(s, 1e6, "deck");
      add_artery(a, s, 2e4, "deck", m);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  auto has = [](const std::string& e, const std::string& what) { return e.find(what) != std::string::npos; };
  EXPECT_EQ(error([](ArteryConfig&) {}), "");
  EXPECT_EQ(error([](ArteryConfig&) {}, "period", true), "");
  EXPECT_TRUE(has(error([](ArteryConfig& a) { a.length = 2.3; }), "'Mesh->Artery->length' = 2.3 must exceed the stent's length 2.3"));
  // The lumen's chords: Ri = 1.51 clears the stent's outer radius 1.5 (1.51 cos(pi / 32) =
  // 1.5027), Ri = 1.5025 only at the nodes (1.4953 at the chords' middles).
  EXPECT_EQ(error([](ArteryConfig& a) { a.inner_diameter = 3.02; }), "");
  const std::string narrow = error([](ArteryConfig& a) { a.inner_diameter = 3.005; });
  EXPECT_TRUE(has(narrow, "'Mesh->Artery->inner diameter' = 3.005 puts the lumen's facets at the radius 1.495")) << narrow;
  EXPECT_TRUE(has(narrow, "not outside the stent's outer radius 1.5")) << narrow;
  EXPECT_TRUE(has(error([](ArteryConfig& a) { a.inner_diameter = 3.4, a.plaque_stenosis = 0.2, a.plaque_length = 1.0; }),
                  "less the plaque's 2 h_max = 0.68"));
  StentConfig period = stent();
  period.sector = "period";
  const std::string copies = std::to_string(2 * period.crowns / period.sector_half_pitches());
  EXPECT_TRUE(has(error([](ArteryConfig& a) { a.elements_around = 36; }, "period"),
                  "'Mesh->Artery->elements around' = 36 must be divisible by " + copies + " ('Mesh->Stent->sector' = period keeps 1/" +
                      copies));
  EXPECT_TRUE(has(error([](ArteryConfig& a) { a.elements_around = 30; }, "quarter"), "must be divisible by 4"));
  EXPECT_TRUE(has(error([](ArteryConfig& a) { a.elements_along = 7; }, "full", true),
                  "'Mesh->Artery->elements along' = 7 must be even ('Mesh->Stent->half length' = true"));
  EXPECT_TRUE(has(error([](ArteryConfig& a) { a.thickness[1] = 0.0; }), "'Mesh->Artery->media thickness' must be > 0"));
  EXPECT_TRUE(has(error([](ArteryConfig& a) {
                    a.inner_diameter = 4.0, a.plaque_stenosis = 0.1, a.plaque_length = 1.0, a.plaque_shape = "eccentric";
                  }, "period"),
                  "'Mesh->Artery->plaque shape' = eccentric is symmetric about y = 0 only"));
  const std::string many = error([](ArteryConfig& a) { a.elements_around = 128, a.elements_along = 80; });
  EXPECT_TRUE(has(many, "the stent and the artery would have")) << many;
  EXPECT_TRUE(has(many, "more than 'Mesh->max cells' = 20000")) << many;
}
