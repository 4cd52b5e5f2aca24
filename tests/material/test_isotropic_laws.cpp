// Material-point verification of the compressible neo-Hookean and Mooney–Rivlin laws
// and of the law dispatch (docs/verification.md, "Material point: neo-Hookean,
// Mooney–Rivlin").
//
//   neo-Hookean:   W = mu/2 (I1 - 3) - mu ln J + lambda/2 (ln J)^2
//   Mooney–Rivlin: W = C1 (I1 - 3) + C2 (I2 - 3) - 2 (C1 + 2 C2) ln J + lam/2 (ln J)^2
//
// Closed forms: for diagonal C = diag(a, b, c) (squared principal stretches) both laws
// give diagonal S with, from W written in a, b, c and differentiated by hand,
//   NH: S_11 = mu (1 - 1/a) + lambda ln J / a,
//   MR: S_11 = 2 [C1 + C2 (b + c)] - (2 (C1 + 2 C2) - lam ln J) / a     (cyclically),
// J = sqrt(abc): a separate route from the tensor formulas in the headers. In the
// nearly incompressible limit (lam >> C1, C2) uniaxial and equibiaxial tension tend to
// the classical incompressible results (Rivlin 1948; Treloar, The Physics of Rubber
// Elasticity): P = 2 (l - l^-2)(C1 + C2/l), resp. P = 2 (l - l^-5)(C1 + C2 l^2).
//
// Measured numbers quoted in the docs are printed with the prefix "[iso]".
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>

#include "MaterialSamples.hpp"
#include "material/DiscreteGradient.hpp"
#include "material/ElasticConstants.hpp"
#include "material/ElasticLaw.hpp"
#include "material/MooneyRivlin.hpp"
#include "material/NeoHookean.hpp"

using stentor::ElasticLaw;
using stentor::Mat3;
using stentor::MooneyRivlin;
using stentor::NeoHookean;
using stentor::Ten4;
using stentor::testing::random_F;
using stentor::testing::diag;
using stentor::testing::stress_fd_error;
using stentor::testing::sym_unit;
using stentor::testing::tangent_fd_error;

namespace {

// Moderate and nearly incompressible parameter sets.
const NeoHookean kNH[] = {{1.2, 2.5}, {0.8, 4000.0}};
const MooneyRivlin kMR[] = {{0.4, 0.25, 1.8}, {0.5, 0.15, 5000.0}, {0.3, 0.0, 1.0}};

// CC(I) = lambda I⊗I + 2 mu II, entrywise.
template <class Law>
double identity_tangent_error(const Law& m, double mu, double lambda) {
  Mat3 S;
  Ten4 CC;
  m.stress_and_tangent(Mat3::identity(), S, CC);
  double e = max_abs(S);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      for (int k = 0; k < 3; ++k)
        for (int l = 0; l < 3; ++l) {
          const double ref = lambda * (i == j) * (k == l) + mu * ((i == k) * (j == l) + (i == l) * (j == k));
          e = std::fmax(e, std::fabs(CC(i, j, k, l) - ref));
        }
  return e / (lambda + mu);
}

// Principal-stretch stresses (the closed forms above).
double nh_S11(const NeoHookean& m, double a, double b, double c) {
  const double lnJ = 0.5 * std::log(a * b * c);
  return m.mu * (1.0 - 1.0 / a) + m.lambda * lnJ / a;
}
double mr_S11(const MooneyRivlin& m, double a, double b, double c) {
  const double lnJ = 0.5 * std::log(a * b * c);
  return 2.0 * (m.C1 + m.C2 * (b + c)) - (2.0 * (m.C1 + 2.0 * m.C2) - m.lam * lnJ) / a;
}

// Lateral squared stretch b of uniaxial stress (stretch^2 = a along 1, S22 = S33 = 0)
// or, equibiaxial (a along 1 and 2), the free c; by bisection on the law's own S.
template <class Law>
double free_stretch2(const Law& m, double a, bool equibiaxial) {
  double lo = 1e-3, hi = 10.0;
  for (int it = 0; it < 200; ++it) {
    const double x = 0.5 * (lo + hi);
    const Mat3 S = equibiaxial ? m.stress(diag(a, a, x)) : m.stress(diag(a, x, x));
    const double s = equibiaxial ? S(2, 2) : S(1, 1);
    (s > 0.0 ? hi : lo) = x;  // S_free increases with x
  }
  return 0.5 * (lo + hi);
}

}  // namespace

