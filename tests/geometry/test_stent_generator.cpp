// The parametric stent (geometry/StentGenerator.hpp) against its parameters: radii,
// metal volume = centreline length x width x thickness, crowns, reductions, groups.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <functional>
#include <cmath>
#include <cstdio>
#include <map>
#include <set>
#include <string>
#include <tuple>

#include "deck/Config.hpp"
#include "geometry/StentGenerator.hpp"
#include "mesh/MeshCheck.hpp"
#include "mesh/MeshQuery.hpp"
#include "MeshMeasures.hpp"
#include "StentFixtures.hpp"

using namespace stentor;

namespace {

const double kPi = 3.14159265358979323846;

// A balloon-expandable stent as cut, in mm: OD 3, strut 0.1 x 0.1, 8 crowns.
StentConfig base() { return test::s6_ring_as_cut(); }

using test::duplicate_nodes;
using test::hex_volume;

double volume(const Mesh& m) {
  double v = 0.0;
  for (const auto& b : m.volumes)
    for (std::size_t c = 0; c < b.num_cells(); ++c) v += hex_volume(m, &b.conn[8 * c]);
  return v;
}

const CellBlock* group(const Mesh& m, const std::string& name) {
  for (const auto& b : m.boundaries)
    if (b.name == name) return &b;
  return nullptr;
}

// Area of a quad facet group (two triangles per bilinear quad is not exact; 2x2 Gauss is).
double area(const Mesh& m, const std::string& name) {
  const CellBlock* b = group(m, name);
  if (!b) return -1.0;
  const double g = 1.0 / std::sqrt(3.0), s[4][2] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
  double a = 0.0;
  for (std::size_t c = 0; c < b->num_cells(); ++c)
    for (int q = 0; q < 4; ++q) {
      const double xi = s[q][0] * g, eta = s[q][1] * g;
      double t1[3] = {}, t2[3] = {};
      for (int n = 0; n < 4; ++n) {
        const double* X = m.coord(b->conn[4 * c + n]);
        for (int i = 0; i < 3; ++i) {
          t1[i] += X[i] * s[n][0] * (1 + s[n][1] * eta) / 4;
          t2[i] += X[i] * s[n][1] * (1 + s[n][0] * xi) / 4;
        }
      }
      const double n0 = t1[1] * t2[2] - t1[2] * t2[1], n1 = t1[2] * t2[0] - t1[0] * t2[2], n2 = t1[0] * t2[1] - t1[1] * t2[0];
      a += std::sqrt(n0 * n0 + n1 * n1 + n2 * n2);
    }
  return a;
}

double radius(const Mesh& m, GId n) { return std::hypot(m.coord(n)[0], m.coord(n)[1]); }

}  // namespace

TEST(StentGenerator, RadiiVolumeAndGroupsOfOneFullRing) {
  const StentConfig s = base();
  const Mesh m = generate_stent(s, 1e6, "test");
  EXPECT_EQ(count_inverted_cells(m), 0u);
  EXPECT_NO_THROW(check_mesh(m));
  EXPECT_EQ(duplicate_nodes(m), 0u);
  for (const char* g : {"inner", "outer", "end_proximal", "end_distal", "ring_0", "anchor"})
    EXPECT_NE(group(m, g), nullptr) << g;
  for (const char* g : {"symmetry_x", "symmetry_y", "symmetry_z", "links"}) EXPECT_EQ(group(m, g), nullptr) << g;
  for (GId n : group(m, "inner")->conn) EXPECT_NEAR(radius(m, n), 1.4, 1e-12);
  for (GId n : group(m, "outer")->conn) EXPECT_NEAR(radius(m, n), 1.5, 1e-12);
  double rmin = 1e9, rmax = 0;
  for (std::size_t n = 0; n < m.num_nodes(); ++n) {
    rmin = std::min(rmin, radius(m, static_cast<GId>(n)));
    rmax = std::max(rmax, radius(m, static_cast<GId>(n)));
  }
  EXPECT_NEAR(rmin, 1.4, 1e-12);
  EXPECT_NEAR(rmax, 1.5, 1e-12);
  // Metal = centreline length x w x t (the band of an embedded closed curve; u at Rm);
  // inner/outer areas: the unrolled area L w scaled by r / Rm. The straight-edged cells
  // cut the crowns' curved edges: second order in the element length.
  const double L = s.centreline_length();
  const double exact[3] = {L * s.strut_width * s.thickness, L * s.strut_width * 1.4 / 1.45, L * s.strut_width * 1.5 / 1.45};
  auto errors = [&](const Mesh& mesh) {
    return std::array<double, 3>{std::abs(volume(mesh) / exact[0] - 1), std::abs(area(mesh, "inner") / exact[1] - 1),
                                 std::abs(area(mesh, "outer") / exact[2] - 1)};
  };
  StentConfig fine = s;
  fine.element_length = 0.5 * s.element_h();
  const auto e1 = errors(m), e2 = errors(generate_stent(fine, 1e6, "test"));
  for (int i = 0; i < 3; ++i) {
    EXPECT_LT(e1[i], 4e-3) << i;
    EXPECT_LT(e2[i], e1[i] / 3.0) << i << ": " << e1[i] << " -> " << e2[i];
  }
  EXPECT_NEAR(area(m, "ring_0"), area(m, "outer"), 1e-12);
  // The struts' side faces: the two edges (offsets +-w/2 of a closed curve: lengths L -+ w/2
  // times the total turning, 2 L together) through the thickness; the contact surface of
  // a balloon, `inner_and_sides`, is the inner faces and the sides, facet for facet.
  EXPECT_NEAR(area(m, "sides") / (2.0 * L * s.thickness), 1.0, 4e-3);
  EXPECT_EQ(group(m, "inner_and_sides")->num_cells(), group(m, "inner")->num_cells() + group(m, "sides")->num_cells());
  EXPECT_NEAR(area(m, "inner_and_sides"), area(m, "inner") + area(m, "sides"), 1e-12 * area(m, "inner_and_sides"));
  // The ring spans z in [0, ring length].
  const Mesh::Box box = m.bounding_box();
  EXPECT_NEAR(box.lo[2], 0.0, 1e-12);
  EXPECT_NEAR(box.hi[2], s.ring_length, 1e-12);
}

