// Necking (issue 11; docs/plasticity.md, "Necking"): the Considère point of the
// Ciarlet–Geymonat + von Mises + linear hardening law under uniaxial stress (closed form,
// against the material point driven in uniaxial stress) and in plane strain (material
// point against the rigid-plastic closed form), and a plane-strain strip with a 1.8%
// width imperfection (inputs/necking_strip.geo, tri6) pulled past its peak load: yield
// onset at the closed-form load, peak load at the Considère load of the weakest section,
// and the neck localising at mid-length.
//
// Units: mm, MPa, N (forces of the 2D model per mm of out-of-plane thickness).
#include <gtest/gtest.h>

#include <Tpetra_Core.hpp>
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "CsvSeries.hpp"
#include "deck/Config.hpp"
#include "material/Kinematics.hpp"
#include "material/Plasticity.hpp"
#include "run/Simulation.hpp"
#include "TestDir.hpp"

using namespace stentor;
namespace fs = std::filesystem;

namespace {

fs::path work_dir() { return stentor::testing::test_dir("necking"); }

// Simo's steel moduli (E = 206.9 GPa, nu = 0.29: mu = 2 C1, lambda = 4 D) and yield
// stress, with linear hardening H > Y (plane strain needs H > (sqrt 3 / 2) Y).
const CiarletGeymonatPlasticity kSteel{CiarletGeymonat{40097.0, 0.0, 27686.0}, 450.0, 540.0};

Mat3 diag3(double a, double b, double c) {
  Mat3 F = Mat3::zero();
  F(0, 0) = a, F(1, 1) = b, F(2, 2) = c;
  return F;
}

// ---- Uniaxial stress, closed form. Axial Kirchhoff (= Mandel, = |M|_H) stress of the
// elastic stretch le with free lateral faces (docs/plasticity.md, "Uniaxial closed form").
double tau_axial(const CiarletGeymonat& e, double le) {
  const double K = e.K(), l2 = le * le, a = e.C2 + e.D * l2, b = e.C1 + e.C2 * l2;
  const double m = 2.0 * K / (b + std::sqrt(b * b + 4.0 * a * K));
  return 2.0 * (e.C1 * l2 + 2.0 * e.C2 * l2 * m + e.D * l2 * m * m - e.K());
}

// Elastic tangent E_t = d tau / d ln le (central difference of the closed form, h = 1e-5:
// relative error ~1e-10).
double tangent_axial(const CiarletGeymonat& e, double le) {
  const double h = 1e-5;
  return (tau_axial(e, le * std::exp(h)) - tau_axial(e, le * std::exp(-h))) / (2.0 * h);
}

// ---- Plane strain (F = diag(lam, l, 1)), elastic, S22 = 0, in closed form: S22 =
// 2[C1 + C2 I1 - C2 m + (D I3 - K)/m] = 0 with m = l^2, I1 = lam^2 + m + 1, I3 = lam^2 m is
// linear in m: m = K / (C1 + C2 (lam^2 + 1) + D lam^2). Principal Mandel stresses
// M_A = c_A S_A = 2[(C1 + C2 I1) c_A - C2 c_A^2 + D I3 - K] (M_2 = 0), |M|_H from them,
// nominal stress P11 = M_1 / lam. Yield: |M|_H(lam_y) = Y (bisection).
struct Elastic2D {
  double hill, P;
};
Elastic2D plane_strain_elastic(const CiarletGeymonat& e, double lam) {
  const double l2 = lam * lam, m = e.K() / (e.C1 + e.C2 * (l2 + 1.0) + e.D * l2);
  const double I1 = l2 + m + 1.0, I3 = l2 * m, c[3] = {l2, m, 1.0};
  double M[3];
  for (int A = 0; A < 3; ++A) M[A] = 2.0 * ((e.C1 + e.C2 * I1) * c[A] - e.C2 * c[A] * c[A] + e.D * I3 - e.K());
  const double q = std::sqrt(0.5 * ((M[0] - M[1]) * (M[0] - M[1]) + (M[1] - M[2]) * (M[1] - M[2]) + (M[2] - M[0]) * (M[2] - M[0])));
  return {q, M[0] / lam};
}
Elastic2D plane_strain_yield(const CiarletGeymonatPlasticity& m, double& lam_y) {
  double lo = 1.0, hi = 1.5;
  for (int i = 0; i < 200; ++i) (plane_strain_elastic(m.elastic, 0.5 * (lo + hi)).hill < m.Y ? lo : hi) = 0.5 * (lo + hi);
  lam_y = 0.5 * (lo + hi);
  return plane_strain_elastic(m.elastic, lam_y);
}

struct Considere {
  double lambda, tau, alpha, P;  // total stretch, Kirchhoff stress, alpha, nominal stress
};

// Considère point in uniaxial stress. The force F = tau A0 / lambda (A = J A0 / lambda,
// tau = J sigma) is stationary where d tau / d ln lambda = tau. After yield the axial flow
// direction is fixed (n = (1, -1/2, -1/2)), so ln lambda = ln le + alpha with
// tau(le) = Y + H alpha: d tau / d ln lambda = (1/H + 1/E_t(le))^-1. The peak is at the le
// with tau(le) = (1/H + 1/E_t(le))^-1 (bisection), alpha = (tau - Y)/H, lambda = le e^alpha,
// P = tau / lambda. Rigid-plastic limit (E_t -> inf): tau = H, alpha = 1 - Y/H.
Considere considere_uniaxial(const CiarletGeymonatPlasticity& m) {
  auto g = [&](double le) { return tau_axial(m.elastic, le) - 1.0 / (1.0 / m.H + 1.0 / tangent_axial(m.elastic, le)); };
  double lo = 1.0, hi = 1.5;
  for (int i = 0; i < 200; ++i) (g(0.5 * (lo + hi)) < 0.0 ? lo : hi) = 0.5 * (lo + hi);
  const double le = 0.5 * (lo + hi), tau = tau_axial(m.elastic, le), alpha = (tau - m.Y) / m.H;
  return {le * std::exp(alpha), tau, alpha, tau / (le * std::exp(alpha))};
}

// ---- Material point driven in a stress state S22 = 0 with F = diag(lam, l, l) (uniaxial,
// S33 = S22 by symmetry) or diag(lam, l, 1) (plane strain): Newton on the lateral stretch l
// with the consistent tangent, dS22/dl = (CC_2222 [+ CC_2233]) l.
PointResponse drive(const CiarletGeymonatPlasticity& m, bool plane, double lam, double& l, const PlasticState& s0,
                    CiarletGeymonatPlasticity::Step& st) {
  PointResponse r;
  for (int it = 0; it < 50; ++it) {
    r = m.update_state(right_cauchy_green(diag3(lam, l, plane ? 1.0 : l)), s0, st);
    if (std::fabs(r.S(1, 1)) <= 1e-12 * m.Y) break;
    l -= r.S(1, 1) / ((r.CC(1, 1, 1, 1) + (plane ? 0.0 : r.CC(1, 1, 2, 2))) * l);
  }
  return r;
}

// Monotonic loading to lam_max in `steps` equal steps; the maximum of the nominal stress
// P11 = lam S11 (parabola through the largest sample and its neighbours) and its stretch.
// Also the yield stretch and nominal stress (first flow, bracketed by bisection on lam).
struct Drive {
  double P_max, lam_max, P_yield, lam_yield;
};
Drive drive_to_peak(const CiarletGeymonatPlasticity& m, bool plane, double lam_end, int steps) {
  PlasticState s{Mat3::identity(), 0.0};
  std::vector<double> lam(1, 1.0), P(1, 0.0);
  double l = 1.0;
  for (int k = 1; k <= steps; ++k) {
    CiarletGeymonatPlasticity::Step st;
    const double x = 1.0 + (lam_end - 1.0) * k / steps;
    const PointResponse r = drive(m, plane, x, l, s, st);
    EXPECT_TRUE(r.converged);
    s = st.state;
    lam.push_back(x);
    P.push_back(x * r.S(0, 0));
  }
  const std::size_t i = static_cast<std::size_t>(std::max_element(P.begin(), P.end()) - P.begin());
  EXPECT_TRUE(i > 0 && i + 1 < P.size()) << "no interior maximum of P up to lambda = " << lam_end;
  Drive d{};
  const double h = lam[i + 1] - lam[i], a = 0.5 * (P[i + 1] - 2.0 * P[i] + P[i - 1]) / (h * h),
               b = 0.5 * (P[i + 1] - P[i - 1]) / h;
  d.lam_max = lam[i] - b / (2.0 * a);
  d.P_max = P[i] - b * b / (4.0 * a);
  // Yield: the largest stretch still elastic from the virgin state (bisection).
  double lo = 1.0, hi = lam_end, ll = 1.0;
  for (int it = 0; it < 60; ++it) {
    CiarletGeymonatPlasticity::Step st;
    const double x = 0.5 * (lo + hi);
    ll = 1.0;
    drive(m, plane, x, ll, PlasticState{Mat3::identity(), 0.0}, st);
    (st.dgamma > 0.0 ? hi : lo) = x;
  }
  CiarletGeymonatPlasticity::Step st;
  ll = 1.0;
  const PointResponse r = drive(m, plane, lo, ll, PlasticState{Mat3::identity(), 0.0}, st);
  d.lam_yield = lo;
  d.P_yield = lo * r.S(0, 0);
  return d;
}

}  // namespace

