// The stent's deformable balloon (Mesh->Balloon, docs/stent.md "The deformable balloon")
// inflated freely, without contact, against references computed independently of the
// finite elements. The deck: the S6 ring as cut (one strut's sector, `sector` = period),
// unloaded, its neo-Hookean metal held by the sector's planes and z at `anchor`, and the
// balloon of tests/cli/decks/stent_balloon_ring.xml (OD 2.7 mm, wall 0.05 mm, the same
// Holzapfel-Gasser-Ogden wall: E = 3 MPa, nu = 0.4, k1 = 0.4 MPa, k2 = 0.1, both fibre
// families circumferential) under a follower pressure on `balloon_inner`; no contact pair,
// so the balloon passes through the stent.
//
// References (their laws built from the deck's own material entry):
//  1. the radial boundary-value problem of the compressible law at a uniform axial stretch
//     (RadialTubeReference.hpp, shared with test_artery_inflation.cpp): exact for a tube
//     whose cross-sections all have that lambda_z, of any wall thickness;
//  2. the thin-tube (membrane) formula of docs/stent.md, for lambda_z = 1 and the
//     compressible law: the hoop tension balances the pressure, p r = P_tt t0 (P_tt the
//     nominal hoop stress, sigma_rr = 0 through the membrane), so
//       p = t0 / (R lambda) dW/dlambda_t
//         = t0 / R [ mu (1 - lambda_r^2 / lambda^2) + 4 k1 (lambda^2 - 1) exp(k2 (lambda^2 - 1)^2) ],
//     lambda_r from S_rr = 0: mu (lambda_r^2 - 1) + lambda_L ln(lambda lambda_r) = 0 (lambda_L the
//     Lame constant); incompressible lambda_r = 1 / lambda. A membrane formula: R and lambda
//     those of the mid-surface.
//
// Which ends: with the balloon's ends held only axially (components z: both end planes
// stay at their z, free to open), every cross-section is in the plane-strain state of the
// reference (no end effect at all: the FE solution is uniform along z, checked). Held
// whole (components all, the catheter bond of the decks), the middle of a long balloon is
// uniform too but stretched axially by the shoulders at the ends: it is compared with the
// reference at the axial stretch it shows, and that stretch's effect measured at 10 and
// 20 radii. docs/verification.md, "Deformable balloon inflated freely".
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "AssemblerFixture.hpp"
#include "CsvSeries.hpp"
#include "H5Results.hpp"
#include "RadialTubeReference.hpp"
#include "geometry/Generators.hpp"
#include "mesh/GmshReader.hpp"
#include "run/Simulation.hpp"
#include "TestDir.hpp"

using namespace stentor;
using namespace stentor::testing::radial;
namespace fs = std::filesystem;

namespace {

fs::path work_dir() { return stentor::testing::test_dir("balloon_inflation"); }

struct Balloon {
  double length = 1.2;          // the whole balloon's
  double element_length = 0.1;  // around and along
  int through = 2;              // cells through the wall
  std::string ends = "z";       // components held on balloon_ends
  int steps = 4;
  double volume_ratio = 0.0;    // > 0: a fluid cavity (bulk modulus `bulk`) instead of the pressure
  double bulk = 2200.0;
};

// The inflation load: a follower pressure p, or the fluid cavity of b.
std::string inflation(const Balloon& b, double p) {
  if (b.volume_ratio <= 0.0)
    return R"(<ParameterList name="inflation"><Parameter name="type" type="string" value="pressure"/>
      <Parameter name="boundary" type="string" value="balloon_inner"/>
      <Parameter name="pressure" type="double" value=")" +
           std::to_string(p) + R"("/></ParameterList>)";
  char buf[600];
  std::snprintf(buf, sizeof buf, R"X(<ParameterList name="inflation"><Parameter name="type" type="string" value="fluid cavity"/>
      <Parameter name="boundary" type="string" value="balloon_inner"/>
      <Parameter name="volume ratio" type="double" value="%.17g"/>
      <Parameter name="bulk modulus" type="double" value="%.17g"/>
      <Parameter name="axis point" type="Array(double)" value="{0, 0, 0}"/>
      <Parameter name="axis" type="Array(double)" value="{0, 0, 1}"/></ParameterList>)X",
                b.volume_ratio, b.bulk);
  return buf;
}