TEST(StentGenerator, CountsItsCrownsAsPeaksOfTheDistalEdge) {
  for (int crowns : {6, 8, 12}) {
    StentConfig s = base();
    s.crowns = crowns;
    s.ring_length = 0.6;
    const Mesh m = generate_stent(s, 1e6, "test");
    // The distal edge's outer nodes in theta order; peaks of z around the circle.
    std::map<double, double> z_of_theta;
    for (GId n : group(m, "end_distal")->conn)
      if (std::abs(radius(m, n) - 1.5) < 1e-9) z_of_theta[std::atan2(m.coord(n)[1], m.coord(n)[0])] = m.coord(n)[2];
    std::vector<double> z;
    for (auto& [t, v] : z_of_theta) z.push_back(v);
    int peaks = 0;
    for (std::size_t i = 0; i < z.size(); ++i)
      if (z[i] > z[(i + z.size() - 1) % z.size()] && z[i] >= z[(i + 1) % z.size()]) ++peaks;
    EXPECT_EQ(peaks, crowns);
  }
}

TEST(StentGenerator, QuarterIsAQuarterWithExactSymmetryPlanes) {
  StentConfig s = base();
  const double full = volume(generate_stent(s, 1e6, "test"));
  s.sector = "quarter";
  const Mesh q = generate_stent(s, 1e6, "test");
  EXPECT_EQ(count_inverted_cells(q), 0u);
  EXPECT_NEAR(volume(q) / full, 0.25, 1e-12);
  for (const char* g : {"symmetry_x", "symmetry_y"}) {
    ASSERT_NE(group(q, g), nullptr) << g;
    const int c = g[9] == 'x' ? 0 : 1;
    for (GId n : group(q, g)->conn) EXPECT_EQ(q.coord(n)[c], 0.0);
    // The planes cut crowns, where the strut's section is the rectangle w x t.
    EXPECT_NEAR(area(q, g), s.strut_width * s.thickness, 1e-12) << g;
  }
  for (std::size_t n = 0; n < q.num_nodes(); ++n) {
    EXPECT_GE(q.coord(static_cast<GId>(n))[0], 0.0);
    EXPECT_GE(q.coord(static_cast<GId>(n))[1], 0.0);
  }
}