// Uniaxial stress: the Considère closed form above against the material point driven in
// uniaxial stress (400 steps to lambda = 1.8; the axial flow direction is fixed, so every
// step is exact and only the parabola through the samples is approximate).
TEST(Necking, ConsidereUniaxialClosedFormAtMaterialPoint) {
  for (const double H : {540.0, 600.0, 900.0}) {
    CiarletGeymonatPlasticity m = kSteel;
    m.H = H;
    const Considere c = considere_uniaxial(m);
    const Drive d = drive_to_peak(m, false, 1.8, 400);
    std::printf("[ measured ] uniaxial H = %g: Considere closed form P_c = %.6f MPa at lambda %.6f "
                "(rigid-plastic %.6f at %.6f); material point %.6f at %.6f; P_y = %.6f\n",
                H, c.P, c.lambda, H * std::exp(m.Y / H - 1.0), std::exp(1.0 - m.Y / H), d.P_max, d.lam_max, d.P_yield);
    EXPECT_NEAR(d.P_max / c.P, 1.0, 1e-8);
    EXPECT_NEAR(d.lam_max, c.lambda, 2e-3);
    EXPECT_NEAR(c.alpha, 1.0 - m.Y / H, 0.01);  // rigid-plastic limit, O(Y/E) apart
    EXPECT_GT(c.P, d.P_yield);                   // a true maximum above first yield
  }
}

