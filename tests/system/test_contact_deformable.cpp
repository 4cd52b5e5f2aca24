// Contact between deformable bodies (node-to-segment, docs/contact.md):
//  1. The contact tangent K' = Q K + G against central finite differences of the
//     contact-modified residual, for frictionless, sticking and sliding nodes on a
//     non-matching interface (the active set is frozen across the differences), with the
//     gap and the persistence condition, and with a rigid capsule pressing the same body.
//  2. Contact patch test (two blocks, uniform pressure), 2D and 3D (hex, symmetry planes):
//     matching interface meshes give the homogeneous solution to round-off; non-matching
//     ones (node-to-segment, one pass) transmit the total force exactly, with a measured
//     local error.
//  3. Two identical bars impacting (frictionless persistence, gonzalez): total linear
//     momentum and energy of both bodies conserved through the impact, contact duration.
//  4. Scene S3 (coarse): the S1 ring on a deformable foundation: frictionless, the energy
//     of both bodies is conserved through the impact; with mu = 0.3 the energy drop equals
//     the frictional dissipation, which is >= 0 every step.
//  5. A rigid circular balloon inflated into a clamped ring and deflated (curved obstacle,
//     friction): no cut-back, few Newton iterations (the normal's derivative is in the
//     tangent; the tolerance keeps a force scale once the load is gone).
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>

#include "CsvSeries.hpp"
#include "run/Model.hpp"
#include "run/Simulation.hpp"
#include "solver/Newton.hpp"

using namespace stentor;

namespace {

const std::string kInputs = std::string(STENTOR_SOURCE_DIR) + "/inputs/";

// The run's own set-up (mesh, loads, partition, assembler, linear solver, contact).
struct Rig {
  Config cfg;
  Timers timers;
  Model m;
  Mesh& mesh;
  std::unique_ptr<Distribution>& dist;
  std::unique_ptr<Assembler>& assembler;
  std::unique_ptr<Contact>& contact;
  explicit Rig(const Config& c)
      : cfg(c), m(cfg, RunOptions{}, timers), mesh(m.mesh), dist(m.dist), assembler(m.assembler), contact(m.contact) {
    m.discretise(timers);
  }
  // Contact-modified residual (and tangent when asked).
  la::RCP<la::CrsMatrix> eval(const la::Vector& u, la::Vector& r, bool tangent) {
    assembler->assemble(u, 1.0, 1.0, r, tangent);
    return contact->apply(u, r, tangent ? assembler->matrix() : la::RCP<la::CrsMatrix>());
  }
};

// Max |K v - (R(u + h v) - R(u - h v)) / 2h| / max |K v| over random directions v.
double fd_error(Rig& rig, const la::Vector& u, std::mt19937& gen) {
  const auto& map = rig.dist->owned_map();
  la::Vector r(map), rp(map), rm(map), Kv(map), v(map), up(map), um(map);
  {
    auto vh = v.getLocalViewHost(Tpetra::Access::OverwriteAll);
    std::uniform_real_distribution<double> U(-1.0, 1.0);
    for (std::size_t i = 0; i < vh.extent(0); ++i) vh(i, 0) = rig.assembler->is_dirichlet(static_cast<la::LO>(i)) ? 0.0 : U(gen);
  }
  auto K = rig.eval(u, r, true);
  K->apply(v, Kv);
  const double h = 1e-7;
  up.update(1.0, u, h, v, 0.0);
  um.update(1.0, u, -h, v, 0.0);
  rig.eval(up, rp, false);
  EXPECT_FALSE(rig.contact->active_set_changed()) << "the active set changed within the difference";
  rig.eval(um, rm, false);
  EXPECT_FALSE(rig.contact->active_set_changed()) << "the active set changed within the difference";
  rp.update(-1.0 / (2 * h), rm, 1.0 / (2 * h));
  rp.update(-1.0, Kv, 1.0);
  return rp.normInf() / Kv.normInf();
}

// The upper block pushed 1e-3 into the lower one and compressed (its top moves 2e-3),
// sheared by `shift`, plus noise.
la::Vector penetrated_state(Rig& rig, double shift, std::mt19937& gen) {
  la::Vector u(rig.dist->owned_map());
  auto uh = u.getLocalViewHost(Tpetra::Access::OverwriteAll);
  std::uniform_real_distribution<double> U(-1e-5, 1e-5);
  for (la::LO n = 0; n < rig.dist->num_owned_nodes(); ++n) {
    const double y = rig.mesh.x[3 * static_cast<std::size_t>(rig.dist->global_node(n)) + 1];
    const double t = std::max(0.0, y - 0.5) / 0.5;  // 0 on the interface .. 1 on top
    uh(2 * n, 0) = (y >= 0.5 ? shift : 0.0) + U(gen);
    uh(2 * n + 1, 0) = (y >= 0.5 ? -1e-3 * (1.0 + t) : 0.0) + U(gen);
  }
  return u;
}

Config patch_deck(double mu, const std::string& formulation) {
  Config cfg = read_deck(kInputs + "contact_patch2d.xml");
  cfg.contact[0].friction = mu;
  cfg.contact[0].formulation = formulation;
  return cfg;
}

// Counts of slave nodes per state (index = state) at the last evaluation.
std::array<int, 4> states(const Rig& rig) {
  std::array<int, 4> n{};
  const auto f = rig.contact->nodal_fields();
  for (std::size_t i = 0; i < f.nodes.size(); ++i) ++n[static_cast<std::size_t>(f.values[Contact::kNodalValues * i])];
  return n;
}

// FD check of the deck's contact at a penetrated, sheared state after the step
// t = 0 -> dt from rest; returns the state counts.
std::array<int, 4> check_tangent(const Config& cfg, double shift, double dt, unsigned seed = 7) {
  Rig rig(cfg);
  std::mt19937 gen(seed);
  la::Vector u0(rig.dist->owned_map());
  rig.contact->initialize(u0, 1.0);
  rig.contact->begin_step(0.0, dt, u0);
  const la::Vector u = penetrated_state(rig, shift, gen);
  for (int k = 0; k < 3; ++k)
    EXPECT_LT(fd_error(rig, u, gen), 1e-6) << "mu " << cfg.contact[0].friction << ", " << cfg.contact[0].formulation << ", shift " << shift;
  const auto n = states(rig);
  std::printf("states free %d inactive %d stick %d slip %d\n", n[0], n[1], n[2], n[3]);
  return n;
}
std::array<int, 4> check_tangent(double mu, const std::string& formulation, double shift, double dt) {
  return check_tangent(patch_deck(mu, formulation), shift, dt);
}

}  // namespace

