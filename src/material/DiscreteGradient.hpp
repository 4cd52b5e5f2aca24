// Energy-consistent material-point stresses for the time integrator
// (mission.md, model items 3 and 4; docs/verification.md, section
// "Material point: Gonzalez discrete gradient and Curnier viscosity").
//
// Gonzalez (2000) discrete gradient of a hyperelastic W(C) between C0 = C_n and
// C1 = C_{n+1}, with S = 2 dW/dC, CC = 2 dS/dC (any Mat with energy(C),
// stress(C), stress_and_tangent(C, S, CC), e.g. CiarletGeymonat):
//
//   Cm = (C0 + C1)/2,  dC = C1 - C0,  q = dC:dC,  Sm = S(Cm),
//   g  = W(C1) - W(C0) - 1/2 Sm:dC,
//   Sigma = Sm + 2 g dC / q          =>  1/2 Sigma:dC = W(C1) - W(C0)  exactly.
//
// Tangent w.r.t. C1 (C0 fixed), D_IJKL = dSigma_IJ/d(C1)_KL:
//   dSm/dC1 = 1/2 dS/dC(Cm) = 1/4 CC(Cm)
//   dg/dC1  = 1/2 S(C1) - 1/2 Sm - 1/8 CC(Cm):dC     (major symmetry of CC)
//   dq/dC1  = 2 dC
//   D = 1/4 CCm + 2 [ dC⊗dg/q - 2 g dC⊗dC/q^2 + (g/q) II ],
//   II_IJKL = 1/2(δ_IK δ_JL + δ_IL δ_JK).
// D has both minor symmetries but NOT major symmetry (dC⊗dg term): the
// Gonzalez tangent stiffness is unsymmetric.
//
// Small increments. The midpoint rule on f(t) = W(C0 + t dC), f' = 1/2 S:dC, gives
//   g = (1/24) d3W(Cm)[dC,dC,dC] + O(|dC|^5),
// so the correction |2 g dC/q| <= (1/12)|d3W| |dC|^2 + O(|dC|^4): Sigma -> Sm as
// O(|dC|^2). Computed as W(C1) - W(C0) - ..., g carries the absolute round-off
// eps_W ~ 1e-16 x (sum of |terms| of W) of the energy difference, which the
// correction amplifies to ~2 eps_W/|dC| in Sigma and ~6 eps_W/q in D (measured:
// ~5e-8 relative in Sigma at |dC| = 1e-6). Two remedies:
//
// 1. |dC| < kGonzalezSimpson = 1e-3: g by Simpson's rule on f' instead,
//      g_S = (1/12) (S0 + S1 - 2 Sm):dC,   S0 = S(C0), S1 = S(C1),
//    free of cancellation (round-off ~eps |S| |dC|). Its truncation error is
//    g_S - g = f^(5)(xi)/2880 = O(|d5W| |dC|^5 / 2880); for Ciarlet-Geymonat only
//    -K ln I3 contributes (f^(5) = -24 K tr((C^-1 dC)^5)), so
//    |g_S - g| <= K (|dC|/lmin)^5 / 120, lmin = smallest eigenvalue of C: at
//    |dC| = 1e-3 that is 8e-18 K for lmin = 1, 3e-16 K for lmin = 0.5 (round-off
//    level), 8e-13 K for lmin = 0.1 (stretch 0.3); then 1/2 Sigma:dC = dW holds
//    to that, not to round-off. In this branch D uses the exact derivative of g_S,
//      dg_S/dC1 = (1/12) [1/2 (CC(C1) - CC(Cm)):dC + S0 + S1 - 2 Sm],
//    so D is the exact derivative of the returned Sigma in both branches.
// 2. |dC| = sqrt(q) < kGonzalezGuard = 1e-6 (C is dimensionless, ~I), and dC = 0:
//      Sigma = Sm,  D = 1/4 CC(Cm).
//    This drops a correction of at most (1/12)|d3W| 1e-12 in Sigma (~1e-13 of
//    the moduli) and O(|d3W| |dC|) ~ 1e-7 of the moduli in D, and leaves
//    1/2 Sigma:dC - [W(C1) - W(C0)] = -g = O(|d3W| |dC|^3 / 24) < ~1e-19 |d3W|,
//    below the round-off of the computed energy difference itself. (Without the
//    guard, g_S/q and the dC(x)dg/q term would amplify round-off as eps |S|/|dC|.)
// 3. A law whose energy is only C^1 on some segments (Holzapfel–Gasser–Ogden: the fibres
//    switch on at I4 = 1, where the tangent jumps) defines smooth_between(C0, C1); where it
//    is false, Simpson's error bound (which needs d5W) does not hold, so g is evaluated
//    directly, W(C1) - W(C0) - 1/2 Sm:dC, at any |dC| >= kGonzalezGuard: the identity then
//    holds to the round-off of the energy difference (~eps_W / |dC| in Sigma).
#pragma once
#include <type_traits>