// Plane strain (F33 = 1, S22 = 0): the flow direction turns slightly as the elastic
// out-of-plane strain builds up, so the material point is driven in small steps (1000 and
// 2000 to lambda = 1.7 agree to 1.7e-6: first order in the step). Rigid-plastic closed form: n3 = 0 gives
// tau3 = tau1/2, |M|_H = (sqrt 3 / 2) tau1, ln lambda = (sqrt 3 / 2) alpha, so
// tau1 = (2/sqrt 3) Y + (4/3) H ln lambda, and d tau1 / d ln lambda = tau1 at
// tau1_c = 4H/3, ln lambda_c = 1 - (sqrt 3 / 2) Y / H, P_c = tau1_c / lambda_c (the force
// per unit thickness is again tau1 w0 / lambda). Yield onset: the closed form above
// (small strain: P_y = Y / sqrt(1 - nu + nu^2), not the rigid-plastic (2/sqrt 3) Y).
TEST(Necking, ConsiderePlaneStrainAtMaterialPoint) {
  const CiarletGeymonatPlasticity& m = kSteel;
  const Drive d1 = drive_to_peak(m, true, 1.7, 1000), d2 = drive_to_peak(m, true, 1.7, 2000);
  const double lnl = 1.0 - std::sqrt(3.0) / 2.0 * m.Y / m.H, Pc_rigid = 4.0 * m.H / 3.0 * std::exp(-lnl);
  std::printf("[ measured ] plane strain: material point P_c = %.6f MPa at lambda %.5f (1000 steps: %.6f); "
              "rigid-plastic %.6f at %.5f; P_y = %.6f at lambda %.7f\n",
              d2.P_max, d2.lam_max, d1.P_max, Pc_rigid, std::exp(lnl), d2.P_yield, d2.lam_yield);
  double lam_y;
  const Elastic2D y = plane_strain_yield(m, lam_y);
  std::printf("[ measured ] plane strain yield: closed form P_y = %.8f at lambda %.9f, material point %.8f at %.9f\n",
              y.P, lam_y, d2.P_yield, d2.lam_yield);
  EXPECT_NEAR(d1.P_max / d2.P_max, 1.0, 1e-5);
  EXPECT_NEAR(d2.P_max / Pc_rigid, 1.0, 5e-3);
  EXPECT_NEAR(d2.lam_max / std::exp(lnl), 1.0, 5e-3);
  EXPECT_NEAR(d2.P_yield / y.P, 1.0, 1e-9);
  EXPECT_NEAR(d2.lam_yield / lam_y, 1.0, 1e-12);
  EXPECT_GT(d2.P_max, 1.05 * y.P);
}