// sector = period: one strut (0 <= theta <= pi / crowns), a sixteenth of the 8-crown ring,
// cut on y = 0 and on the oblique plane theta = pi / 8 through crowns (sections w x t);
// with 8 peak-to-peak links on 3 rings, the same sector; with 4, none.
TEST(StentGenerator, PeriodSectorIsOneStrutBetweenItsPlanes) {
  StentConfig s = base();
  const double full = volume(generate_stent(s, 1e6, "test"));
  s.sector = "period";
  EXPECT_EQ(s.sector_half_pitches(), 1);
  EXPECT_DOUBLE_EQ(s.symmetry_copies(), 16.0);
  const Mesh q = generate_stent(s, 1e6, "test");
  EXPECT_EQ(count_inverted_cells(q), 0u);
  EXPECT_NEAR(volume(q) / full, 1.0 / 16.0, 1e-12);
  const double th = kPi / s.crowns, ro = s.outer_radius();
  ASSERT_NE(group(q, "symmetry_y"), nullptr);
  ASSERT_NE(group(q, "symmetry_sector"), nullptr);
  for (GId n : group(q, "symmetry_y")->conn) EXPECT_EQ(q.coord(n)[1], 0.0);
  for (GId n : group(q, "symmetry_sector")->conn)
    EXPECT_NEAR(std::sin(th) * q.coord(n)[0] - std::cos(th) * q.coord(n)[1], 0.0, 1e-14 * ro);
  for (const char* g : {"symmetry_y", "symmetry_sector"}) EXPECT_NEAR(area(q, g), s.strut_width * s.thickness, 1e-12) << g;
  for (std::size_t n = 0; n < q.num_nodes(); ++n) {
    const double* x = q.coord(static_cast<GId>(n));
    EXPECT_GE(x[1], 0.0);
    EXPECT_GE(std::sin(th) * x[0] - std::cos(th) * x[1], -1e-14 * ro);
  }
  EXPECT_EQ(group(q, "symmetry_x"), nullptr);
  s.rings = 3;
  s.gap = 0.3;
  s.links_per_ring = 8;
  EXPECT_EQ(s.sector_half_pitches(), 1);
  EXPECT_EQ(stent_config_error(s), "");
  s.links_per_ring = 4;
  EXPECT_EQ(s.sector_half_pitches(), 0);
  EXPECT_NE(stent_config_error(s).find("'Mesh->Stent->sector' = period"), std::string::npos);
}

TEST(StentGenerator, LinksJoinRingsAndAddTheirArea) {
  for (const std::string links : {"peak-to-peak", "peak-to-valley"}) {
    StentConfig s = base();
    s.rings = 3;
    s.links = links;
    s.links_per_ring = 4;
    s.ring_length = 0.9;
    s.element_length = s.strut_width / 6;
    const Mesh m = generate_stent(s, 1e6, "test");
    EXPECT_EQ(count_inverted_cells(m), 0u) << links;
    EXPECT_EQ(duplicate_nodes(m), 0u) << links;
    ASSERT_NE(group(m, "links"), nullptr);
    for (const char* g : {"ring_0", "ring_1", "ring_2", "end_proximal", "end_distal"}) EXPECT_NE(group(m, g), nullptr) << g;
    // The links' outer facets: their unrolled area (x Ro / Rm) is the straight bar,
    // gap x link width at its middle, longer at its sides between two crown tips
    // (peak-to-peak: both edges fall away from the bar), shorter inside a crown
    // (peak-to-valley: the crown's concave edge, of radius rho - w/2, falls faster than
    // the facing tip's, of radius rho + w/2).
    const double bars = 2 * 4 * s.gap * s.strut_width;
    const double extra = area(m, "links") * 1.45 / 1.5 / bars;
    EXPECT_GT(extra, links == "peak-to-peak" ? 1.0 : 0.8) << links;
    EXPECT_LT(extra, links == "peak-to-peak" ? 1.1 : 1.0) << links;
    // The metal: rings (centreline length x w x t, to the crowns' chord error) + links.
    const double rings = 3 * s.centreline_length() * s.strut_width * s.thickness;
    EXPECT_NEAR(volume(m) / (rings + extra * bars * s.thickness), 1.0, 2e-3) << links;
    // One connected piece: every node reached from node 0 through the cells.
    std::vector<int> comp(m.num_nodes());
    for (std::size_t i = 0; i < comp.size(); ++i) comp[i] = static_cast<int>(i);
    std::function<int(int)> root = [&](int i) { return comp[i] == i ? i : comp[i] = root(comp[i]); };
    const auto& b = m.volumes[0];
    for (std::size_t c = 0; c < b.num_cells(); ++c)
      for (int k = 1; k < 8; ++k) comp[root(static_cast<int>(b.conn[8 * c]))] = root(static_cast<int>(b.conn[8 * c + k]));
    std::set<int> roots;
    for (std::size_t i = 0; i < comp.size(); ++i) roots.insert(root(static_cast<int>(i)));
    EXPECT_EQ(roots.size(), 1u) << links;
  }
}

