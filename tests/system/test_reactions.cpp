// Reactions per Dirichlet set (issue 13; docs/deck.md, "Loads and ramps"): each set
// reports the components it constrains, a dof constrained by two sets counts once (for the
// first in deck order), and nothing else. The uniaxial block (unit cube, inputs/block3d.geo,
// P1, stretched to lambda = 1.2 with symmetry supports, a homogeneous state the mesh
// reproduces exactly): the pulled face's x reaction is P11(lambda) A0, the opposite face's
// its negative, the lateral supports carry nothing (lateral stress free), and the columns
// for unconstrained components (reaction_front_x, ...) are absent. Before issue 13 the sum
// ran over every component of every node of the set: reaction_front_x was the x reactions
// of the front face's edge nodes on the left and right faces, far from 0.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "BlockDeck.hpp"
#include "CsvSeries.hpp"
#include "deck/Config.hpp"
#include "run/Simulation.hpp"
#include "TestDir.hpp"

using namespace stentor;
namespace fs = std::filesystem;

namespace {

constexpr double kC1 = 0.5e6, kC2 = 0.005e6, kD = 0.35e6;

// Ciarlet–Geymonat under uniaxial stress, F = diag(lam, s, s), b = s^2 from the lateral
// stress-free condition C1 + C2 (a + b) + D a b - K / b = 0 (a = lam^2, K = C1 + 2 C2 + D),
// P11 = lam * 2 (C1 + 2 C2 b + D b^2 - K / a) (tests/material/test_ciarlet_geymonat.cpp).
double uniaxial_P11(double lam) {
  const double a = lam * lam, K = kC1 + 2 * kC2 + kD;
  const double qa = kC2 + kD * a, qb = kC1 + kC2 * a;
  const double b = (-qb + std::sqrt(qb * qb + 4 * qa * K)) / (2 * qa);  // the positive root
  return lam * 2.0 * (kC1 + 2 * kC2 * b + kD * b * b - K / a);
}

using stentor::testing::dirichlet_xml;

}  // namespace

TEST(Reactions, UniaxialBlockPerConstrainedComponent) {
  const fs::path dir = stentor::testing::test_dir("reactions");
  fs::create_directories(dir);
  const std::string geo = std::string(STENTOR_SOURCE_DIR) + "/inputs/block3d.geo";
  // left_again constrains what left does (same nodes, x): its reaction is 0, left's the whole.
  const std::string deck =
      stentor::testing::block_deck_xml(geo,
                                       dirichlet_xml("left", "left", "x") + dirichlet_xml("front", "front", "y") +
                                           dirichlet_xml("bottom", "bottom", "z") + dirichlet_xml("pull", "right", "x", "{0.2}") +
                                           dirichlet_xml("left_again", "left", "x"),
                                       "uniaxial");
  const fs::path p = dir / "uniaxial.xml";
  std::ofstream(p) << deck;
  const Config cfg = read_deck(p.string());
  RunOptions o;
  o.output_dir = (dir / "out").string();
  o.overwrite = true;
  RunResult res;
  ASSERT_EQ(run_simulation(cfg, o, &res), 0);

  const double F = uniaxial_P11(1.2);  // force on the unit reference area
  const double tol = 1e-8 * F;
  ASSERT_EQ(res.reactions.size(), 5u);
  std::printf("[ reactions ] uniaxial lambda = 1.2: P11 A0 = %.12g N; pull x %.12g, left x %.12g, front y %.3g, bottom z %.3g\n",
              F, res.reactions[3][0], res.reactions[0][0], res.reactions[1][1], res.reactions[2][2]);
  // Final state, per set (deck order): only the constrained component is non-zero.
  const std::vector<std::array<double, 3>> expected = {{-F, 0, 0}, {0, 0, 0}, {0, 0, 0}, {F, 0, 0}, {0, 0, 0}};
  for (std::size_t s = 0; s < 5; ++s)
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(res.reactions[s][k], expected[s][k], tol) << "set " << s << " axis " << k;
  for (int k : {1, 2}) EXPECT_EQ(res.reactions[0][k], 0.0);  // not constrained: exactly 0
  EXPECT_EQ(res.reactions[1][0], 0.0);
  EXPECT_EQ(res.reactions[4][0], 0.0);  // left_again: left's dofs, reported once, for left

  // The history: one column per constrained component, at every step P11(1 + 0.2 t) A0.
  const auto h = stentor::testing::read_csv(dir / "out" / "uniaxial_history.csv");
  ASSERT_EQ(h.rows(), 2u);
  for (const char* absent : {"reaction_left_y", "reaction_left_z", "reaction_front_x", "reaction_front_z",
                             "reaction_bottom_x", "reaction_bottom_y", "reaction_pull_y", "reaction_pull_z",
                             "reaction_left_again_y"})
    EXPECT_FALSE(h.has(absent)) << absent;
  for (std::size_t i = 0; i < 2; ++i) {
    const double Fi = uniaxial_P11(1.0 + 0.2 * h["time"][i]);
    EXPECT_NEAR(h["reaction_pull_x"][i], Fi, tol);
    EXPECT_NEAR(h["reaction_left_x"][i], -Fi, tol);
    EXPECT_NEAR(h["reaction_front_y"][i], 0.0, tol);
    EXPECT_NEAR(h["reaction_bottom_z"][i], 0.0, tol);
    EXPECT_EQ(h["reaction_left_again_x"][i], 0.0);
  }
}
