// Dynamics verification (docs/verification.md, "Dynamics"): energy and momentum of the
// time schemes (gonzalez | midpoint | newmark | hht), read from the <basename>_energy.csv
// that every dynamic run writes (per step: kinetic, strain, total, cumulative external
// work / support work / dissipation, the balance residual E_{n+1} - E_n - (W_ext + W_sup - D)
// of the step, linear and angular momentum).
//  a. Free-flying L-block (inputs/lblock.xml): self-equilibrated pulse, then free flight;
//     midpoint drifts at dt = 0.5 and blows up at dt = 1.
//  b. Stiff spinning strip at growing dt: midpoint blows up, Gonzalez does not.
//  c. Viscous spinning square: balance to solver tolerance, E decreases by exactly D.
//  d. Second order in dt of all four schemes (clamped block under a ramped body force).
//  e. Spinning, translating free square: linear and angular momentum (gonzalez, midpoint).
//  f. A support moved from rest: the support work equals the energy (balance closes).
//  g. Newmark/HHT free fall under a constant body force with the default linear solver:
//     the initial acceleration b / rho, u(T) = a T^2 / 2 exactly.
// The numbers printed here are the ones quoted in docs/verification.md.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
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

fs::path work_dir() { return stentor::testing::test_dir("dynamics"); }

// ---- Energy CSV.

double norm(const std::array<double, 3>& a) { return std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]); }
double dist(const std::array<double, 3>& a, const std::array<double, 3>& b) {
  return norm({a[0] - b[0], a[1] - b[1], a[2] - b[2]});
}

struct RunOut {
  int status = -1;
  RunResult res;
  Series energy;  // from <dir> or, after a failure, <dir>.partial
};

RunOut run(const Config& cfg, const std::string& tag) {
  RunOptions opts;
  opts.output_dir = (work_dir() / tag).string();
  RunOut r;
  r.status = run_simulation(cfg, opts, &r.res);
  const fs::path dir = r.status == 0 ? work_dir() / tag : fs::path((work_dir() / tag).string() + ".partial");
  r.energy = read_csv(dir / (cfg.output.basename + "_energy.csv"));
  return r;
}

// Largest |total(i) - total(i0)| / scale over rows i >= i0.
double energy_drift(const Series& s, std::size_t i0, double scale) {
  double d = 0.0;
  for (std::size_t i = i0; i < s.rows(); ++i) d = std::max(d, std::abs(s["total"][i] - s["total"][i0]));
  return d / scale;
}
double max_abs(const std::vector<double>& v) {
  double m = 0.0;
  for (double x : v) m = std::max(m, std::abs(x));
  return m;
}
// Largest |m(i) - m(i0)| over rows i >= i0 of a vector column ("momentum", "angular_momentum").
double vector_drift(const Series& s, const std::string& stem, std::size_t i0) {
  double d = 0.0;
  for (std::size_t i = i0; i < s.rows(); ++i) d = std::max(d, dist(s.vec(stem, i), s.vec(stem, i0)));
  return d;
}

// ---- 2D decks written on the fly (plane strain, Ciarlet-Geymonat with C2 = 0 from E, nu).
struct Spec {
  std::string mesh = std::string(STENTOR_SOURCE_DIR) + "/inputs/block2d.geo";
  double size = 0.25;  // Mesh->size (0: the .geo's own)
  std::string body = "block";
  double E = 3e3, nu = 0.3, rho = 1.0, eta = 0.0;
  double omega = 0.0;
  std::array<double, 2> center{0.5, 0.5}, velocity{0.0, 0.0};
  std::string scheme = "gonzalez";
  double hht_alpha = -0.1;
  double T = 1.0;
  int steps = 10, cutbacks = 0;
  std::string bcs;  // entries of "Boundary Conditions" (raw XML)
  std::string model;        // empty: Ciarlet-Geymonat from C1 = mu/2, D = lambda/4; else this model from E, nu
  std::string material_xml;  // extra parameters of the material (raw XML)
};

