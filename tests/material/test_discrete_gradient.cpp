// Material-point verification of the Gonzalez discrete-gradient stress and the
// Curnier viscous stress (docs/verification.md, section "Material point:
// Gonzalez discrete gradient and Curnier viscosity").
//
//   Sigma = S(Cm) + 2 g dC/(dC:dC),  g = W(C1) - W(C0) - 1/2 S(Cm):dC,
//   Cm = (C0 + C1)/2, dC = C1 - C0;  D = dSigma/dC1 (C0 fixed).
//   S^v = 2 eta (C1 - C0)/dt,  dissipation S^v : dC/2 = eta dC:dC/dt.
//
// The measured numbers quoted in the docs are printed with the prefix "[dg]".
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>
#include <string>

#include "MaterialSamples.hpp"
#include "material/CiarletGeymonat.hpp"
#include "material/DiscreteGradient.hpp"

using stentor::CiarletGeymonat;
using stentor::Mat3;
using stentor::Ten4;
using stentor::testing::kMats;
using stentor::testing::random_F;
using stentor::testing::sym_unit;

namespace {

double norm(const Mat3& m) { return std::sqrt(stentor::ddot(m, m)); }

Mat3 random_C(std::mt19937& rng, bool plane) {
  const Mat3 F = random_F(rng, plane);
  return stentor::tmul(F, F);
}

// A pair (C0, C1) with C1 - C0 along the direction between two random C's and of
// Frobenius norm `size` (size <= 0: the full random pair). C1 stays positive
// definite: it is a convex combination of two positive definite C's (scale
// factor <= 1; pairs closer than `size` are redrawn).
void random_pair(std::mt19937& rng, bool plane, double size, Mat3& C0, Mat3& C1) {
  for (;;) {
    C0 = random_C(rng, plane);
    const Mat3 Cb = random_C(rng, plane);
    const Mat3 d = Cb - C0;
    if (size <= 0.0) {
      C1 = Cb;
      return;
    }
    const double t = size / norm(d);
    if (t > 1.0) continue;  // pair too close for this size: draw again
    C1 = C0 + t * d;
    return;
  }
}

// Symmetric unit perturbation E = (e_I⊗e_J + e_J⊗e_I)/2: for D with minor
// symmetry in KL, D:E = D_..IJ, so a central difference along E gives D_..IJ.
// max |D - FD(Sigma)| / max |D| with central differences of step h.
template <class Mat>
double tangent_fd_error(const Mat& m, const Mat3& C0, const Mat3& C1, double h) {
  Mat3 Sig;
  Ten4 D, diff;
  stentor::gonzalez_stress_and_tangent(m, C0, C1, Sig, D);
  for (int K = 0; K < 3; ++K)
    for (int L = 0; L < 3; ++L) {
      const Mat3 E = sym_unit(K, L);
      const Mat3 dS = (1.0 / (2.0 * h)) *
                      (stentor::gonzalez_stress(m, C0, C1 + h * E) - stentor::gonzalez_stress(m, C0, C1 - h * E));
      for (int I = 0; I < 3; ++I)
        for (int J = 0; J < 3; ++J) diff(I, J, K, L) = D(I, J, K, L) - dS(I, J);
    }
  return max_abs(diff) / max_abs(D);
}

}  // namespace

// ---------------------------------------------------------------------------
// Gonzalez stress
// ---------------------------------------------------------------------------

// 1/2 Sigma:dC = W(C1) - W(C0) for random pairs, 3D and plane strain, from far
// apart down to |dC| = 1e-5 (both evaluations of g: direct for |dC| >= 1e-3,
// Simpson below); relative to |W0| + |W1| + |1/2 S(Cm):dC|.
TEST(GonzalezStress, DiscreteEnergyIdentityRandomPairs) {
  std::mt19937 rng(21);
  for (double size : {0.0, 0.3, 1e-2, 2e-3, 9e-4, 5e-4, 1e-5}) {
    double worst = 0.0;
    for (const auto& m : kMats)
      for (bool plane : {false, true})
        for (int n = 0; n < 20; ++n) {
          Mat3 C0, C1;
          random_pair(rng, plane, size, C0, C1);
          const Mat3 dC = C1 - C0;
          const Mat3 Sig = stentor::gonzalez_stress(m, C0, C1);
          const double W0 = m.energy(C0), W1 = m.energy(C1);
          const double scale =
              std::fabs(W0) + std::fabs(W1) + 0.5 * std::fabs(stentor::ddot(m.stress(0.5 * (C0 + C1)), dC));
          const double rel = std::fabs(0.5 * stentor::ddot(Sig, dC) - (W1 - W0)) / scale;
          worst = std::fmax(worst, rel);
          EXPECT_LE(rel, 1e-12) << "plane " << plane << " size " << size << " sample " << n;
          EXPECT_EQ(max_abs(Sig - stentor::transpose(Sig)), 0.0);
          if (plane) {  // in-plane pairs keep the out-of-plane shear at zero
            EXPECT_EQ(Sig(0, 2), 0.0);
            EXPECT_EQ(Sig(1, 2), 0.0);
          }
        }
    std::printf("[dg] energy identity, |dC| = %s: max relative residual %.2e\n",
                size > 0.0 ? std::to_string(size).c_str() : "random", worst);
  }
}