#include "stentor/tensor.hpp"

namespace stentor {

// smooth_between(C0, C1) of the law if it has one, else true (smooth laws).
template <class Mat, class = void>
struct HasSmoothBetween : std::false_type {};
template <class Mat>
struct HasSmoothBetween<Mat, std::void_t<decltype(std::declval<const Mat&>().smooth_between(Mat3(), Mat3()))>>
    : std::true_type {};
template <class Mat>
KOKKOS_INLINE_FUNCTION bool gonzalez_smooth(const Mat& m, const Mat3& C0, const Mat3& C1) {
  if constexpr (HasSmoothBetween<Mat>::value)
    return m.smooth_between(C0, C1);
  else
    return true;
}

// |C1 - C0| below which the discrete gradient falls back to S(Cm) (see above).
constexpr double kGonzalezGuard = 1e-6;
// |C1 - C0| below which g is evaluated by Simpson's rule on the stress.
constexpr double kGonzalezSimpson = 1e-3;

template <class Mat>
KOKKOS_INLINE_FUNCTION Mat3 gonzalez_stress(const Mat& m, const Mat3& C0, const Mat3& C1) {
  const Mat3 Cm = 0.5 * (C0 + C1);
  const Mat3 dC = C1 - C0;
  const double q = ddot(dC, dC);
  const Mat3 Sm = m.stress(Cm);
  const double n = std::sqrt(q);
  if (!(n >= kGonzalezGuard)) return Sm;  // also catches NaN
  const double g = n < kGonzalezSimpson && gonzalez_smooth(m, C0, C1)
                       ? ddot((m.stress(C0) - Sm) + (m.stress(C1) - Sm), dC) / 12.0
                       : m.energy(C1) - m.energy(C0) - 0.5 * ddot(Sm, dC);
  return Sm + (2.0 * g / q) * dC;
}

template <class Mat>
KOKKOS_INLINE_FUNCTION void gonzalez_stress_and_tangent(const Mat& m, const Mat3& C0, const Mat3& C1,
                                                        Mat3& Sigma, Ten4& D) {
  const Mat3 Cm = 0.5 * (C0 + C1);
  // Symmetric part of dC, so that D is symmetric in IJ and KL for any input.
  Mat3 dC;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) dC(i, j) = 0.5 * ((C1(i, j) - C0(i, j)) + (C1(j, i) - C0(j, i)));
  const double q = ddot(dC, dC);
  Mat3 Sm;
  m.stress_and_tangent(Cm, Sm, D);  // D <- CC(Cm)
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      for (int k = 0; k < 3; ++k)
        for (int l = 0; l < 3; ++l) D(i, j, k, l) *= 0.25;
  const double n = std::sqrt(q);
  if (!(n >= kGonzalezGuard)) {
    Sigma = Sm;
    return;
  }
  const Mat3 dCraw = C1 - C0;
  double g;
  Mat3 G;  // dg/dC1
  if (n < kGonzalezSimpson && gonzalez_smooth(m, C0, C1)) {
    // g_S = (1/12)(S0 + S1 - 2 Sm):dC,
    // dg_S/dC1 = (1/12)[1/2 (CC1 - CCm):dC + S0 + S1 - 2 Sm], with D = CCm/4 here.
    Mat3 S1;
    Ten4 CC1;
    m.stress_and_tangent(C1, S1, CC1);
    const Mat3 R = (m.stress(C0) - Sm) + (S1 - Sm);
    g = ddot(R, dCraw) / 12.0;
    for (int k = 0; k < 3; ++k)
      for (int l = 0; l < 3; ++l) {
        double cd = 0.0;
        for (int i = 0; i < 3; ++i)
          for (int j = 0; j < 3; ++j) cd += dC(i, j) * (0.5 * CC1(i, j, k, l) - 2.0 * D(i, j, k, l));
        G(k, l) = (cd + R(k, l)) / 12.0;
      }
  } else {
    // g = W1 - W0 - 1/2 Sm:dC,
    // dg/dC1 = 1/2 S(C1) - 1/2 Sm - 1/8 CCm:dC = 1/2 (S1 - Sm) - 1/2 (dC:D), D = CCm/4 here.
    g = m.energy(C1) - m.energy(C0) - 0.5 * ddot(Sm, dCraw);
    const Mat3 S1 = m.stress(C1);
    for (int k = 0; k < 3; ++k)
      for (int l = 0; l < 3; ++l) {
        double cd = 0.0;
        for (int i = 0; i < 3; ++i)
          for (int j = 0; j < 3; ++j) cd += dC(i, j) * D(i, j, k, l);
        G(k, l) = 0.5 * (S1(k, l) - Sm(k, l)) - 0.5 * cd;
      }
  }
  for (int k = 0; k < 3; ++k)  // symmetrise (exact for symmetric C0, C1 already)
    for (int l = k + 1; l < 3; ++l) G(k, l) = G(l, k) = 0.5 * (G(k, l) + G(l, k));
  const double gq = g / q;
  Sigma = Sm + (2.0 * gq) * dCraw;