Config make_deck(const Spec& s, const std::string& tag) {
  const double mu = s.E / (2 * (1 + s.nu)), lambda = s.E * s.nu / ((1 + s.nu) * (1 - 2 * s.nu));
  std::ostringstream x;
  x.precision(17);
  x << "<ParameterList name=\"stentor\">\n"
    << " <ParameterList name=\"Problem\"><Parameter name=\"analysis\" type=\"string\" value=\"dynamic\"/></ParameterList>\n"
    << " <ParameterList name=\"Mesh\"><Parameter name=\"file\" type=\"string\" value=\"" << s.mesh << "\"/>"
    << "<Parameter name=\"size\" type=\"double\" value=\"" << s.size << "\"/></ParameterList>\n"
    << " <ParameterList name=\"Materials\"><ParameterList name=\"m\">"
    << "<Parameter name=\"" << (s.model.empty() ? "C1" : "E") << "\" type=\"double\" value=\"" << (s.model.empty() ? mu / 2 : s.E)
    << "\"/>"
    << "<Parameter name=\"" << (s.model.empty() ? "D" : "nu") << "\" type=\"double\" value=\"" << (s.model.empty() ? lambda / 4 : s.nu)
    << "\"/>"
    << (s.model.empty() ? std::string() : "<Parameter name=\"model\" type=\"string\" value=\"" + s.model + "\"/>")
    << s.material_xml
    << "<Parameter name=\"density\" type=\"double\" value=\"" << s.rho << "\"/>"
    << "<Parameter name=\"viscosity\" type=\"double\" value=\"" << s.eta << "\"/></ParameterList></ParameterList>\n"
    << " <ParameterList name=\"Bodies\"><ParameterList name=\"" << s.body
    << "\"><Parameter name=\"material\" type=\"string\" value=\"m\"/></ParameterList></ParameterList>\n";
  if (!s.bcs.empty()) x << " <ParameterList name=\"Boundary Conditions\">" << s.bcs << "</ParameterList>\n";
  x << " <ParameterList name=\"Initial Conditions\">"
    << "<Parameter name=\"angular velocity\" type=\"Array(double)\" value=\"{" << s.omega << "}\"/>"
    << "<Parameter name=\"center\" type=\"Array(double)\" value=\"{" << s.center[0] << ", " << s.center[1] << "}\"/>"
    << "<Parameter name=\"velocity\" type=\"Array(double)\" value=\"{" << s.velocity[0] << ", " << s.velocity[1] << "}\"/>"
    << "</ParameterList>\n"
    << " <ParameterList name=\"Time Integration\"><Parameter name=\"scheme\" type=\"string\" value=\"" << s.scheme << "\"/>"
    << "<Parameter name=\"hht alpha\" type=\"double\" value=\"" << s.hht_alpha << "\"/></ParameterList>\n"
    << " <ParameterList name=\"Stepping\"><Parameter name=\"end time\" type=\"double\" value=\"" << s.T << "\"/>"
    << "<Parameter name=\"steps\" type=\"int\" value=\"" << s.steps << "\"/>"
    << "<Parameter name=\"max cutbacks\" type=\"int\" value=\"" << s.cutbacks << "\"/></ParameterList>\n"
    << " <ParameterList name=\"Newton\"><Parameter name=\"relative residual tolerance\" type=\"double\" value=\"1e-12\"/>"
    << "<Parameter name=\"absolute residual tolerance\" type=\"double\" value=\"1e-12\"/>"
    << "<Parameter name=\"max iterations\" type=\"int\" value=\"30\"/></ParameterList>\n"
    << " <ParameterList name=\"Linear Solver\"><Parameter name=\"method\" type=\"string\" value=\"direct\"/></ParameterList>\n"
    << " <ParameterList name=\"Output\"><Parameter name=\"fields\" type=\"bool\" value=\"false\"/>"
    << "<Parameter name=\"basename\" type=\"string\" value=\"run\"/></ParameterList>\n"
    << "</ParameterList>\n";
  fs::create_directories(work_dir());
  const fs::path deck = work_dir() / (tag + ".xml");
  std::ofstream(deck) << x.str();
  return read_deck(deck.string());
}

// ---------------------------------------------------------------------------------------
// a. Free-flying L-block (inputs/lblock.xml; geometry, loads and resultants documented
// there): dt = 0.5 (10 steps of pulse, then 20 of free flight), coarse P1 (173 nodes).
RunOut lblock(const std::string& scheme, double dt, double T) {
  Config cfg = read_deck(std::string(STENTOR_SOURCE_DIR) + "/inputs/lblock.xml");
  cfg.output.fields = false;
  cfg.time.scheme = scheme;
  cfg.stepping.end_time = T;
  cfg.stepping.num_steps = static_cast<int>(std::lround(T / dt));
  cfg.stepping.max_cutbacks = 0;  // dt stays the one named
  cfg.newton.max_iterations = 30;
  return run(cfg, "lblock_" + scheme + "_" + std::to_string(cfg.stepping.num_steps));
}

