// The deck's `neo-Hookean plasticity` and `neo-Hookean damage` models end to end (deck ->
// run -> CSV / HDF5 / XDMF; docs/deck.md, "Materials"; docs/plasticity.md, "Adding a
// material"): uniaxial tension of the unit cube against the closed forms of the
// neo-Hookean law (yield onset, plateau, hardening; the Mullins effect of the damage law
// on the reaction force), and a dynamic impact with each law whose per-step energy
// balance, with the dissipation of the law, closes to solver tolerance.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <sstream>
#include <string>
#include <vector>

#include "CsvSeries.hpp"
#include "H5Results.hpp"
#include "deck/Config.hpp"
#include "run/Simulation.hpp"
#include "TestDir.hpp"

using namespace stentor;
namespace fs = std::filesystem;

namespace {

fs::path work_dir() { return stentor::testing::test_dir("neo_hookean_inelastic"); }
constexpr double kMu = 1.0e6, kLambda = 1.5e6, kY = 0.1e6;

std::string num(double v) {
  std::ostringstream os;
  os << std::setprecision(17) << v;
  return os.str();
}
std::string param(const std::string& name, const std::string& type, const std::string& value) {
  return "<Parameter name=\"" + name + "\" type=\"" + type + "\" value=\"" + value + "\"/>";
}
std::string dirichlet(const std::string& set, const std::string& components, const std::string& extra = "") {
  return "<ParameterList name=\"" + set + "\">" + param("type", "string", "Dirichlet") + param("boundary", "string", set) +
         param("components", "string", components) + extra + "</ParameterList>";
}

// The neo-Hookean constants and the model's own parameters.
std::string plastic_params(double Y, double H) {
  return param("model", "string", "neo-Hookean plasticity") + param("mu", "double", num(kMu)) +
         param("lambda", "double", num(kLambda)) + param("yield stress", "double", num(Y)) + param("hardening", "double", num(H));
}
std::string damage_params(double d_inf, double beta) {
  return param("model", "string", "neo-Hookean damage") + param("mu", "double", num(kMu)) +
         param("lambda", "double", num(kLambda)) + param("saturation damage", "double", num(d_inf)) +
         param("damage energy scale", "double", num(beta));
}

// Unit cube (inputs/block3d.geo, tet4, h = 0.5: 100 cells) with symmetry supports on
// left / front / bottom and the right face pulled in x by `pull` times the ramp `ramp`
// (Dirichlet parameters): a homogeneous uniaxial state the mesh reproduces exactly.
std::string tension_deck(const std::string& material, double pull, const std::string& ramp, double end_time, int steps,
                         const std::string& name) {
  const std::string geo = std::string(STENTOR_SOURCE_DIR) + "/inputs/block3d.geo";
  return "<ParameterList name=\"stentor\"><ParameterList name=\"Mesh\">" + param("file", "string", geo) +
         param("size", "double", "0.5") + "</ParameterList><ParameterList name=\"Materials\"><ParameterList name=\"m\">" +
         material + "</ParameterList></ParameterList><ParameterList name=\"Bodies\"><ParameterList name=\"block\">" +
         param("material", "string", "m") + "</ParameterList></ParameterList><ParameterList name=\"Boundary Conditions\">" +
         dirichlet("left", "x") + dirichlet("front", "y") + dirichlet("bottom", "z") +
         "<ParameterList name=\"pull\">" + param("type", "string", "Dirichlet") + param("boundary", "string", "right") +
         param("components", "string", "x") + param("values", "Array(double)", "{" + num(pull) + "}") + ramp +
         "</ParameterList></ParameterList><ParameterList name=\"Stepping\">" + param("end time", "double", num(end_time)) +
         param("steps", "int", std::to_string(steps)) + "</ParameterList><ParameterList name=\"Linear Solver\">" +
         param("method", "string", "direct") + "</ParameterList><ParameterList name=\"Output\">" +
         param("basename", "string", name) + "</ParameterList></ParameterList>";
}

// The cube at 5 m/s towards its face x = 0, held fixed from t = 0 (as PlasticityFE's
// impact): a compressive wave, the law's dissipation near the wall; gonzalez, 20 steps.
std::string impact_deck(const std::string& material, const std::string& name) {
  const std::string geo = std::string(STENTOR_SOURCE_DIR) + "/inputs/block3d.geo";
  return "<ParameterList name=\"stentor\"><ParameterList name=\"Problem\">" + param("analysis", "string", "dynamic") +
         "</ParameterList><ParameterList name=\"Mesh\">" + param("file", "string", geo) + param("size", "double", "0.5") +
         "</ParameterList><ParameterList name=\"Materials\"><ParameterList name=\"m\">" + material +
         param("density", "double", "1000") + param("viscosity", "double", "50") +
         "</ParameterList></ParameterList><ParameterList name=\"Bodies\"><ParameterList name=\"block\">" +
         param("material", "string", "m") + "</ParameterList></ParameterList><ParameterList name=\"Boundary Conditions\">" +
         dirichlet("left", "all") + "</ParameterList><ParameterList name=\"Initial Conditions\">" +
         param("velocity", "Array(double)", "{-5.0, 0.0, 0.0}") + "</ParameterList><ParameterList name=\"Stepping\">" +
         param("end time", "double", "0.02") + param("steps", "int", "20") + "</ParameterList><ParameterList name=\"Linear Solver\">" +
         param("method", "string", "direct") + "</ParameterList><ParameterList name=\"Output\">" + param("basename", "string", name) +
         "</ParameterList></ParameterList>";
}

// Writes and runs a deck in work_dir()/<name>; returns the output folder.
fs::path run(const std::string& deck, const std::string& name) {
  const fs::path dir = work_dir() / name;
  fs::create_directories(dir);
  std::ofstream(dir / "deck.xml") << deck;
  const Config cfg = read_deck((dir / "deck.xml").string());
  RunOptions o;
  o.output_dir = (dir / "out").string();
  o.overwrite = true;
  EXPECT_EQ(run_simulation(cfg, o, nullptr), 0) << name;
  return dir / "out";
}

// ---- Closed form of neo-Hookean uniaxial stress (lateral stress free). Principal
// Kirchhoff stresses tau_A = mu (c_A - 1) + lambda ln J; with the lateral stretch^2 m from
// tau_2 = mu (m - 1) + lambda ln(l m) = 0 (increasing in m), tau_1 = mu (l^2 - m).
struct Uniaxial {
  double m, J, tau, W0;  // lateral c, det F, axial Kirchhoff stress, virgin energy density
};
Uniaxial uniaxial(double l) {
  double m = 1.0 / l;
  for (int i = 0; i < 60; ++i) m -= (kMu * (m - 1.0) + kLambda * std::log(l * m)) / (kMu + kLambda / m);
  const double J = l * m, lnJ = std::log(J);
  return {m, J, kMu * (l * l - m), 0.5 * kMu * (l * l + 2.0 * m - 3.0) - kMu * lnJ + 0.5 * kLambda * lnJ * lnJ};
}

// Elastic stretch le of total stretch l under flow (tau_1(le) = Y + H ln(l / le)), or l
// while tau_1(l) <= Y. Then alpha = ln(l / le) and P_11 = tau_1(le) / l.
double elastic_stretch(double l, double Y, double H) {
  if (uniaxial(l).tau <= Y) return l;
  double lo = 1.0, hi = l;
  for (int i = 0; i < 200; ++i) {
    const double mid = 0.5 * (lo + hi);
    (uniaxial(mid).tau - Y - H * std::log(l / mid) > 0.0 ? hi : lo) = mid;
  }
  return 0.5 * (lo + hi);
}

// The stretch of the yield onset, tau_1(l_y) = mu (l_y^2 - m) = Y.
double yield_stretch(double Y) {
  double lo = 1.0, hi = 2.0;
  for (int i = 0; i < 200; ++i) {
    const double mid = 0.5 * (lo + hi);
    (uniaxial(mid).tau > Y ? hi : lo) = mid;
  }
  return 0.5 * (lo + hi);
}

// Damage d = d_inf (1 - exp(-alpha / beta)) (material/Damage.hpp).
double damage_of(double alpha, double d_inf, double beta) { return -d_inf * std::expm1(-alpha / beta); }

double max_abs_diff(const std::vector<double>& v, double x) {
  double e = 0.0;
  for (double a : v) e = std::max(e, std::abs(a - x));
  return e;
}

std::string read_text(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

}  // namespace

// Uniaxial tension to 20% in 10 steps, perfect plasticity and hardening: the reaction on
// the pulled face (area 1) is P_11 of the closed form at every step; the written fields of
// the last step are the closed-form alpha and |M|_H = Y + H alpha in every cell, and the
// accumulated plastic dissipation field is the sum of the per-step column.
TEST(NeoHookeanPlasticityFE, UniaxialTensionMatchesClosedForm) {
  for (const double H : {0.0, 0.5e6}) {
    const std::string name = H == 0.0 ? "uniaxial_perfect" : "uniaxial_hardening";
    const fs::path out = run(tension_deck(plastic_params(kY, H), 0.2, "", 1.0, 10, name), name);
    const auto hist = stentor::testing::read_csv(out / (name + "_history.csv"));
    ASSERT_EQ(hist.rows(), 10u);
    double worst = 0.0, dp_sum = 0.0;
    for (std::size_t i = 0; i < hist.rows(); ++i) {
      const double l = 1.0 + 0.2 * hist["time"][i], le = elastic_stretch(l, kY, H);
      worst = std::max(worst, std::abs(hist["reaction_pull_x"][i] - uniaxial(le).tau / l) / kY);
      EXPECT_GE(hist["plastic_dissipation"][i], 0.0);
      dp_sum += hist["plastic_dissipation"][i];
    }
    const double alpha = std::log(1.2 / elastic_stretch(1.2, kY, H));
    const stentor::testing::H5Results h5(out / (name + ".h5"));
    const auto a = h5.read("/step_10/equivalent_plastic_strain"), q = h5.read("/step_10/mandel_hill_norm");
    const auto flag = h5.read("/step_10/yielding"), dp = h5.read("/step_10/plastic_dissipation");
    ASSERT_EQ(a.size(), 100u);
    ASSERT_EQ(dp.size(), 100u);
    std::cout << "[ nh-plastic ] uniaxial H = " << H << ": max |reaction - P11 closed form| / Y = " << worst << ", alpha = " << alpha
              << ", max |alpha - closed form| = " << max_abs_diff(a, alpha)
              << ", max | |M|_H - (Y + H alpha) | / Y = " << max_abs_diff(q, kY + H * alpha) / kY
              << ", sum D_p / (Y alpha) = " << dp_sum / (kY * alpha) << "\n";
    EXPECT_LT(worst, 1e-8);
    EXPECT_GT(alpha, 0.1);
    EXPECT_LT(max_abs_diff(a, alpha), 1e-10);
    EXPECT_LT(max_abs_diff(q, kY + H * alpha), 1e-10 * kY);
    EXPECT_EQ(max_abs_diff(flag, 1.0), 0.0);
    EXPECT_LT(max_abs_diff(dp, dp_sum), 1e-10 * dp_sum);
    EXPECT_GE(dp_sum, kY * alpha);  // D_p >= Y dg + H dg^2 / 2 per step (docs/plasticity.md)
  }
}

// The yield onset at the closed-form stretch l_y (mu (l_y^2 - m) = Y): a step to
// (1 - 1e-6)(l_y - 1) stays elastic (no point yielding, no dissipation, |M|_H just below
// Y), the next to (1 + 1e-6)(l_y - 1) flows everywhere (perfect plasticity: |M|_H = Y).
TEST(NeoHookeanPlasticityFE, YieldOnsetAtTheClosedFormStretch) {
  const double ly = yield_stretch(kY);
  const std::string ramp = param("ramp", "string", "table") + param("ramp times", "Array(double)", "{0, 1, 2}") +
                           param("ramp factors", "Array(double)", "{0, 0.999999, 1.000001}");
  const fs::path out = run(tension_deck(plastic_params(kY, 0.0), ly - 1.0, ramp, 2.0, 2, "onset"), "onset");
  const auto hist = stentor::testing::read_csv(out / "onset_history.csv");
  ASSERT_EQ(hist.rows(), 2u);
  const stentor::testing::H5Results h5(out / "onset.h5");
  const auto q1 = h5.read("/step_1/mandel_hill_norm"), q2 = h5.read("/step_2/mandel_hill_norm");
  const auto y1 = h5.read("/step_1/yielding"), y2 = h5.read("/step_2/yielding");
  const auto a2 = h5.read("/step_2/equivalent_plastic_strain");
  ASSERT_EQ(q1.size(), 100u);
  std::cout << "[ nh-plastic ] yield onset at stretch " << std::setprecision(12) << ly << ": |M|_H / Y = " << q1[0] / kY
            << " before, " << q2[0] / kY << " after; alpha after = " << a2[0] << ", D_p = " << hist["plastic_dissipation"][0]
            << " / " << hist["plastic_dissipation"][1] << " J\n";
  EXPECT_EQ(hist["plastic_dissipation"][0], 0.0);
  EXPECT_GT(hist["plastic_dissipation"][1], 0.0);
  EXPECT_EQ(max_abs_diff(y1, 0.0), 0.0);
  EXPECT_EQ(max_abs_diff(y2, 1.0), 0.0);
  EXPECT_LT(max_abs_diff(q1, kY * (1.0 - 1.5e-6)), 1.5e-6 * kY);  // in (1 - 3e-6, 1) Y
  EXPECT_LT(max_abs_diff(q2, kY), 1e-10 * kY);
  EXPECT_GT(a2[0], 0.0);
  EXPECT_NEAR(hist["reaction_pull_x"][1], kY / (1.0 + 1.000001 * (ly - 1.0)), 1e-8 * kY);
}

// Dynamic impact (gonzalez, energy-dissipative): E_{n+1} - E_n = W_ext + W_sup - D_visc
// - D_law per step to solver tolerance, with D_law (the `plastic_dissipation` column) >= 0
// per step and a sizeable share of the initial energy.
void check_impact_balance(const std::string& material, const std::string& name) {
  const fs::path out = run(impact_deck(material, name), name);
  const auto e = stentor::testing::read_csv(out / (name + "_energy.csv"));
  ASSERT_EQ(e.rows(), 21u);
  const double E0 = e["total"][0];
  double worst = 0.0, dmin = 1e300;
  for (std::size_t i = 1; i < e.rows(); ++i) {
    worst = std::max(worst, std::abs(e["balance_residual"][i]) / E0);
    dmin = std::min(dmin, e["plastic_dissipation"][i] - e["plastic_dissipation"][i - 1]);
  }
  const double dl = e["plastic_dissipation"][e.rows() - 1];
  std::cout << "[ " << name << " ] E0 = " << E0 << " J, law dissipation " << dl / E0 << " E0, viscous "
            << (e["dissipation"][e.rows() - 1] - dl) / E0 << " E0, max |balance| per step / E0 = " << worst
            << ", min D per step = " << dmin << " J\n";
  EXPECT_GT(dl, 0.01 * E0);
  EXPECT_GE(dmin, 0.0);
  EXPECT_LT(worst, 1e-9);
}

TEST(NeoHookeanPlasticityFE, DynamicImpactEnergyBalance) { check_impact_balance(plastic_params(kY, 0.2e6), "nh_plastic_impact"); }

TEST(NeoHookeanDamageFE, DynamicImpactEnergyBalance) { check_impact_balance(damage_params(0.5, 5.0e3), "damage_impact"); }

// The Mullins effect: uniaxial tension 1 -> 1.3 -> 1 -> 1.3 -> 1.5 (10 steps each). The
// reaction is (1 - d) P0(l) at every step, P0 the virgin neo-Hookean nominal stress and d =
// g(alpha), alpha the largest virgin energy W0 of the steps so far: on unloading and
// reloading below 1.3 it is the virgin curve scaled by the frozen 1 - d(1.3) (elastic,
// softened, no dissipation, the same force on the way down and up, no permanent set),
// beyond 1.3 damage grows again. The damage fields of the HDF5 (and their XDMF entries) hold d, alpha and
// the accumulated dissipation.
TEST(NeoHookeanDamageFE, MullinsEffectOnTheReactionForce) {
  const double d_inf = 0.6, beta = 0.05e6;
  const std::string ramp = param("ramp", "string", "table") + param("ramp times", "Array(double)", "{0, 1, 2, 3, 4}") +
                           param("ramp factors", "Array(double)", "{0, 0.6, 0, 0.6, 1}");
  const fs::path out = run(tension_deck(damage_params(d_inf, beta), 0.5, ramp, 4.0, 40, "mullins"), "mullins");
  const auto hist = stentor::testing::read_csv(out / "mullins_history.csv");
  ASSERT_EQ(hist.rows(), 40u);
  const auto stretch = [](double t) {  // 1 + 0.5 x the ramp factor at t
    return 1.0 + 0.5 * (t <= 1 ? 0.6 * t : t <= 2 ? 0.6 * (2 - t) : t <= 3 ? 0.6 * (t - 2) : 0.6 + 0.4 * (t - 3));
  };
  double alpha = 0.0, worst = 0.0, d_sum = 0.0, scale = 0.0;
  std::vector<double> force(40), lam(40);
  for (std::size_t i = 0; i < 40; ++i) {
    lam[i] = stretch(hist["time"][i]);
    const Uniaxial u = uniaxial(lam[i]);
    alpha = std::max(alpha, u.W0);
    force[i] = hist["reaction_pull_x"][i];
    const double P = (1.0 - damage_of(alpha, d_inf, beta)) * u.tau / lam[i];
    scale = std::max(scale, std::abs(P));
    worst = std::max(worst, std::abs(force[i] - P));
    d_sum += hist["plastic_dissipation"][i];
    if (i >= 10 && i < 28) EXPECT_EQ(hist["plastic_dissipation"][i], 0.0) << "step " << i + 1;  // below the maximum
  }
  // Steps 5, 15 and 25: l = 1.15 on first loading, unloading and reloading.
  const double d1 = damage_of(uniaxial(1.3).W0, d_inf, beta), d15 = damage_of(uniaxial(1.15).W0, d_inf, beta);
  std::cout << std::setprecision(6) << "[ damage ] Mullins: max |reaction - (1 - d) P0| / max P = " << worst / scale << "; d(1.3) = " << d1
            << ", d(1.15) = " << d15 << ", d(1.5) = " << damage_of(alpha, d_inf, beta) << "; force at l = 1.15 first loading "
            << force[4] << " N, unloading " << force[14] << " N, reloading " << force[24] << " N\n";
  EXPECT_LT(worst, 1e-8 * scale);
  EXPECT_NEAR(lam[4], 1.15, 1e-12);
  EXPECT_NEAR(lam[14], 1.15, 1e-12);
  EXPECT_NEAR(lam[24], 1.15, 1e-12);
  EXPECT_LT(std::abs(force[19]), 1e-8 * scale);  // back at l = 1: no force, no permanent set
  EXPECT_NEAR(force[14] / force[4], (1.0 - d1) / (1.0 - d15), 1e-8);  // softer than the first loading
  EXPECT_LT(force[14], 0.8 * force[4]);
  EXPECT_NEAR(force[24], force[14], 1e-10 * force[4]);  // reloading retraces the unloading: elastic
  EXPECT_NEAR(force[24] / (uniaxial(1.15).tau / 1.15), 1.0 - d1, 1e-8);  // the virgin stiffness times 1 - d(1.3)
  EXPECT_GT(hist["plastic_dissipation"][30], 0.0);  // past the maximum damage grows again
  const stentor::testing::H5Results h5(out / "mullins.h5");
  const auto d20 = h5.read("/step_20/damage"), d40 = h5.read("/step_40/damage");
  const auto a40 = h5.read("/step_40/max_virgin_energy"), dd40 = h5.read("/step_40/damage_dissipation");
  ASSERT_EQ(d40.size(), 100u);
  EXPECT_LT(max_abs_diff(d20, d1), 1e-10);
  EXPECT_LT(max_abs_diff(d40, damage_of(alpha, d_inf, beta)), 1e-10);
  EXPECT_LT(max_abs_diff(a40, alpha), 1e-10 * alpha);
  EXPECT_LT(max_abs_diff(dd40, d_sum), 1e-10 * d_sum);
  const std::string xdmf = read_text(out / "mullins.xdmf");
  for (const char* f : {"\"damage\"", "\"max_virgin_energy\"", "\"damage_dissipation\""}) EXPECT_NE(xdmf.find(f), std::string::npos) << f;
}