TEST(IsotropicLaws, ReferenceStateAndSmallStrainLimit) {
  for (const auto& m : kNH) {
    EXPECT_NEAR(m.energy(Mat3::identity()), 0.0, 1e-15 * (m.mu + m.lambda));
    EXPECT_LE(identity_tangent_error(m, m.mu, m.lambda), 1e-15);
  }
  for (const auto& m : kMR) {
    EXPECT_NEAR(m.energy(Mat3::identity()), 0.0, 1e-15 * (m.C1 + m.C2 + m.lam));
    EXPECT_LE(identity_tangent_error(m, 2.0 * (m.C1 + m.C2), m.lam + 4.0 * m.C2), 1e-15);
    EXPECT_DOUBLE_EQ(m.shear_modulus(), 2.0 * (m.C1 + m.C2));
  }
  // From E, nu (ElasticConstants.hpp): the small-strain tensor is that of E and nu.
  for (double nu : {0.0, 0.3, 0.49}) {
    const auto l = stentor::lame_from_young(3.0, nu);
    EXPECT_LE(identity_tangent_error(NeoHookean{l.mu, l.lambda}, 3.0 / (2.0 * (1.0 + nu)), 3.0 * nu / ((1 + nu) * (1 - 2 * nu))),
              1e-15);
    const auto c = stentor::mooney_rivlin_from_lame(l, 0.1 * l.mu);
    EXPECT_LE(identity_tangent_error(MooneyRivlin{c.C1, c.C2, c.lam}, l.mu, l.lambda), 1e-15);
  }
}

TEST(IsotropicLaws, StressAndTangentMatchFiniteDifferences) {
  std::mt19937 rng(5);
  double worst_s = 0.0, worst_t = 0.0;
  for (int n = 0; n < 20; ++n) {
    const Mat3 F = random_F(rng, n % 4 == 3);
    const Mat3 C = stentor::tmul(F, F);
    for (const auto& m : kNH) {
      worst_s = std::fmax(worst_s, stress_fd_error(m, C, m.mu + m.lambda));
      worst_t = std::fmax(worst_t, tangent_fd_error(m, C));
    }
    for (const auto& m : kMR) {
      worst_s = std::fmax(worst_s, stress_fd_error(m, C, m.C1 + m.C2 + m.lam));
      worst_t = std::fmax(worst_t, tangent_fd_error(m, C));
    }
  }
  std::printf("[iso] FD: stress %.1e, tangent %.1e (max relative)\n", worst_s, worst_t);
  EXPECT_LE(worst_s, 1e-8);
  EXPECT_LE(worst_t, 1e-7);
}

TEST(IsotropicLaws, TangentSymmetries) {
  std::mt19937 rng(6);
  const Mat3 F = random_F(rng);
  const Mat3 C = stentor::tmul(F, F);
  Mat3 S;
  Ten4 CC;
  kMR[0].stress_and_tangent(C, S, CC);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      for (int k = 0; k < 3; ++k)
        for (int l = 0; l < 3; ++l) {
          EXPECT_NEAR(CC(i, j, k, l), CC(k, l, i, j), 1e-13 * max_abs(CC));
          EXPECT_EQ(CC(i, j, k, l), CC(j, i, k, l));
          EXPECT_EQ(CC(i, j, k, l), CC(i, j, l, k));
        }
  EXPECT_LE(max_abs(S - stentor::transpose(S)), 1e-15 * max_abs(S));
}