TEST(Dynamics, LBlockGonzalezConservesEnergyAndMomentaMidpointDrifts) {
  const RunOut g = lblock("gonzalez", 0.5, 15.0);
  ASSERT_EQ(g.status, 0);
  const Series& s = g.energy;
  ASSERT_EQ(s.rows(), 31u);
  const std::size_t i5 = 10;  // t = 5: end of the pulse
  ASSERT_NEAR(s["time"][i5], 5.0, 1e-12);
  const double E5 = s["total"][i5];
  ASSERT_GT(E5, 0.0);
  // During the pulse the energy grows by exactly the work of the tractions.
  EXPECT_NEAR(E5, s["external_work"][i5], 1e-9 * E5);
  const double bal = max_abs(s["balance_residual"]) / E5;
  const double drift = energy_drift(s, i5, E5);
  // Linear momentum: zero initially, zero net force. Scale: sqrt(2 m E), m = rho V = 153.
  const double pscale = std::sqrt(2.0 * 153.0 * E5);
  double pmax = 0.0;
  for (std::size_t i = 0; i < s.rows(); ++i) pmax = std::max(pmax, norm(s.vec("momentum", i)));
  const std::array<double, 3> H5 = s.vec("angular_momentum", i5);
  const double hdrift = vector_drift(s, "angular_momentum", i5) / norm(H5);
  std::printf("[lblock] gonzalez dt 0.5: E(5) %.10e = W_ext %.10e; max |balance|/E %.2e; max |E - E(5)|/E after the pulse %.2e; "
              "max |p| / sqrt(2 m E) %.2e; H(5) = (%.4f, %.4f, %.4f), max |H - H(5)|/|H(5)| after %.2e\n",
              E5, s["external_work"][i5], bal, drift, pmax / pscale, H5[0], H5[1], H5[2], hdrift);
  EXPECT_LT(bal, 1e-8);
  EXPECT_LT(drift, 1e-9);
  EXPECT_LT(pmax / pscale, 1e-10);
  EXPECT_LT(hdrift, 1e-8);
  // The pulse imparts about 2.5 M = 2.5 (-204, -204, 204) (dead loads: the moment of the
  // reference resultants changes as the block turns, hence "about").
  EXPECT_NEAR(norm(H5), 2.5 * 204.0 * std::sqrt(3.0), 0.1 * 2.5 * 204.0 * std::sqrt(3.0));

  // Plain midpoint rule, same dt.
  const RunOut m = lblock("midpoint", 0.5, 15.0);
  if (m.status == 0) {
    const Series& q = m.energy;
    ASSERT_EQ(q.rows(), 31u);
    const double E5m = q["total"][i5];
    const double mdrift = energy_drift(q, i5, E5m);
    const double mbal = max_abs(q["balance_residual"]) / E5m;
    const double mh = vector_drift(q, "angular_momentum", i5) / norm(q.vec("angular_momentum", i5));
    std::printf("[lblock] midpoint dt 0.5: completed; max |balance|/E %.2e; max |E - E(5)|/E after the pulse %.2e "
                "(%.1e x Gonzalez's); angular momentum still conserved: %.2e\n",
                mbal, mdrift, mdrift / std::max(drift, 1e-16), mh);
    EXPECT_GT(mdrift, 100.0 * drift);
    EXPECT_GT(mdrift, 1e-4);
    EXPECT_LT(mh, 1e-8);
  } else {
    // Newton failure at this dt is acceptable evidence, but it must be reported as such.
    std::printf("[lblock] midpoint dt 0.5: FAILED (status %d) after %d steps\n", m.status, m.res.steps);
    EXPECT_EQ(m.status, 3);
    EXPECT_FALSE(m.res.converged);
  }
}

// Same block at dt = 1 (5 steps of pulse) to t = 20: Gonzalez still conserves; the
// midpoint rule's energy grows until Newton fails (no cut-back allowed, so dt stays 1).
TEST(Dynamics, LBlockLargeStepMidpointBlowsUpGonzalezDoesNot) {
  const std::size_t i5 = 5;
  const RunOut g = lblock("gonzalez", 1.0, 20.0);
  ASSERT_EQ(g.status, 0);
  ASSERT_EQ(g.energy.rows(), 21u);
  const double E5 = g.energy["total"][i5];
  const double drift = energy_drift(g.energy, i5, E5);
  const double hdrift = vector_drift(g.energy, "angular_momentum", i5) / norm(g.energy.vec("angular_momentum", i5));
  EXPECT_LT(drift, 1e-9);
  EXPECT_LT(hdrift, 1e-8);
  const RunOut m = lblock("midpoint", 1.0, 20.0);
  const Series& q = m.energy;
  ASSERT_GT(q.rows(), i5 + 1) << "midpoint must at least get through the pulse";
  const double E5m = q["total"][i5];
  double grow = 0.0;
  for (std::size_t i = i5; i < q.rows(); ++i) grow = std::max(grow, q["total"][i] / E5m);
  std::printf("[lblock] dt 1: gonzalez max |E - E(5)|/E %.2e, |H - H(5)|/|H| %.2e; midpoint max E/E(5) %.3f, %s at t = %g\n", drift,
              hdrift, grow, m.status == 0 ? "completed" : "Newton FAILED", q["time"][q.rows() - 1] + (m.status == 0 ? 0.0 : 1.0));
  EXPECT_GT(grow, 1.5) << "midpoint energy should grow by more than 50% at dt = 1";
  if (m.status != 0) {
    EXPECT_EQ(m.status, 3);
    EXPECT_FALSE(m.res.converged);
  }
}

// ---------------------------------------------------------------------------------------
// b. Stiff spinning strip: [0,1] x [0,0.1], one element thick (10 x 1 squares split in
// triangles), E = 1e4, nu = 0.3, rho = 1, spun at omega = 10 about its centre; T = 1 (1.6
// turns). The axial frequency (~ pi sqrt(E/rho)/L ~ 300 rad/s) is 30x the spin.
const char* kStripGeo = R"(Lx = 1; Ly = 0.1; h = 0.1;
Point(1) = {0, 0, 0, h}; Point(2) = {Lx, 0, 0, h}; Point(3) = {Lx, Ly, 0, h}; Point(4) = {0, Ly, 0, h};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4}; Plane Surface(1) = {1};
Transfinite Curve{1, 3} = 11; Transfinite Curve{2, 4} = 2; Transfinite Surface{1};
Physical Surface("strip") = {1};
)";

