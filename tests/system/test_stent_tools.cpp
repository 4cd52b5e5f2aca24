// The tools of the stent scenes (S4): the rigid capsule balloon and Output->Stent Metrics.
//  1. Capsule geometry: gap and normal against the closed form at points beside the
//     straight part and beyond both ends (2D and 3D); the normal's derivative (Dual
//     numbers, used by the contact tangent) against central differences.
//  2. A capsule of length 0 is a circle: the staged rigid-balloon deck gives the same
//     results with either (to 1e-12).
//  3. Obstacles drawn for ParaView: every sampled point of a capsule (2D stadium, 3D
//     surface) lies at the radius from its segment; the staged balloon run writes the
//     balloon into <basename>_obstacles.h5/.xdmf at every field output (the field file's
//     times), at its radius then, its displacement = position - first position.
//  4. Metrics of an artery cross-section under lumen pressure (inputs/artery_ring.xml at
//     1 kPa, linear regime) against independent calculations: mean and smallest lumen
//     radius and the lumen area from the mesh and the final displacement (recomputed
//     here, area by the shoelace formula over the lumen nodes sorted by angle); the
//     largest circumferential stress against the thick-cylinder (Lame) closed form.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "CsvSeries.hpp"
#include "contact/NodeLaw.hpp"
#include "H5Results.hpp"
#include "io/Obstacles.hpp"
#include "mesh/MeshQuery.hpp"
#include "run/Simulation.hpp"
#include "TestDir.hpp"

using namespace stentor;
using stentor::testing::read_csv;
using stentor::testing::Series;
namespace fs = std::filesystem;

namespace {

fs::path work_dir() { return stentor::testing::test_dir("stent_tools"); }
const std::string kInputs = std::string(STENTOR_SOURCE_DIR) + "/inputs/";

contact::Obstacle capsule(int dim) {
  contact::Obstacle o;
  o.kind = 3;
  o.point[0] = 1.0, o.point[1] = -0.5;
  const double a[3] = {0.6, 0.8, 0.0}, a3[3] = {2.0 / 3.0, 2.0 / 3.0, 1.0 / 3.0};
  for (int k = 0; k < 3; ++k) o.axis[k] = dim == 2 ? a[k] : a3[k];
  o.length = 2.0;
  o.radius = 0.4;
  return o;
}

// Closed form: distance from the segment minus the radius; normal from the closest point.
double expected_gap(const contact::Obstacle& o, const double x[3], double n[3]) {
  double r[3], s = 0.0;
  for (int k = 0; k < 3; ++k) r[k] = x[k] - o.point[k], s += r[k] * o.axis[k];
  s = std::clamp(s, 0.0, o.length);
  double d = 0.0;
  for (int k = 0; k < 3; ++k) r[k] -= s * o.axis[k], d += r[k] * r[k];
  d = std::sqrt(d);
  for (int k = 0; k < 3; ++k) n[k] = r[k] / d;
  return d - o.radius;
}

}  // namespace

// Every obstacle kind the output draws (plane, circle, sphere, cylinder, capsule): every
// sampled point on it (gap 0 to 1e-12), every cell's points in range.
TEST(StentTools, ObstacleSurfacesLieOnTheObstacle) {
  std::vector<std::pair<int, contact::Obstacle>> cases = {{2, capsule(2)}, {3, capsule(3)}};
  for (int dim : {2, 3})
    for (int kind : {0, 1, 2}) {
      if (dim == 2 && kind == 2) continue;  // no cylinder in 2D
      contact::Obstacle o;
      o.kind = kind;
      const double p[3] = {0.3, -0.2, dim == 3 ? 0.7 : 0.0}, n[3] = {0.6, 0.0, 0.8}, n2[3] = {0.6, 0.8, 0.0};
      for (int k = 0; k < 3; ++k) o.point[k] = p[k], o.normal[k] = dim == 3 ? n[k] : n2[k], o.axis[k] = n[k];
      o.radius = 0.4;
      cases.emplace_back(dim, o);
    }
  for (const auto& [dim, o] : cases) {
    ObstacleShape s;
    s.kind = o.kind;
    for (int k = 0; k < 3; ++k) s.point[k] = o.point[k], s.normal[k] = o.normal[k], s.axis[k] = o.axis[k];
    s.radius = o.radius;
    s.length = o.length;
    const ObstacleSurface surf = sample_obstacle(s, dim, 10.0, {0, 0, 0});
    ASSERT_GE(surf.points.size(), 2u);
    for (const auto& x : surf.points) {
      double nx[3];
      EXPECT_NEAR(contact::rigid_gap(o, x.data(), nx), 0.0, 1e-12) << "dim " << dim << " kind " << o.kind;
    }
    for (const auto& c : surf.cells)
      for (int k : c) EXPECT_LT(static_cast<std::size_t>(k), surf.points.size());
  }
}

