// Material-point verification of the Ciarlet–Geymonat law (docs/verification.md,
// section "Material point: Ciarlet–Geymonat").
//
//   W(C) = C1(I1-3) + C2(I2-3) + D(I3-1) - K ln I3,  K = C1 + 2C2 + D.
//
// Closed forms used below. W is isotropic, so for diagonal C = diag(a, b, c)
// (a, b, c the squared principal stretches) S is diagonal too, and with
// I1 = a+b+c, I2 = ab+bc+ca, I3 = abc, differentiating W in a directly gives
//   S_11 = 2 dW/da = 2[C1 + C2(b+c) + D bc - K/a]        (and cyclically).
// This is a separate route from the code's tensor formula
//   S = 2[(C1 + C2 I1) I - C2 C + (D I3 - K) C^{-1}],
// so agreement checks the implementation. Each case below specialises it.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "MaterialSamples.hpp"
#include "material/CiarletGeymonat.hpp"
#include "material/ElasticConstants.hpp"
#include "material/Kinematics.hpp"

using stentor::CiarletGeymonat;
using stentor::Mat3;
using stentor::Ten4;
using stentor::testing::kMats;
using stentor::testing::random_F;
using stentor::testing::diag;
using stentor::testing::sym_unit;

namespace {

// Rotation by angle theta about unit axis n (Rodrigues).
Mat3 rotation(double nx, double ny, double nz, double theta) {
  const double nn = std::sqrt(nx * nx + ny * ny + nz * nz);
  nx /= nn, ny /= nn, nz /= nn;
  Mat3 Kx = Mat3::zero();
  Kx(0, 1) = -nz, Kx(0, 2) = ny, Kx(1, 0) = nz, Kx(1, 2) = -nx, Kx(2, 0) = -ny, Kx(2, 1) = nx;
  return Mat3::identity() + std::sin(theta) * Kx + (1.0 - std::cos(theta)) * stentor::matmul(Kx, Kx);
}

// Symmetric unit perturbation E = (e_I⊗e_J + e_J⊗e_I)/2, so that for symmetric G,
// G:E = G_IJ: a central difference of W along E gives (dW/dC)_IJ directly.
}  // namespace

// ---------------------------------------------------------------------------
// Reference state
// ---------------------------------------------------------------------------

TEST(CiarletGeymonat, StressFreeAndZeroEnergyAtIdentity) {
  for (const auto& m : kMats) {
    const Mat3 I = Mat3::identity();
    EXPECT_NEAR(m.energy(I), 0.0, 1e-14 * (m.C1 + m.C2 + m.D));
    EXPECT_LE(max_abs(m.stress(I)), 1e-13 * (m.C1 + m.C2 + m.D));
  }
}

// At C = I (I3 = 1, Ci = I) the general tangent
//   CC = 4C2(I⊗I - II) + 4D I3 Ci⊗Ci + 4(K - D I3) Ci⊙Ci
// reduces to 4(C2+D) I⊗I + 4(C1+C2) II = lambda I⊗I + 2 mu II.
TEST(CiarletGeymonat, TangentAtIdentityIsIsotropicElasticity) {
  for (const auto& m : kMats) {
    const double mu = 2.0 * (m.C1 + m.C2), lam = 4.0 * (m.C2 + m.D);
    EXPECT_DOUBLE_EQ(m.shear_modulus(), mu);
    EXPECT_DOUBLE_EQ(m.lame_lambda(), lam);
    Ten4 CC;
    m.tangent(Mat3::identity(), CC);
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        for (int k = 0; k < 3; ++k)
          for (int l = 0; l < 3; ++l) {
            const double ref = lam * (i == j) * (k == l) + mu * ((i == k) * (j == l) + (i == l) * (j == k));
            EXPECT_NEAR(CC(i, j, k, l), ref, 1e-13 * (lam + mu)) << i << j << k << l;
          }
  }
}

// ---------------------------------------------------------------------------
// Energy, stress and tangent against finite differences
// ---------------------------------------------------------------------------