TEST(Dynamics, StiffSpinningStripMidpointBlowsUpGonzalezDoesNot) {
  fs::create_directories(work_dir());
  const fs::path geo = work_dir() / "strip.geo";
  std::ofstream(geo) << kStripGeo;
  const std::vector<double> dts = {0.0025, 0.005, 0.01, 0.02};
  std::vector<double> mid;
  for (double dt : dts) {
    double err[2] = {0, 0};
    bool ok[2] = {false, false};
    for (int k = 0; k < 2; ++k) {
      Spec sp;
      sp.mesh = geo.string();
      sp.size = 0.0;
      sp.body = "strip";
      sp.E = 1e4;
      sp.omega = 10.0;
      sp.center = {0.5, 0.05};
      sp.scheme = k == 0 ? "gonzalez" : "midpoint";
      sp.T = 1.0;
      sp.steps = static_cast<int>(std::lround(1.0 / dt));
      const std::string tag = "strip_" + sp.scheme + "_" + std::to_string(sp.steps);
      const RunOut r = run(make_deck(sp, tag), tag);
      ok[k] = r.status == 0;
      const double E0 = r.energy["total"][0];
      err[k] = energy_drift(r.energy, 0, E0);
      if (k == 0) {
        EXPECT_EQ(r.status, 0) << "gonzalez, dt " << dt;
        EXPECT_LT(err[0], 1e-10) << "gonzalez, dt " << dt;
        EXPECT_LT(max_abs(r.energy["balance_residual"]) / E0, 1e-10) << "gonzalez, dt " << dt;
      }
    }
    std::printf("[strip] dt %.4f: max |E - E0|/E0 gonzalez %.2e, midpoint %.2e%s\n", dt, err[0], err[1],
                ok[1] ? "" : " (midpoint Newton failed: energy up to the failure)");
    mid.push_back(ok[1] ? err[1] : HUGE_VAL);  // a failed midpoint run counts as a blow-up
  }
  for (std::size_t i = 0; i + 1 < mid.size(); ++i) EXPECT_GT(mid[i + 1], 2.0 * mid[i]) << "midpoint error grows with dt";
  EXPECT_GT(mid.front(), 1e-5);
  EXPECT_GT(mid.back(), 1.0) << "midpoint energy more than doubles at the largest dt";
}

// ---------------------------------------------------------------------------------------
// c. Viscous spinning square: unit square (P1, h = 0.25), E = 3e3, nu = 0.3, rho = 1,
// Curnier eta = 1, spun at omega = 20 from rest shape: it stretches, vibrates and the
// vibration is damped (rigid rotation dissipates nothing). Gonzalez, dt = 0.005, 50 steps.
TEST(Dynamics, ViscousBodyDissipatesExactlyAndEnergyDecreases) {
  Spec sp;
  sp.eta = 1.0;
  sp.omega = 20.0;
  sp.T = 0.25;
  sp.steps = 50;
  const RunOut r = run(make_deck(sp, "viscous"), "viscous");
  ASSERT_EQ(r.status, 0);
  const Series& s = r.energy;
  const double E0 = s["total"][0];
  const double bal = max_abs(s["balance_residual"]) / E0;
  double max_dE = -HUGE_VAL, min_dD = HUGE_VAL;
  for (std::size_t i = 0; i + 1 < s.rows(); ++i) {
    max_dE = std::max(max_dE, s["total"][i + 1] - s["total"][i]);
    min_dD = std::min(min_dD, s["dissipation"][i + 1] - s["dissipation"][i]);
  }
  const std::size_t n = s.rows() - 1;
  const double D = s["dissipation"][n], closure = (s["total"][n] + D - E0) / E0;
  std::printf("[viscous] E0 %.6e, E(T) %.6e, cumulative D %.6e (%.2f%% of E0); max |balance|/E0 %.2e; "
              "E(T) + D - E0 = %.2e E0; per step: max (E_{n+1} - E_n) %.2e, min D_step %.2e\n",
              E0, s["total"][n], D, 100 * D / E0, bal, closure, max_dE, min_dD);
  EXPECT_LT(bal, 1e-9);
  EXPECT_GT(D, 1e-3 * E0);
  EXPECT_GT(min_dD, 0.0);
  EXPECT_LT(max_dE, 0.0) << "total energy must decrease at every step";
  EXPECT_LT(std::abs(closure), 1e-9);
  EXPECT_EQ(s["external_work"][n], 0.0);
}