// Sigma - S(Cm) = O(|dC|^2): halving dC along a fixed direction divides the
// correction by ~4 (|dC| = 0.02 ... 0.000625, across the Simpson switch).
TEST(GonzalezStress, CorrectionIsSecondOrder) {
  std::mt19937 rng(22);
  double rmin = 1e300, rmax = 0.0;
  for (const auto& m : kMats)
    for (bool plane : {false, true})
      for (int n = 0; n < 5; ++n) {
        Mat3 C0, Cb;
        random_pair(rng, plane, 0.0, C0, Cb);
        const Mat3 d = (1.0 / norm(Cb - C0)) * (Cb - C0);
        double prev = 0.0;
        for (int k = 0; k < 6; ++k) {
          const double s = 0.02 * std::ldexp(1.0, -k);
          const Mat3 C1 = C0 + s * d;
          const double err = max_abs(stentor::gonzalez_stress(m, C0, C1) - m.stress(0.5 * (C0 + C1)));
          if (k > 0) {
            const double r = prev / err;
            rmin = std::fmin(rmin, r), rmax = std::fmax(rmax, r);
            EXPECT_GT(r, 3.7) << "k " << k;
            EXPECT_LT(r, 4.3) << "k " << k;
          }
          prev = err;
        }
      }
  std::printf("[dg] halving |dC| from 0.02: correction ratio in [%.3f, %.3f]\n", rmin, rmax);
}

// Just above and just below each switch the two branches agree:
//  - guard (1e-6): the dropped correction is O(|dC|^2) ~ 1e-13 of the moduli;
//  - Simpson switch (1e-3): g_S - g = O(|dC|^5) plus the round-off of the direct
//    g, ~2 eps_W/|dC| ~ 1e-11 of the moduli in Sigma.
// Sigma to 1e-10 relative; D to 1e-5 at the guard (the dropped part of D is
// O(|d3W| |dC|), ~1e-6 of |D|) and 1e-8 at the Simpson switch.
TEST(GonzalezStress, BranchesAreContinuous) {
  std::mt19937 rng(23);
  struct Case { double tau, tolS, tolD; const char* name; };
  const Case cases[] = {{stentor::kGonzalezGuard, 1e-10, 1e-5, "guard 1e-6"},
                        {stentor::kGonzalezSimpson, 1e-10, 1e-8, "Simpson switch 1e-3"}};
  for (const Case& c : cases) {
    double worstS = 0.0, worstD = 0.0;
    for (const auto& m : kMats)
      for (bool plane : {false, true})
        for (int n = 0; n < 10; ++n) {
          Mat3 C0, Cb;
          random_pair(rng, plane, 0.0, C0, Cb);
          const Mat3 d = (1.0 / norm(Cb - C0)) * (Cb - C0);
          Mat3 Sa, Sb;
          Ten4 Da, Db, dD;
          stentor::gonzalez_stress_and_tangent(m, C0, C0 + (c.tau * (1.0 + 1e-9)) * d, Sa, Da);
          stentor::gonzalez_stress_and_tangent(m, C0, C0 + (c.tau * (1.0 - 1e-9)) * d, Sb, Db);
          // Reference scale: the stress plus the moduli (S can be ~0 near C = I).
          const double scale = max_abs(m.stress(C0)) + m.C1 + m.C2 + m.D;
          const double relS = max_abs(Sa - Sb) / scale;
          for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j)
              for (int k = 0; k < 3; ++k)
                for (int l = 0; l < 3; ++l) dD(i, j, k, l) = Da(i, j, k, l) - Db(i, j, k, l);
          const double relD = max_abs(dD) / max_abs(Da);
          worstS = std::fmax(worstS, relS), worstD = std::fmax(worstD, relD);
          EXPECT_LE(relS, c.tolS) << c.name << " plane " << plane << " sample " << n;
          EXPECT_LE(relD, c.tolD) << c.name << " plane " << plane << " sample " << n;
        }
    std::printf("[dg] continuity at %s: max jump Sigma %.2e, D %.2e (relative)\n", c.name, worstS, worstD);
  }
}

// dC = 0 exactly: no 0/0, Sigma = S(C0), D = CC(C0)/4.
TEST(GonzalezStress, ZeroIncrementGivesStressAndQuarterTangent) {
  std::mt19937 rng(24);
  for (const auto& m : kMats) {
    const Mat3 C = random_C(rng, false);
    Mat3 Sig, S;
    Ten4 D, CC;
    stentor::gonzalez_stress_and_tangent(m, C, C, Sig, D);
    m.stress_and_tangent(C, S, CC);
    EXPECT_EQ(max_abs(Sig - S), 0.0);
    EXPECT_EQ(max_abs(stentor::gonzalez_stress(m, C, C) - S), 0.0);
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        for (int k = 0; k < 3; ++k)
          for (int l = 0; l < 3; ++l) EXPECT_EQ(D(i, j, k, l), 0.25 * CC(i, j, k, l));
  }
}

