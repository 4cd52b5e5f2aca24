// Isotropic continuum damage over a hyperelastic law: the discontinuous (Mullins-type)
// damage of Miehe (1995, Eur. J. Mech. A/Solids 14:697), of the kind Balzani et al.
// (2012, Comput. Methods Biomech. Biomed. Engin. 15:1) use for arterial walls
// overstretched by a stent. A law with Gauss-point history (MaterialState.hpp); a second
// law next to CiarletGeymonatPlasticity with its own history layout
// (docs/plasticity.md, "Adding a material").
//
// Model. Psi(C, d) = (1 - d) W0(C), W0 >= 0 the virgin energy (Elastic: NeoHookean, whose
// W0 = mu/2 (I1 - 3 - 2 ln J) + lambda/2 (ln J)^2 is >= 0 since I1 - 3 >= 2 ln J).
//   alpha_t = max_{s <= t} W0(C_s)   [Pa]: the largest virgin energy reached (history),
//   d = g(alpha) = d_inf (1 - exp(-alpha / beta)),  0 <= d_inf < 1, beta > 0 [Pa].
// Damage grows only while W0 exceeds its past maximum (loading); unloading and reloading
// below alpha are elastic with the softened energy (1 - d) W0.
//
// Update (backward Euler): W0 = W0(C_{n+1}); loading iff W0 > alpha_n, then
// alpha_{n+1} = W0 and d_{n+1} = g(W0), else alpha and d keep their values.
//   S  = (1 - d_{n+1}) S0,
//   CC = 2 dS/dC = (1 - d_{n+1}) CC0 - g'(alpha_{n+1}) S0 (x) S0 while loading
//        (dalpha/dC = dW0/dC = S0/2, g' = (d_inf - d)/beta), (1 - d_{n+1}) CC0 otherwise,
// symmetric in both cases.
// Energy. Psi_{n+1} = (1 - d_{n+1}) W0_{n+1}; dissipation of the step
//   D = (d_{n+1} - d_n) W0_{n+1} >= 0
// (the rate -dPsi/dd d' = W0 d' at the end point). Exact one-step identity:
//   Psi_{n+1} - Psi_n = (1 - d_n) [W0(C_{n+1}) - W0(C_n)] - D,
// whose bracket is the work of the frozen-state potential C -> (1 - d_n) W0(C)
// (frozen_potential), so the Gonzalez step of the kernels is energy-consistent with it.
#pragma once
#include <cmath>

#include "material/MaterialState.hpp"
#include "stentor/tensor.hpp"

namespace stentor {

// A hyperelastic law times a constant factor s (> 0): W = s W0, S = s S0, CC = s CC0.
template <class Elastic>
struct ScaledPotential {
  Elastic law;
  double s;
  KOKKOS_INLINE_FUNCTION double energy(const Mat3& C) const { return s * law.energy(C); }
  KOKKOS_INLINE_FUNCTION Mat3 stress(const Mat3& C) const { return s * law.stress(C); }
  KOKKOS_INLINE_FUNCTION void stress_and_tangent(const Mat3& C, Mat3& S, Ten4& CC) const {
    law.stress_and_tangent(C, S, CC);
    S = s * S;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        for (int k = 0; k < 3; ++k)
          for (int l = 0; l < 3; ++l) CC(i, j, k, l) *= s;
  }
};

template <class Elastic>
struct IsotropicDamage {
  Elastic elastic;  // the virgin law W0 (energy >= 0)
  double d_inf;     // saturation damage, 0 <= d_inf < 1
  double beta;      // damage energy scale [Pa, the unit of the moduli], > 0

  enum : int { kMaxEnergy = 0, kDamage = 1, kDissipation = 2 };
  static constexpr int kNumHist = 3;
  static constexpr HistoryVar kHistory[kNumHist] = {
      {"max_virgin_energy", 0.0, true},    // alpha = max W0 so far [Pa = J/m^3]
      {"damage", 0.0, true},               // d = g(alpha)
      {"damage_dissipation", 0.0, true}};  // accumulated D [Pa = J/m^3]

  // d = g(alpha).
  KOKKOS_INLINE_FUNCTION double damage(double alpha) const { return -d_inf * std::expm1(-alpha / beta); }

  template <bool WithTangent = true, class HIn, class HOut>
  KOKKOS_INLINE_FUNCTION PointResponse update(const Mat3& C, const HIn& hn, const HOut& h1) const {
    PointResponse r;
    Mat3 S0;
    if constexpr (WithTangent)
      elastic.stress_and_tangent(C, S0, r.CC);
    else
      S0 = elastic.stress(C);
    const double W0 = elastic.energy(C);
    const bool loading = W0 > hn[kMaxEnergy];
    const double alpha = loading ? W0 : hn[kMaxEnergy];
    const double d = loading ? damage(W0) : hn[kDamage];
    r.S = (1.0 - d) * S0;
    if constexpr (WithTangent) {
      const double gp = loading ? (d_inf - d) / beta : 0.0;  // g'(alpha)
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
          for (int k = 0; k < 3; ++k)
            for (int l = 0; l < 3; ++l) r.CC(i, j, k, l) = (1.0 - d) * r.CC(i, j, k, l) - gp * S0(i, j) * S0(k, l);
    }
    r.energy = (1.0 - d) * W0;
    r.dissipation = (d - hn[kDamage]) * W0;
    r.iterations = 0;
    r.converged = true;
    h1[kMaxEnergy] = alpha;
    h1[kDamage] = d;
    h1[kDissipation] = hn[kDissipation] + r.dissipation;
    return r;
  }

  // C -> (1 - d_n) W0(C): the potential at the damage of row hn held fixed.
  template <class HIn>
  KOKKOS_INLINE_FUNCTION ScaledPotential<Elastic> frozen_potential(const HIn& hn) const {
    return ScaledPotential<Elastic>{elastic, 1.0 - hn[kDamage]};
  }
};

}  // namespace stentor
