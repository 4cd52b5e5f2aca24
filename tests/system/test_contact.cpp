// Node-to-rigid-obstacle frictional contact (docs/contact.md): primal-dual active set
// inside Newton, "persistence" (leapfrog) and "gap" formulations.
//  1. Static block pressed onto a plane by its top: total contact force = reaction, no penetration.
//  2. Dynamic frictionless impact (gonzalez, persistence): energy conserved to solver tolerance
//     through the impact, the block bounces; the "gap" formulation loses energy at impact.
//  3. Coulomb friction: (a) static block under tangential traction below mu p sticks;
//     (b) dynamic: a block sliding under gravity stops at t = v0 / (mu g) (within 5 %: the
//     elastic block rocks and its contact set chatters) having dissipated its kinetic energy by
//     friction (within 3 %); (c) dynamic: traction above mu p: the block slips with
//     |F_t| = mu |F_n| on the sliding nodes.
//  4. Same deck on 1 and 2 MPI ranks (stentor executable via mpirun): same history.
//  5. Statics with no support in some direction: a translation the step's tangent leaves
//     free stops the run (exit 3); contact that holds the body (friction) does not.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "CsvSeries.hpp"
#include "run/Simulation.hpp"
#include "TestDir.hpp"

using namespace stentor;
using stentor::testing::read_csv;
using stentor::testing::Series;
namespace fs = std::filesystem;