// Energy against an independent evaluation: I2 as the sum of principal minors
// (instead of ((tr C)^2 - tr C^2)/2), I3 by the rule of Sarrus.
TEST(CiarletGeymonat, EnergyMatchesInvariantsByMinors) {
  std::mt19937 rng(11);
  for (const auto& m : kMats)
    for (int n = 0; n < 10; ++n) {
      const Mat3 F = random_F(rng);
      const Mat3 C = stentor::tmul(F, F);
      const double I1 = C(0, 0) + C(1, 1) + C(2, 2);
      const double I2 = C(0, 0) * C(1, 1) - C(0, 1) * C(1, 0) + C(1, 1) * C(2, 2) - C(1, 2) * C(2, 1) +
                        C(0, 0) * C(2, 2) - C(0, 2) * C(2, 0);
      const double I3 = C(0, 0) * C(1, 1) * C(2, 2) + C(0, 1) * C(1, 2) * C(2, 0) +
                        C(0, 2) * C(1, 0) * C(2, 1) - C(0, 2) * C(1, 1) * C(2, 0) -
                        C(0, 1) * C(1, 0) * C(2, 2) - C(0, 0) * C(1, 2) * C(2, 1);
      const double K = m.C1 + 2 * m.C2 + m.D;
      const double W = m.C1 * (I1 - 3) + m.C2 * (I2 - 3) + m.D * (I3 - 1) - K * std::log(I3);
      EXPECT_NEAR(m.energy(C), W, 1e-12 * (std::fabs(W) + K));
    }
}

TEST(CiarletGeymonat, StressMatchesFiniteDifferenceOfEnergy) {
  std::mt19937 rng(1);
  const double h = 1e-5;
  for (const auto& m : kMats)
    for (int n = 0; n < 10; ++n) {
      const Mat3 F = random_F(rng, n % 3 == 2);  // some plane-strain states too
      const Mat3 C = stentor::tmul(F, F);
      const Mat3 S = m.stress(C);
      Mat3 Sfd;
      for (int I = 0; I < 3; ++I)
        for (int J = 0; J < 3; ++J) {
          const Mat3 E = sym_unit(I, J);
          Sfd(I, J) = 2.0 * (m.energy(C + h * E) - m.energy(C - h * E)) / (2.0 * h);
        }
      const double scale = max_abs(S) + m.C1 + m.C2 + m.D;
      EXPECT_LE(max_abs(S - Sfd), 1e-6 * scale) << "sample " << n;
      EXPECT_LE(max_abs(S - stentor::transpose(S)), 1e-14 * scale);
    }
}

TEST(CiarletGeymonat, TangentMatchesFiniteDifferenceOfStress) {
  std::mt19937 rng(2);
  const double h = 1e-6;
  for (const auto& m : kMats)
    for (int n = 0; n < 10; ++n) {
      const Mat3 F = random_F(rng, n % 3 == 2);
      const Mat3 C = stentor::tmul(F, F);
      Ten4 CC, diff;
      m.tangent(C, CC);
      for (int K = 0; K < 3; ++K)
        for (int L = 0; L < 3; ++L) {
          const Mat3 E = sym_unit(K, L);
          const Mat3 dS = (1.0 / (2.0 * h)) * (m.stress(C + h * E) - m.stress(C - h * E));
          for (int I = 0; I < 3; ++I)
            for (int J = 0; J < 3; ++J) diff(I, J, K, L) = CC(I, J, K, L) - 2.0 * dS(I, J);
        }
      EXPECT_LE(max_abs(diff), 1e-6 * max_abs(CC)) << "sample " << n;
    }
}