namespace {

// ---- The plane-strain strip (inputs/necking_strip.geo, one quarter, tri6): width
// 2W = 12.826 mm, length 53.334 mm, width reduced by 1.8% at mid-length. Symmetry on
// `mid` (x = 0) and `axis` (y = 0), the end x = L/2 pulled by U (lateral motion free).
// The ramp takes 2 steps to 0.9 u_y, 20 steps of 1% u_y to 1.1 u_y (the yield onset),
// then the rest in equal steps (u_y: end displacement at first yield, estimated from the
// closed-form yield stretch).
constexpr double kW = 6.413, kL = 53.334, kImperfection = 0.018, kU = 14.0;
constexpr int kSteps = 80;

std::string strip_deck(const CiarletGeymonatPlasticity& m, double u_y, const std::string& name) {
  const std::string geo = std::string(STENTOR_SOURCE_DIR) + "/inputs/necking_strip.geo";
  std::ostringstream ramp_t, ramp_f;
  ramp_t.precision(17), ramp_f.precision(17);
  ramp_t << "{0, " << 2.0 / kSteps << ", " << 22.0 / kSteps << ", 1}";
  ramp_f << "{0, " << 0.9 * u_y / kU << ", " << 1.1 * u_y / kU << ", 1}";
  std::ostringstream mat;
  mat.precision(17);
  mat << R"X(<Parameter name="C1" type="double" value=")X" << m.elastic.C1 << R"X("/>
    <Parameter name="C2" type="double" value=")X" << m.elastic.C2 << R"X("/>
    <Parameter name="D" type="double" value=")X" << m.elastic.D << R"X("/>
    <Parameter name="model" type="string" value="Ciarlet-Geymonat plasticity"/>
    <Parameter name="yield stress" type="double" value=")X" << m.Y << R"X("/>
    <Parameter name="hardening" type="double" value=")X" << m.H << R"X("/>)X";
  return R"X(<ParameterList name="stentor">
  <ParameterList name="Mesh">
    <Parameter name="file" type="string" value=")X" + geo + R"X("/>
    <Parameter name="order" type="int" value="2"/>
  </ParameterList>
  <ParameterList name="Materials"><ParameterList name="steel">
    )X" + mat.str() + R"X(
  </ParameterList></ParameterList>
  <ParameterList name="Bodies"><ParameterList name="strip">
    <Parameter name="material" type="string" value="steel"/>
  </ParameterList></ParameterList>
  <ParameterList name="Boundary Conditions">
    <ParameterList name="mid"><Parameter name="type" type="string" value="Dirichlet"/>
      <Parameter name="boundary" type="string" value="mid"/><Parameter name="components" type="string" value="x"/></ParameterList>
    <ParameterList name="axis"><Parameter name="type" type="string" value="Dirichlet"/>
      <Parameter name="boundary" type="string" value="axis"/><Parameter name="components" type="string" value="y"/></ParameterList>
    <ParameterList name="pull"><Parameter name="type" type="string" value="Dirichlet"/>
      <Parameter name="boundary" type="string" value="end"/><Parameter name="components" type="string" value="x"/>
      <Parameter name="values" type="Array(double)" value="{)X" + std::to_string(kU) + R"X(}"/>
      <Parameter name="ramp" type="string" value="table"/>
      <Parameter name="ramp times" type="Array(double)" value=")X" + ramp_t.str() + R"X("/>
      <Parameter name="ramp factors" type="Array(double)" value=")X" + ramp_f.str() + R"X("/></ParameterList>
  </ParameterList>
  <ParameterList name="Stepping">
    <Parameter name="end time" type="double" value="1.0"/>
    <Parameter name="steps" type="int" value=")X" + std::to_string(kSteps) + R"X("/>
  </ParameterList>
  <ParameterList name="Linear Solver"><Parameter name="method" type="string" value="direct"/></ParameterList>
  <ParameterList name="Output">
    <Parameter name="basename" type="string" value=")X" + name + R"X("/>
    <Parameter name="fields" type="bool" value="false"/>
    <ParameterList name="Probes">
      <ParameterList name="neck"><Parameter name="point" type="Array(double)" value="{0, )X" +
         std::to_string((1.0 - kImperfection) * kW) + R"X(}"/></ParameterList>
      <ParameterList name="shoulder"><Parameter name="point" type="Array(double)" value="{)X" +
         std::to_string(kL / 2) + ", " + std::to_string(kW) + R"X(}"/></ParameterList>
    </ParameterList>
  </ParameterList>
</ParameterList>
)X";
}

}  // namespace