// ---------------------------------------------------------------------------------------
// c2. The other hyperelastic laws with the Gonzalez scheme (docs/verification.md,
// "Material point: neo-Hookean, Mooney-Rivlin" and "Holzapfel-Gasser-Ogden"): the free square of c (E = 3e3, nu = 0.3
// from E/nu, rho = 1, no viscosity) spun at omega = 20 stretches and vibrates; 40 steps of
// dt = 0.005. The total energy stays at E0 to solver tolerance, as with Ciarlet-Geymonat.
TEST(Dynamics, GonzalezConservesEnergyWithEveryLaw) {
  const std::vector<std::pair<std::string, std::string>> laws = {
      {"neo-Hookean", ""},
      {"Mooney-Rivlin", "<Parameter name=\"C2\" type=\"double\" value=\"200\"/>"},
      {"Holzapfel-Gasser-Ogden",  // fibres at +-30 deg around the spin centre (axis normal to the plane)
       "<Parameter name=\"k1\" type=\"double\" value=\"3000\"/><Parameter name=\"k2\" type=\"double\" value=\"2\"/>"
       "<Parameter name=\"fibre angle\" type=\"double\" value=\"30\"/>"
       "<Parameter name=\"axis point\" type=\"Array(double)\" value=\"{0.5, 0.5}\"/>"}};
  for (const auto& [model, extra] : laws) {
    Spec sp;
    sp.model = model;
    sp.material_xml = extra;
    sp.omega = 20.0;
    sp.T = 0.2;
    sp.steps = 40;
    const std::string tag = "law_" + model;
    const RunOut r = run(make_deck(sp, tag), tag);
    ASSERT_EQ(r.status, 0) << model;
    const Series& s = r.energy;
    const double E0 = s["total"][0];
    const double drift = energy_drift(s, 0, E0), bal = max_abs(s["balance_residual"]) / E0;
    double Wmax = 0.0;
    for (std::size_t i = 0; i < s.rows(); ++i) Wmax = std::max(Wmax, s["strain"][i]);
    std::printf("[laws] %s: E0 %.6e, max strain energy %.3e (%.1f%% of E0), max |E - E0|/E0 %.2e, max |balance|/E0 %.2e\n",
                model.c_str(), E0, Wmax, 100 * Wmax / E0, drift, bal);
    EXPECT_GT(Wmax, 1e-3 * E0) << model << ": the body must deform";
    EXPECT_LT(drift, 1e-10) << model;
    EXPECT_LT(bal, 1e-10) << model;
  }
}

// ---------------------------------------------------------------------------------------
// d. Second order in dt: unit square (P1, h = 0.25) clamped at the bottom, body force
// (75000 t, 0) (table ramp from 0), E = 3e3, nu = 0.3, rho = 1, T = 0.02 (corner moves by
// ~0.1). Error: RMS over the nodes of |u(T) - u_ref(T)|, u_ref with dt = T/320, same scheme.
// (The final time is short so that dt resolves the mesh's fastest modes, ~ 1e3 rad/s: with
// dt omega_max >~ 1 the observed order wanders between 1.4 and 2.4.)
std::vector<double> ramp_block(const std::string& scheme, double alpha, int steps) {
  Spec sp;
  sp.scheme = scheme;
  sp.hht_alpha = alpha;
  sp.T = 0.02;
  sp.steps = steps;
  sp.bcs =
      "<ParameterList name=\"clamp\"><Parameter name=\"type\" type=\"string\" value=\"Dirichlet\"/>"
      "<Parameter name=\"boundary\" type=\"string\" value=\"bottom\"/></ParameterList>"
      "<ParameterList name=\"push\"><Parameter name=\"type\" type=\"string\" value=\"body force\"/>"
      "<Parameter name=\"force\" type=\"Array(double)\" value=\"{75000, 0}\"/>"
      "<Parameter name=\"ramp\" type=\"string\" value=\"table\"/>"
      "<Parameter name=\"ramp times\" type=\"Array(double)\" value=\"{0, 1}\"/>"
      "<Parameter name=\"ramp factors\" type=\"Array(double)\" value=\"{0, 1}\"/></ParameterList>";
  const std::string tag = "order_" + scheme + "_" + std::to_string(steps);
  const RunOut r = run(make_deck(sp, tag), tag);
  EXPECT_EQ(r.status, 0) << tag;
  return r.res.displacement;
}

TEST(Dynamics, SecondOrderInTime) {
  const std::vector<int> steps = {10, 20, 40};
  for (const auto& [scheme, alpha] : std::vector<std::pair<std::string, double>>{
           {"gonzalez", 0.0}, {"midpoint", 0.0}, {"newmark", 0.0}, {"hht", -0.05}}) {
    const std::vector<double> ref = ramp_block(scheme, alpha, 320);
    std::vector<double> err;
    for (int n : steps) {
      const std::vector<double> u = ramp_block(scheme, alpha, n);
      double e = 0.0;
      for (std::size_t i = 0; i < u.size(); ++i) e += (u[i] - ref[i]) * (u[i] - ref[i]);
      err.push_back(std::sqrt(e / (u.size() / 3)));
    }
    double umax = 0.0;
    for (double v : ref) umax = std::max(umax, std::abs(v));
    std::printf("[order] %-8s%s: max |u_ref| %.4f; RMS error dt = T/10, T/20, T/40: %.3e %.3e %.3e; orders %.3f %.3f\n",
                scheme.c_str(), scheme == "hht" ? " (alpha -0.05)" : "", umax, err[0], err[1], err[2],
                std::log2(err[0] / err[1]), std::log2(err[1] / err[2]));
    for (std::size_t i = 0; i + 1 < err.size(); ++i) {
      const double p = std::log2(err[i] / err[i + 1]);
      EXPECT_GE(p, 1.8) << scheme;
      EXPECT_LE(p, 2.2) << scheme;
    }
  }
}

