// Material-point verification of NeoHookeanPlasticity = MultiplicativePlasticity<NeoHookean>
// (src/material/Plasticity.hpp: the return map of the Ciarlet–Geymonat plasticity with the
// neo-Hookean principal functions; docs/plasticity.md, "Adding a material"): the
// neo-Hookean law below yield bit for bit, det Ftr = 1 and KKT after chains of large
// random steps, the consistent tangent against central differences at elastic and plastic
// points, D >= Y dg + 1/2 H dg^2 and the exact one-step energy identity with the Gonzalez
// stress of the frozen potential, the yield onset of uniaxial tension in closed form, and
// the stress-only update equal to the full one.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>

#include "MaterialSamples.hpp"
#include "material/DiscreteGradient.hpp"
#include "material/Kinematics.hpp"
#include "material/Plasticity.hpp"

using stentor::Mat3;
using stentor::max_abs;
using stentor::NeoHookean;
using stentor::NeoHookeanPlasticity;
using stentor::PlasticState;
using stentor::PointResponse;
using stentor::Ten4;
using stentor::testing::diag;
using stentor::testing::random_F;
using stentor::testing::sym_unit;
using Step = NeoHookeanPlasticity::Step;

namespace {

// Moderate (mu = 1) and nearly incompressible (mu = 100, lambda = 8000) elasticity, each
// perfectly plastic and hardening; yield at a strain of about Y / (3 mu) ~ 2-3%.
const NeoHookeanPlasticity kPlast[] = {{NeoHookean{1.0, 1.5}, 0.1, 0.0},
                                       {NeoHookean{1.0, 1.5}, 0.1, 0.5},
                                       {NeoHookean{100.0, 8000.0}, 5.0, 0.0},
                                       {NeoHookean{100.0, 8000.0}, 5.0, 20.0}};

PlasticState virgin() { return {Mat3::identity(), 0.0}; }

Mat3 elastic_C(const Mat3& C, const Mat3& Ftr) {
  const Mat3 G = stentor::inverse(Ftr);
  return stentor::tmul(G, stentor::matmul(C, G));
}

PlasticState random_state(const NeoHookeanPlasticity& m, std::mt19937& rng) {
  Step st;
  m.update_state(stentor::right_cauchy_green(random_F(rng)), virgin(), st);
  return st.state;
}

// max |CC - central difference of 2 dS/dC (h = 1e-6)| / max |CC| at (C, s0).
double rel_tangent_error(const NeoHookeanPlasticity& m, const Mat3& C, const PlasticState& s0) {
  Step st;
  const PointResponse r = m.update_state(C, s0, st);
  const double h = 1e-6;
  double err = 0.0, scale = 0.0;
  for (int K = 0; K < 3; ++K)
    for (int L = K; L < 3; ++L) {
      const Mat3 E = sym_unit(K, L);
      const Mat3 Sp = m.update_state(C + h * E, s0, st).S;
      const Mat3 Sm = m.update_state(C - h * E, s0, st).S;
      for (int I = 0; I < 3; ++I)
        for (int J = 0; J < 3; ++J) {
          err = std::fmax(err, std::fabs((Sp(I, J) - Sm(I, J)) / h - r.CC(I, J, K, L)));
          scale = std::fmax(scale, std::fabs(r.CC(I, J, K, L)));
        }
    }
  return err / scale;
}

}  // namespace

// Small strains from the virgin state: S, CC, W are the neo-Hookean law's, bit for bit.
TEST(NeoHookeanPlasticity, BelowYieldIsNeoHookeanBitwise) {
  std::mt19937 rng(7);
  for (const auto& m : kPlast)
    for (int t = 0; t < 50; ++t) {
      const Mat3 C = stentor::right_cauchy_green(Mat3::identity() + 0.01 * (random_F(rng) - Mat3::identity()));
      Step st;
      const PointResponse r = m.update_state(C, virgin(), st);
      ASSERT_EQ(st.dgamma, 0.0);
      Mat3 S;
      Ten4 CC;
      m.elastic.stress_and_tangent(C, S, CC);
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
          EXPECT_EQ(r.S(i, j), S(i, j));
          for (int k = 0; k < 3; ++k)
            for (int l = 0; l < 3; ++l) EXPECT_EQ(r.CC(i, j, k, l), CC(i, j, k, l));
        }
      EXPECT_EQ(r.energy, m.elastic.energy(C));
    }
}