// The strip pulled past its peak (80 steps plus cut-backs at the ramp's kink, 594 dofs,
// ~4 s). Checked against the closed forms (plane strain, weakest section w_min = 0.982 W):
//  - yield onset at F_y = P_y w_min (P_y: closed-form elastic plane-strain state at
//    |M|_H = Y): the straight elastic part of the force-elongation curve (force
//    increments within 10% of the elastic one, steps of 1% of F_y there) ends at F_y to
//    0.2% and the next step is above F_y; the first Gauss point yields at most 2% earlier (the mirrored taper has a kink at mid-length, a mild
//    stress concentration on the free edge);
//  - peak load within 1% above F_c = P_c w_min, the Considère load of the weakest section
//    (P_c: the plane-strain material point above), and below that of the uniform strip
//    P_c W;
//  - localisation: after the peak the shoulder (end) thins by less than 0.5% of W (it
//    flows a little more, then unloads elastically) while the neck thins by more than 30%
//    of W; at the end the neck's width ratio w/w0 is below 0.3 times the shoulder's.
TEST(Necking, PlaneStrainStripPeakLoadAndLocalisation) {
  const CiarletGeymonatPlasticity& m = kSteel;
  const Drive mp = drive_to_peak(m, true, 1.7, 2000);
  double lam_y;
  const Elastic2D y = plane_strain_yield(m, lam_y);
  const double w0_neck = (1.0 - kImperfection) * kW;
  const double F_y = y.P * w0_neck, F_c = mp.P_max * w0_neck;
  const double u_y = (lam_y - 1.0) * 0.5 * kL * (1.0 - 0.5 * kImperfection);
  const std::string name = "strip";
  fs::create_directories(work_dir());
  const fs::path deck = work_dir() / (name + ".xml");
  std::ofstream(deck) << strip_deck(m, u_y, name);
  const Config cfg = read_deck(deck.string());
  RunOptions o;
  o.output_dir = (work_dir() / name).string();
  o.overwrite = true;
  ASSERT_EQ(run_simulation(cfg, o), 0);
  const auto h = stentor::testing::read_csv(work_dir() / name / (name + "_history.csv"));
  ASSERT_GE(h.rows(), static_cast<std::size_t>(kSteps));
  const std::size_t n = h.rows() + 1, last = n - 1;  // row 0: the undeformed state
  std::vector<double> F(n, 0.0), w_neck(n, w0_neck), w_end(n, kW), Dp(n, 0.0);
  for (std::size_t i = 1; i < n; ++i) {
    F[i] = std::fabs(h["reaction_pull_x"][i - 1]);
    w_neck[i] = w0_neck + h["u_neck_y"][i - 1];
    w_end[i] = kW + h["u_shoulder_y"][i - 1];
    Dp[i] = h["plastic_dissipation"][i - 1];
  }
  std::size_t first = 0, knee = 0;
  for (std::size_t i = 1; i < n && !first; ++i)
    if (Dp[i] > 0.0) first = i;
  const double dF_elastic = F[4] - F[3];  // 1% of u_y, elastic
  for (std::size_t i = 4; i < n && !knee; ++i)
    if (F[i] - F[i - 1] < 0.9 * dF_elastic) knee = i;
  ASSERT_GT(first, 3u);
  ASSERT_GT(knee, first);
  const std::size_t ipk = static_cast<std::size_t>(std::max_element(F.begin(), F.end()) - F.begin());
  const double neck_ratio = (w_neck[last] / w0_neck) / (w_end[last] / kW);
  std::printf("[ measured ] strip: closed-form yield F_y = %.2f N/mm; first plastic point at F = %.2f (%.2f%%), "
              "elastic line ends at %.2f (%+.3f%%), next %.2f; peak %.2f N/mm at step %d, Considere F_c = %.2f (%+.3f%%), "
              "uniform strip %.2f; final force %.2f; neck w/w0 = %.4f (at the peak %.4f), shoulder %.4f (at the "
              "peak %.4f), ratio %.4f\n",
              F_y, F[first], 100.0 * (F[first] / F_y - 1.0), F[knee - 1], 100.0 * (F[knee - 1] / F_y - 1.0), F[knee],
              F[ipk], static_cast<int>(ipk), F_c, 100.0 * (F[ipk] / F_c - 1.0), mp.P_max * kW, F[last],
              w_neck[last] / w0_neck, w_neck[ipk] / w0_neck, w_end[last] / kW, w_end[ipk] / kW, neck_ratio);
  // Yield onset.
  EXPECT_NEAR(F[knee - 1] / F_y, 1.0, 2e-3);
  EXPECT_GT(F[knee], F_y);
  EXPECT_GT(F[first], 0.98 * F_y);
  EXPECT_LT(F[first - 1], F_y);
  // Peak load: an interior maximum, within 1% above the weakest section's Considère load.
  EXPECT_GT(F[ipk], F_c);
  EXPECT_LT(F[ipk], 1.01 * F_c);
  EXPECT_LT(F[ipk], mp.P_max * kW);
  EXPECT_LT(ipk, last - 10);
  EXPECT_LT(F[last], 0.8 * F[ipk]);
  // Localisation.
  EXPECT_LT(w_end[ipk] - w_end[last], 5e-3 * kW);
  EXPECT_LT(w_neck[last], w_neck[ipk] - 0.3 * kW);
  EXPECT_LT(neck_ratio, 0.3);
}