// ---------------------------------------------------------------------------------------
// e. Momentum: free unit square (P1, h = 0.25), Ciarlet-Geymonat rubber-like (E = 3e6,
// nu = 0.3, rho = 1000), v0 = (1, 0.5) + 20 e_z x (X - (0.5, 0.5)); T = 0.5, 50 steps.
// Exact initial momenta (P1 represents the rigid field, the consistent mass integrates it
// exactly): p = m v = (1000, 500), H_z = m (x_c x v)_z + I_c omega = -250 + 1000 * 20 / 6.
TEST(Dynamics, SpinningSquareConservesMomenta) {
  for (const std::string scheme : {"gonzalez", "midpoint"}) {
    Spec sp;
    sp.E = 3e6;
    sp.rho = 1000.0;
    sp.omega = 20.0;
    sp.velocity = {1.0, 0.5};
    sp.scheme = scheme;
    sp.T = 0.5;
    sp.steps = 50;
    const RunOut r = run(make_deck(sp, "spin_" + scheme), "spin_" + scheme);
    ASSERT_EQ(r.status, 0) << scheme;
    const Series& s = r.energy;
    const std::array<double, 3> p0 = s.vec("momentum", 0), H0 = s.vec("angular_momentum", 0);
    EXPECT_NEAR(p0[0], 1000.0, 1e-9);
    EXPECT_NEAR(p0[1], 500.0, 1e-9);
    EXPECT_NEAR(H0[2], -250.0 + 1000.0 * 20.0 / 6.0, 1e-9);
    const double dp = vector_drift(s, "momentum", 0) / norm(p0), dH = vector_drift(s, "angular_momentum", 0) / norm(H0);
    const double E0 = s["total"][0];
    std::printf("[spin] %-8s: max |p - p0|/|p0| %.2e, max |H - H0|/|H0| %.2e; max |E - E0|/E0 %.2e\n", scheme.c_str(), dp, dH,
                energy_drift(s, 0, E0));
    EXPECT_LT(dp, 1e-10) << scheme;
    EXPECT_LT(dH, 1e-10) << scheme;
  }
}

}  // namespace

// Stepping->predictor = velocity (u_n + dt v_n; + dt^2/2 a_n for newmark): the same
// solution as Newton started at u_n (to Newton's tolerance), the energy identity still
// exact for Gonzalez, and no more Newton iterations on the contact impact deck (measured
// table: docs/robustness.md).
TEST(Dynamics, VelocityPredictorSameSolution) {
  for (const std::string scheme : {"gonzalez", "newmark"}) {
    Config cfg = read_deck(std::string(STENTOR_SOURCE_DIR) + "/inputs/contact_block_impact.xml");
    cfg.output.fields = false;
    cfg.time.scheme = scheme;
    cfg.stepping.end_time = 0.06;
    cfg.stepping.num_steps = 60;
    const RunOut a = run(cfg, "pred_none_" + scheme);
    cfg.stepping.predictor = "velocity";
    const RunOut b = run(cfg, "pred_velocity_" + scheme);
    ASSERT_EQ(a.status, 0);
    ASSERT_EQ(b.status, 0);
    double d = 0.0, n = 0.0;
    for (std::size_t i = 0; i < a.res.displacement.size(); ++i) {
      d = std::max(d, std::abs(a.res.displacement[i] - b.res.displacement[i]));
      n = std::max(n, std::abs(a.res.displacement[i]));
    }
    EXPECT_LT(d, 1e-6 * n) << scheme;
    EXPECT_LE(b.res.newton_iterations, a.res.newton_iterations) << scheme;
    if (scheme == "gonzalez") EXPECT_LT(max_abs(b.energy["balance_residual"]), 1e-5) << "energy identity";
  }
}