TEST(StentGenerator, ReductionsOfALinkedStent) {
  StentConfig s = base();
  s.rings = 2;
  s.links_per_ring = 4;
  s.ring_length = 0.9;
  const double full = volume(generate_stent(s, 1e6, "test"));
  s.half_length = true;
  const Mesh h = generate_stent(s, 1e6, "test");
  EXPECT_NEAR(volume(h) / full, 0.5, 1e-12);
  ASSERT_NE(group(h, "symmetry_z"), nullptr);
  EXPECT_EQ(group(h, "end_distal"), nullptr);
  EXPECT_EQ(group(h, "ring_1"), nullptr);
  // The plane cuts the 4 links in their middle: 4 sections w x t.
  // (flat quads on the arc of a link's width: 1e-4 of chord error)
  EXPECT_NEAR(area(h, "symmetry_z") / (4 * s.strut_width * s.thickness), 1.0, 1e-4);
  s.sector = "quarter";
  const Mesh q = generate_stent(s, 1e6, "test");
  EXPECT_EQ(count_inverted_cells(q), 0u);
  EXPECT_NEAR(volume(q) / full, 0.125, 1e-12);
}

TEST(StentGenerator, RefusesWhatCannotBeBuilt) {
  auto error = [](auto change) {
    StentConfig s = base();
    change(s);
    try {
      generate_stent(s, 1e6, "deck");
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  auto has = [](const std::string& e, const std::string& what) { return e.find(what) != std::string::npos; };
  EXPECT_TRUE(has(error([](StentConfig& s) { s.strut_width = 0.6; }), "'Mesh->Stent->strut width'"));
  EXPECT_TRUE(has(error([](StentConfig& s) { s.ring_length = 2.0; }), "fold onto itself"));
  EXPECT_TRUE(has(error([](StentConfig& s) { s.ring_length = 0.1; }), "'Mesh->Stent->ring length'"));
  EXPECT_TRUE(has(error([](StentConfig& s) { s.thickness = 1.6; }), "'Mesh->Stent->thickness'"));
  EXPECT_TRUE(has(error([](StentConfig& s) { s.sector = "quarter"; s.crowns = 6; }), "'Mesh->Stent->sector'"));
  EXPECT_TRUE(has(error([](StentConfig& s) { s.half_length = true; }), "'Mesh->Stent->half length'"));
  EXPECT_TRUE(has(error([](StentConfig& s) { s.rings = 2; s.gap = 0; }), "'Mesh->Stent->gap'"));
  EXPECT_TRUE(has(error([](StentConfig& s) { s.rings = 2; s.links_per_ring = 3; }), "'Mesh->Stent->links per ring'"));
  EXPECT_TRUE(has(error([](StentConfig& s) { s.rings = 2; s.links_per_ring = 2; s.link_width = 0.6; }),
                  "'Mesh->Stent->link width'"));
  EXPECT_TRUE(has(error([](StentConfig& s) { s.element_length = 1e-4; }), "'Mesh->max cells'"));
  EXPECT_EQ(error([](StentConfig&) {}), "");
}

// A ring's outer surface split into struts at its crown apices (tributary_areas_by with the
// half crown pitch of the facet's centroid, as the artery metrics' per-strut malapposition
// does): every facet lies within one half pitch (the apex lines are node lines of the
// pattern), the 16 struts of the 8-crown ring have the same area (the pattern's symmetry),
// and their shares add up to the ring's tributary areas node by node.
TEST(StentGenerator, OuterSurfaceSplitsIntoStrutsAtTheCrownApices) {
  const StentConfig s = stentor::test::s6_ring_as_cut();
  const Mesh m = generate_stent(s, 1e6, "test");
  const double pi = 3.14159265358979323846, h = pi / s.crowns;
  int straddling = 0;
  const auto pitch_of = [&](const double* c) {
    double theta = std::atan2(c[1], c[0]);
    if (theta < 0.0) theta += 2.0 * pi;
    const double j = theta / h;
    // The facet's centroid is off the apex lines by far more than round-off.
    if (std::abs(j - std::round(j)) < 1e-3) ++straddling;
    return std::min(2 * s.crowns - 1, static_cast<int>(std::floor(j)));
  };
  const auto parts = tributary_areas_by(m, "ring_0", 2 * s.crowns, pitch_of);
  const auto whole = tributary_areas(m, "ring_0");
  EXPECT_EQ(straddling, 0);
  ASSERT_EQ(parts.size(), 16u);
  std::vector<double> area;
  std::map<GId, double> sum;
  for (const auto& p : parts) {
    double a = 0.0;
    for (const auto& [g, v] : p) a += v, sum[g] += v;
    area.push_back(a);
  }
  const double lo = *std::min_element(area.begin(), area.end()), hi = *std::max_element(area.begin(), area.end());
  std::printf("[stent] struts of one ring: 16 of outer area %.6f .. %.6f mm^2\n", lo, hi);
  EXPECT_GT(lo, 0.0);
  EXPECT_LT((hi - lo) / hi, 1e-10);
  ASSERT_EQ(sum.size(), whole.size());
  for (const auto& [g, v] : whole) EXPECT_NEAR(sum.at(g), v, 1e-14 * (1.0 + v)) << g;
}
