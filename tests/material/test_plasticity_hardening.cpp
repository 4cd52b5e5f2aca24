// Nonlinear isotropic hardening of MultiplicativePlasticity (src/material/IsotropicHardening.hpp,
// src/material/Plasticity.hpp; docs/plasticity.md, "Hardening laws"): the hardening functions
// against their closed forms, uniaxial tension against the 1D curve sigma_y(alpha), the
// consistent tangent against central differences (Voce; a table, across its kinks and past its
// last point), the one-step energy identity with Dp >= Y dg, the incremental potential of the
// dynamic step (its gradient is the stress, Dp = Y dg) and linear = Voce with Y_inf = Y bitwise.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include "MaterialSamples.hpp"
#include "material/DiscreteGradient.hpp"
#include "material/Kinematics.hpp"
#include "material/MaterialState.hpp"
#include "material/Plasticity.hpp"

using stentor::CiarletGeymonat;
using stentor::CiarletGeymonatPlasticity;
using stentor::Mat3;
using stentor::max_abs;
using stentor::NeoHookean;
using stentor::NeoHookeanPlasticity;
using stentor::NonlinearHardening;
using stentor::PlasticState;
using stentor::PointResponse;
using stentor::Ten4;
using stentor::testing::diag;
using stentor::testing::kMats;
using stentor::testing::sym_unit;

namespace {

// A concave table with kinks at alpha = 0.03, 0.1, 0.25 (slopes 2, 0.857, 0.2, then 0.2 past
// the last point) and a Voce law, both from Y = 0.1 (moduli of order 1: yield near 1.5% strain).
// The stresses scale with the elastic moduli (x 50 for the nearly incompressible set).
const double kEps[] = {0.0, 0.03, 0.1, 0.25};
const double kSig[] = {0.1, 0.16, 0.22, 0.25};
NonlinearHardening table(double scale = 1.0) {
  const double s[] = {scale * kSig[0], scale * kSig[1], scale * kSig[2], scale * kSig[3]};
  return NonlinearHardening::table(kEps, s, 4);
}
NonlinearHardening voce(double Y, double Yinf, double delta) { return NonlinearHardening::voce(Y, Yinf, delta); }

template <class L>
L with(L m, const NonlinearHardening& h) {
  m.nonlinear = h;
  return m;
}

const CiarletGeymonatPlasticity kCG[] = {
    with(CiarletGeymonatPlasticity{kMats[0], 0.1, 0.05}, voce(0.1, 0.3, 20.0)),
    with(CiarletGeymonatPlasticity{kMats[1], 5.0, 2.0}, voce(5.0, 15.0, 10.0)),
    with(CiarletGeymonatPlasticity{kMats[0], 0.1, 0.0}, table()),
    with(CiarletGeymonatPlasticity{kMats[1], 5.0, 0.0}, table(50.0))};
const NeoHookeanPlasticity kNH[] = {with(NeoHookeanPlasticity{NeoHookean{1.0, 1.5}, 0.1, 0.05}, voce(0.1, 0.3, 20.0)),
                                    with(NeoHookeanPlasticity{NeoHookean{1.0, 1.5}, 0.1, 0.0}, table())};

PlasticState virgin() { return {Mat3::identity(), 0.0}; }

// Distance of alpha to the nearest kink of the table (1e300 for other laws).
template <class L>
double kink_distance(const L& m, double alpha) {
  double d = 1e300;
  if (m.nonlinear.kind == NonlinearHardening::kTable)
    for (int i = 1; i < m.nonlinear.n; ++i) d = std::fmin(d, std::fabs(alpha - m.nonlinear.eps[i]));
  return d;
}

// A random walk F_{k+1} = F_k + delta U (U uniform in [-1, 1]^{3x3}, det >= 0.5) from the
// virgin state; f(C0, C1, s0) at each step, then the state moves on.
template <class L, class Fn>
void walk(const L& m, double delta, unsigned seed, int walks, int nsteps, Fn&& f) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int w = 0; w < walks; ++w) {
    PlasticState s = virgin();
    Mat3 F = Mat3::identity();
    for (int k = 0; k < nsteps; ++k) {
      Mat3 F1;
      do {
        F1 = F;
        for (int i = 0; i < 3; ++i)
          for (int j = 0; j < 3; ++j) F1(i, j) += delta * u(rng);
      } while (stentor::det(F1) < 0.5);
      const Mat3 C0 = stentor::right_cauchy_green(F), C1 = stentor::right_cauchy_green(F1);
      f(C0, C1, s);
      typename L::Step st;
      m.update_state(C1, s, st);
      s = st.state, F = F1;
    }
  }
}