// f. A prescribed motion in dynamics: the block's base clamped, its top pushed down 5% by
// a linear ramp from rest (Gonzalez, no loads, no viscosity). All energy enters through the
// supports: the cumulative support work equals E(t) and the per-step balance closes to
// solver tolerance (it was 2 W_sup per step while the support work had the wrong sign).
TEST(Dynamics, MovingSupportWorkEqualsEnergy) {
  fs::create_directories(work_dir());
  const fs::path deck = work_dir() / "moving_support.xml";
  std::ofstream(deck) << R"XML(<ParameterList name="stentor">
  <ParameterList name="Problem"><Parameter name="analysis" type="string" value="dynamic"/></ParameterList>
  <ParameterList name="Mesh">
    <Parameter name="file" type="string" value=")XML" << STENTOR_SOURCE_DIR << R"XML(/inputs/block2d.geo"/>
    <Parameter name="size" type="double" value="0.5"/>
  </ParameterList>
  <ParameterList name="Materials"><ParameterList name="rubber">
    <Parameter name="C1" type="double" value="0.5e6"/><Parameter name="D" type="double" value="0.35e6"/>
    <Parameter name="density" type="double" value="1000"/>
  </ParameterList></ParameterList>
  <ParameterList name="Bodies"><ParameterList name="block"><Parameter name="material" type="string" value="rubber"/></ParameterList></ParameterList>
  <ParameterList name="Boundary Conditions">
    <ParameterList name="base"><Parameter name="type" type="string" value="Dirichlet"/><Parameter name="boundary" type="string" value="bottom"/></ParameterList>
    <ParameterList name="top">
      <Parameter name="type" type="string" value="Dirichlet"/><Parameter name="boundary" type="string" value="top"/>
      <Parameter name="components" type="string" value="y"/><Parameter name="values" type="Array(double)" value="{-0.05}"/>
    </ParameterList>
  </ParameterList>
  <ParameterList name="Stepping"><Parameter name="end time" type="double" value="0.05"/><Parameter name="steps" type="int" value="25"/></ParameterList>
  <ParameterList name="Newton"><Parameter name="relative residual tolerance" type="double" value="1e-12"/></ParameterList>
  <ParameterList name="Linear Solver"><Parameter name="method" type="string" value="direct"/></ParameterList>
  <ParameterList name="Output"><Parameter name="fields" type="bool" value="false"/><Parameter name="basename" type="string" value="moving"/></ParameterList>
</ParameterList>
)XML";
  const RunOut r = run(read_deck(deck.string()), "moving_support");
  ASSERT_EQ(r.status, 0);
  const Series& s = r.energy;
  const std::size_t n = s.rows() - 1;
  const double E = max_abs(s["total"]), bal = max_abs(s["balance_residual"]) / E;
  double closure = 0.0;
  for (std::size_t i = 0; i <= n; ++i) closure = std::max(closure, std::abs(s["total"][i] - s["support_work"][i]) / E);
  std::printf("[moving support] E(T) %.6e, W_sup(T) %.6e; max |balance|/E %.2e, max |E - W_sup|/E %.2e\n", s["total"][n],
              s["support_work"][n], bal, closure);
  EXPECT_GT(s["support_work"][n], 0.0);  // the supports push energy in
  EXPECT_LT(bal, 1e-9);
  EXPECT_LT(closure, 1e-9);
  EXPECT_EQ(s["external_work"][n], 0.0);
}

// g. Newmark and HHT from a loaded state with the default linear solver (GMRES + MueLu):
// a_0 = M^{-1} (f_ext - f_int) is solved before the first step, by a second linear solver
// that got no node coordinates, so MueLu refused the mass matrix ("MueLu: dimension must be
// 2 or 3 (got 0)", reported as bad input, exit 2; issue 12). A free block (unit square /
// cube, coarse P1, rho = 2) under a constant body force b: a rigid translation with
// a = b / rho from t = 0. Both schemes integrate a constant acceleration exactly when
// a_0 = a, so every node ends at u(T) = a T^2 / 2 (Newmark with a_0 = 0 would end at
// a (T^2 - T dt + dt^2 / 2) / 2, 22% short with 4 steps).
TEST(Dynamics, NewmarkInitialAccelerationUnderBodyForceDefaultSolver) {
  fs::create_directories(work_dir());
  for (const int dim : {2, 3}) {
    for (const std::string scheme : {"newmark", "hht"}) {
      const std::string tag = "free_fall_" + scheme + "_" + std::to_string(dim) + "d";
      const std::array<double, 3> b = {30.0, -60.0, dim == 3 ? 15.0 : 0.0};
      const double rho = 2.0, T = 0.1;
      std::ostringstream force;
      force << "{" << b[0] << ", " << b[1] << (dim == 3 ? ", " + std::to_string(b[2]) : std::string()) << "}";
      const fs::path deck = work_dir() / (tag + ".xml");
      std::ofstream(deck) << R"XML(<ParameterList name="stentor">
  <ParameterList name="Problem"><Parameter name="analysis" type="string" value="dynamic"/></ParameterList>
  <ParameterList name="Mesh">
    <Parameter name="file" type="string" value=")XML" << STENTOR_SOURCE_DIR << "/inputs/block" << dim << R"XML(d.geo"/>
    <Parameter name="size" type="double" value="0.5"/>
  </ParameterList>
  <ParameterList name="Materials"><ParameterList name="rubber">
    <Parameter name="C1" type="double" value="0.5e6"/><Parameter name="D" type="double" value="0.35e6"/>
    <Parameter name="density" type="double" value="2"/>
  </ParameterList></ParameterList>
  <ParameterList name="Bodies"><ParameterList name="block"><Parameter name="material" type="string" value="rubber"/></ParameterList></ParameterList>
  <ParameterList name="Boundary Conditions"><ParameterList name="gravity">
    <Parameter name="type" type="string" value="body force"/>
    <Parameter name="force" type="Array(double)" value=")XML" << force.str() << R"XML("/>
    <Parameter name="ramp" type="string" value="constant"/>
  </ParameterList></ParameterList>
  <ParameterList name="Time Integration"><Parameter name="scheme" type="string" value=")XML" << scheme << R"XML("/></ParameterList>
  <ParameterList name="Stepping"><Parameter name="end time" type="double" value="0.1"/><Parameter name="steps" type="int" value="4"/></ParameterList>
  <ParameterList name="Newton"><Parameter name="relative residual tolerance" type="double" value="1e-12"/></ParameterList>
  <ParameterList name="Output"><Parameter name="fields" type="bool" value="false"/><Parameter name="basename" type="string" value="fall"/></ParameterList>
</ParameterList>
)XML";
      const Config cfg = read_deck(deck.string());
      ASSERT_EQ(cfg.linear.method, "gmres");
      ASSERT_EQ(cfg.linear.preconditioner, "auto");  // MueLu where Trilinos has it
      const RunOut r = run(cfg, tag);
      ASSERT_EQ(r.status, 0) << tag;
      double err = 0.0;
      const std::size_t nodes = r.res.displacement.size() / 3;
      for (std::size_t n = 0; n < nodes; ++n)
        for (int c = 0; c < dim; ++c)
          err = std::max(err, std::abs(r.res.displacement[3 * n + static_cast<std::size_t>(c)] - 0.5 * b[static_cast<std::size_t>(c)] / rho * T * T));
      const double u_exact = 0.5 * norm(b) / rho * T * T;
      std::printf("[free fall] %-7s %dD: %zu nodes, max |u - a T^2/2| / |a T^2/2| = %.2e\n", scheme.c_str(), dim, nodes, err / u_exact);
      EXPECT_LT(err, 1e-8 * u_exact) << tag;
    }
  }
}