// Mooney–Rivlin with C2 = 0 is neo-Hookean with mu = 2 C1, lambda = lam.
TEST(IsotropicLaws, MooneyRivlinWithoutC2IsNeoHookean) {
  std::mt19937 rng(7);
  const MooneyRivlin mr{0.35, 0.0, 2.2};
  const NeoHookean nh{0.7, 2.2};
  for (int n = 0; n < 10; ++n) {
    const Mat3 F = random_F(rng);
    const Mat3 C = stentor::tmul(F, F);
    EXPECT_NEAR(mr.energy(C), nh.energy(C), 1e-14 * (1.0 + std::fabs(nh.energy(C))));
    Mat3 S1, S2;
    Ten4 T1, T2;
    mr.stress_and_tangent(C, S1, T1);
    nh.stress_and_tangent(C, S2, T2);
    EXPECT_LE(max_abs(S1 - S2), 1e-14 * (1.0 + max_abs(S2)));
    double e = 0.0;
    for (int i = 0; i < 81; ++i) e = std::fmax(e, std::fabs((&T1.a[0][0][0][0])[i] - (&T2.a[0][0][0][0])[i]));
    EXPECT_LE(e, 1e-13 * max_abs(T2));
  }
}

// Diagonal states: S against the principal-stretch formulas; uniaxial and equibiaxial
// tension against the incompressible closed forms when nearly incompressible.
TEST(IsotropicLaws, PrincipalStretchesUniaxialAndEquibiaxial) {
  const double states[][3] = {{1.44, 0.81, 1.1}, {0.5, 2.0, 1.3}, {3.0, 0.6, 0.6}};
  for (const auto& s : states) {
    const Mat3 C = diag(s[0], s[1], s[2]);
    for (const auto& m : kNH) {
      const Mat3 S = m.stress(C);
      EXPECT_NEAR(S(0, 0), nh_S11(m, s[0], s[1], s[2]), 1e-13 * (m.mu + m.lambda));
      EXPECT_NEAR(S(2, 2), nh_S11(m, s[2], s[0], s[1]), 1e-13 * (m.mu + m.lambda));
    }
    for (const auto& m : kMR) {
      const Mat3 S = m.stress(C);
      EXPECT_NEAR(S(0, 0), mr_S11(m, s[0], s[1], s[2]), 1e-13 * (m.C1 + m.C2 + m.lam));
      EXPECT_NEAR(S(1, 1), mr_S11(m, s[1], s[2], s[0]), 1e-13 * (m.C1 + m.C2 + m.lam));
    }
  }
  // Nearly incompressible: lam = 1e5 and 1e6 x (C1 + C2); the compressible answer tends to
  // the incompressible closed form as O((C1 + C2)/lam): ten times closer at ten times lam.
  double worst[2] = {0.0, 0.0};
  for (int k = 0; k < 2; ++k) {
    const double f = k == 0 ? 1e5 : 1e6;
    const MooneyRivlin mr{0.5, 0.2, 0.7 * f};
    const NeoHookean nh{1.0, f};
    for (double l : {0.7, 1.1, 1.5, 2.5}) {
      const double a = l * l;
      const double b = free_stretch2(mr, a, false), c = free_stretch2(mr, a, true);
      const double P_uni = l * mr.stress(diag(a, b, b))(0, 0), P_bi = l * mr.stress(diag(a, a, c))(0, 0);
      const double ref_uni = 2.0 * (l - 1.0 / (l * l)) * (mr.C1 + mr.C2 / l);
      const double ref_bi = 2.0 * (l - std::pow(l, -5.0)) * (mr.C1 + mr.C2 * l * l);
      const double bn = free_stretch2(nh, a, false);
      const double P_nh = l * nh.stress(diag(a, bn, bn))(0, 0), ref_nh = nh.mu * (l - 1.0 / (l * l));
      for (double e : {std::fabs(P_uni - ref_uni) / std::fabs(ref_uni), std::fabs(P_bi - ref_bi) / std::fabs(ref_bi),
                       std::fabs(P_nh - ref_nh) / std::fabs(ref_nh)})
        worst[k] = std::fmax(worst[k], e);
    }
  }
  std::printf("[iso] uniaxial/equibiaxial vs incompressible closed forms: max rel %.1e (lam = 1e5 (C1+C2)), %.1e (1e6)\n",
              worst[0], worst[1]);
  EXPECT_LE(worst[0], 3e-4);
  EXPECT_LE(worst[1], 3e-5);
  EXPECT_GT(worst[0] / worst[1], 8.0);
}