// max |CC - central FD (h = 1e-6)| / max |CC| at (C, s0).
template <class L>
double tangent_error(const L& m, const Mat3& C, const PlasticState& s0) {
  typename L::Step st;
  const PointResponse r = m.update_state(C, s0, st);
  const double h = 1e-6;
  double err = 0.0;
  for (int K = 0; K < 3; ++K)
    for (int L2 = K; L2 < 3; ++L2) {
      const Mat3 E = sym_unit(K, L2);
      const Mat3 Sp = m.update_state(C + h * E, s0, st).S, Sm = m.update_state(C - h * E, s0, st).S;
      for (int I = 0; I < 3; ++I)
        for (int J = 0; J < 3; ++J) err = std::fmax(err, std::fabs((Sp(I, J) - Sm(I, J)) / h - r.CC(I, J, K, L2)));
    }
  return err / max_abs(r.CC);
}

// Uniaxial stress (S22 = S33 = 0) at axial stretch lam from s0: scalar Newton on the lateral
// stretch l (initial guess in, result out), as in test_plasticity.
template <class L>
PointResponse uniaxial(const L& m, double lam, double& l, const PlasticState& s0, typename L::Step& st) {
  PointResponse r;
  for (int it = 0; it < 50; ++it) {
    r = m.update_state(stentor::right_cauchy_green(diag(lam, l, l)), s0, st);
    if (std::fabs(r.S(1, 1)) <= 1e-13 * m.Y) break;
    l -= r.S(1, 1) / ((r.CC(1, 1, 1, 1) + r.CC(1, 1, 2, 2)) * l);
  }
  return r;
}

// Ciarlet-Geymonat in uniaxial stress, closed form (test_plasticity): lateral m = l^2 and the
// axial Kirchhoff stress at stretch lam.
double axial_tau(const CiarletGeymonat& e, double lam) {
  const double a = e.C2 + e.D * lam * lam, b = e.C1 + e.C2 * lam * lam;
  const double c = lam * lam, m = 2.0 * e.K() / (b + std::sqrt(b * b + 4.0 * a * e.K()));
  return 2.0 * (e.C1 * c + 2.0 * e.C2 * c * m + e.D * c * m * m - e.K());
}

}  // namespace

// kappa, psi and their increments against their definitions: d psi/d alpha = kappa (central
// differences), psi(a0 + dg) - psi(a0) = the increment, kappa' = slope, the table through its
// points and extrapolated linearly, phi's series continuous with the direct formula.
TEST(Hardening, FunctionsAgainstTheirDefinitions) {
  const NonlinearHardening hs[] = {voce(0.1, 0.3, 20.0), voce(5.0, 15.0, 0.5), table()};
  double e_psi = 0.0, e_inc = 0.0, e_slope = 0.0;
  for (const auto& h : hs)
    for (double a = 0.0013; a < 0.6; a += 0.0173) {
      const double d = 1e-6, scale = std::fmax(1.0, std::fabs(h.kappa(a)));
      e_psi = std::fmax(e_psi, std::fabs((h.energy(a + d) - h.energy(a - d)) / (2 * d) - h.kappa(a)) / scale);
      e_slope = std::fmax(e_slope, std::fabs((h.kappa(a + d) - h.kappa(a - d)) / (2 * d) - h.slope(a)) /
                                       std::fmax(1.0, std::fabs(h.slope(a))));
      for (const double dg : {1e-9, 1e-4, 0.07, 0.4}) {
        const double inc = h.energy_increment(a, dg), diff = h.energy(a + dg) - h.energy(a);
        e_inc = std::fmax(e_inc, std::fabs(inc - diff) / std::fmax(1e-300, std::fabs(h.energy(a + dg))));
        EXPECT_GE(inc, 0.0);
        // Convexity: kappa(a0) dg <= psi increment <= kappa(a1) dg.
        EXPECT_LE(h.kappa(a) * dg, inc * (1 + 1e-12) + 1e-300);
        EXPECT_LE(inc, h.kappa(a + dg) * dg * (1 + 1e-12) + 1e-300);
        EXPECT_NEAR(h.kappa_increment(a, dg), h.kappa(a + dg) - h.kappa(a), 1e-14 * std::fmax(1.0, h.kappa(a + dg)));
      }
    }
  const NonlinearHardening t = table();
  for (int i = 0; i < 4; ++i) EXPECT_NEAR(t.kappa(kEps[i]), kSig[i] - kSig[0], 1e-16);
  EXPECT_NEAR(t.kappa(0.45), 0.15 + 0.2 * 0.2, 1e-15);  // past the last point: slope 0.2
  EXPECT_NEAR(t.energy(0.03), 0.5 * 0.03 * 0.06, 1e-17);
  const NonlinearHardening v = voce(0.1, 0.3, 20.0);
  EXPECT_NEAR(v.kappa(0.1), 0.2 * (1 - std::exp(-2.0)), 1e-16);
  EXPECT_NEAR(v.energy(0.1), 0.2 * (0.1 - (1 - std::exp(-2.0)) / 20.0), 1e-16);
  for (const double x : {0.0499999, 0.05})  // series and direct formula meet at 0.05
    EXPECT_NEAR(NonlinearHardening::phi(x), x + std::expm1(-x), 2e-14 * x * x);
  std::printf("[ measured ] d psi/d alpha - kappa %.2e, psi increment %.2e, kappa' %.2e\n", e_psi, e_inc, e_slope);
  EXPECT_LT(e_psi, 1e-8);
  EXPECT_LT(e_inc, 1e-13);
  EXPECT_LT(e_slope, 1e-7);
}