Config deck(const Balloon& b, double p, const std::string& name) {
  const std::string text = R"(<ParameterList name="stentor">
  <ParameterList name="Problem"><Parameter name="analysis" type="string" value="static"/>
    <Parameter name="units" type="string" value="mm-N-s"/></ParameterList>
  <ParameterList name="Mesh"><Parameter name="generator" type="string" value="stent"/>
    <ParameterList name="Stent">
      <Parameter name="rings" type="int" value="1"/><Parameter name="crowns" type="int" value="8"/>
      <Parameter name="outer diameter" type="double" value="3.0"/>
      <Parameter name="thickness" type="double" value="0.1"/>
      <Parameter name="strut width" type="double" value="0.1"/>
      <Parameter name="ring length" type="double" value="1.0"/>
      <Parameter name="elements through width" type="int" value="2"/>
      <Parameter name="elements through thickness" type="int" value="2"/>
      <Parameter name="sector" type="string" value="period"/>
    </ParameterList>
    <ParameterList name="Balloon">
      <Parameter name="outer diameter" type="double" value="2.7"/>
      <Parameter name="thickness" type="double" value="0.05"/>
      <Parameter name="length" type="double" value=")" + std::to_string(b.length) + R"("/>
      <Parameter name="element length" type="double" value=")" + std::to_string(b.element_length) + R"("/>
      <Parameter name="elements through thickness" type="int" value=")" + std::to_string(b.through) + R"("/>
    </ParameterList></ParameterList>
  <ParameterList name="Materials">
    <ParameterList name="steel"><Parameter name="model" type="string" value="neo-Hookean"/>
      <Parameter name="E" type="double" value="196000"/><Parameter name="nu" type="double" value="0.3"/></ParameterList>
    <ParameterList name="balloon wall"><Parameter name="model" type="string" value="Holzapfel-Gasser-Ogden"/>
      <Parameter name="E" type="double" value="3.0"/><Parameter name="nu" type="double" value="0.4"/>
      <Parameter name="k1" type="double" value="0.4"/><Parameter name="k2" type="double" value="0.1"/>
      <Parameter name="fibre angle" type="double" value="0.0"/></ParameterList>
  </ParameterList>
  <ParameterList name="Bodies">
    <ParameterList name="stent"><Parameter name="material" type="string" value="steel"/></ParameterList>
    <ParameterList name="balloon"><Parameter name="material" type="string" value="balloon wall"/></ParameterList>
  </ParameterList>
  <ParameterList name="Boundary Conditions">
    <ParameterList name="sym_sector"><Parameter name="type" type="string" value="Dirichlet"/>
      <Parameter name="boundary" type="string" value="symmetry_sector"/>
      <Parameter name="components" type="string" value="normal"/></ParameterList>
    <ParameterList name="sym_y"><Parameter name="type" type="string" value="Dirichlet"/>
      <Parameter name="boundary" type="string" value="symmetry_y"/>
      <Parameter name="components" type="string" value="y"/></ParameterList>
    <ParameterList name="anchor"><Parameter name="type" type="string" value="Dirichlet"/>
      <Parameter name="boundary" type="string" value="anchor"/>
      <Parameter name="components" type="string" value="z"/></ParameterList>
    <ParameterList name="catheter"><Parameter name="type" type="string" value="Dirichlet"/>
      <Parameter name="boundary" type="string" value="balloon_ends"/>
      <Parameter name="components" type="string" value=")" + b.ends + R"("/></ParameterList>
    )" + inflation(b, p) + R"(
  </ParameterList>
  <ParameterList name="Stepping"><Parameter name="end time" type="double" value="1.0"/>
    <Parameter name="steps" type="int" value=")" + std::to_string(b.steps) + R"("/></ParameterList>
  <ParameterList name="Linear Solver"><Parameter name="method" type="string" value="direct"/></ParameterList>
  <ParameterList name="Output"><Parameter name="basename" type="string" value="balloon"/>
    <Parameter name="field list" type="string" value="displacement"/></ParameterList>
</ParameterList>
)";
  fs::create_directories(work_dir());
  const fs::path f = work_dir() / (name + ".xml");
  std::ofstream(f) << text;
  return read_deck(f.string());
}

// The balloon's nodes (those inside the stent's inner radius) at one output step: their
// reference coordinates and displacements, and the pressure then (the load's value times
// its linear ramp at the step's time).
struct State {
  double p;
  std::vector<double> X, u;
};

