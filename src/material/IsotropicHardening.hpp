// The nonlinear part of the isotropic hardening of MultiplicativePlasticity (Plasticity.hpp,
// docs/plasticity.md "Hardening laws"). The yield stress at equivalent plastic strain alpha is
//   sigma_y(alpha) = Y + H alpha + kappa(alpha),
// Y > 0 the initial yield stress and H >= 0 the linear modulus (members of the plasticity law),
// kappa the nonlinear part held here, kappa(0) = 0, non-decreasing:
//   none:  kappa = 0 (linear hardening; every function below returns an exact 0.0, so
//          `x + kappa` is bit for bit `x`);
//   Voce:  kappa = Q (1 - exp(-delta alpha)), Q = Y_inf - Y >= 0, delta > 0 [-]
//          (sigma_y = Y + H alpha + (Y_inf - Y)(1 - exp(-delta alpha)): saturation at Y_inf
//          plus the linear slope H);
//   table: sigma_y piecewise linear through the points (eps_i, sigma_i), eps_0 = 0 < eps_1 <
//          ... (at most kMaxPoints), sigma_0 = Y <= sigma_1 <= ..., extrapolated past the last
//          point with the slope of the last segment (a table ending in two equal stresses is
//          perfectly plastic from there); kappa = sigma_y - sigma_0, and the law has H = 0.
// Stored energy of the hardening psi(alpha) = int_0^alpha kappa, in closed form:
//   Voce:  psi = Q phi(delta alpha) / delta,  phi(x) = x + expm1(-x) = x^2/2 - x^3/6 + ...
//          (its series below |x| = 0.05, free of the cancellation of x + expm1(-x));
//   table: the exact integral of the piecewise-linear kappa (trapezoids over the segments).
// psi is convex (kappa non-decreasing); its increments over a step come without cancellation:
//   Voce:  psi(a0 + dg) - psi(a0) = Q [-expm1(-delta a0) dg + exp(-delta a0) phi(delta dg) / delta],
//          kappa(a0 + dg) - kappa(a0) = -Q exp(-delta a0) expm1(-delta dg);
//   table: the exact integral over [a0, a0 + dg] only, segment by segment.
#pragma once
#include <cmath>

#include "stentor/tensor.hpp"

namespace stentor {

struct NonlinearHardening {
  enum Kind : int { kNone = 0, kVoce = 1, kTable = 2 };
  static constexpr int kMaxPoints = 32;
  int kind = kNone;
  double Q = 0.0;      // Voce: Y_inf - Y >= 0
  double delta = 0.0;  // Voce: saturation rate > 0 [-]
  int n = 0;           // table: number of points, 2 ... kMaxPoints
  double eps[kMaxPoints] = {};  // table: equivalent plastic strains, eps[0] = 0, increasing
  double kap[kMaxPoints] = {};  // table: sigma_i - sigma_0, non-decreasing

  static NonlinearHardening voce(double Y, double Y_inf, double delta) {
    NonlinearHardening h;
    h.kind = kVoce, h.Q = Y_inf - Y, h.delta = delta;
    return h;
  }
  // The table (sigma_i, eps_i), i < count (validated by the deck: deck/Config.cpp).
  static NonlinearHardening table(const double* strains, const double* stresses, int count) {
    NonlinearHardening h;
    h.kind = kTable, h.n = count;
    for (int i = 0; i < count; ++i) h.eps[i] = strains[i], h.kap[i] = stresses[i] - stresses[0];
    return h;
  }

  // phi(x) = x + expm1(-x) >= 0 for x >= 0.
  KOKKOS_INLINE_FUNCTION static double phi(double x) {
    if (x < 0.05) return x * x * (0.5 + x * (-1.0 / 6 + x * (1.0 / 24 + x * (-1.0 / 120 + x * (1.0 / 720 + x * (-1.0 / 5040 + x / 40320))))));
    return x + std::expm1(-x);
  }
  // Table segment of alpha: eps[i] <= alpha < eps[i+1], the last one past the last point.
  KOKKOS_INLINE_FUNCTION int segment(double alpha) const {
    int i = 0;
    while (i < n - 2 && alpha >= eps[i + 1]) ++i;
    return i;
  }
  KOKKOS_INLINE_FUNCTION double seg_slope(int i) const { return (kap[i + 1] - kap[i]) / (eps[i + 1] - eps[i]); }
  KOKKOS_INLINE_FUNCTION double seg_kappa(int i, double a) const { return kap[i] + seg_slope(i) * (a - eps[i]); }

  KOKKOS_INLINE_FUNCTION double kappa(double alpha) const {
    if (kind == kVoce) return -Q * std::expm1(-delta * alpha);
    if (kind == kTable) return seg_kappa(segment(alpha), alpha);
    return 0.0;
  }
  // d kappa / d alpha (the right derivative at a table point).
  KOKKOS_INLINE_FUNCTION double slope(double alpha) const {
    if (kind == kVoce) return Q * delta * std::exp(-delta * alpha);
    if (kind == kTable) return seg_slope(segment(alpha));
    return 0.0;
  }
  KOKKOS_INLINE_FUNCTION double kappa_increment(double a0, double dg) const {
    if (kind == kVoce) return -Q * std::exp(-delta * a0) * std::expm1(-delta * dg);
    if (kind == kTable) return kappa(a0 + dg) - kappa(a0);
    return 0.0;
  }
  // psi(a0 + dg) - psi(a0), dg >= 0.
  KOKKOS_INLINE_FUNCTION double energy_increment(double a0, double dg) const {
    if (kind == kVoce)
      return Q * (-std::expm1(-delta * a0) * dg + std::exp(-delta * a0) * phi(delta * dg) / delta);
    if (kind != kTable) return 0.0;
    // Segment by segment over lengths (not end points), so a step inside one segment gives
    // (kappa(a0) + 1/2 slope dg) dg with the dg itself.
    double sum = 0.0, lo = a0, rest = dg;
    while (rest > 0.0) {
      const int i = segment(lo);
      const double len = i < n - 2 ? std::fmin(rest, eps[i + 1] - lo) : rest;
      sum += (seg_kappa(i, lo) + 0.5 * seg_slope(i) * len) * len;
      if (len == rest) break;
      rest -= len, lo = eps[i + 1];
    }
    return sum;
  }
  KOKKOS_INLINE_FUNCTION double energy(double alpha) const {
    if (kind == kVoce) return Q * phi(delta * alpha) / delta;
    return energy_increment(0.0, alpha);
  }
};

}  // namespace stentor