// Uniaxial tension of the Ciarlet-Geymonat laws to lam = 1.5 in 100 steps. The flow direction
// is fixed (diag(1, -1/2, -1/2)), so the exponential update is exact and the finite-strain
// closed form is the scalar equation tau(lam_e) = sigma_y(alpha), ln lam = ln lam_e + alpha
// (tau the elastic uniaxial Kirchhoff stress): the return map must follow the 1D curve
// tau = sigma_y(alpha) along the whole path, through the table's kinks and past its last point.
TEST(Hardening, UniaxialTensionFollowsTheHardeningCurve) {
  double e_curve = 0.0, e_alpha = 0.0;
  for (const auto& m : kCG) {
    PlasticState s = virgin();
    double l = 1.0;
    for (int k = 1; k <= 100; ++k) {
      const double lam = 1.0 + 0.5 * k / 100.0;
      CiarletGeymonatPlasticity::Step st;
      const PointResponse r = uniaxial(m, lam, l, s, st);
      ASSERT_TRUE(r.converged);
      s = st.state;
      if (s.alpha == 0.0) continue;
      const double tau = lam * lam * r.S(0, 0);
      e_curve = std::fmax(e_curve, std::fabs(tau - m.yield_stress(s.alpha)) / m.Y);
      // Closed form: bisection on alpha of tau(lam e^-alpha) - sigma_y(alpha) (decreasing).
      double lo = 0.0, hi = std::log(lam);
      for (int it = 0; it < 200; ++it) {
        const double a = 0.5 * (lo + hi);
        (axial_tau(m.elastic, lam * std::exp(-a)) > m.yield_stress(a) ? lo : hi) = a;
      }
      e_alpha = std::fmax(e_alpha, std::fabs(s.alpha - 0.5 * (lo + hi)));
    }
    EXPECT_GT(s.alpha, 0.3);  // past the table's last point (0.25)
  }
  std::printf("[ measured ] uniaxial: max |tau - sigma_y(alpha)|/Y = %.2e, |alpha - closed form| = %.2e\n", e_curve,
              e_alpha);
  EXPECT_LT(e_curve, 1e-10);
  EXPECT_LT(e_alpha, 1e-10);
}

// Consistent tangent against central differences at plastic points of random walks (large
// steps: alpha up to ~1, so the table's points are crossed and passed), both elastic parts.
// Table points whose alpha_{n+1} lies within 1e-4 of a kink are not differentiable there
// (sigma_y' jumps; a perturbation of C by 1e-6 moves alpha by ~1e-6): they are counted
// and left out of the comparison, and the test requires points beyond every kink.
template <class L>
void check_tangent(const L& m, unsigned seed, double& worst, int& plastic, int& near_kink, int (&beyond)[4]) {
  walk(m, 0.08, seed, 20, 8, [&](const Mat3&, const Mat3& C1, const PlasticState& s0) {
    typename L::Step st;
    const PointResponse r = m.update_state(C1, s0, st);
    ASSERT_TRUE(r.converged);
    if (st.dgamma == 0.0) return;
    if (kink_distance(m, st.state.alpha) < 1e-4) {
      ++near_kink;
      return;
    }
    ++plastic;
    for (int i = 1; i < 4; ++i) beyond[i] += m.nonlinear.kind == NonlinearHardening::kTable && st.state.alpha > kEps[i];
    worst = std::fmax(worst, tangent_error(m, C1, s0));
  });
}