// Runs the deck to the pressure p_max; the states at every step (t = 0 excluded).
std::vector<State> run(const Balloon& b, double p_max, const std::string& name) {
  const Config cfg = deck(b, p_max, name);
  RunOptions opts;
  opts.output_dir = (work_dir() / name).string();
  opts.overwrite = true;
  RunResult res;
  EXPECT_EQ(run_simulation(cfg, opts, &res), 0) << name;
  EXPECT_TRUE(res.converged) << name;
  std::printf("[balloon] %s: %zu balloon cells, %d steps, %d cut-backs, %d Newton iterations\n", name.c_str(),
              static_cast<std::size_t>(cfg.mesh.balloon.cells(cfg.mesh.stent)), res.steps, res.cutbacks,
              res.newton_iterations);
  const stentor::testing::H5Results h5(work_dir() / name / "balloon.h5");
  EXPECT_GE(h5.f, 0) << name;
  const std::vector<double> x = h5.read("/mesh/coordinates"), t = h5.times();
  const double inside = cfg.mesh.stent.inner_radius();
  std::vector<State> out;
  for (std::size_t k = 1; k < t.size(); ++k) {
    const std::vector<double> u = h5.read("/step_" + std::to_string(k) + "/displacement");
    EXPECT_EQ(u.size(), x.size()) << name;
    State s{p_max * t[k], {}, {}};
    for (std::size_t i = 0; 3 * i + 2 < std::min(x.size(), u.size()); ++i)
      if (std::hypot(x[3 * i], x[3 * i + 1]) < inside)
        for (int c = 0; c < 3; ++c) s.X.push_back(x[3 * i + c]), s.u.push_back(u[3 * i + c]);
    out.push_back(std::move(s));
  }
  return out;
}

// The deformed radii of the nodes at reference radius R0, by reference z (sorted).
struct Ring {
  double z, r;
};
std::vector<Ring> profile(const State& s, double R0) {
  std::vector<Ring> out;
  for (std::size_t i = 0; 3 * i < s.X.size(); ++i) {
    const double* X = &s.X[3 * i];
    const double* u = &s.u[3 * i];
    if (std::fabs(std::hypot(X[0], X[1]) - R0) > 1e-9 * R0) continue;
    out.push_back({X[2], std::hypot(X[0] + u[0], X[1] + u[1])});
  }
  std::sort(out.begin(), out.end(), [](const Ring& a, const Ring& b) { return a.z < b.z; });
  return out;
}

// Mean deformed radius of the nodes at reference radius R0 on the plane z = z0; spread:
// the largest |r - mean| over every z (0 for a state uniform along the balloon).
double fe_radius(const State& s, double R0, double z0, double* spread = nullptr) {
  const std::vector<Ring> all = profile(s, R0);
  double sum = 0.0;
  int n = 0;
  for (const Ring& q : all)
    if (std::fabs(q.z - z0) < 1e-9) sum += q.r, ++n;
  EXPECT_GE(n, 3) << "nodes at R = " << R0 << ", z = " << z0;
  const double mean = sum / n;
  if (spread) {
    *spread = 0.0;
    for (const Ring& q : all) *spread = std::fmax(*spread, std::fabs(q.r - mean));
  }
  return mean;
}

// The thin-tube pressure at hoop stretch l (docs/stent.md), compressible: lambda_r from
// S_rr = 0 (Newton on the log of lambda_r).
// incompressible: lambda_r = 1 / lambda (the formula as docs/stent.md first gave it).
double thin_tube_pressure(double l, double mu, double lam, double k1, double k2, double t0, double R,
                          bool incompressible = false) {
  double lr = 1.0 / l;
  for (int it = 0; it < 50 && !incompressible; ++it) {
    const double f = mu * (lr * lr - 1.0) + lam * std::log(l * lr), df = 2.0 * mu * lr * lr + lam;  // d/d ln lr
    lr *= std::exp(-f / df);
  }
  const double x = l * l - 1.0;
  return t0 / R * (mu * (1.0 - lr * lr / (l * l)) + 4.0 * k1 * x * std::exp(k2 * x * x));
}