TEST(CiarletGeymonat, TangentHasMinorAndMajorSymmetry) {
  std::mt19937 rng(3);
  for (const auto& m : kMats) {
    const Mat3 F = random_F(rng);
    Ten4 CC;
    m.tangent(stentor::tmul(F, F), CC);
    const double tol = 1e-14 * max_abs(CC);
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        for (int k = 0; k < 3; ++k)
          for (int l = 0; l < 3; ++l) {
            EXPECT_NEAR(CC(i, j, k, l), CC(j, i, k, l), tol);
            EXPECT_NEAR(CC(i, j, k, l), CC(i, j, l, k), tol);
            EXPECT_NEAR(CC(i, j, k, l), CC(k, l, i, j), tol);
          }
  }
}

TEST(CiarletGeymonat, StressAndTangentMatchSeparateCalls) {
  std::mt19937 rng(4);
  for (const auto& m : kMats) {
    const Mat3 F = random_F(rng);
    const Mat3 C = stentor::tmul(F, F);
    Mat3 S;
    Ten4 A, B;
    m.stress_and_tangent(C, S, A);
    m.tangent(C, B);
    EXPECT_EQ(max_abs(S - m.stress(C)), 0.0);
    double d = 0.0;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        for (int k = 0; k < 3; ++k)
          for (int l = 0; l < 3; ++l) d = std::fmax(d, std::fabs(A(i, j, k, l) - B(i, j, k, l)));
    EXPECT_EQ(d, 0.0);
  }
}

// A_iJkL = dP_iJ/dF_kL with P = F S(F^T F), against central differences of P.
TEST(Kinematics, FirstPiolaTangentMatchesFiniteDifference) {
  std::mt19937 rng(5);
  const double h = 1e-6;
  for (const auto& m : kMats)
    for (int n = 0; n < 6; ++n) {
      const Mat3 F = random_F(rng, n % 3 == 2);
      Mat3 S;
      Ten4 CC, A, diff;
      m.stress_and_tangent(stentor::tmul(F, F), S, CC);
      stentor::spatial_tangent_dPdF(F, S, CC, A);
      auto P_of = [&](const Mat3& G) { return stentor::first_piola(G, m.stress(stentor::tmul(G, G))); };
      for (int k = 0; k < 3; ++k)
        for (int L = 0; L < 3; ++L) {
          Mat3 E = Mat3::zero();
          E(k, L) = 1.0;
          const Mat3 dP = (1.0 / (2.0 * h)) * (P_of(F + h * E) - P_of(F - h * E));
          for (int i = 0; i < 3; ++i)
            for (int J = 0; J < 3; ++J) diff(i, J, k, L) = A(i, J, k, L) - dP(i, J);
        }
      EXPECT_LE(max_abs(diff), 1e-6 * max_abs(A)) << "sample " << n;
      // dP/dF is the Hessian of W(F^T F) in F: major symmetry A_iJkL = A_kLiJ.
      for (int i = 0; i < 3; ++i)
        for (int J = 0; J < 3; ++J)
          for (int k = 0; k < 3; ++k)
            for (int L = 0; L < 3; ++L) EXPECT_NEAR(A(i, J, k, L), A(k, L, i, J), 1e-13 * max_abs(A));
    }
}

TEST(Kinematics, CauchyStressAndVonMises) {
  // sigma = P F^T / J must equal F S F^T / J and be symmetric.
  std::mt19937 rng(6);
  const CiarletGeymonat& m = kMats[0];
  const Mat3 F = random_F(rng);
  const Mat3 S = m.stress(stentor::tmul(F, F));
  const Mat3 sig = stentor::cauchy_stress(F, stentor::first_piola(F, S));
  const Mat3 ref = (1.0 / stentor::det(F)) * stentor::matmul(stentor::matmul(F, S), stentor::transpose(F));
  EXPECT_LE(max_abs(sig - ref), 1e-13 * max_abs(ref));
  EXPECT_LE(max_abs(sig - stentor::transpose(sig)), 1e-13 * max_abs(ref));
  // von Mises: uniaxial |s|, pure shear sqrt(3)|t|, hydrostatic 0.
  EXPECT_NEAR(stentor::von_mises(diag(-7.0, 0.0, 0.0)), 7.0, 1e-14);
  Mat3 sh = Mat3::zero();
  sh(0, 1) = sh(1, 0) = 2.0;
  EXPECT_NEAR(stentor::von_mises(sh), 2.0 * std::sqrt(3.0), 1e-14);
  EXPECT_NEAR(stentor::von_mises(diag(5.0, 5.0, 5.0)), 0.0, 1e-14);
}