TEST(DeformableContact, TangentMatchesFiniteDifferencesFrictionless) {
  const auto n = check_tangent(0.0, "gap", 0.0, 1.0);
  EXPECT_EQ(n[3], 6);  // all six slave nodes active (frictionless nodes count as slip)
}

// Persistence (dynamics): the condition on n . (relative displacement) and its tangent.
TEST(DeformableContact, TangentMatchesFiniteDifferencesPersistence) {
  Config cfg = patch_deck(0.3, "persistence");
  cfg.problem.analysis = "dynamic";
  const auto n = check_tangent(cfg, 2e-4, 0.02, 11);
  EXPECT_EQ(n[2] + n[3], 6);
}

// A rigid capsule (a balloon) pressing the upper block's top while its bottom touches
// the lower block: a rigid pair (rows rewritten in place) and a master surface (K' = Q K
// + G) on the same body, both active.
TEST(DeformableContact, TangentWithRigidCapsuleAndMasterSurfaceOnOneBody) {
  Config cfg = patch_deck(0.0, "gap");
  ContactPairConfig c;
  c.name = "balloon";
  c.slave = "upper_top";
  c.obstacle = "capsule";
  c.point = {-0.5, 1.297, 0.0};  // the top moves to y = 0.998: 1e-3 into the capsule
  c.point_len = 2;
  c.axis = {1.0, 0.0, 0.0};
  c.axis_len = 2;
  c.length = 2.0;
  c.radius = 0.3;
  c.formulation = "gap";
  c.c_normal = 1e12;
  cfg.contact.push_back(c);
  const auto n = check_tangent(cfg, 1e-4, 1.0);
  EXPECT_EQ(n[3], 12);  // six slave nodes per pair, all active
}