// Its inverse: the hoop stretch at pressure p (bisection; p grows with l).
double thin_tube_stretch(double p, double mu, double lam, double k1, double k2, double t0, double R,
                         bool incompressible = false) {
  double lo = 1.0, hi = 4.0;
  for (int it = 0; it < 200; ++it) {
    const double mid = 0.5 * (lo + hi);
    (thin_tube_pressure(mid, mu, lam, k1, k2, t0, R, incompressible) < p ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

// The pressure is ramped to 0.3 MPa in 6 steps; compared at 0.05, 0.15 and 0.3 MPa (hoop
// stretch about 1.2, 1.6 and 1.85).
constexpr double kPressure = 0.3;
constexpr int kSteps = 6;
const int kCompared[3] = {0, 2, 5};  // steps

}  // namespace

// The axially held balloon (plane strain everywhere) against the radial solution of the
// same compressible law, at three pressures, on two meshes; and against the thin-tube
// formula to its O(t0 / R) accuracy.
TEST(BalloonInflation, AxiallyHeldBalloonMatchesTheRadialSolution) {
  const Config cfg = deck(Balloon{}, kPressure, "read");
  const MaterialConfig& m = cfg.material("balloon wall");
  const double Ri = cfg.mesh.balloon.inner_radius(), Ro = cfg.mesh.balloon.outer_radius(), Rm = 0.5 * (Ri + Ro);
  const double t0 = Ro - Ri, zmid = 0.5 * cfg.mesh.stent.total_length();
  const double beta = m.fibre_angle * 3.14159265358979323846 / 180.0;
  const std::vector<Layer> L{{cylindrical_law(m.mu, m.lambda, m.k1, m.k2, beta), Ri, Ro}};
  const std::vector<Layer> L2k1{{cylindrical_law(m.mu, m.lambda, 2.0 * m.k1, m.k2, beta), Ri, Ro}};
  std::printf("[balloon] wall Ri %.4f Ro %.4f (t0/Rm %.4f); mu %.6f lambda %.6f k1 %g k2 %g MPa\n", Ri, Ro, t0 / Rm,
              m.mu, m.lambda, m.k1, m.k2);

  // Two meshes: element length 0.1 mm around and along, 2 cells through the wall; half both.
  const Balloon meshes[2] = {Balloon{1.2, 0.1, 2, "z", kSteps}, Balloon{1.2, 0.05, 4, "z", kSteps}};
  double ri[3], ro[3], ri2[3], ro2[3], lt[3], li[3], p[3];
  double err[2][3] = {}, thin = 0.0, thin_inc = 0.0, k1_shift = 1e300;
  for (int k = 0; k < 2; ++k) {
    const std::vector<State> st = run(meshes[k], kPressure, "axial_" + std::to_string(k));
    ASSERT_EQ(st.size(), static_cast<std::size_t>(kSteps));
    for (int i = 0; i < 3; ++i) {
      const State& s = st[kCompared[i]];
      if (k == 0) {
        p[i] = s.p;
        reference_radii(L, p[i], ri[i], ro[i]);
        reference_radii(L2k1, p[i], ri2[i], ro2[i]);
        lt[i] = thin_tube_stretch(p[i], m.mu, m.lambda, m.k1, m.k2, t0, Rm);
        li[i] = thin_tube_stretch(p[i], m.mu, m.lambda, m.k1, m.k2, t0, Rm, true);
        ASSERT_TRUE(std::isfinite(ri[i]) && std::isfinite(ro[i]) && std::isfinite(ri2[i]) && std::isfinite(lt[i]));
        k1_shift = std::fmin(k1_shift, std::fabs(ri2[i] - ri[i]) / ri[i]);
      }
      ASSERT_NEAR(s.p, p[i], 1e-12);
      double si, so;
      const double fi = fe_radius(s, Ri, zmid, &si), fo = fe_radius(s, Ro, zmid, &so), fm = fe_radius(s, Rm, zmid);
      ASSERT_TRUE(std::isfinite(fi) && std::isfinite(fo) && std::isfinite(fm));
      const double ei = (fi - ri[i]) / ri[i], eo = (fo - ro[i]) / ro[i];
      const double et = (lt[i] * Rm - fm) / fm, eti = (li[i] * Rm - fm) / fm;
      err[k][i] = std::fmax(std::fabs(ei), std::fabs(eo));
      thin = std::fmax(thin, std::fabs(et));
      thin_inc = std::fmax(thin_inc, std::fabs(eti));
      // The state is uniform along the balloon (ends held axially only: no end effect);
      // measured 1.3e-15.
      EXPECT_LT(std::fmax(si, so), 1e-10 * ro[i]) << "p " << p[i];
      std::printf("[balloon] mesh %d (h %.3f, %d through): p %.3f MPa: inner %.6f (ref %.6f, rel %+.2e), outer %.6f "
                  "(ref %.6f, rel %+.2e), spread along z %.1e; k1 x 2: inner %.6f; thin tube: mid %.6f (FE %.6f, rel "
                  "%+.2e; incompressible %+.2e), hoop stretch %.4f\n",
                  k, meshes[k].element_length, meshes[k].through, p[i], fi, ri[i], ei, fo, ro[i], eo,
                  std::fmax(si, so), ri2[i], lt[i] * Rm, fm, et, eti, lt[i]);
    }
  }
  // What a 1 % error in the pressure does to the radius where it does least (the highest
  // pressure: the fibres stiffen exponentially).
  double ri_p, ro_p;
  reference_radii(L, 1.01 * p[2], ri_p, ro_p);
  const double p_shift = (ri_p - ri[2]) / ri[2];
  const double coarse = *std::max_element(err[0], err[0] + 3), fine = *std::max_element(err[1], err[1] + 3);
  std::printf("[balloon] largest rel error: coarse %.2e, fine %.2e (ratio %.2f); thin tube %.2e, incompressible "
              "thin tube %.2e (t0/Rm %.3f, squared %.2e); k1 x 2 moves the inner radius by >= %.2e, p x 1.01 at %.2f "
              "MPa by %.2e\n",
              coarse, fine, coarse / fine, thin, thin_inc, t0 / Rm, t0 * t0 / (Rm * Rm), k1_shift, p[2], p_shift);
  // Measured 1.65e-4 and 4.79e-5 (ratio 3.44: second order in the mesh size).
  EXPECT_LT(coarse, 2.5e-4);
  EXPECT_LT(fine, 7.5e-5);
  EXPECT_GT(coarse / fine, 2.5);
  // The references tell a wrong material or pressure from the mesh error (measured 6.9e-2
  // for k1 x 2, 1.8e-3 for a 1 % pressure error at 0.3 MPa).
  EXPECT_GT(k1_shift, 100.0 * 2.5e-4);
  EXPECT_GT(p_shift, 5.0 * 2.5e-4);
  // The thin tube: measured 8.7e-4, below (t0/Rm)^2 = 1.4e-3 (mid-surface radius and
  // stretch); its incompressible form errs by more (the compressible wall thins less).
  EXPECT_LT(thin, t0 * t0 / (Rm * Rm));
  EXPECT_LT(thin, thin_inc);
}

// Ends held whole (the catheter bond of the decks), balloons of 10 and 20 radii (coarse:
// element length 0.2 mm, 2 cells through the wall). The middle is a uniform state again,
// but not plane strain: the pressure on the shoulders next to the held ends pushes them
// towards the ends, and the length they take up stretches the middle axially, by about
// (the shoulders' share) / L. The middle against the radial solution at the axial stretch
// it shows (the axial spacing of its node planes) and, for the size of this end effect,
// the same solution at lambda_z = 1. Pressures to 0.08 MPa: the held tube has a limit
// point near 0.09-0.1 MPa (the middle lengthens and opens at a pressure that no longer
// rises: a 6.6 mm balloon stalled at 0.098 MPa with h = 0.1, 0.109 with h = 0.2; a 13.4 mm
// one with h = 0.1 was cutting back at 0.089).
TEST(BalloonInflation, HeldEndsStretchTheMiddleOfALongBalloonAxially) {
  const Config cfg = deck(Balloon{}, kPressure, "read_held");
  const MaterialConfig& m = cfg.material("balloon wall");
  const double Ri = cfg.mesh.balloon.inner_radius(), Ro = cfg.mesh.balloon.outer_radius(), Rm = 0.5 * (Ri + Ro);
  const double zmid = 0.5 * cfg.mesh.stent.total_length();
  const std::vector<Layer> L{
      {cylindrical_law(m.mu, m.lambda, m.k1, m.k2, m.fibre_angle * 3.14159265358979323846 / 180.0), Ri, Ro}};
  const double lengths[2] = {13.2, 26.4};  // 10 and 20 Rm, to an even number of cells along
  double effect[2] = {}, worst = 0.0, flattest = 0.0;
  for (int k = 0; k < 2; ++k) {
    const Balloon held{lengths[k], 0.2, 2, "all", 4};
    const std::vector<State> st = run(held, 0.08, "held_" + std::to_string(k));
    ASSERT_EQ(st.size(), 4u);
    for (int i : {1, 3}) {  // 0.04 and 0.08 MPa
      const State& s = st[i];
      // lambda_z at the middle: the axial spacing of the node planes either side of it.
      const std::vector<Ring> mid = profile(s, Rm);
      const auto next = std::find_if(mid.begin(), mid.end(), [&](const Ring& q) { return q.z > zmid + 1e-9; });
      ASSERT_TRUE(next != mid.end());
      const double Zp = next->z, Zm = 2.0 * zmid - Zp;  // the mesh is symmetric about the middle
      double zp = 0.0, zm = 0.0;
      int np = 0, nm = 0;
      for (std::size_t n = 0; 3 * n < s.X.size(); ++n) {
        const double Z = s.X[3 * n + 2];
        if (std::fabs(Z - Zp) < 1e-9) zp += Z + s.u[3 * n + 2], ++np;
        if (std::fabs(Z - Zm) < 1e-9) zm += Z + s.u[3 * n + 2], ++nm;
      }
      ASSERT_GT(np, 2);
      ASSERT_EQ(np, nm);
      const double lz = (zp / np - zm / nm) / (Zp - Zm);
      const double fi = fe_radius(s, Ri, zmid), fo = fe_radius(s, Ro, zmid);
      // The middle third is uniform (the end effect there is the stretch, not a bulge);
      // edge: how far from the held end the outer radius is off the middle's by 1e-3.
      double spread = 0.0, edge = 0.0;
      const std::vector<Ring> prof = profile(s, Ro);
      for (const Ring& q : prof) {
        if (std::fabs(q.z - zmid) < lengths[k] / 6.0) spread = std::fmax(spread, std::fabs(q.r - fo) / fo);
        if (q.z < zmid && std::fabs(q.r - fo) > 1e-3 * fo) edge = std::fmax(edge, q.z - prof.front().z);
      }
      double ri, ro, ri1, ro1;
      reference_radii(L, s.p, ri, ro, lz);
      reference_radii(L, s.p, ri1, ro1);
      ASSERT_TRUE(std::isfinite(ri) && std::isfinite(ro) && std::isfinite(ri1) && std::isfinite(ro1));
      const double e = std::fmax(std::fabs(fi - ri) / ri, std::fabs(fo - ro) / ro), end_effect = (ro - ro1) / ro1;
      std::printf("[balloon] held ends, L %.1f mm (%.0f Rm): p %.3f MPa: middle lambda_z %.5f; inner %.6f, outer %.6f; "
                  "reference at that lambda_z %.6f, %.6f (max rel %.2e); at lambda_z = 1 outer %.6f (end effect "
                  "%+.2e); middle third uniform to %.1e, off by 1e-3 up to %.2f mm from the end\n",
                  lengths[k], lengths[k] / Rm, s.p, lz, fi, fo, ri, ro, e, ro1, end_effect, spread, edge);
      worst = std::fmax(worst, e);
      flattest = std::fmax(flattest, spread);
      if (i == 3) effect[k] = end_effect;
    }
  }
  std::printf("[balloon] held ends: largest rel error against the reference at the middle's lambda_z %.2e; middle "
              "third uniform to %.1e; end effect on the outer radius at 0.08 MPa %.2e (10 Rm), %.2e (20 Rm), ratio "
              "%.2f\n",
              worst, flattest, effect[0], effect[1], effect[0] / effect[1]);
  // Measured 4.05e-4 (the coarse mesh's error: 1.65e-4 at h = 0.1 above, x 4 at most).
  EXPECT_LT(worst, 6e-4);
  EXPECT_LT(flattest, 2e-6);  // measured 4.3e-7
  // The end effect falls like 1 / L (measured ratio 2.0) and, at 10 radii, is ten times the
  // mesh error: a held-end balloon is not compared with the plane-strain solution.
  EXPECT_GT(effect[1], 0.0);
  EXPECT_NEAR(effect[0] / effect[1], 2.0, 0.2);
  EXPECT_GT(effect[0], 5.0 * 6e-4);
}

// Volume control (`type` = fluid cavity, docs/stent.md "Volume control"): the ends held
// axially as above, the fluid's volume at zero pressure ramped to 1.6 V0 (K = 2200 MPa). At
// every step the cavity's volume is the fluid's at the pressure the run reports,
// V = V_fluid exp(-p / K); the cavity of the scaled polygon (the wall's nodes all at one
// radius, as the radial solution keeps them) is (r / Ri)^2 V0; and the radius matches the
// radial solution at that pressure as the pressure-driven balloon does.
TEST(BalloonInflation, FluidCavityHoldsItsVolumeAndMatchesTheRadialSolution) {
  const Balloon b{1.2, 0.1, 2, "z", 4, 1.6, 2200.0};
  const Config cfg = deck(b, 0.0, "cavity_read");
  const MaterialConfig& m = cfg.material("balloon wall");
  const double Ri = cfg.mesh.balloon.inner_radius(), Ro = cfg.mesh.balloon.outer_radius();
  const double zmid = 0.5 * cfg.mesh.stent.total_length();
  const std::vector<Layer> L{{cylindrical_law(m.mu, m.lambda, m.k1, m.k2, m.fibre_angle * 3.14159265358979323846 / 180.0), Ri, Ro}};
  const std::vector<State> st = run(b, 0.0, "cavity");
  const stentor::testing::Series h = stentor::testing::read_csv(work_dir() / "cavity" / "balloon_history.csv");
  ASSERT_EQ(st.size(), 4u);
  ASSERT_EQ(h.rows(), 4u);
  double worst_law = 0.0, worst_poly = 0.0, worst_ref = 0.0;
  for (std::size_t i = 0; i < 4; ++i) {
    const double f = h["time"][i], p = h["pressure_inflation"][i], v = h["volume_ratio_inflation"][i];
    const double fluid = 1.0 + f * (b.volume_ratio - 1.0);
    double spread = 0.0, ri = 0.0, ro = 0.0;
    const double fi = fe_radius(st[i], Ri, zmid, &spread);
    reference_radii(L, p, ri, ro);
    ASSERT_TRUE(std::isfinite(ri));
    const double law = std::fabs(v - fluid * std::exp(-p / b.bulk)), poly = std::fabs(v - fi * fi / (Ri * Ri)) / v;
    const double ref = std::fabs(fi - ri) / ri;
    std::printf("[balloon] cavity step %zu: V_fluid/V0 %.4f, V/V0 %.10f, p %.6f MPa; |V - V_fluid e^(-p/K)|/V0 %.1e; "
                "(r/Ri)^2 %.10f (rel %.1e); inner %.6f, radial solution at p %.6f (rel %.2e); spread along z %.1e\n",
                i + 1, fluid, v, p, law, fi * fi / (Ri * Ri), poly, fi, ri, ref, spread);
    worst_law = std::fmax(worst_law, law);
    worst_poly = std::fmax(worst_poly, poly);
    worst_ref = std::fmax(worst_ref, ref);
    EXPECT_GT(p, 0.0);
  }
  EXPECT_LT(worst_law, 1e-12);   // the state's own relation: round-off
  EXPECT_LT(worst_poly, 1e-10);  // the volume integral against the polygon's area
  EXPECT_LT(worst_ref, 2.5e-4);  // the pressure-driven coarse mesh's bound above
}

// A balloon held whole at its ends has a limit point near 0.1 MPa (the pressure-driven
// test above stops short of it): under volume control the run passes it, the pressure
// rising to a maximum, falling as a bulge forms, and rising again as the fibres stiffen.
TEST(BalloonInflation, FluidCavityPassesTheLimitPointOfAHeldBalloon) {
  const Balloon b{6.6, 0.2, 2, "all", 20, 5.0, 2200.0};
  const std::vector<State> st = run(b, 0.0, "cavity_limit");
  const stentor::testing::Series h = stentor::testing::read_csv(work_dir() / "cavity_limit" / "balloon_history.csv");
  ASSERT_GE(h.rows(), 20u);
  const std::vector<double>& p = h["pressure_inflation"];
  const std::size_t top = static_cast<std::size_t>(std::max_element(p.begin(), p.begin() + static_cast<long>(p.size() / 2 + 2)) - p.begin());
  const double low = *std::min_element(p.begin() + static_cast<long>(top), p.end());
  const std::size_t n = h.rows() - 1;
  std::printf("[balloon] held balloon under volume control: %zu steps; the largest pressure %.5f MPa at V/V0 %.3f (step "
              "%zu), falling to %.5f MPa, then %.5f MPa at V/V0 %.4f\n",
              h.rows(), p[top], h["volume_ratio_inflation"][top], top + 1, low, p[n], h["volume_ratio_inflation"][n]);
  EXPECT_GT(top, 0u);
  EXPECT_GT(p[top], 0.09);  // measured 0.1092 (pressure control stalled at 0.098-0.109)
  EXPECT_LT(p[top], 0.12);
  EXPECT_LT(low, p[top] - 0.005);  // the drop: measured to 0.1009
  EXPECT_GT(p[n], p[top]);         // and the rise: 0.1199 at V/V0 5
  EXPECT_NEAR(h["volume_ratio_inflation"][n], 5.0 * std::exp(-p[n] / b.bulk), 1e-12);
  EXPECT_NEAR(h["time"][n], 1.0, 1e-12);
}

// The cavity's tangent against central differences of the residual (the assembler alone):
// dr/du v = K v + c l (r . v), K the assembled matrix (the follower pressure's part at p) and
// c l r^T the rank-one term of Assembler::Cavity; and dV/du . v against differences of the
// volume. At a state off the radial solution (the balloon opened by 10 % plus a smooth
// non-homogeneous field), directions v with the constraints' rows held (zero on Dirichlet
// dofs, in the symmetry planes), free rows compared.
TEST(BalloonInflation, FluidCavityTangentMatchesFiniteDifferences) {
  for (const double K : {5.0, 2200.0}) {
    const Config cfg = deck(Balloon{1.2, 0.1, 2, "z", 4, 1.6, K}, 0.0, "cavity_fd");
    set_mesh_generator(&generate_mesh);
    stentor::testing::AssemblerFixture fx(cfg);
    const auto map = fx.dist->owned_map();
    la::Vector u(map), v(map), up(map), um(map), r(map), rp(map), rm(map), Jv(map);
    fx.fill(u, 0.05);
    fx.fill(v, 1.0, 0.3);
    {
      auto uh = u.getLocalViewHost(Tpetra::Access::ReadWrite);
      for (la::LO l = 0; l < fx.dist->num_owned_nodes(); ++l) {
        const double* X = fx.mesh.coord(fx.dist->global_node(l));
        if (std::hypot(X[0], X[1]) < 0.5 * (cfg.mesh.stent.inner_radius() + cfg.mesh.balloon.outer_radius()))
          uh(3 * l, 0) += 0.1 * X[0], uh(3 * l + 1, 0) += 0.1 * X[1];
        else uh(3 * l, 0) = uh(3 * l + 1, 0) = uh(3 * l + 2, 0) = 0.0;  // the stent at rest (thin struts invert under the field)
      }
    }
    fx.as->apply_dirichlet(u, 1.0, 1.0);
    {
      auto vh = v.getLocalViewHost(Tpetra::Access::ReadWrite);
      for (la::LO i = 0; i < static_cast<la::LO>(vh.extent(0)); ++i)
        if (fx.as->is_cartesian_dirichlet(i)) vh(i, 0) = 0.0;
    }
    fx.as->project_on_planes(v);
    ASSERT_EQ(fx.as->assemble(u, 1.0, 1.0, r, true).inverted, 0) << fx.as->smallest_det_f(3);
    const Assembler::Cavity c = fx.as->cavities().at(0);
    ASSERT_TRUE(c.on);
    ASSERT_GT(c.tangent_c, 0.0);
    fx.as->matrix()->apply(v, Jv);
    Jv.update(c.tangent_c * c.right->dot(v), *c.left, 1.0);
    const double h = 1e-6;
    up.update(1.0, u, h, v, 0.0);
    um.update(1.0, u, -h, v, 0.0);
    fx.as->assemble(up, 1.0, 1.0, rp, false);
    const double Vp = fx.as->cavities().at(0).V;
    fx.as->assemble(um, 1.0, 1.0, rm, false);
    const double Vm = fx.as->cavities().at(0).V;
    rp.update(-1.0 / (2.0 * h), rm, 1.0 / (2.0 * h));
    double diff = 0.0, norm = 0.0;
    {
      auto a = Jv.getLocalViewHost(Tpetra::Access::ReadOnly);
      auto b = rp.getLocalViewHost(Tpetra::Access::ReadOnly);
      for (la::LO i = 0; i < static_cast<la::LO>(a.extent(0)); ++i) {
        if (fx.as->is_dirichlet(i)) continue;
        diff = std::fmax(diff, std::fabs(a(i, 0) - b(i, 0)));
        norm = std::fmax(norm, std::fabs(b(i, 0)));
      }
    }
    const double dV = c.right->dot(v), dV_fd = (Vp - Vm) / (2.0 * h);
    la::Vector Kv(map);
    fx.as->matrix()->apply(v, Kv);
    Kv.update(-1.0, rp, 1.0);
    std::printf("[balloon] cavity K %g MPa: p %.5f MPa, V/V0 %.5f, c = K/V %.4e; |dr/du v - FD| / |FD| %.2e (without the "
                "rank-one term %.2e); dV/du . v %.10e, FD %.10e (rel %.1e)\n",
                K, c.p, c.V / c.V0, c.tangent_c, diff / norm, Kv.normInf() / norm, dV, dV_fd, std::fabs(dV - dV_fd) / std::fabs(dV_fd));
    EXPECT_LT(diff / norm, 1e-8);           // measured 5.0e-11 for both K
    EXPECT_GT(Kv.normInf(), 1e3 * diff);    // the rank-one term matters: 1.1e-5 and 5.0e-3 without it
    EXPECT_LT(std::fabs(dV - dV_fd), 1e-7 * std::fabs(dV_fd));  // measured 1.7e-9
  }
}
