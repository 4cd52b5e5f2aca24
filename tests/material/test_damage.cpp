// Material-point verification of IsotropicDamage (src/material/Damage.hpp; Miehe 1995
// discontinuous damage over the neo-Hookean law; docs/plasticity.md, "Adding a material"):
// consistent tangent against central differences while loading and while unloading, the
// damage function and its memory (growth only beyond the past maximum of W0), D >= 0 and
// the exact one-step energy identity with the Gonzalez stress of the frozen potential,
// the stress-only update equal to the full one bit for bit, and d_inf = 0 equal to the
// neo-Hookean law bit for bit.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>

#include "MaterialSamples.hpp"
#include "material/Damage.hpp"
#include "material/DiscreteGradient.hpp"
#include "material/Kinematics.hpp"
#include "material/NeoHookean.hpp"

using stentor::Mat3;
using stentor::NeoHookean;
using stentor::PointResponse;
using stentor::Ten4;
using stentor::testing::random_F;
using stentor::testing::sym_unit;
using Damage = stentor::IsotropicDamage<NeoHookean>;

namespace {

// Moderate and nearly incompressible elasticity; beta of the order of W0 at the random
// deformations of random_F (strains up to 40%), so that d is well below d_inf there and
// the loading term g' S0 (x) S0 of the tangent is of the order of (1 - d) CC0.
const Damage kDamage[] = {{NeoHookean{2.0, 3.0}, 0.8, 0.5}, {NeoHookean{100.0, 8000.0}, 0.5, 2000.0}};

// One Gauss point's history row; p() is what update() takes (double*: h_{n+1} is written).
struct Row {
  double h[Damage::kNumHist];
  double* p() { return h; }
  const double* p() const { return h; }
};

Row virgin() {
  Row r;
  stentor::init_history<Damage>(r.p());
  return r;
}

PointResponse step(const Damage& m, const Mat3& C, const Row& hn, Row& h1) { return m.update(C, hn.p(), h1.p()); }

// max |CC - FD| / max |CC| at C from state hn (central differences in C, h = 1e-6).
double rel_tangent_error(const Damage& m, const Mat3& C, const Row& hn) {
  Row h1;
  const PointResponse r = step(m, C, hn, h1);
  const double h = 1e-6;
  double err = 0.0, scale = 0.0;
  for (int K = 0; K < 3; ++K)
    for (int L = 0; L < 3; ++L) {
      const Mat3 E = sym_unit(K, L);
      const Mat3 Sp = step(m, C + h * E, hn, h1).S;
      const Mat3 Sm = step(m, C - h * E, hn, h1).S;
      for (int I = 0; I < 3; ++I)
        for (int J = 0; J < 3; ++J) {
          const double fd = (Sp(I, J) - Sm(I, J)) / h;  // 2 dS/dC_KL along the symmetric direction
          const double cc = 0.5 * (r.CC(I, J, K, L) + r.CC(I, J, L, K));
          err = std::fmax(err, std::fabs(fd - cc));
          scale = std::fmax(scale, std::fabs(cc));
        }
    }
  return err / scale;
}

}  // namespace

// Loading points (W0 beyond the committed maximum: damage grows, the S0 (x) S0 term is
// active) and unloading points (elastic with the softened moduli), from a damaged state.
TEST(Damage, TangentMatchesFiniteDifferences) {
  std::mt19937 rng(11);
  for (const Damage& m : kDamage) {
    double worst_load = 0.0, worst_unload = 0.0;
    int loading = 0, unloading = 0, coupled = 0;
    for (int k = 0; k < 200; ++k) {
      Row h0 = virgin(), h1;
      step(m, stentor::right_cauchy_green(random_F(rng)), h0, h1);  // a damaged committed state
      const Mat3 C = stentor::right_cauchy_green(random_F(rng));
      const bool load = m.elastic.energy(C) > h1.h[Damage::kMaxEnergy] * (1.0 + 1e-6);
      const bool unload = m.elastic.energy(C) < h1.h[Damage::kMaxEnergy] * (1.0 - 1e-6);
      if (!load && !unload) continue;  // too close to the switch for a central difference
      const double e = rel_tangent_error(m, C, h1);
      (load ? worst_load : worst_unload) = std::fmax(load ? worst_load : worst_unload, e);
      ++(load ? loading : unloading);
      if (load) {  // size of the loading term: g' |S0|^2 against (1 - d) |CC0|
        Row h2;
        const PointResponse r = step(m, C, h1, h2);
        const double d = h2.h[Damage::kDamage], gp = (m.d_inf - d) / m.beta;
        const Mat3 S0 = (1.0 / (1.0 - d)) * r.S;
        coupled += gp * stentor::ddot(S0, S0) > 0.1 * (1.0 - d) * (m.elastic.mu + m.elastic.lambda);
      }
    }
    std::printf("[ damage ] mu = %g: |CC - FD|/|CC| loading %.2e (%d points, %d with a loading term > 10%%), unloading %.2e (%d points)\n",
                m.elastic.mu, worst_load, loading, coupled, worst_unload, unloading);
    EXPECT_GT(loading, 50);
    EXPECT_GT(coupled, loading / 4);
    EXPECT_GT(unloading, 50);
    EXPECT_LT(worst_load, 1e-6);
    EXPECT_LT(worst_unload, 1e-6);
  }
}