TEST(Hardening, TangentMatchesFiniteDifferences) {
  double worst[2] = {0.0, 0.0};
  int plastic = 0, near_kink = 0, beyond[4] = {0, 0, 0, 0};
  unsigned seed = 5;
  for (const auto& m : kCG) check_tangent(m, seed++, worst[0], plastic, near_kink, beyond);
  for (const auto& m : kNH) check_tangent(m, seed++, worst[1], plastic, near_kink, beyond);
  std::printf("[ measured ] |CC - FD|/|CC|: Ciarlet-Geymonat %.2e, neo-Hookean %.2e; %d plastic points (%d/%d/%d "
              "past the table points 0.03/0.1/0.25), %d within 1e-4 of a kink\n",
              worst[0], worst[1], plastic, beyond[1], beyond[2], beyond[3], near_kink);
  EXPECT_GT(plastic, 400);
  EXPECT_GT(beyond[3], 20);
  EXPECT_LT(worst[0], 1e-6);
  EXPECT_LT(worst[1], 1e-6);
}

// Psi_{n+1} - Psi_n = [W(Ce^tr) - W(Ce_n)] - Dp (the elastic-predictor work at frozen Ftr_n)
// to round-off, and Dp >= Y dg (convexity of psi_h and of W in log strains) over random chains.
template <class L>
void energy_chain(const L& m, unsigned seed, double& identity, double& bound, int& plastic) {
  walk(m, 0.05, seed, 20, 20, [&](const Mat3& C0, const Mat3& C1, const PlasticState& s0) {
    typename L::Step st;
    const PointResponse r = m.template update_state<false>(C1, s0, st);
    const stentor::FrozenPotential<decltype(m.elastic)> frozen{m.elastic, stentor::inverse(s0.Ftr)};
    const double psi_n = frozen.energy(C0) + m.hardening_energy(s0.alpha);
    const double work = frozen.energy(C1) - frozen.energy(C0);
    const double scale = std::fabs(psi_n) + std::fabs(r.energy) + r.dissipation;
    identity = std::fmax(identity, std::fabs(r.energy - psi_n - (work - r.dissipation)) / scale);
    if (st.dgamma > 0.0) {
      ++plastic;
      bound = std::fmin(bound, r.dissipation / (m.Y * st.dgamma));
    }
  });
}

TEST(Hardening, EnergyIdentityAndDissipationBound) {
  double identity = 0.0, bound = 1e300;
  int plastic = 0;
  unsigned seed = 17;
  for (const auto& m : kCG) energy_chain(m, seed++, identity, bound, plastic);
  for (const auto& m : kNH) energy_chain(m, seed++, identity, bound, plastic);
  std::printf("[ measured ] energy identity %.2e (relative), min Dp / (Y dg) = %.4f over %d plastic steps\n", identity,
              bound, plastic);
  EXPECT_GT(plastic, 1000);
  EXPECT_LT(identity, 1e-12);
  EXPECT_GE(bound, 1.0);
}

// The dynamic step with nonlinear hardening: 2 dW_inc/dC = S (central differences of the
// incremental potential W_inc = Psi + Y dg), the identity Psi_{n+1} - Psi_n = 1/2 Sigma : dC - Dp
// with Dp = Y dg exactly, and D = dSigma/dC1 against central differences.
template <class L>
void dynamic_chain(const L& m, unsigned seed, double (&worst)[3], int& plastic) {
  using Elastic = decltype(m.elastic);
  double hn[L::kNumHist] = {}, h1[L::kNumHist] = {}, scratch[L::kNumHist] = {};
  walk(m, 0.03, seed, 6, 25, [&](const Mat3& C0, const Mat3& C1, const PlasticState& s0) {
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) hn[L::kFtr + 3 * i + j] = s0.Ftr(i, j);
    hn[L::kAlpha] = s0.alpha;
    hn[L::kDissipation] = 0.0;
    Ten4 D, Dd;
    const PointResponse r = m.template dynamic_update<true>(C0, C1, hn, static_cast<double*>(h1), D);
    ASSERT_TRUE(r.converged);
    const double dg = h1[L::kAlpha] - s0.alpha;
    EXPECT_NEAR(r.dissipation, m.Y * dg, 1e-14 * m.Y);
    const double psi_n = m.frozen_potential(hn).energy(C0) + m.hardening_energy(s0.alpha);
    const double scale = std::fabs(psi_n) + std::fabs(r.energy) + r.dissipation;
    worst[0] = std::fmax(worst[0], std::fabs(r.energy - psi_n - (0.5 * ddot(r.S, C1 - C0) - r.dissipation)) / scale);
    if (dg == 0.0 || kink_distance(m, h1[L::kAlpha]) < 1e-4) return;
    ++plastic;
    const stentor::IncrementalPotential<Elastic> pot{m, s0, stentor::inverse(s0.Ftr)};
    typename L::Step st;
    const Mat3 S = m.update_state(C1, s0, st).S;
    const double h = 1e-6;
    double err_s = 0.0, err_d = 0.0, ref_d = 0.0;
    for (int K = 0; K < 3; ++K)
      for (int L2 = 0; L2 < 3; ++L2) {
        const Mat3 E = sym_unit(K, L2);
        err_s = std::fmax(err_s, std::fabs((pot.energy(C1 + h * E) - pot.energy(C1 - h * E)) / h - S(K, L2)));
        const Mat3 Sp = m.template dynamic_update<false>(C0, C1 + h * E, hn, static_cast<double*>(scratch), Dd).S;
        const Mat3 Sm = m.template dynamic_update<false>(C0, C1 - h * E, hn, static_cast<double*>(scratch), Dd).S;
        for (int I = 0; I < 3; ++I)
          for (int J = 0; J < 3; ++J) {
            const double an = 0.5 * (D(I, J, K, L2) + D(I, J, L2, K));
            err_d = std::fmax(err_d, std::fabs((Sp(I, J) - Sm(I, J)) / (2 * h) - an));
            ref_d = std::fmax(ref_d, std::fabs(an));
          }
      }
    worst[1] = std::fmax(worst[1], err_s / max_abs(S));
    worst[2] = std::fmax(worst[2], err_d / ref_d);
    EXPECT_TRUE(pot.converged);
  });
}