// ---------------------------------------------------------------------------
// Homogeneous states in closed form (3D)
// ---------------------------------------------------------------------------

// (a) Uniaxial stress, F = diag(lam, s, s): a = lam^2, b = s^2, C = diag(a, b, b).
// From S_11 = 2[C1 + C2(b+c) + D bc - K/a] with c = b:
//   S_11 = 2[C1 + 2 C2 b + D b^2 - K/a]
//   S_22 = S_33 = 2[C1 + C2(a+b) + D a b - K/b].
// Lateral stress free: g(b) = C1 + C2(a+b) + D a b - K/b = 0, i.e. the quadratic
//   (C2 + D a) b^2 + (C1 + C2 a) b - K = 0,
// with one positive root (product of roots -K/(C2+Da) < 0). Solved by Newton
// (g'(b) = C2 + D a + K/b^2 > 0, g increasing and concave: converges from the left)
// and checked against the quadratic formula. At lam = 1, b = 1 (K = C1+2C2+D).
// Small-strain checks: dP_11/dlam at 1 = E = mu(3 lambda + 2 mu)/(lambda + mu),
// -ds/dlam at 1 = nu = lambda / (2(lambda + mu)).
namespace {
double uniaxial_b(const CiarletGeymonat& m, double a) {
  const double K = m.C1 + 2 * m.C2 + m.D;
  double b = 1e-3;  // left of the root: g(b) < 0 for small b
  for (int it = 0; it < 100; ++it) {
    const double g = m.C1 + m.C2 * (a + b) + m.D * a * b - K / b;
    const double dg = m.C2 + m.D * a + K / (b * b);
    const double db = -g / dg;
    b += db;
    if (std::fabs(db) < 1e-15 * b) break;
  }
  return b;
}
double uniaxial_P11(const CiarletGeymonat& m, double lam) {
  const double a = lam * lam, b = uniaxial_b(m, a), K = m.C1 + 2 * m.C2 + m.D;
  return lam * 2.0 * (m.C1 + 2 * m.C2 * b + m.D * b * b - K / a);
}
}  // namespace

TEST(CiarletGeymonat, UniaxialStress3D) {
  for (const auto& m : kMats) {
    const double K = m.C1 + 2 * m.C2 + m.D;
    for (double lam : {0.6, 0.9, 1.0, 1.3, 2.0}) {
      const double a = lam * lam;
      const double b = uniaxial_b(m, a);
      const double qa = m.C2 + m.D * a, qb = m.C1 + m.C2 * a;
      const double b_quad = (-qb + std::sqrt(qb * qb + 4 * qa * K)) / (2 * qa);
      EXPECT_NEAR(b, b_quad, 1e-13 * b_quad);
      const double s = std::sqrt(b);
      const Mat3 F = diag(lam, s, s);
      const Mat3 S = m.stress(stentor::tmul(F, F));
      const double S11 = 2.0 * (m.C1 + 2 * m.C2 * b + m.D * b * b - K / a);
      const double scale = std::fabs(S11) + K;
      EXPECT_NEAR(S(0, 0), S11, 1e-12 * scale) << lam;
      EXPECT_NEAR(S(1, 1), 0.0, 1e-12 * scale) << lam;
      EXPECT_NEAR(S(2, 2), 0.0, 1e-12 * scale) << lam;
      EXPECT_NEAR(max_abs(S - diag(S(0, 0), S(1, 1), S(2, 2))), 0.0, 1e-14 * scale);
      // Cauchy: sigma_11 = lam^2 S_11 / (lam s^2); von Mises = |sigma_11|.
      const Mat3 sig = stentor::cauchy_stress(F, stentor::first_piola(F, S));
      EXPECT_NEAR(sig(0, 0), lam * S11 / b, 1e-12 * scale / b);
      EXPECT_NEAR(stentor::von_mises(sig), std::fabs(lam * S11 / b), 1e-11 * scale / b);
      if (lam > 1.0) {
        EXPECT_GT(S11, 0.0);
      }
      if (lam < 1.0) {
        EXPECT_LT(S11, 0.0);
      }
    }
    // Small-strain Young's modulus and Poisson ratio.
    const double mu = m.shear_modulus(), la = m.lame_lambda();
    const double E = mu * (3 * la + 2 * mu) / (la + mu), nu = la / (2 * (la + mu));
    const double d = 1e-5;
    EXPECT_NEAR((uniaxial_P11(m, 1 + d) - uniaxial_P11(m, 1 - d)) / (2 * d), E, 1e-7 * E);
    const double ds = (std::sqrt(uniaxial_b(m, (1 + d) * (1 + d))) -
                       std::sqrt(uniaxial_b(m, (1 - d) * (1 - d)))) / (2 * d);
    EXPECT_NEAR(-ds, nu, 1e-7);
  }
}