  const double a = 2.0 / q, b = -4.0 * gq / q, c = 2.0 * gq;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      for (int k = 0; k < 3; ++k)
        for (int l = 0; l < 3; ++l) {
          double v = dC(i, j) * (a * G(k, l) + b * dC(k, l));
          v += c * 0.5 * ((i == k && j == l ? 1.0 : 0.0) + (i == l && j == k ? 1.0 : 0.0));
          D(i, j, k, l) += v;
        }
}

// Curnier viscosity, W^v(Cdot) = eta/2 tr(Cdot^2): S^v = 2 eta Cdot with the
// discrete rate Cdot = (C1 - C0)/dt (evaluated at n+1/2).
KOKKOS_INLINE_FUNCTION Mat3 curnier_viscous_stress(double eta, const Mat3& C0, const Mat3& C1, double dt) {
  return (2.0 * eta / dt) * (C1 - C0);
}

// dS^v/dC1 = (2 eta/dt) II (symmetric identity).
KOKKOS_INLINE_FUNCTION void curnier_viscous_tangent(double eta, double dt, Ten4& D) {
  const double c = eta / dt;  // 2 eta/dt * 1/2
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      for (int k = 0; k < 3; ++k)
        for (int l = 0; l < 3; ++l)
          D(i, j, k, l) = c * ((i == k && j == l ? 1.0 : 0.0) + (i == l && j == k ? 1.0 : 0.0));
}

// Energy dissipated over the step per unit reference volume:
// S^v : 1/2 dC = eta dC:dC / dt >= 0 (the power S^v:1/2 Cdot times dt).
KOKKOS_INLINE_FUNCTION double curnier_dissipation(double eta, const Mat3& C0, const Mat3& C1, double dt) {
  const Mat3 dC = C1 - C0;
  return eta * ddot(dC, dC) / dt;
}

}  // namespace stentor