TEST(Hardening, DynamicStepIncrementalPotential) {
  double worst[3] = {0.0, 0.0, 0.0};
  int plastic = 0;
  unsigned seed = 29;
  for (const auto& m : kCG) dynamic_chain(m, seed++, worst, plastic);
  for (const auto& m : kNH) dynamic_chain(m, seed++, worst, plastic);
  std::printf("[ measured ] dynamic step: identity %.2e, |2 dW_inc/dC - S|/|S| %.2e, |D - FD|/|D| %.2e (%d plastic "
              "steps)\n",
              worst[0], worst[1], worst[2], plastic);
  EXPECT_GT(plastic, 150);
  EXPECT_LT(worst[0], 1e-11);
  EXPECT_LT(worst[1], 1e-6);
  EXPECT_LT(worst[2], 1e-5);
}

// Voce with Y_inf = Y (Q = 0) is the linear law bit for bit (every kappa term is an exact
// zero), and a two-point table through (0, Y), (1, Y + H) is the linear law to round-off.
TEST(Hardening, DegenerateLawsAreTheLinearOne) {
  const CiarletGeymonatPlasticity lin{kMats[0], 0.1, 0.5};
  const CiarletGeymonatPlasticity q0 = with(lin, voce(0.1, 0.1, 7.0));
  const double te[] = {0.0, 1.0}, ts[] = {0.1, 0.6};
  const CiarletGeymonatPlasticity tab = with(CiarletGeymonatPlasticity{kMats[0], 0.1, 0.0}, NonlinearHardening::table(te, ts, 2));
  double e_tab = 0.0;
  int plastic = 0;
  walk(lin, 0.05, 53, 10, 20, [&](const Mat3&, const Mat3& C1, const PlasticState& s0) {
    CiarletGeymonatPlasticity::Step a, b, c;
    const PointResponse ra = lin.update_state(C1, s0, a), rb = q0.update_state(C1, s0, b), rc = tab.update_state(C1, s0, c);
    plastic += a.dgamma > 0.0;
    EXPECT_EQ(max_abs(ra.S - rb.S), 0.0);
    EXPECT_EQ(ra.energy, rb.energy);
    EXPECT_EQ(ra.dissipation, rb.dissipation);
    EXPECT_EQ(a.state.alpha, b.state.alpha);
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        for (int k = 0; k < 3; ++k)
          for (int l = 0; l < 3; ++l) EXPECT_EQ(ra.CC(i, j, k, l), rb.CC(i, j, k, l));
    e_tab = std::fmax(e_tab, max_abs(ra.S - rc.S) / max_abs(ra.S));
    e_tab = std::fmax(e_tab, std::fabs(ra.energy - rc.energy) / std::fabs(ra.energy));
  });
  std::printf("[ measured ] two-point table vs linear: %.2e (%d plastic steps)\n", e_tab, plastic);
  EXPECT_GT(plastic, 50);
  EXPECT_LT(e_tab, 1e-12);
}