namespace {

fs::path work_dir() { return stentor::testing::test_dir("contact"); }
const std::string kInputs = std::string(STENTOR_SOURCE_DIR) + "/inputs/";


struct Outcome {
  int status = -1;
  RunResult res;
  Series history, energy;
};

Outcome run(const Config& cfg, const std::string& tag) {
  RunOptions opts;
  const fs::path dir = work_dir() / tag;
  opts.output_dir = dir.string();
  Outcome r;
  r.status = run_simulation(cfg, opts, &r.res);
  EXPECT_EQ(r.status, 0) << tag;
  r.history = read_csv(dir / (cfg.output.basename + "_history.csv"));
  if (cfg.problem.dynamic()) r.energy = read_csv(dir / (cfg.output.basename + "_energy.csv"));
  return r;
}

LoadConfig traction(const std::string& boundary, double tx, double ty) {
  LoadConfig l;
  l.type = LoadConfig::Type::Traction;
  l.name = "load";
  l.group = boundary;
  l.vector = {tx, ty, 0.0};
  l.ramp.kind = Ramp::Kind::Constant;
  return l;
}

// ---- 1. Static, frictionless: force balance and no penetration.
TEST(Contact, StaticBlockOnPlane) {
  Config cfg = read_deck(kInputs + "contact_block_static.xml");
  const Outcome r = run(cfg, "static");
  ASSERT_EQ(r.history.rows(), 4u);
  for (std::size_t i = 0; i < r.history.rows(); ++i) {
    const double fy = r.history["contact_floor_force_y"][i], reac = r.history["reaction_press_y"][i];
    std::printf("[contact] static step %zu: contact force %.10e, top reaction %.10e, active %g, min gap %.2e\n", i + 1, fy,
                reac, r.history["contact_floor_active"][i], r.history["contact_floor_min_gap"][i]);
    EXPECT_GT(fy, 0.0);
    EXPECT_NEAR(fy, -reac, 1e-9 * std::abs(reac));
    EXPECT_NEAR(r.history["contact_floor_force_x"][i], -r.history["reaction_press_x"][i], 1e-9 * std::abs(reac));
    // Frictionless on the plane y = 0 (normal +y): the normal force is the force's y part.
    EXPECT_NEAR(r.history["contact_floor_normal_force"][i], fy, 1e-12 * std::abs(fy));
    // A static step has no impulse to average: the two-step mean is the step's force.
    EXPECT_EQ(r.history["contact_floor_two_step_mean_normal_force"][i], r.history["contact_floor_normal_force"][i]);
    EXPECT_GE(r.history["contact_floor_min_gap"][i], -1e-10);
    EXPECT_EQ(r.history["contact_floor_active"][i], 9.0);  // every bottom node (h = 1/8)
  }
  // No node below the plane.
  for (std::size_t n = 0; n < r.res.mesh.num_nodes(); ++n) EXPECT_GE(r.res.mesh.x[3 * n + 1] + r.res.displacement[3 * n + 1], -1e-10);
}

// ---- 2. Dynamic frictionless impact.
Config impact_deck(const std::string& formulation) {
  Config cfg = read_deck(kInputs + "contact_block_impact.xml");
  cfg.contact[0].formulation = formulation;
  return cfg;
}

TEST(Contact, ImpactPersistenceConservesEnergy) {
  const Outcome r = run(impact_deck("persistence"), "impact_persistence");
  const Series& e = r.energy;
  ASSERT_GT(e.rows(), 100u);
  const double E0 = e["total"][0];
  double max_bal = 0, max_dev = 0;
  for (std::size_t i = 0; i < e.rows(); ++i) {
    max_bal = std::max(max_bal, std::abs(e["balance_residual"][i]));
    max_dev = std::max(max_dev, std::abs(e["total"][i] - E0));
  }
  const double py0 = e["momentum_y"][0], py1 = e["momentum_y"][e.rows() - 1];
  double active_steps = 0;
  for (double a : r.history["contact_floor_active"]) active_steps += a > 0;
  std::printf("[contact] impact persistence: E0 %.9e, max |E - E0| %.3e (rel %.2e), max |balance| %.3e, contact work %.3e, "
              "p_y %.4e -> %.4e, %g steps with contact\n",
              E0, max_dev, max_dev / E0, max_bal, e["contact_work"][e.rows() - 1], py0, py1, active_steps);
  EXPECT_LT(max_bal, 1e-8 * E0);
  EXPECT_LT(max_dev, 1e-8 * E0);                                   // frictionless persistence: no energy lost or gained
  EXPECT_LT(std::abs(e["contact_work"][e.rows() - 1]), 1e-8 * E0);  // the normal increment vanishes on active nodes
  EXPECT_GT(active_steps, 3);
  EXPECT_LT(py0, 0.0);
  EXPECT_GT(py1, 0.5 * std::abs(py0));  // bounced
  // The history's two-step mean: the impulse of the last two steps over their duration.
  const Series& h = r.history;
  for (std::size_t i = 1; i < h.rows(); ++i) {
    const double dt0 = h["dt"][i - 1], dt1 = h["dt"][i], F0 = h["contact_floor_normal_force"][i - 1], F1 = h["contact_floor_normal_force"][i];
    EXPECT_NEAR(h["contact_floor_two_step_mean_normal_force"][i], (dt0 * F0 + dt1 * F1) / (dt0 + dt1), 1e-12 * (std::abs(F0) + std::abs(F1) + 1.0));
  }
}

// The first step's leapfrog test sees the initial velocity (Contact::initialize with v_0):
// the block starts 0.02 m above the plane at 2 m/s and the step is 0.03 s, so it would
// cross the plane within the first step. Before, the first step had no gap history
// (d_-1 = d_0), the block was free in it and ended 0.04 m below the plane (measured);
// now its nodes are candidates in step 1 and persistence stops them above it.
TEST(Contact, FirstStepLeapfrogUsesTheInitialVelocity) {
  Config cfg = impact_deck("persistence");
  cfg.stepping.num_steps = 4;  // dt = 0.03 s: 0.06 m per step at 2 m/s
  const Outcome r = run(cfg, "impact_first_step");
  const Series& h = r.history;
  const double E0 = r.energy["total"][0];
  double dev = 0.0;
  for (double E : r.energy["total"]) dev = std::max(dev, std::abs(E - E0));
  std::printf("[contact] first step: active %g, min gap %.4e m; max |E - E0| / E0 %.2e\n", h["contact_floor_active"][0],
              h["contact_floor_min_gap"][0], dev / E0);
  EXPECT_GT(h["contact_floor_active"][0], 0.0);
  for (double g : h["contact_floor_min_gap"]) EXPECT_GT(g, -1e-12);
  EXPECT_LT(dev, 1e-8 * E0);
}

TEST(Contact, ImpactGapLosesEnergy) {
  const Outcome r = run(impact_deck("gap"), "impact_gap");
  const Series& e = r.energy;
  const std::size_t last = e.rows() - 1;
  const double E0 = e["total"][0], E1 = e["total"][last];
  double max_bal = 0;
  for (std::size_t i = 0; i < e.rows(); ++i) max_bal = std::max(max_bal, std::abs(e["balance_residual"][i]));
  double min_gap = 1e300;
  for (double g : r.history["contact_floor_min_gap"]) min_gap = std::min(min_gap, g);
  std::printf("[contact] impact gap: E0 %.6e, E_end %.6e (loss %.2f %%), contact work %.4e, max |balance| %.3e, min gap %.2e\n", E0, E1,
              100 * (E0 - E1) / E0, e["contact_work"][last], max_bal, min_gap);
  EXPECT_LT(E1, 0.99 * E0);                                          // measurable loss at impact
  EXPECT_NEAR(E1 - E0, e["contact_work"][last], 1e-6 * E0);          // ... all of it through the contact work
  EXPECT_LT(max_bal, 1e-8 * E0);
  for (double g : r.history["contact_floor_min_gap"]) EXPECT_GE(g, -1e-10);  // gap: no penetration
}

// ---- 3. Coulomb friction.
TEST(Contact, CoulombStickBelowLimit) {
  Config cfg = read_deck(kInputs + "contact_block_static.xml");
  const double p = 1e5, mu = 0.5;
  cfg.loads = {traction("top", 0.2 * p, -p)};
  cfg.loads[0].ramp.kind = Ramp::Kind::Linear;
  cfg.contact[0].friction = mu;
  const Outcome r = run(cfg, "stick");
  const std::size_t last = r.history.rows() - 1;
  const double fx = r.history["contact_floor_force_x"][last], fy = r.history["contact_floor_force_y"][last];
  double ux_bottom = 0, ux_top = 0;
  for (std::size_t n = 0; n < r.res.mesh.num_nodes(); ++n) {
    const double X = r.res.mesh.x[3 * n];
    if (std::abs(r.res.mesh.x[3 * n + 1]) < 1e-12 && X > 0.2 && X < 0.8) ux_bottom = std::max(ux_bottom, std::abs(r.res.displacement[3 * n]));
    if (std::abs(r.res.mesh.x[3 * n + 1] - 1) < 1e-12) ux_top = std::max(ux_top, std::abs(r.res.displacement[3 * n]));
  }
  std::printf("[contact] stick: F = (%.6e, %.6e) (applied (%.1e, %.1e)), stick %g slip %g, max |u_x| bottom (0.2 < x < 0.8) %.3e top %.3e\n", fx, fy,
              0.2 * p, -p, r.history["contact_floor_stick"][last], r.history["contact_floor_slip"][last], ux_bottom, ux_top);
  EXPECT_NEAR(fx, -0.2 * p, 1e-8 * p);
  EXPECT_NEAR(fy, p, 1e-8 * p);
  EXPECT_GT(ux_top, 1e-3);
  EXPECT_LT(ux_bottom, 1e-10);
  EXPECT_EQ(r.history["contact_floor_slip"][last], 0.0);
}

Config sliding_deck(double mu, double v0, double g) {
  Config cfg = read_deck(kInputs + "contact_block_impact.xml");
  cfg.contact[0].point = {0.0, 0.0, 0.0};
  cfg.contact[0].friction = mu;
  cfg.initial.velocity = {v0, 0.0, 0.0};
  LoadConfig grav;
  grav.type = LoadConfig::Type::BodyForce;
  grav.name = "gravity";
  grav.vector = {0.0, -1000.0 * g, 0.0};
  grav.ramp.kind = Ramp::Kind::Constant;
  cfg.loads = {grav};
  // Stiff (C1 = 50 MPa) so the block is nearly rigid: the elastic shear oscillation left
  // when it stops, and the start-up of the normal force, are small.
  cfg.materials[0].C1 = 50e6;
  cfg.materials[0].C2 = 0.5e6;
  cfg.materials[0].D = 35e6;
  return cfg;
}

TEST(Contact, CoulombSlidingBlockStops) {
  const double mu = 0.5, v0 = 1.0, g = 10.0, m = 1000.0;
  Config cfg = sliding_deck(mu, v0, g);
  cfg.stepping.end_time = 0.3;
  cfg.stepping.num_steps = 150;
  const Outcome r = run(cfg, "sliding");
  const Series& e = r.energy;
  const std::size_t last = e.rows() - 1;
  // Stop time: first time the x momentum reaches (nearly) zero, interpolated.
  double t_stop = -1;
  for (std::size_t i = 1; i < e.rows(); ++i)
    if (e["momentum_x"][i] <= 1e-3 * m * v0) {
      const double a = e["momentum_x"][i - 1], b = e["momentum_x"][i];
      t_stop = e["time"][i - 1] + (e["time"][i] - e["time"][i - 1]) * a / std::max(a - b, 1e-300);
      break;
    }
  const double t_exact = m * v0 / (mu * m * g), ke0 = 0.5 * m * v0 * v0;
  double max_bal = 0;
  for (std::size_t i = 0; i < e.rows(); ++i) max_bal = std::max(max_bal, std::abs(e["balance_residual"][i]));
  std::printf("[contact] sliding: stop time %.5f (analytic m v0/(mu N) = %.5f, %.2f %%), friction dissipation %.5e (KE0 %.5e, %.2f %%), "
              "final p_x %.3e, max |balance| %.3e, final stick %g slip %g\n",
              t_stop, t_exact, 100 * (t_stop - t_exact) / t_exact, e["friction_dissipation"][last], ke0,
              100 * (e["friction_dissipation"][last] - ke0) / ke0, e["momentum_x"][last], max_bal, r.history["contact_floor_stick"].back(),
              r.history["contact_floor_slip"].back());
  EXPECT_NEAR(t_stop, t_exact, 0.05 * t_exact);
  EXPECT_NEAR(e["friction_dissipation"][last], ke0, 0.03 * ke0);
  EXPECT_LT(std::abs(e["momentum_x"][last]), 3e-2 * m * v0);
  EXPECT_LT(max_bal, 1e-7 * ke0);
}

TEST(Contact, CoulombSlipAboveLimit) {
  // Pushed sideways by a body force above mu * weight (uniform, so the block does not tip
  // over as it would under a push on its top): slips, |F_t| = mu |F_n|.
  const double mu = 0.3, g = 10.0, m = 1000.0;
  Config cfg = sliding_deck(mu, 0.0, g);
  cfg.loads[0].vector[0] = 0.6 * m * g;
  cfg.stepping.end_time = 0.1;
  cfg.stepping.num_steps = 50;
  const Outcome r = run(cfg, "slip");
  const Series& h = r.history;
  const std::size_t last = h.rows() - 1;
  double worst = 0;
  for (std::size_t i = 0; i < h.rows(); ++i)
    if (h["contact_floor_stick"][i] == 0 && h["contact_floor_slip"][i] > 0)
      worst = std::max(worst, std::abs(std::abs(h["contact_floor_force_x"][i]) - mu * std::abs(h["contact_floor_force_y"][i])));
  // Momentum balance (exact in the discrete scheme): p_x(T) = F_push T + int F_x dt.
  std::printf("[contact] slip: final p_x %.5e (rigid estimate (0.6 - mu) m g T = %.5e), max ||F_x| - mu |F_y|| %.3e on all-slip steps, "
              "slip %g stick %g, friction dissipation %.4e\n",
              r.energy["momentum_x"][r.energy.rows() - 1], (0.6 - mu) * m * g * 0.1, worst, h["contact_floor_slip"][last],
              h["contact_floor_stick"][last], r.energy["friction_dissipation"][r.energy.rows() - 1]);
  EXPECT_GT(h["contact_floor_slip"][last], 0);
  EXPECT_LT(worst, 1e-6 * m * g);
  // Exact discrete momentum balance (midpoint family): p_x(T) = F_push T + sum_n dt F_x,n, with
  // F_x the reported contact force; on all-slip steps F_x = -mu F_y (checked above).
  const double T = 0.1, px = r.energy["momentum_x"].back();
  double impulse = 0.6 * m * g * T;
  for (std::size_t i = 0; i < h.rows(); ++i) impulse += h["dt"][i] * h["contact_floor_force_x"][i];
  std::printf("[contact] slip: p_x %.8e, F_push T + sum dt F_x = %.8e\n", px, impulse);
  EXPECT_NEAR(px, impulse, 1e-6 * m * g * T);
  EXPECT_NEAR(px, (0.6 - mu) * m * g * T, 0.05 * (0.6 - mu) * m * g * T);
  EXPECT_GT(r.energy["friction_dissipation"][r.energy.rows() - 1], 0.0);
}

// ---- 3d. The sets do not depend on c_nu, c_tau ("set update" = linearised): the sliding
// block (impact on the plane, slip, then stick as it stops) with the automatic c (about
// 1.6e6 Pa s/m here: the node's tangent diagonal x dt over its area) and c_nu = c_tau =
// 1e8, 1e12, 1e16 Pa s/m (1e2 to 1e10 times it) has the same active, stick and slip
// counts at every step and the same Newton iterations per step to +-1.
TEST(Contact, LinearisedSetsDoNotDependOnC) {
  const double cs[] = {0.0, 1e8, 1e12, 1e16};
  std::vector<Outcome> out;
  for (double c : cs) {
    Config cfg = sliding_deck(0.5, 1.0, 10.0);
    cfg.stepping.end_time = 0.24;
    cfg.stepping.num_steps = 120;
    cfg.contact[0].c_normal = cfg.contact[0].c_tangent = c;
    std::ostringstream tag;
    tag << "c_independent_" << c;
    out.push_back(run(cfg, tag.str()));
  }
  const Series& h0 = out[0].history;
  ASSERT_EQ(h0.rows(), 120u);
  double stick_steps = 0, slip_steps = 0;
  for (std::size_t i = 0; i < h0.rows(); ++i) stick_steps += h0["contact_floor_stick"][i] > 0, slip_steps += h0["contact_floor_slip"][i] > 0;
  EXPECT_GT(stick_steps, 10);  // the block stops: both regimes are exercised
  EXPECT_GT(slip_steps, 10);
  for (std::size_t k = 1; k < out.size(); ++k) {
    const Series& h = out[k].history;
    ASSERT_EQ(h.rows(), h0.rows()) << "c = " << cs[k];
    int worst = 0;
    for (std::size_t i = 0; i < h.rows(); ++i) {
      for (const char* col : {"contact_floor_active", "contact_floor_stick", "contact_floor_slip"})
        EXPECT_EQ(h[col][i], h0[col][i]) << col << " at step " << i + 1 << ", c = " << cs[k];
      worst = std::max(worst, static_cast<int>(std::abs(h["newton_iterations"][i] - h0["newton_iterations"][i])));
    }
    std::printf("[contact] c = %.0e: %d cut-backs, %d Newton iterations (automatic c: %d), largest per-step difference %d\n", cs[k],
                out[k].res.cutbacks, out[k].res.newton_iterations, out[0].res.newton_iterations, worst);
    EXPECT_EQ(out[k].res.cutbacks, 0);
    EXPECT_LE(worst, 1) << "c = " << cs[k];
  }
}

// ---- 1b. Steps that land on the contact (Stepping->contact approach): the block of test 1
// starts 0.06 above the plane and its top moves down by 0.1 in 4 static steps, so the bottom
// touches at t = 0.6, inside the third step (0.5 -> 0.75), which would end 0.015 deep. With
// `contact approach` = 0.05 the third step is shortened so that the deepest predicted
// bottom node (the predictor extrapolates the last increment, 0.025 per 0.25 s) ends it at
// 0.05 of its size: the corner nodes, half an element (0.0625): 0.003125 deep, i.e. dt =
// 0.25 (0.01 + 0.003125) / 0.025 = 0.13125; the step after it is the time in which the
// contact deepens by that much, 0.25 x 0.003125 / 0.025 = 0.03125, and the steps grow back
// by 1.5. The end state is the one of the fixed steps (elastic, path-independent).
TEST(Contact, ContactApproachLandsOnTheFirstTouch) {
  Config cfg = read_deck(kInputs + "contact_block_static.xml");
  cfg.contact[0].point[1] = -0.06;
  const Outcome fixed = run(cfg, "approach_off");
  cfg.stepping.contact_approach = 0.05;
  const Outcome landing = run(cfg, "approach_on");
  const Series& h = landing.history;
  ASSERT_GE(h.rows(), 5u);
  EXPECT_EQ(h["contact_floor_active"][1], 0.0);
  EXPECT_NEAR(h["dt"][2], 0.13125, 1e-12);
  EXPECT_GT(h["contact_floor_active"][2], 0.0);
  EXPECT_NEAR(h["dt"][3], 0.03125, 1e-12);
  EXPECT_NEAR(h["dt"][4], 1.5 * 0.03125, 1e-12);
  EXPECT_EQ(landing.res.cutbacks, 0);
  const double f_fixed = fixed.history["reaction_press_y"].back(), f_landing = h["reaction_press_y"].back();
  std::printf("[contact] contact approach: %zu steps (fixed: %zu), top reaction at t = 1: %.12e (fixed: %.12e)\n", h.rows(),
              fixed.history.rows(), f_landing, f_fixed);
  EXPECT_NEAR(f_landing, f_fixed, 1e-8 * std::abs(f_fixed));
}

// In dynamics the nodes are predicted with their velocity: the block of contact_block_impact.xml
// (v = -2 m/s, no other load: free flight is exact) 0.025 above the plane, steps of 0.01 s.
// The first ends 0.005 above it; the second would end 0.015 deep, and is shortened so that
// the corner nodes (size 0.1, allowed 0.005) end 0.005 deep: dt = 0.01 (0.005 + 0.005) /
// 0.02 = 0.005; the next is the time to deepen by 0.005 at 2 m/s, 0.0025. The energy
// identity holds through the impact as with fixed steps.
TEST(Contact, ContactApproachPredictsWithTheVelocity) {
  Config cfg = read_deck(kInputs + "contact_block_impact.xml");
  cfg.contact[0].point[1] = -0.025;
  cfg.stepping.end_time = 0.06;
  cfg.stepping.num_steps = 6;
  cfg.stepping.contact_approach = 0.05;
  const Outcome r = run(cfg, "approach_dynamic");
  const Series& h = r.history;
  ASSERT_GE(h.rows(), 4u);
  EXPECT_NEAR(h["dt"][0], 0.01, 1e-15);
  EXPECT_EQ(h["contact_floor_active"][0], 0.0);
  EXPECT_NEAR(h["dt"][1], 0.005, 1e-12);
  EXPECT_NEAR(h["dt"][2], 0.0025, 1e-12);
  double worst = 0.0;
  for (double b : r.energy["balance_residual"]) worst = std::max(worst, std::abs(b));
  std::printf("[contact] contact approach, dynamic: dt %.6g, %.6g, %.6g; %zu steps; max |balance| %.2e of E0 %.4e\n", h["dt"][0],
              h["dt"][1], h["dt"][2], h.rows(), worst, r.energy["total"][0]);
  EXPECT_LT(worst, 1e-12 * r.energy["total"][0]);
}

// The same landing on 2 ranks (the bottom's nodes split between them): the same steps, to
// the round-off of the solves that the predictor extrapolates.
TEST(Contact, ContactApproachSameStepsOnTwoRanks) {
  if (std::system("command -v mpirun > /dev/null 2>&1") != 0) GTEST_SKIP() << "mpirun not found";
  const fs::path dir = work_dir() / "approach_mpi";
  fs::create_directories(dir);
  fs::copy_file(kInputs + "block2d.geo", dir / "block2d.geo", fs::copy_options::overwrite_existing);
  std::ifstream in(kInputs + "contact_block_static.xml");
  std::stringstream text;
  text << in.rdbuf();
  std::string deck = text.str();
  const auto replace = [&](const std::string& a, const std::string& b) {
    const auto at = deck.find(a);
    ASSERT_NE(at, std::string::npos) << a;
    deck.replace(at, a.size(), b);
  };
  replace("value=\"{0.0, 0.0}\"", "value=\"{0.0, -0.06}\"");
  replace("<Parameter name=\"steps\" type=\"int\" value=\"4\"/>",
          "<Parameter name=\"steps\" type=\"int\" value=\"4\"/><Parameter name=\"contact approach\" type=\"double\" value=\"0.05\"/>");
  std::ofstream(dir / "deck.xml") << deck;
  Series h[2];
  for (int np = 1; np <= 2; ++np) {
    const fs::path out = dir / ("np" + std::to_string(np));
    const std::string cmd = "env -i PATH=\"$PATH\" HOME=\"$HOME\" OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMP_NUM_THREADS=1 mpirun --oversubscribe -np " +
                            std::to_string(np) + " " + std::string(STENTOR_BINARY_DIR) + "/stentor " + (dir / "deck.xml").string() +
                            " --output " + out.string() + " > " + out.string() + ".log 2>&1";
    ASSERT_EQ(std::system(cmd.c_str()), 0) << cmd;
    h[np - 1] = read_csv(out / "contact_block_static_history.csv");
  }
  ASSERT_EQ(h[0].rows(), h[1].rows());
  EXPECT_NEAR(h[1]["dt"][2], 0.13125, 1e-12);
  for (std::size_t i = 0; i < h[0].rows(); ++i) EXPECT_NEAR(h[0]["dt"][i], h[1]["dt"][i], 1e-12) << "step " << i + 1;  // the solves' round-off
  EXPECT_NEAR(h[0]["reaction_press_y"].back(), h[1]["reaction_press_y"].back(), 1e-9 * std::abs(h[0]["reaction_press_y"].back()));
}

// ---- 3e. A constructed set cycle: the block of contact_block_impact.xml falls onto a rigid
// circle (R = 2 m, top at y = -0.02) while sliding sideways at 3 m/s, frictionless. On a
// curved obstacle a node held on its linearised gap ends each solve slightly off the
// circle. With the old update (`set update` = residual, lambda + c g from the bulk residual)
// and c_nu = 1e16 Pa s/m the decision is the sign of that nonlinear remainder: the corner
// node enters, leaves and enters contact every other iterate until the iteration limit
// (measured: 93 cut-backs, 5165 Newton iterations). The linearised update keeps a node of
// the solve's active set while it presses: the same sets and iteration counts (to +-1) for
// the automatic c, 1e12 and 1e16, and no cut-back.
TEST(Contact, LinearisedSetsResolveTheResidualCycleOnACurvedObstacle) {
  auto deck = [](bool linearised, double c) {
    Config cfg = read_deck(kInputs + "contact_block_impact.xml");
    auto& k = cfg.contact[0];
    k.obstacle = "circle";
    k.point = {0.5, -2.02, 0.0};
    k.radius = 2.0;
    k.linearised_sets = linearised;
    k.c_normal = c;
    cfg.initial.velocity = {3.0, -2.0, 0.0};
    return cfg;
  };
  const double cs[] = {0.0, 1e12, 1e16};
  std::vector<Outcome> lin;
  for (double c : cs) {
    std::ostringstream tag;
    tag << "circle_cycle_linearised_" << c;
    lin.push_back(run(deck(true, c), tag.str()));
    ASSERT_EQ(lin.back().status, 0) << "c = " << c;
  }
  const Outcome old = run(deck(false, 1e16), "circle_cycle_residual");
  std::printf("[contact] sliding over a rigid circle: linearised %d / %d / %d Newton iterations (c auto, 1e12, 1e16), residual "
              "update with c = 1e16: %d cut-backs, %d Newton iterations\n",
              lin[0].res.newton_iterations, lin[1].res.newton_iterations, lin[2].res.newton_iterations, old.res.cutbacks,
              old.res.newton_iterations);
  EXPECT_GT(old.res.cutbacks, 10) << "the residual update no longer cycles here: the test lost its point";
  const Series& h0 = lin[0].history;
  double touching = 0;
  for (std::size_t i = 0; i < h0.rows(); ++i) touching += h0["contact_floor_active"][i] > 0;
  EXPECT_GT(touching, 10);  // the block slides on the circle for a while
  for (std::size_t k = 0; k < lin.size(); ++k) {
    EXPECT_EQ(lin[k].res.cutbacks, 0) << "c = " << cs[k];
    const Series& h = lin[k].history;
    ASSERT_EQ(h.rows(), h0.rows()) << "c = " << cs[k];
    for (std::size_t i = 0; i < h.rows(); ++i) {
      EXPECT_EQ(h["contact_floor_active"][i], h0["contact_floor_active"][i]) << "step " << i + 1 << ", c = " << cs[k];
      EXPECT_LE(std::abs(h["newton_iterations"][i] - h0["newton_iterations"][i]), 1.0) << "step " << i + 1 << ", c = " << cs[k];
    }
  }
}

// ---- 4. 1 vs 2 MPI ranks through the executable.
TEST(Contact, SameHistoryOnOneAndTwoRanks) {
  if (std::system("command -v mpirun > /dev/null 2>&1") != 0) GTEST_SKIP() << "mpirun not found";
  const std::string exe = std::string(STENTOR_BINARY_DIR) + "/stentor";
  const std::string deck = kInputs + "contact_block_impact.xml";
  Series h[2], e[2];
  fs::create_directories(work_dir());  // the shell writes <dir>.log there, before stentor creates <dir>
  for (int np = 1; np <= 2; ++np) {
    const fs::path dir = work_dir() / ("mpi" + std::to_string(np));
    // env -i: the test process is itself an MPI singleton; its OMPI_*/PMIX_* variables would
    // confuse the nested mpirun.
    const std::string cmd = "env -i PATH=\"$PATH\" HOME=\"$HOME\" OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMP_NUM_THREADS=1 mpirun --oversubscribe -np " +
                            std::to_string(np) + " " + exe + " " + deck + " --output " + dir.string() + " > " + dir.string() +
                            ".log 2>&1";
    const int st = std::system(cmd.c_str());
    ASSERT_EQ(st, 0) << cmd << " (see " << dir.string() << ".log)";
    h[np - 1] = read_csv(dir / "contact_block_impact_history.csv");
    e[np - 1] = read_csv(dir / "contact_block_impact_energy.csv");
  }
  ASSERT_EQ(h[0].rows(), h[1].rows());
  double dforce = 0, dact = 0, dE = 0, fscale = 0;
  for (std::size_t i = 0; i < h[0].rows(); ++i) {
    dact = std::max(dact, std::abs(h[0]["contact_floor_active"][i] - h[1]["contact_floor_active"][i]));
    dforce = std::max(dforce, std::abs(h[0]["contact_floor_force_y"][i] - h[1]["contact_floor_force_y"][i]));
    fscale = std::max(fscale, std::abs(h[0]["contact_floor_force_y"][i]));
  }
  for (std::size_t i = 0; i < e[0].rows(); ++i) dE = std::max(dE, std::abs(e[0]["total"][i] - e[1]["total"][i]));
  std::printf("[contact] 1 vs 2 ranks: max |d active| %g, max |d F_y| %.3e (scale %.3e), max |d E| %.3e\n", dact, dforce, fscale, dE);
  EXPECT_EQ(dact, 0.0);
  EXPECT_LT(dforce, 1e-6 * fscale);
  EXPECT_LT(dE, 1e-8 * e[0]["total"][0]);
}

// ---- 5. A free translation in statics (issue 12; Stepper::free_translation). The block of
// 1 pressed down 0.1 by its top in y only: frictionless, nothing holds it in x, the tangent is
// singular and the equilibrium not unique (on main: exit 0, with whatever x offset the
// solver chose) -- the run stops at its first step, exit 3. With friction mu = 0.3 the
// sticking bottom nodes hold x: it runs, as does CoulombStickBelowLimit (no Dirichlet
// condition at all, held by friction alone).
TEST(Contact, StaticFreeTranslationStopsTheRun) {
  for (const double mu : {0.0, 0.3}) {
    Config cfg = read_deck(kInputs + "contact_block_static.xml");
    ASSERT_EQ(cfg.loads.size(), 1u);
    cfg.loads[0].components = {false, true, false};
    cfg.loads[0].all_components = false;
    cfg.loads[0].vector = {0.0, -0.1, 0.0};
    cfg.contact[0].friction = mu;
    RunOptions opts;
    opts.output_dir = (work_dir() / ("free_x_mu" + std::to_string(mu))).string();
    RunResult res;
    const int status = run_simulation(cfg, opts, &res);
    std::printf("[contact] block pressed in y only, mu = %g: exit %d after %d steps\n", mu, status, res.steps);
    if (mu == 0.0) {
      EXPECT_EQ(status, 3);
      EXPECT_EQ(res.steps, 1);  // stopped at the first converged step, not cut back
      EXPECT_EQ(res.cutbacks, 0);
    } else {
      EXPECT_EQ(status, 0);
      EXPECT_EQ(res.steps, 4);
    }
  }
}

}  // namespace