TEST(DeformableContact, TangentMatchesFiniteDifferencesSlip) {
  // A tangential shift of 2e-3 against 1e-3 penetration: Coulomb slip.
  const auto n = check_tangent(0.3, "gap", 2e-3, 1.0);
  EXPECT_GT(n[3], 0);
}

TEST(DeformableContact, TangentMatchesFiniteDifferencesStick) {
  // A large c_tau dt-scaled slip measure is small when dt is large: nodes stick.
  const auto n = check_tangent(0.3, "gap", 1e-6, 1e3);
  EXPECT_GT(n[2], 0);
}

namespace {

namespace fs = std::filesystem;
const fs::path kDir = fs::path(STENTOR_BINARY_DIR) / "system_tests" / "contact_deformable";

// two_blocks.geo with nl / nu divisions on the lower / upper side of the interface.
// A copy of inputs/<geo> with `DefineNumber[<old>` defaults replaced, written to the test folder.
std::string geo_variant(const std::string& geo, const std::vector<std::pair<std::string, std::string>>& subs, const std::string& name) {
  std::ifstream in(kInputs + geo);
  std::stringstream ss;
  ss << in.rdbuf();
  std::string t = ss.str();
  for (const auto& [from, to] : subs) {
    const auto at = t.find(from);
    if (at != std::string::npos) t.replace(at, from.size(), to);
  }
  fs::create_directories(kDir);
  const fs::path p = kDir / name;
  std::ofstream(p) << t;
  return p.string();
}

std::string blocks_geo(int nl, int nu) {
  return geo_variant("two_blocks.geo", {{"nl = DefineNumber[4", "nl = DefineNumber[" + std::to_string(nl)}, {"nu = DefineNumber[5", "nu = DefineNumber[" + std::to_string(nu)}},
                     "two_blocks_" + std::to_string(nl) + "_" + std::to_string(nu) + ".geo");
}

struct PatchResult {
  double affine_error = 0.0;   // max |u - (a_c x_c)| / |a_dim-1| over all nodes
  double force_error = 0.0;    // |sum of contact forces - p A| / (p A)
  int newton = 0;
};

// The homogeneous solution u_c = a_c x_c (a from the node at (1, 1[, 1])) against the run's
// displacements, and the total contact force (column `force`) against p A = 1e4 N.
PatchResult measure_patch(const RunResult& res, const fs::path& history, int dim, const std::string& force) {
  PatchResult out;
  out.newton = res.newton_iterations;
  const auto& x = res.mesh.x;
  double a[3] = {0, 0, 0};
  for (std::size_t n = 0; n < res.mesh.num_nodes(); ++n) {
    bool corner = true;
    for (int c = 0; c < dim; ++c) corner = corner && std::abs(x[3 * n + c] - 1.0) < 1e-12;
    if (corner)
      for (int c = 0; c < dim; ++c) a[c] = res.displacement[3 * n + c];
  }
  for (std::size_t n = 0; n < res.mesh.num_nodes(); ++n) {
    double e2 = 0.0;
    for (int c = 0; c < dim; ++c) e2 += std::pow(res.displacement[3 * n + c] - a[c] * x[3 * n + c], 2);
    out.affine_error = std::max(out.affine_error, std::sqrt(e2) / std::abs(a[dim - 1]));
  }
  // F = r_p on the upper body: +p A upwards.
  out.force_error = std::abs(stentor::testing::read_csv(history)[force].back() - 1e4) / 1e4;
  return out;
}

// symmetry: x = 0 rollers on both blocks' left edges instead of the two corner points, so
// the upper block's slave corner node has a prescribed component.
PatchResult patch(int nl, int nu, bool symmetry = false) {
  Config cfg = read_deck(kInputs + "contact_patch2d.xml");
  cfg.mesh.file = blocks_geo(nl, nu);
  if (symmetry)
    for (auto& l : cfg.loads)
      if (l.name == "base_corner" || l.name == "top_corner") l.group = l.name == "base_corner" ? "lower_left" : "upper_left";
  RunOptions opts;
  const fs::path dir = kDir / ("patch_" + std::to_string(nl) + "_" + std::to_string(nu) + (symmetry ? "_sym" : ""));
  opts.output_dir = dir.string();
  RunResult res;
  EXPECT_EQ(run_simulation(cfg, opts, &res), 0);
  return measure_patch(res, dir / (cfg.output.basename + "_history.csv"), 2, "contact_interface_force_y");
}

}  // namespace

