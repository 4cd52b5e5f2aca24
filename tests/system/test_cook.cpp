// Cook's membrane (docs/verification.md, "Statics (mesh)"), deck inputs/cook.xml: finite
// strain (tip displacement ~15% of the length, large rotation), no closed form, so
// self-convergence of the vertical displacement of the top-right corner (48, 60) under
// uniform refinement (h halved twice), for P1 and P2:
//   * successive differences shrink: |v3 - v2| < 0.6 |v2 - v1|;
//   * the finest P1 and P2 values agree within 2%;
//   * the finest P2 value is within 1% of the extrapolated reference 7.42 (docs).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "run/Simulation.hpp"
#include "TestDir.hpp"

using namespace stentor;
namespace fs = std::filesystem;

namespace {

fs::path work_dir() { return stentor::testing::test_dir("cook"); }

// Vertical displacement of the node at (48, 60) (a geometry vertex: always a mesh node).
double tip_displacement(int order, double size) {
  Config cfg = read_deck(std::string(STENTOR_SOURCE_DIR) + "/inputs/cook.xml");
  cfg.mesh.order = order;
  cfg.mesh.size = size;
  cfg.output.fields = false;
  cfg.stepping.num_steps = 2;  // the deck's 5 steps give the same end state (to 1e-13), slower
  RunOptions opts;
  opts.output_dir = (work_dir() / ("cook_p" + std::to_string(order) + "_" + std::to_string(size))).string();
  RunResult res;
  EXPECT_EQ(run_simulation(cfg, opts, &res), 0);
  EXPECT_TRUE(res.converged);
  for (std::size_t n = 0; n < res.mesh.num_nodes(); ++n)
    if (std::hypot(res.mesh.x[3 * n] - 48.0, res.mesh.x[3 * n + 1] - 60.0) < 1e-9) {
      std::printf("[cook] P%d size %.1f: %zu nodes, tip displacement (%.6f, %.6f)\n", order, size, res.mesh.num_nodes(),
                  res.displacement[3 * n], res.displacement[3 * n + 1]);
      return res.displacement[3 * n + 1];
    }
  ADD_FAILURE() << "no node at (48, 60)";
  return 0.0;
}

std::vector<double> self_convergence(int order, const std::vector<double>& sizes) {
  std::vector<double> v;
  for (double h : sizes) v.push_back(tip_displacement(order, h));
  const double d1 = v[1] - v[0], d2 = v[2] - v[1];
  std::printf("[cook] P%d: differences %.4e, %.4e, ratio %.3f\n", order, d1, d2, d2 / d1);
  EXPECT_LT(std::abs(d2), 0.6 * std::abs(d1)) << "P" << order;
  return v;
}

}  // namespace

TEST(Cook, TipDisplacementSelfConvergence) {
  const std::vector<double> p1 = self_convergence(1, {4.0, 2.0, 1.0});
  const std::vector<double> p2 = self_convergence(2, {8.0, 4.0, 2.0});
  EXPECT_NEAR(p1.back(), p2.back(), 0.02 * std::abs(p2.back()));
  EXPECT_NEAR(p2.back(), 7.42, 0.01 * 7.42);
}