// Per-body initial state (issue 9): the left bar of two_bars.geo (L = 1, H = 0.1, rho = 1000,
// mass m = 100 kg/m) moves at v = (0.5, 0), spins at w = 2 rad/s about its centroid
// c = (0.5, 0.05) and starts displaced by d = (0.001, 0.002); the right bar rests. With a
// linear velocity field the consistent mass integrates the kinetic energy exactly:
//   K0 = m v^2 / 2 + w^2 I / 2,  I = m (L^2 + H^2) / 12 (about c);
//   p0 = m v;  L0_z = m ((c + d) x v)_z + I w (about the origin, on x = X + d).
// The bars are 0.01 m apart, so no contact in the 4 steps: K + W stays at K0 (Gonzalez).
TEST(Dynamics, PerBodyInitialVelocityRotationAndDisplacement) {
  fs::create_directories(work_dir());
  const fs::path deck = work_dir() / "body_initial.xml";
  std::ofstream(deck) << R"XML(<ParameterList name="stentor">
  <ParameterList name="Problem"><Parameter name="analysis" type="string" value="dynamic"/></ParameterList>
  <ParameterList name="Mesh"><Parameter name="file" type="string" value=")XML"
                      << STENTOR_SOURCE_DIR << R"XML(/inputs/two_bars.geo"/></ParameterList>
  <ParameterList name="Materials"><ParameterList name="rubber">
    <Parameter name="C1" type="double" value="0.5e6"/><Parameter name="D" type="double" value="0.35e6"/>
    <Parameter name="density" type="double" value="1000"/></ParameterList></ParameterList>
  <ParameterList name="Bodies">
    <ParameterList name="left"><Parameter name="material" type="string" value="rubber"/>
      <Parameter name="initial velocity" type="Array(double)" value="{0.5, 0}"/>
      <Parameter name="initial angular velocity" type="Array(double)" value="{2}"/>
      <Parameter name="rotation center" type="Array(double)" value="{0.5, 0.05}"/>
      <Parameter name="initial displacement" type="Array(double)" value="{0.001, 0.002}"/></ParameterList>
    <ParameterList name="right"><Parameter name="material" type="string" value="rubber"/></ParameterList>
  </ParameterList>
  <ParameterList name="Stepping"><Parameter name="end time" type="double" value="0.002"/><Parameter name="steps" type="int" value="4"/></ParameterList>
  <ParameterList name="Linear Solver"><Parameter name="method" type="string" value="direct"/></ParameterList>
  <ParameterList name="Output"><Parameter name="fields" type="bool" value="false"/></ParameterList>
</ParameterList>
)XML";
  const RunOut r = run(read_deck(deck.string()), "body_initial");
  ASSERT_EQ(r.status, 0);
  const double m = 100.0, I = m * (1.0 + 0.01) / 12.0, w = 2.0, v = 0.5;
  const double K0 = 0.5 * m * v * v + 0.5 * I * w * w;
  const double Lz = m * ((0.5 + 0.001) * 0.0 - (0.05 + 0.002) * v) + I * w;
  const Series& e = r.energy;
  ASSERT_GE(e.rows(), 5u);
  std::printf("[dynamics] per-body initial state: K0 %.12g (closed form %.12g), p_x %.12g, L_z %.12g (%.12g)\n", e["kinetic"][0], K0,
              e["momentum_x"][0], e["angular_momentum_z"][0], Lz);
  EXPECT_NEAR(e["kinetic"][0], K0, 1e-12 * K0);
  EXPECT_LT(std::abs(e["strain"][0]), 1e-12 * K0) << "a rigid displacement stores no energy (round-off: 2.7e-12 J/m)";
  EXPECT_NEAR(e["momentum_x"][0], m * v, 1e-12 * m * v);
  EXPECT_NEAR(e["momentum_y"][0], 0.0, 1e-12 * m * v);
  EXPECT_NEAR(e["angular_momentum_z"][0], Lz, 1e-12 * std::abs(Lz));
  EXPECT_LT(energy_drift(e, 0, K0), 1e-10);
}