TEST(StentTools, CapsuleGapNormalAndDerivative) {
  for (int dim : {2, 3}) {
    const contact::Obstacle o = capsule(dim);
    // Beside the straight part, beyond the start and beyond the end.
    const double pts[3][3] = {{2.2, -0.9, dim == 3 ? 0.3 : 0.0}, {0.2, -1.1, dim == 3 ? -0.2 : 0.0}, {2.9, 1.6, dim == 3 ? 1.2 : 0.0}};
    for (const auto& x : pts) {
      double n[3], ne[3];
      const double g = contact::rigid_gap(o, x, n), ge = expected_gap(o, x, ne);
      EXPECT_NEAR(g, ge, 1e-14);
      for (int k = 0; k < 3; ++k) EXPECT_NEAR(n[k], ne[k], 1e-14);
      // dn/dx with duals against central differences.
      contact::AD xd[3], nd[3];
      for (int k = 0; k < 3; ++k) xd[k] = contact::AD::seed(x[k], k);
      contact::rigid_gap(o, xd, nd);
      const double h = 1e-6;
      for (int j = 0; j < dim; ++j) {
        double xp[3] = {x[0], x[1], x[2]}, xm[3] = {x[0], x[1], x[2]}, np[3], nm[3];
        xp[j] += h, xm[j] -= h;
        contact::rigid_gap(o, xp, np);
        contact::rigid_gap(o, xm, nm);
        for (int k = 0; k < dim; ++k) EXPECT_NEAR(nd[k].d[j], (np[k] - nm[k]) / (2 * h), 1e-8) << "dim " << dim;
      }
    }
  }
}

TEST(StentTools, CapsuleOfLengthZeroIsACircle) {
  auto run = [](bool as_capsule, const std::string& tag, RunResult& res) {
    Config cfg = read_deck(kInputs + "balloon_stages.xml");
    if (as_capsule) {
      auto& c = cfg.contact.at(0);
      c.obstacle = "capsule";
      c.axis = {1.0, 0.0, 0.0};
      c.axis_len = 2;
      c.length = 0.0;
    }
    RunOptions opts;
    opts.output_dir = (work_dir() / tag).string();
    EXPECT_EQ(run_simulation(cfg, opts, &res), 0);
    return read_csv(work_dir() / tag / "balloon_stages_history.csv");
  };
  RunResult a, b;
  const Series ha = run(false, "circle", a), hb = run(true, "capsule", b);
  ASSERT_EQ(a.displacement.size(), b.displacement.size());
  double umax = 0.0;
  for (std::size_t i = 0; i < a.displacement.size(); ++i) {
    EXPECT_NEAR(a.displacement[i], b.displacement[i], 1e-12);
    umax = std::max(umax, std::abs(a.displacement[i]));
  }
  EXPECT_GT(std::abs(ha["contact_balloon_force_y"].at(3)), 0.0) << "the balloon never touched the block";
  EXPECT_NEAR(ha["contact_balloon_force_y"].at(3), hb["contact_balloon_force_y"].at(3), 1e-9 * std::abs(ha["contact_balloon_force_y"].at(3)));

  // The balloon for ParaView: outputs at t = 0 and every step, the field file's times; at
  // t = 1 (output 4, end of inflation) its radius is 0.45 + 0.15 about (0.5, -0.5).
  using H5 = stentor::testing::H5Results;
  H5 obstacles(work_dir() / "capsule" / "balloon_stages_obstacles.h5"), fields(work_dir() / "capsule" / "balloon_stages.h5");
  ASSERT_GE(obstacles.f, 0);
  const std::vector<double> t = obstacles.times();
  EXPECT_EQ(t.size(), ha.rows() + 1);
  EXPECT_EQ(t, fields.times());
  EXPECT_EQ(t.at(4), 1.0);
  const auto x0 = obstacles.read("/step_0/coordinates"), x4 = obstacles.read("/step_4/coordinates"), u4 = obstacles.read("/step_4/displacement");
  ASSERT_GT(x4.size(), 180u);
  ASSERT_EQ(u4.size(), x4.size());
  for (std::size_t i = 0; i < x4.size(); i += 3) {
    EXPECT_NEAR(std::hypot(x4[i] - 0.5, x4[i + 1] + 0.5), 0.6, 1e-12);
    for (std::size_t c = 0; c < 3; ++c) EXPECT_EQ(u4[i + c], x4[i + c] - x0[i + c]);
  }
}