// ElasticLaw forwards to the chosen law, and the Gonzalez discrete gradient of each
// new law keeps the discrete energy identity 1/2 Sigma:dC = W(C1) - W(C0) (both
// evaluations of g: direct for |dC| >= 1e-3, Simpson below) and has an exact tangent.
TEST(IsotropicLaws, DispatchAndGonzalezEnergyIdentity) {
  const ElasticLaw laws[] = {ElasticLaw::neo_hookean(kNH[0]), ElasticLaw::neo_hookean(kNH[1]),
                             ElasticLaw::mooney_rivlin(kMR[0]), ElasticLaw::mooney_rivlin(kMR[1]),
                             ElasticLaw::ciarlet_geymonat({0.8, 0.3, 1.5})};
  std::mt19937 rng(8);
  double worst = 0.0, worst_t = 0.0;
  for (const auto& law : laws)
    for (double size : {0.0, 0.2, 2e-3, 5e-4, 1e-5})
      for (int n = 0; n < 10; ++n) {
        const Mat3 F0 = random_F(rng, n % 2 == 1);
        const Mat3 C0 = stentor::tmul(F0, F0);
        const Mat3 Fb = random_F(rng, n % 2 == 1);
        const Mat3 Cb = stentor::tmul(Fb, Fb);
        const Mat3 d = Cb - C0;
        const double t = size > 0.0 ? std::fmin(1.0, size / std::sqrt(stentor::ddot(d, d))) : 1.0;
        const Mat3 C1 = C0 + t * d;
        if (n == 0) {  // dispatch: the same numbers as the law itself
          const double e = law.kind == ElasticLaw::kNeoHookean     ? law.nh.energy(C1)
                           : law.kind == ElasticLaw::kMooneyRivlin ? law.mr.energy(C1)
                                                                   : law.cg.energy(C1);
          EXPECT_EQ(law.energy(C1), e);
        }
        const Mat3 Sig = stentor::gonzalez_stress(law, C0, C1);
        const double W0 = law.energy(C0), W1 = law.energy(C1);
        const double scale = std::fabs(W0) + std::fabs(W1) + 0.5 * std::fabs(stentor::ddot(law.stress(0.5 * (C0 + C1)), C1 - C0));
        worst = std::fmax(worst, std::fabs(0.5 * stentor::ddot(Sig, C1 - C0) - (W1 - W0)) / scale);
        if (size == 0.2 || size == 5e-4) {  // tangent of the discrete gradient by central differences
          Mat3 S;
          Ten4 D;
          stentor::gonzalez_stress_and_tangent(law, C0, C1, S, D);
          const double h = 1e-7;
          for (int K = 0; K < 3; ++K)
            for (int L = 0; L < 3; ++L) {
              const Mat3 E = sym_unit(K, L);
              const Mat3 dS = (0.5 / h) * (stentor::gonzalez_stress(law, C0, C1 + h * E) - stentor::gonzalez_stress(law, C0, C1 - h * E));
              for (int I = 0; I < 3; ++I)
                for (int J = 0; J < 3; ++J)
                  worst_t = std::fmax(worst_t, std::fabs(D(I, J, K, L) - dS(I, J)) / max_abs(D));
            }
        }
      }
  std::printf("[iso] Gonzalez energy identity: max relative residual %.1e; tangent vs FD %.1e\n", worst, worst_t);
  EXPECT_LE(worst, 1e-12);
  EXPECT_LE(worst_t, 1e-6);
}