// Chains of 300 random steps (strains up to 40% each): det Ftr = 1, the local Newton
// converges, f_{n+1} = 0 at active points by the tensor route (mandel_hill_norm of the
// stored state, independent of the spectral solve), f <= 0 at elastic ones.
TEST(NeoHookeanPlasticity, DetFtrAndKKTAlongRandomChains) {
  std::mt19937 rng(13);
  double det_err = 0.0, fmax = 0.0;
  int plastic = 0, iters = 0;
  for (const auto& m : kPlast) {
    PlasticState s = virgin();
    for (int t = 0; t < 300; ++t) {
      const Mat3 C = stentor::right_cauchy_green(random_F(rng));
      Step st;
      const PointResponse r = m.update_state(C, s, st);
      ASSERT_TRUE(r.converged);
      iters = std::max(iters, r.iterations);
      const double f = m.mandel_hill_norm(elastic_C(C, st.state.Ftr)) - m.Y - m.H * st.state.alpha;
      if (st.dgamma > 0.0) {
        fmax = std::fmax(fmax, std::fabs(f) / m.Y);
        ++plastic;
      } else {
        EXPECT_LE(f, 0.0);
      }
      det_err = std::fmax(det_err, std::fabs(stentor::det(st.state.Ftr) - 1.0));
      s = st.state;
    }
  }
  std::printf("[ nh-plastic ] %d plastic steps: max |det Ftr - 1| = %.2e, max |f|/Y = %.2e, max local iterations %d\n",
              plastic, det_err, fmax, iters);
  EXPECT_GT(plastic, 600);
  EXPECT_LE(det_err, 1e-13);
  EXPECT_LE(fmax, 1e-10);
}

// Elastic points (near the identity on a random ray) and plastic points (far out), from
// the virgin state and from a plastic one.
TEST(NeoHookeanPlasticity, ConsistentTangentMatchesFiniteDifferences) {
  std::mt19937 rng(17);
  double worst_el = 0.0, worst_pl = 0.0;
  int n_el = 0, n_pl = 0;
  for (const auto& m : kPlast)
    for (int t = 0; t < 40; ++t) {
      const PlasticState s0 = (t % 2) ? random_state(m, rng) : virgin();
      const Mat3 Fb = random_F(rng);
      for (double a : {0.01, 1.0}) {
        const Mat3 C = stentor::right_cauchy_green(Mat3::identity() + a * (Fb - Mat3::identity()));
        const double f_tr = m.mandel_hill_norm(elastic_C(C, s0.Ftr)) - m.Y - m.H * s0.alpha;
        if (std::fabs(f_tr) < 1e-3 * m.Y) continue;  // the stencil would straddle the yield kink
        const double e = rel_tangent_error(m, C, s0);
        if (f_tr > 0.0)
          worst_pl = std::fmax(worst_pl, e), ++n_pl;
        else
          worst_el = std::fmax(worst_el, e), ++n_el;
      }
    }
  std::printf("[ nh-plastic ] tangent vs FD: elastic %.2e (%d points), plastic %.2e (%d points)\n", worst_el, n_el, worst_pl,
              n_pl);
  EXPECT_GT(n_el, 20);
  EXPECT_GT(n_pl, 100);
  EXPECT_LE(worst_el, 1e-7);
  EXPECT_LE(worst_pl, 1e-6);
}