// D against central differences of Sigma w.r.t. C1, symmetric perturbations:
// far pairs and |dC| = 1e-2 (direct g, h = 1e-6), |dC| = 1e-4 and 1e-5 (Simpson
// g, near the guard, h = 1e-7), and inside the guard (|dC| = 1e-7, h = 1e-8 so
// that every evaluation stays inside).
TEST(GonzalezStress, TangentMatchesFiniteDifference) {
  std::mt19937 rng(25);
  struct Case { double size, h; const char* name; };
  const Case cases[] = {{0.0, 1e-6, "random pairs"}, {1e-2, 1e-6, "|dC| = 1e-2"},
                        {1e-4, 1e-7, "|dC| = 1e-4"}, {1e-5, 1e-7, "|dC| = 1e-5"}, {1e-7, 1e-8, "|dC| = 1e-7 (guard)"}};
  for (const Case& c : cases) {
    double worst = 0.0;
    for (const auto& m : kMats)
      for (bool plane : {false, true})
        for (int n = 0; n < 8; ++n) {
          Mat3 C0, C1;
          random_pair(rng, plane, c.size, C0, C1);
          const double e = tangent_fd_error(m, C0, C1, c.h);
          worst = std::fmax(worst, e);
          EXPECT_LE(e, 1e-6) << c.name << " plane " << plane << " sample " << n;
        }
    std::printf("[dg] tangent vs FD, %s: max relative error %.2e\n", c.name, worst);
  }
}

// D has both minor symmetries; stress_and_tangent's Sigma equals gonzalez_stress.
TEST(GonzalezStress, TangentMinorSymmetryAndConsistency) {
  std::mt19937 rng(26);
  for (const auto& m : kMats)
    for (double size : {0.0, 1e-4}) {
      Mat3 C0, C1, Sig;
      Ten4 D;
      random_pair(rng, false, size, C0, C1);
      stentor::gonzalez_stress_and_tangent(m, C0, C1, Sig, D);
      EXPECT_EQ(max_abs(Sig - stentor::gonzalez_stress(m, C0, C1)), 0.0);
      const double tol = 1e-14 * max_abs(D);
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
          for (int k = 0; k < 3; ++k)
            for (int l = 0; l < 3; ++l) {
              EXPECT_NEAR(D(i, j, k, l), D(j, i, k, l), tol);
              EXPECT_NEAR(D(i, j, k, l), D(i, j, l, k), tol);
            }
    }
}

// ---------------------------------------------------------------------------
// Curnier viscosity
// ---------------------------------------------------------------------------

TEST(CurnierViscosity, StressDissipationAndTangent) {
  std::mt19937 rng(27);
  const double eta = 0.37;
  for (bool plane : {false, true})
    for (int n = 0; n < 10; ++n) {
      const Mat3 C0 = random_C(rng, plane), C1 = random_C(rng, plane);
      const double dt = 1e-3 * (n + 1);
      const Mat3 Sv = stentor::curnier_viscous_stress(eta, C0, C1, dt);
      const Mat3 Cdot = (1.0 / dt) * (C1 - C0);
      EXPECT_LE(max_abs(Sv - (2.0 * eta) * Cdot), 1e-15 * max_abs(Sv));
      const double dis = stentor::curnier_dissipation(eta, C0, C1, dt);
      EXPECT_GE(dis, 0.0);
      EXPECT_NEAR(dis, eta * stentor::ddot(C1 - C0, C1 - C0) / dt, 1e-14 * dis);
      EXPECT_NEAR(dis, 0.5 * stentor::ddot(Sv, C1 - C0), 1e-13 * dis);  // S^v : dC/2
      // Tangent: linear in C1, so the central difference is exact up to round-off.
      Ten4 Dv;
      stentor::curnier_viscous_tangent(eta, dt, Dv);
      const double h = 1e-3;
      for (int K = 0; K < 3; ++K)
        for (int L = 0; L < 3; ++L) {
          const Mat3 E = sym_unit(K, L);
          const Mat3 dS = (1.0 / (2.0 * h)) * (stentor::curnier_viscous_stress(eta, C0, C1 + h * E, dt) -
                                               stentor::curnier_viscous_stress(eta, C0, C1 - h * E, dt));
          for (int I = 0; I < 3; ++I)
            for (int J = 0; J < 3; ++J) EXPECT_NEAR(Dv(I, J, K, L), dS(I, J), 1e-9 * eta / dt);
        }
    }
  // No motion, no dissipation.
  const Mat3 C = random_C(rng, false);
  EXPECT_EQ(stentor::curnier_dissipation(eta, C, C, 0.1), 0.0);
  EXPECT_EQ(max_abs(stentor::curnier_viscous_stress(eta, C, C, 0.1)), 0.0);
}