// Prints the result; the homogeneous solution to round-off when `exact`, else only the total force.
static void expect_patch(const PatchResult& r, const std::string& label, bool exact) {
  std::printf("%s: affine error %.3e, force error %.3e, newton %d\n", label.c_str(), r.affine_error, r.force_error, r.newton);
  if (exact) EXPECT_LT(r.affine_error, 1e-9) << label;
  EXPECT_LT(r.force_error, 1e-9) << label;  // global equilibrium: exact in every case
}

TEST(DeformableContact, PatchTestMatchingMeshesIsExact) { expect_patch(patch(4, 4), "patch 4/4", true); }

TEST(DeformableContact, PatchTestSymmetryPlaneSlaveNodeStaysInContact) {
  // The slave corner on the symmetry line (u_x = 0 prescribed) keeps its normal condition.
  expect_patch(patch(4, 4, true), "patch 4/4 with symmetry rollers", true);
}

TEST(DeformableContact, PatchTestNonMatchingMeshes) {
  for (const auto& [nl, nu] : std::vector<std::pair<int, int>>{{4, 5}, {5, 4}, {3, 7}}) {
    const PatchResult r = patch(nl, nu);
    expect_patch(r, "patch " + std::to_string(nl) + "/" + std::to_string(nu), false);
    EXPECT_LT(r.affine_error, 0.06);  // node-to-segment (one pass): 1.8-5.3 % measured (docs/contact.md)
  }
}

TEST(DeformableContact, TwoBarsImpactConservesMomentumAndEnergy) {
  Config cfg = read_deck(kInputs + "two_bars.xml");
  cfg.output.fields = false;
  RunOptions opts;
  const fs::path dir = kDir / "two_bars";
  opts.output_dir = dir.string();
  RunResult res;
  ASSERT_EQ(run_simulation(cfg, opts, &res), 0);
  const auto e = stentor::testing::read_csv(dir / "two_bars_energy.csv");
  const auto h = stentor::testing::read_csv(dir / "two_bars_history.csv");
  const auto& E = e["total"];
  const auto& px = e["momentum_x"];
  const auto& active = h["contact_impact_active"];
  double dE = 0.0, dp = 0.0;
  for (std::size_t i = 0; i < E.size(); ++i) {
    dE = std::max(dE, std::abs(E[i] - E[0]));
    dp = std::max(dp, std::abs(px[i] - px[0]));
  }
  double t_first = -1, t_last = -1;
  for (std::size_t i = 0; i < active.size(); ++i)
    if (active[i] > 0) {
      if (t_first < 0) t_first = h["time"][i];
      t_last = h["time"][i];
    }
  std::printf("two bars: E0 %.6e max|E-E0|/E0 %.3e, p0 %.6e max|p-p0|/p0 %.3e, contact %.4f .. %.4f s\n", E[0], dE / E[0], px[0], dp / px[0],
              t_first, t_last);
  // First touch at t = g / v0 = 0.01 s; 1D duration 2L/c = 0.0374 s (c = 53.4 m/s, plane-strain bar modulus).
  EXPECT_NEAR(t_first, 0.0105, 1e-9);
  EXPECT_NEAR(t_last - t_first + 5e-4, 0.0374, 2e-3);
  EXPECT_LT(dp / px[0], 1e-8);
  EXPECT_LT(dE / E[0], 1e-6);
}

namespace {

std::string s3_geo() {
  return geo_variant("s3_ring_foundation.geo", {{"h = DefineNumber[0.05", "h = DefineNumber[0.1"}, {"hf = DefineNumber[0.1", "hf = DefineNumber[0.25"}},
                     "s3_coarse.geo");
}

struct S3 {
  stentor::testing::Series e, h;
};
S3 run_s3(double mu, const std::string& tag) {
  Config cfg = read_deck(kInputs + "s3_ring_foundation.xml");
  cfg.mesh.file = s3_geo();
  cfg.contact[0].friction = mu;
  cfg.stepping.end_time = 0.2;
  cfg.stepping.num_steps = 100;
  cfg.output.fields = false;
  RunOptions opts;
  const fs::path dir = kDir / tag;
  opts.output_dir = dir.string();
  EXPECT_EQ(run_simulation(cfg, opts, nullptr), 0);
  return {stentor::testing::read_csv(dir / "s3_ring_foundation_energy.csv"), stentor::testing::read_csv(dir / "s3_ring_foundation_history.csv")};
}

}  // namespace