// (b) Equibiaxial, F = diag(lam, lam, s), a = lam^2, c = s^2, C = diag(a, a, c):
//   S_33 = 2[C1 + 2 C2 a + D a^2 - K/c] = 0  =>  c = K / (C1 + 2 C2 a + D a^2)
//   S_11 = S_22 = 2[C1 + C2(a + c) + D a c - K/a].
TEST(CiarletGeymonat, EquibiaxialStress3D) {
  for (const auto& m : kMats) {
    const double K = m.C1 + 2 * m.C2 + m.D;
    for (double lam : {0.7, 1.0, 1.2, 1.8}) {
      const double a = lam * lam;
      const double c = K / (m.C1 + 2 * m.C2 * a + m.D * a * a);
      const Mat3 F = diag(lam, lam, std::sqrt(c));
      const Mat3 S = m.stress(stentor::tmul(F, F));
      const double S11 = 2.0 * (m.C1 + m.C2 * (a + c) + m.D * a * c - K / a);
      const double scale = std::fabs(S11) + K;
      EXPECT_NEAR(S(0, 0), S11, 1e-12 * scale) << lam;
      EXPECT_NEAR(S(1, 1), S11, 1e-12 * scale) << lam;
      EXPECT_NEAR(S(2, 2), 0.0, 1e-12 * scale) << lam;
    }
  }
}

// (c) Hydrostatic, F = J^{1/3} I, C = a I with a = J^{2/3}:
//   S = 2[C1 + 2 C2 a + D a^2 - K/a] I,  sigma = F S F^T / J = (a/J) S = -p I,
//   p(J) = (2/J)[K - C1 J^{2/3} - 2 C2 J^{4/3} - D J^2].
// p(1) = 0 and p'(1) = -(4/3 C1 + 16/3 C2 + 4 D) = -(lambda + 2 mu / 3): the bulk modulus.
TEST(CiarletGeymonat, Hydrostatic3D) {
  for (const auto& m : kMats) {
    const double K = m.C1 + 2 * m.C2 + m.D;
    for (double J : {0.5, 0.8, 1.0, 1.1, 1.5}) {
      const double p = (2.0 / J) * (K - m.C1 * std::pow(J, 2.0 / 3.0) - 2 * m.C2 * std::pow(J, 4.0 / 3.0) -
                                    m.D * J * J);
      const double f = std::cbrt(J);
      const Mat3 F = diag(f, f, f);
      const Mat3 sig = stentor::cauchy_stress(F, stentor::first_piola(F, m.stress(stentor::tmul(F, F))));
      const double scale = std::fabs(p) + K;
      EXPECT_NEAR(-stentor::trace(sig) / 3.0, p, 1e-12 * scale) << J;
      EXPECT_NEAR(max_abs(sig - diag(-p, -p, -p)), 0.0, 1e-12 * scale) << J;
      EXPECT_NEAR(stentor::von_mises(sig), 0.0, 1e-11 * scale) << J;
      if (J < 1.0) {
        EXPECT_GT(p, 0.0);
      }
      if (J > 1.0) {
        EXPECT_LT(p, 0.0);
      }
    }
    const double kappa = m.lame_lambda() + 2.0 * m.shear_modulus() / 3.0;
    EXPECT_NEAR(4.0 / 3.0 * m.C1 + 16.0 / 3.0 * m.C2 + 4.0 * m.D, kappa, 1e-12 * kappa);
  }
}