TEST(StentTools, MetricsOfAPressurisedArteryRing) {
  Config cfg = read_deck(kInputs + "artery_ring.xml");
  const double p = 1.0e3, ri = 1.5e-3, ro = 2.0e-3;
  for (auto& l : cfg.loads)
    if (l.type == LoadConfig::Type::Pressure) l.value = p;
  cfg.stepping.num_steps = 1;
  cfg.output.fields = false;
  auto& m = cfg.output.metrics;
  m.enabled = true;
  m.axis_point = {0.0, 0.0, 0.0};
  m.axis = {0.0, 0.0, 1.0};
  m.stent = m.lumen = "lumen";
  m.artery = "artery";
  RunOptions opts;
  opts.output_dir = (work_dir() / "ring").string();
  RunResult res;
  ASSERT_EQ(run_simulation(cfg, opts, &res), 0);
  const Series s = read_csv(work_dir() / "ring" / (cfg.output.basename + "_metrics.csv"));
  ASSERT_EQ(s.rows(), 2u);  // t = 0 and the one step
  const Series st = read_csv(work_dir() / "ring" / (cfg.output.basename + "_stages.csv"));
  ASSERT_EQ(st.rows(), 1u);

  // Independent: the lumen nodes' current radii and the polygon through them.
  const std::vector<GId> nodes = boundary_nodes(res.mesh, "lumen");
  struct P { double ang, x, y; };
  std::vector<P> pts;
  double rsum = 0.0, rmin = 1e300;
  for (GId n : nodes) {
    const auto i = static_cast<std::size_t>(n);
    const double x = res.mesh.x[3 * i] + res.displacement[3 * i], y = res.mesh.x[3 * i + 1] + res.displacement[3 * i + 1];
    const double r = std::hypot(x, y);
    rsum += r, rmin = std::min(rmin, r);
    pts.push_back({std::atan2(y, x), x, y});
  }
  std::sort(pts.begin(), pts.end(), [](const P& a, const P& b) { return a.ang < b.ang; });
  double area = 0.0;
  for (std::size_t k = 0; k < pts.size(); ++k) {
    const P& a = pts[k];
    const P& b = pts[(k + 1) % pts.size()];
    area += 0.5 * (a.x * b.y - b.x * a.y);
  }
  const std::size_t last = 1;
  EXPECT_NEAR(s["lumen_radius_mean"][last], rsum / double(nodes.size()), 1e-15);
  EXPECT_NEAR(s["lumen_radius_min"][last], rmin, 1e-15);
  EXPECT_NEAR(s["lumen_area"][last], area, 1e-12 * area);
  EXPECT_NEAR(s["lumen_radius_mean"][0], ri, 1e-3 * ri);  // t = 0: the mesh's polygon
  EXPECT_GT(s["lumen_radius_mean"][last], s["lumen_radius_mean"][0]);  // the lumen grew
  EXPECT_NEAR(st["lumen_gain"][0], s["lumen_radius_mean"][last] / s["lumen_radius_mean"][0] - 1.0, 1e-12);

  // Lame: sigma_theta(r) = p ri^2 / (ro^2 - ri^2) (1 + ro^2 / r^2), largest at r = ri; the
  // cell averages of the innermost cells sit slightly outside ri.
  const double hoop_ri = p * (ro * ro + ri * ri) / (ro * ro - ri * ri);
  EXPECT_NEAR(s["artery_hoop_stress_max"][last], hoop_ri, 0.05 * hoop_ri);
  EXPECT_LT(s["artery_hoop_stress_max"][last], hoop_ri);
  EXPECT_EQ(s["contact_pressure_max"][last], 0.0);
}