TEST(DeformableContact, S3FrictionlessConservesEnergyOfBothBodies) {
  const S3 r = run_s3(0.0, "s3_mu0");
  const auto& E = r.e["total"];
  double dev = 0.0;
  for (double x : E) dev = std::max(dev, std::abs(x - E[0]));
  int contact_steps = 0;
  for (double a : r.h["contact_impact_active"]) contact_steps += a > 0;
  std::printf("S3 frictionless: E0 %.6e, max |E - E0| / E0 %.3e, %d steps in contact\n", E[0], dev / E[0], contact_steps);
  EXPECT_GT(contact_steps, 20);
  EXPECT_LT(dev / E[0], 1e-8);
}

TEST(DeformableContact, S3FrictionDissipatesExactlyTheEnergyLost) {
  const S3 r = run_s3(0.3, "s3_mu03");
  const auto& E = r.e["total"];
  const auto& D = r.e["friction_dissipation"];
  double closure = 0.0, min_step = 0.0;
  for (std::size_t i = 0; i < E.size(); ++i) {
    closure = std::max(closure, std::abs(E[i] + D[i] - E[0]));
    if (i > 0) min_step = std::min(min_step, D[i] - D[i - 1]);
  }
  std::printf("S3 mu = 0.3: E0 %.6e, D_fric(T) %.6e, max |E + D - E0| / E0 %.3e, min step dissipation %.3e\n", E[0], D.back(),
              closure / E[0], min_step);
  EXPECT_GT(D.back(), 1e-3 * E[0]);
  EXPECT_LT(closure / E[0], 1e-8);
  EXPECT_GE(min_step, -1e-9 * E[0]);
}

TEST(CurvedObstacle, BalloonInflateDeflateConvergesWithoutCutbacks) {
  Config cfg = read_deck(kInputs + "balloon_ring.xml");
  ContactPairConfig& c = cfg.contact[0];
  c.radius_ramp.kind = Ramp::Kind::Table;
  c.radius_ramp.times = {0.0, 0.5, 1.0};
  c.radius_ramp.factors = {0.0, 1.0, 0.0};
  cfg.stepping.num_steps = 8;
  RunOptions opts;
  const fs::path dir = kDir / "balloon";
  opts.output_dir = dir.string();
  RunResult res;
  ASSERT_EQ(run_simulation(cfg, opts, &res), 0);
  const auto h = stentor::testing::read_csv(dir / "balloon_ring_history.csv");
  double max_newton = 0.0, max_active = 0.0;
  for (double n : h["newton_iterations"]) max_newton = std::max(max_newton, n);
  for (double a : h["contact_balloon_active"]) max_active = std::max(max_active, a);
  std::printf("balloon: %d cut-backs, max %g Newton iterations per step, up to %g active nodes\n", res.cutbacks, max_newton, max_active);
  EXPECT_EQ(res.cutbacks, 0);
  EXPECT_LE(max_newton, 8.0);
  EXPECT_GT(max_active, 50.0);
}

namespace {

// tet: tetrahedral blocks (tri3 interface facets, tri6 with order 2) instead of hexahedra.
PatchResult patch3d(int nl, int nu, bool tet = false, int order = 1) {
  const std::string tag = "patch3d_" + std::to_string(nl) + "_" + std::to_string(nu) + (tet ? "_tet" + std::to_string(order) : "");
  Config cfg = read_deck(kInputs + "contact_patch3d.xml");
  cfg.mesh.file = geo_variant("two_blocks3d.geo",
                              {{"nl = DefineNumber[3", "nl = DefineNumber[" + std::to_string(nl)},
                               {"nu = DefineNumber[4", "nu = DefineNumber[" + std::to_string(nu)},
                               {"tet = DefineNumber[0", tet ? "tet = DefineNumber[1" : "tet = DefineNumber[0"}},
                              tag + ".geo");
  cfg.mesh.order = order;
  cfg.output.fields = false;
  RunOptions opts;
  const fs::path dir = kDir / tag;
  opts.output_dir = dir.string();
  RunResult res;
  EXPECT_EQ(run_simulation(cfg, opts, &res), 0);
  return measure_patch(res, dir / (cfg.output.basename + "_history.csv"), 3, "contact_interface_force_z");  // quarter model: p x 1 m^2
}

}  // namespace