// ---------------------------------------------------------------------------
// Plane strain (F_33 = 1, so c = C_33 = 1)
// ---------------------------------------------------------------------------

// (d1) Uniaxial in-plane, F = diag(lam, s, 1), a = lam^2, b = s^2, c = 1:
//   S_22 = 2[C1 + C2(a + 1) + D a - K/b] = 0  =>  b = K / (C1 + C2(a+1) + D a)
//   S_11 = 2[C1 + C2(b + 1) + D b - K/a]
//   S_33 = 2[C1 + C2(a + b) + D a b - K]      (out-of-plane reaction)
TEST(CiarletGeymonat, PlaneStrainUniaxial) {
  for (const auto& m : kMats) {
    const double K = m.C1 + 2 * m.C2 + m.D;
    for (double lam : {0.6, 1.0, 1.25, 2.0}) {
      const double a = lam * lam;
      const double b = K / (m.C1 + m.C2 * (a + 1) + m.D * a);
      const Mat3 F = diag(lam, std::sqrt(b), 1.0);
      const Mat3 S = m.stress(stentor::tmul(F, F));
      const double S11 = 2.0 * (m.C1 + m.C2 * (b + 1) + m.D * b - K / a);
      const double S33 = 2.0 * (m.C1 + m.C2 * (a + b) + m.D * a * b - K);
      const double scale = std::fabs(S11) + std::fabs(S33) + K;
      EXPECT_NEAR(S(0, 0), S11, 1e-12 * scale) << lam;
      EXPECT_NEAR(S(1, 1), 0.0, 1e-12 * scale) << lam;
      EXPECT_NEAR(S(2, 2), S33, 1e-12 * scale) << lam;
    }
  }
}

// (d2) Equibiaxial in-plane, F = diag(lam, lam, 1), a = lam^2, c = 1:
//   S_11 = S_22 = 2[C1 + C2(a + 1) + D a - K/a],  S_33 = 2[C1 + 2 C2 a + D a^2 - K].
// Also: plane-strain states keep S_13 = S_23 = 0 for any in-plane F.
TEST(CiarletGeymonat, PlaneStrainEquibiaxial) {
  for (const auto& m : kMats) {
    const double K = m.C1 + 2 * m.C2 + m.D;
    for (double lam : {0.8, 1.0, 1.3}) {
      const double a = lam * lam;
      const Mat3 F = diag(lam, lam, 1.0);
      const Mat3 S = m.stress(stentor::tmul(F, F));
      const double S11 = 2.0 * (m.C1 + m.C2 * (a + 1) + m.D * a - K / a);
      const double S33 = 2.0 * (m.C1 + 2 * m.C2 * a + m.D * a * a - K);
      const double scale = std::fabs(S11) + std::fabs(S33) + K;
      EXPECT_NEAR(S(0, 0), S11, 1e-12 * scale);
      EXPECT_NEAR(S(1, 1), S11, 1e-12 * scale);
      EXPECT_NEAR(S(2, 2), S33, 1e-12 * scale);
    }
    std::mt19937 rng(7);
    for (int n = 0; n < 5; ++n) {
      const Mat3 F = random_F(rng, true);
      const Mat3 S = m.stress(stentor::tmul(F, F));
      EXPECT_EQ(S(0, 2), 0.0);
      EXPECT_EQ(S(1, 2), 0.0);
      EXPECT_EQ(S(2, 0), 0.0);
      EXPECT_EQ(S(2, 1), 0.0);
    }
  }
}