// Along random chains: D >= Y dg + 1/2 H dg^2 (convexity of W in log strains) and
// Psi_{n+1} - Psi_n = 1/2 Sigma:(C_{n+1} - C_n) - D with Sigma the Gonzalez discrete
// gradient of the frozen potential C -> W(G^T C G), G = Ftr_n^-1.
TEST(NeoHookeanPlasticity, DissipationBoundAndEnergyIdentity) {
  std::mt19937 rng(23);
  double min_ratio = 1e300, worst = 0.0;
  for (const auto& m : kPlast) {
    PlasticState s = virgin();
    Mat3 C0 = Mat3::identity();
    double psi0 = 0.0;
    for (int t = 0; t < 300; ++t) {
      const Mat3 C1 = stentor::right_cauchy_green(random_F(rng));
      Step st;
      const PointResponse r = m.update_state(C1, s, st);
      if (st.dgamma > 0.0) min_ratio = std::fmin(min_ratio, r.dissipation / (m.Y * st.dgamma + 0.5 * m.H * st.dgamma * st.dgamma));
      const stentor::FrozenPotential<NeoHookean> frozen{m.elastic, stentor::inverse(s.Ftr)};
      const double work = 0.5 * stentor::ddot(stentor::gonzalez_stress(frozen, C0, C1), C1 - C0);
      worst = std::fmax(worst, std::fabs(r.energy - psi0 - (work - r.dissipation)) / (m.elastic.mu + m.elastic.lambda));
      s = st.state, C0 = C1, psi0 = r.energy;
    }
  }
  std::printf("[ nh-plastic ] min D / (Y dg + H dg^2 / 2) = %.6f, max |energy identity| / (mu + lambda) = %.2e\n", min_ratio,
              worst);
  EXPECT_GE(min_ratio, 1.0 - 1e-9);
  EXPECT_LE(worst, 1e-11);
}

// Uniaxial tension, lateral stress free. Elastic closed form for the neo-Hookean law with
// C = diag(l^2, m, m): tau_2 = mu m + lambda ln(l m) - mu = 0 fixes m (increasing in m),
// tau_1 = mu (l^2 - m) = |M|_H; yield where mu (l^2 - m) = Y. The law's norm at the closed
// form is Y, and the law flows just above the onset and not just below it.
TEST(NeoHookeanPlasticity, UniaxialYieldOnsetClosedForm) {
  for (const auto& m : kPlast) {
    const double mu = m.elastic.mu, lam = m.elastic.lambda;
    auto lateral = [&](double l) {
      double lo = 1e-3, hi = 1.0;  // tau_2 < 0 at lo, >= 0 at hi for l >= 1
      for (int i = 0; i < 200; ++i) {
        const double mid = 0.5 * (lo + hi);
        (mu * mid + lam * std::log(l * mid) - mu < 0.0 ? lo : hi) = mid;
      }
      return 0.5 * (lo + hi);
    };
    double lo = 1.0, hi = 2.0;  // mu (l^2 - m(l)) - Y increases in l
    for (int i = 0; i < 200; ++i) {
      const double mid = 0.5 * (lo + hi);
      (mu * (mid * mid - lateral(mid)) < m.Y ? lo : hi) = mid;
    }
    const double ly = 0.5 * (lo + hi);
    const double my = lateral(ly);
    const Mat3 Cy = diag(ly * ly, my, my);
    EXPECT_NEAR(m.elastic.stress(Cy)(1, 1), 0.0, 1e-12 * mu) << "closed-form lateral stress";
    EXPECT_NEAR(m.mandel_hill_norm(Cy) / m.Y, 1.0, 1e-11);
    Step below, above;
    const double eb = (1.0 - 1e-6) * ly, ea = (1.0 + 1e-6) * ly;
    m.update_state(diag(eb * eb, lateral(eb), lateral(eb)), virgin(), below);
    m.update_state(diag(ea * ea, lateral(ea), lateral(ea)), virgin(), above);
    EXPECT_EQ(below.dgamma, 0.0);
    EXPECT_GT(above.dgamma, 0.0);
    std::printf("[ nh-plastic ] mu = %g, Y = %g: uniaxial yield at stretch %.9f\n", mu, m.Y, ly);
  }
}

// update<false> (residual-only kernels) returns the same S, state, energy and D bit for bit.
TEST(NeoHookeanPlasticity, StressOnlyUpdateIsBitwiseTheFullOne) {
  std::mt19937 rng(29);
  for (const auto& m : kPlast)
    for (int t = 0; t < 100; ++t) {
      const PlasticState s0 = (t % 2) ? random_state(m, rng) : virgin();
      const Mat3 C = stentor::right_cauchy_green(random_F(rng));
      Step a, b;
      const PointResponse full = m.update_state<true>(C, s0, a);
      const PointResponse only = m.update_state<false>(C, s0, b);
      EXPECT_EQ(max_abs(full.S - only.S), 0.0);
      EXPECT_EQ(max_abs(a.state.Ftr - b.state.Ftr), 0.0);
      EXPECT_EQ(a.state.alpha, b.state.alpha);
      EXPECT_EQ(full.energy, only.energy);
      EXPECT_EQ(full.dissipation, only.dissipation);
    }
}