TEST(DeformableContact, PatchTest3DHexMatchingIsExactNonMatchingMeasured) {
  expect_patch(patch3d(3, 3), "patch3d 3/3", true);
  for (const auto& [nl, nu] : std::vector<std::pair<int, int>>{{3, 4}, {4, 3}}) {
    const PatchResult r = patch3d(nl, nu);
    expect_patch(r, "patch3d " + std::to_string(nl) + "/" + std::to_string(nu), false);
    EXPECT_LT(r.affine_error, 0.2);  // node-to-segment, one pass, coarse: 8.5 % and 15.6 % measured
  }
}

// Tetrahedral blocks: the master facets are tri3 (P1) and tri6 (P2). Structured triangles
// on the faces, so nl = nu gives matching interface triangulations. Measured: matching
// 2.1e-14 (tri3) and 2.4e-14 (tri6); non-matching 3/4 and 4/3: 7.2 % and 9.7 % (tri3),
// 2.0 % and 7.1 % (tri6) nodal error; total force exact (1e-14); 3-5 Newton iterations.
// Before the release hysteresis (Contact::evaluate_nodes) the tri6 runs never settled: the
// corner nodes of tri6 slave facets carry no force under a uniform pressure and flipped
// between active and inactive on round-off.
TEST(DeformableContact, PatchTest3DTetTri3AndTri6) {
  for (int order : {1, 2}) {
    const std::string o = order == 1 ? "tri3" : "tri6";
    const PatchResult m = patch3d(3, 3, true, order);
    expect_patch(m, "patch3d tet " + o + " 3/3", true);
    EXPECT_LE(m.newton, 6);
    for (const auto& [nl, nu] : std::vector<std::pair<int, int>>{{3, 4}, {4, 3}}) {
      const PatchResult r = patch3d(nl, nu, true, order);
      expect_patch(r, "patch3d tet " + o + " " + std::to_string(nl) + "/" + std::to_string(nu), false);
      EXPECT_LT(r.affine_error, 0.15);
      EXPECT_LE(r.newton, 6);
    }
  }
}

namespace {

struct RigSystem : NewtonSystem {
  Rig& rig;
  la::RCP<la::CrsMatrix> K;
  explicit RigSystem(Rig& r) : rig(r) {}
  bool evaluate(const la::Vector& u, la::Vector& r, bool tangent) override {
    auto k = rig.eval(u, r, tangent);
    if (tangent) K = k;
    return true;
  }
  la::RCP<la::CrsMatrix> matrix() override { return K; }
  bool settled() const override { return !rig.contact->active_set_changed(); }
};

}  // namespace

TEST(DeformableContact, MasterTractionEqualsThePressure) {
  // Matching 4/4 interface: the reaction on every master node divided by its tributary
  // area is the applied pressure (0, -p).
  Config cfg = read_deck(kInputs + "contact_patch2d.xml");
  cfg.mesh.file = blocks_geo(4, 4);
  Rig rig(cfg);
  la::Vector u(rig.dist->owned_map());
  rig.contact->initialize(u, 1.0);
  rig.contact->begin_step(0.0, 1.0, u);
  RigSystem sys(rig);
  ASSERT_TRUE(newton_solve(sys, u, *rig.m.linear, rig.cfg.newton, nullptr).converged);
  const auto mf = rig.contact->master_fields();
  ASSERT_EQ(mf.nodes.size(), 5u);
  double fy = 0.0, worst = 0.0;
  for (std::size_t i = 0; i < mf.nodes.size(); ++i) {
    const double* v = &mf.values[Contact::kMasterValues * i];
    fy += v[1];
    worst = std::max({worst, std::abs(v[0] / v[3]) / 1e4, std::abs(v[1] / v[3] + 1e4) / 1e4});
  }
  std::printf("master traction: total force %.6e, max deviation from (0, -p) %.3e\n", fy, worst);
  EXPECT_NEAR(fy, -1e4, 1e-6);
  EXPECT_LT(worst, 1e-8);
}