// Along a path that loads, unloads and reloads: alpha is the running maximum of W0, d = g(alpha)
// in closed form, unchanged while W0 stays below alpha; D >= 0; the one-step identity
// Psi_{n+1} - Psi_n = 1/2 Sigma:(C_{n+1} - C_n) - D with Sigma the Gonzalez discrete gradient
// of the frozen potential (1 - d_n) W0.
TEST(Damage, MemoryDissipationAndEnergyIdentity) {
  for (const Damage& m : kDamage) {
    Row h = virgin();
    Mat3 C0 = Mat3::identity();
    double psi0 = 0.0, wmax = 0.0, worst_identity = 0.0, min_d = 0.0;
    const Mat3 dir = stentor::testing::diag(1.0, -0.3, 0.1) + 0.2 * sym_unit(0, 1);
    for (int n = 1; n <= 60; ++n) {
      const double s = 0.25 * std::sin(0.25 * n) * (1.0 + n / 30.0);  // load, unload, reload further
      const Mat3 F = Mat3::identity() + s * dir;
      const Mat3 C1 = stentor::right_cauchy_green(F);
      Row h1;
      const PointResponse r = step(m, C1, h, h1);
      const double W0 = m.elastic.energy(C1);
      wmax = std::fmax(wmax, W0);
      EXPECT_EQ(h1.h[Damage::kMaxEnergy], wmax) << "step " << n;
      EXPECT_NEAR(h1.h[Damage::kDamage], m.d_inf * (1.0 - std::exp(-wmax / m.beta)), 1e-15) << "step " << n;
      if (W0 <= h.h[Damage::kMaxEnergy]) EXPECT_EQ(h1.h[Damage::kDamage], h.h[Damage::kDamage]) << "step " << n;
      min_d = std::fmin(min_d, r.dissipation);
      const auto frozen = m.frozen_potential(h.p());
      const Mat3 Sig = stentor::gonzalez_stress(frozen, C0, C1);
      const double work = 0.5 * stentor::ddot(Sig, C1 - C0);
      worst_identity = std::fmax(worst_identity, std::fabs(r.energy - psi0 - (work - r.dissipation)) / (m.elastic.mu + std::fabs(psi0)));
      EXPECT_NEAR(h1.h[Damage::kDissipation], h.h[Damage::kDissipation] + r.dissipation, 1e-15 * m.elastic.mu);
      h = h1;
      C0 = C1;
      psi0 = r.energy;
    }
    std::printf("[ damage ] mu = %g: final d = %.4f, min D = %g, max |identity| / mu = %.2e\n", m.elastic.mu,
                h.h[Damage::kDamage], min_d, worst_identity);
    EXPECT_GT(h.h[Damage::kDamage], 0.1 * m.d_inf);
    EXPECT_GE(min_d, 0.0);
    EXPECT_LT(worst_identity, 1e-12);
  }
}

// update<false> (residual-only kernels) returns the same S, history, energy and D bit for bit.
TEST(Damage, StressOnlyUpdateIsBitwiseTheFullOne) {
  std::mt19937 rng(5);
  for (const Damage& m : kDamage)
    for (int k = 0; k < 100; ++k) {
      Row h0 = virgin(), h1, a, b;
      step(m, stentor::right_cauchy_green(random_F(rng)), h0, h1);
      const Mat3 C = stentor::right_cauchy_green(random_F(rng));
      const PointResponse full = m.update<true>(C, h1.p(), a.p());
      const PointResponse only = m.update<false>(C, h1.p(), b.p());
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) EXPECT_EQ(full.S(i, j), only.S(i, j));
      for (int i = 0; i < Damage::kNumHist; ++i) EXPECT_EQ(a.h[i], b.h[i]);
      EXPECT_EQ(full.energy, only.energy);
      EXPECT_EQ(full.dissipation, only.dissipation);
    }
}

// d_inf = 0: the neo-Hookean law itself (S, CC, W bit for bit), no dissipation.
TEST(Damage, NoDamageIsTheElasticLaw) {
  std::mt19937 rng(3);
  const NeoHookean nh{2.0, 3.0};
  const Damage m{nh, 0.0, 0.02};
  for (int k = 0; k < 100; ++k) {
    Row h0 = virgin(), h1;
    const Mat3 C = stentor::right_cauchy_green(random_F(rng));
    const PointResponse r = step(m, C, h0, h1);
    Mat3 S;
    Ten4 CC;
    nh.stress_and_tangent(C, S, CC);
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) {
        EXPECT_EQ(r.S(i, j), S(i, j));
        for (int a = 0; a < 3; ++a)
          for (int b = 0; b < 3; ++b) EXPECT_EQ(r.CC(i, j, a, b), CC(i, j, a, b));
      }
    EXPECT_EQ(r.energy, nh.energy(C));
    EXPECT_EQ(r.dissipation, 0.0);
  }
}