// (d3) In-plane hydrostatic, F = diag(f, f, 1), area ratio J = f^2 = det F:
//   sigma_11 = sigma_22 = f^2 S_11 / J = S_11 = 2[C1 + C2(1 + J) + D J - K/J],
//   in-plane pressure p2(J) = -sigma_11 = 2[K/J - C1 - C2(1 + J) - D J],
//   sigma_33 = S_33 / J = (2/J)[C1 + 2 C2 J + D J^2 - K].
// p2'(1) = -2(K + C2 + D) = -(lambda + mu): the plane-strain bulk modulus.
TEST(CiarletGeymonat, PlaneStrainHydrostatic) {
  for (const auto& m : kMats) {
    const double K = m.C1 + 2 * m.C2 + m.D;
    for (double J : {0.5, 0.9, 1.0, 1.2}) {
      const double p2 = 2.0 * (K / J - m.C1 - m.C2 * (1 + J) - m.D * J);
      const double s33 = (2.0 / J) * (m.C1 + 2 * m.C2 * J + m.D * J * J - K);
      const double f = std::sqrt(J);
      const Mat3 F = diag(f, f, 1.0);
      const Mat3 sig = stentor::cauchy_stress(F, stentor::first_piola(F, m.stress(stentor::tmul(F, F))));
      const double scale = std::fabs(p2) + std::fabs(s33) + K;
      EXPECT_NEAR(sig(0, 0), -p2, 1e-12 * scale) << J;
      EXPECT_NEAR(sig(1, 1), -p2, 1e-12 * scale) << J;
      EXPECT_NEAR(sig(2, 2), s33, 1e-12 * scale) << J;
      EXPECT_NEAR(sig(0, 1), 0.0, 1e-14 * scale);
    }
    const double kappa2 = m.lame_lambda() + m.shear_modulus();
    EXPECT_NEAR(2.0 * (K + m.C2 + m.D), kappa2, 1e-12 * kappa2);
  }
}

// ---------------------------------------------------------------------------
// Objectivity and small-strain limit
// ---------------------------------------------------------------------------

// F -> QF leaves C, hence W and S, unchanged; P -> QP and sigma -> Q sigma Q^T.
TEST(CiarletGeymonat, Objectivity) {
  std::mt19937 rng(8);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (const auto& m : kMats)
    for (int n = 0; n < 5; ++n) {
      const Mat3 F = random_F(rng);
      const Mat3 Q = rotation(u(rng), u(rng), u(rng), 3.0 * u(rng));
      ASSERT_LE(max_abs(stentor::tmul(Q, Q) - Mat3::identity()), 1e-14);
      ASSERT_NEAR(stentor::det(Q), 1.0, 1e-14);
      const Mat3 QF = stentor::matmul(Q, F);
      const Mat3 C = stentor::tmul(F, F), Cq = stentor::tmul(QF, QF);
      const double W = m.energy(C), Wq = m.energy(Cq);
      const double K = m.C1 + 2 * m.C2 + m.D;
      EXPECT_NEAR(Wq, W, 1e-12 * (std::fabs(W) + K));
      const Mat3 S = m.stress(C), Sq = m.stress(Cq);
      EXPECT_LE(max_abs(Sq - S), 1e-12 * (max_abs(S) + K));
      const Mat3 P = stentor::first_piola(F, S), Pq = stentor::first_piola(QF, Sq);
      EXPECT_LE(max_abs(Pq - stentor::matmul(Q, P)), 1e-12 * (max_abs(P) + K));
      const Mat3 sig = stentor::cauchy_stress(F, P), sigq = stentor::cauchy_stress(QF, Pq);
      const Mat3 rot = stentor::matmul(stentor::matmul(Q, sig), stentor::transpose(Q));
      EXPECT_LE(max_abs(sigq - rot), 1e-12 * (max_abs(sig) + K));
      EXPECT_NEAR(stentor::von_mises(sigq), stentor::von_mises(sig), 1e-12 * (max_abs(sig) + K));
    }
}

// F = I + eps H: C - I = 2 eps e + eps^2 H^T H with e = sym(H), so
// S = CC(I) : (C - I)/2 + O(eps^2) = lambda tr(eps e) I + 2 mu eps e + O(eps^2).
// Check the remainder is O(eps^2): bounded by c eps^2 and ratio ~4 when eps halves.
TEST(CiarletGeymonat, SmallStrainLimit) {
  std::mt19937 rng(9);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (const auto& m : kMats) {
    Mat3 H;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) H(i, j) = u(rng);
    const double mu = m.shear_modulus(), la = m.lame_lambda();
    auto remainder = [&](double eps) {
      const Mat3 F = Mat3::identity() + eps * H;
      const Mat3 e = (0.5 * eps) * (H + stentor::transpose(H));
      const Mat3 lin = la * stentor::trace(e) * Mat3::identity() + (2.0 * mu) * e;
      return max_abs(m.stress(stentor::tmul(F, F)) - lin);
    };
    const double eps = 1e-3;
    const double r1 = remainder(eps), r2 = remainder(eps / 2);
    EXPECT_LE(r1, 50.0 * (la + mu) * eps * eps);
    EXPECT_GT(r1 / r2, 3.6);
    EXPECT_LT(r1 / r2, 4.4);
  }
}

// Input alternative E/nu (material/ElasticConstants.hpp): the tangent at C = I of the
// law built from (E, nu, C2) is the isotropic elasticity tensor of E and nu, checked on
// two states written with E and nu only (not mu, lambda): uniaxial stress
// eps = diag(1, -nu, -nu)/E gives sigma = diag(1, 0, 0); pure shear eps_01 = eps_10 = g/2
// gives sigma_01 = E/(2(1+nu)) g. In small strain S = 1/2 CC:dC, dC = 2 eps.
TEST(CiarletGeymonat, FromYoungPoissonTangentIsIsotropicElasticity) {
  const double cases[][3] = {{210e3, 0.3, 0.0}, {1.0, 0.45, 0.0}, {5.0, 0.25, 0.4}, {2.0, 0.49, 0.1}};
  for (const auto& cs : cases) {
    const double E = cs[0], nu = cs[1];
    const auto k = stentor::ciarlet_geymonat_from_lame(stentor::lame_from_young(E, nu), cs[2]);
    const CiarletGeymonat m{k.C1, k.C2, k.D};
    ASSERT_GT(m.C1, 0.0);
    ASSERT_GT(m.D, 0.0);
    EXPECT_EQ(m.C2, cs[2]);
    Ten4 CC;
    m.tangent(Mat3::identity(), CC);
    auto sigma = [&](const Mat3& eps) {  // sigma = CC : eps (= 1/2 CC : 2 eps)
      Mat3 s = Mat3::zero();
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
          for (int a = 0; a < 3; ++a)
            for (int b = 0; b < 3; ++b) s(i, j) += CC(i, j, a, b) * eps(a, b);
      return s;
    };
    const Mat3 s1 = sigma((1.0 / E) * diag(1.0, -nu, -nu));
    EXPECT_LE(max_abs(s1 - diag(1.0, 0.0, 0.0)), 1e-12 / (1.0 - 2.0 * nu)) << E << " " << nu;
    Mat3 shear = Mat3::zero();
    shear(0, 1) = shear(1, 0) = 0.5e-3;
    const Mat3 s2 = sigma(shear);
    Mat3 ref = Mat3::zero();
    ref(0, 1) = ref(1, 0) = E / (2.0 * (1.0 + nu)) * 1e-3;
    EXPECT_LE(max_abs(s2 - ref), 1e-14 * E) << E << " " << nu;
  }
}
