// Gauss-point state interface for materials with internal variables (docs/plasticity.md).
//
// A material with state is a small value type (copied into Kokkos kernels, like
// CiarletGeymonat) that declares a flat array of history variables per Gauss point and
// maps (C_{n+1}, history_n) -> (S, CC, history_{n+1}, stored energy, dissipation).
// It is the same idea as ExaCMech's getHistInfo / getResponseSngl, in Stentor's
// conventions (total Lagrangian, S and CC = 2 dS/dC, dP/dF by spatial_tangent_dPdF):
//
//   static constexpr int kNumHist;                        // doubles per Gauss point, > 0
//   static constexpr HistoryVar kHistory[kNumHist];       // name, initial value, output?
//   template <bool WithTangent = true, class HIn, class HOut>
//   KOKKOS_INLINE_FUNCTION PointResponse update(const Mat3& C, const HIn& h_n,
//                                               const HOut& h_np1) const;
//   template <class HIn>
//   KOKKOS_INLINE_FUNCTION Potential frozen_potential(const HIn& h_n) const;
//
// update<false> may leave PointResponse::CC unset (the residual-only kernels call it);
// S, h_np1, energy and dissipation must be those of update<true>. frozen_potential(h_n)
// is the elastic potential C -> Psi(C, h_n) at the state h_n held fixed, a value type
// with energy(C), stress(C) and stress_and_tangent(C, S, CC) like a hyperelastic law:
// the Gonzalez step of dynamics takes its discrete gradient (docs/plasticity.md,
// "Dynamics"), and the output takes its stress at the committed state. The update is
// then energy-consistent when Psi_{n+1} - Psi_n = [Psi(C_{n+1}, h_n) - Psi(C_n, h_n)] - D
// holds with the returned energy and dissipation D >= 0.
//
// The element kernels, the history views (commit / roll back), the checkpoint tables
// and the cell output are generic over such a law; MaterialRegistry.hpp lists the laws
// a block can have (docs/plasticity.md, "Adding a material").
//
// h_n and h_np1 are anything with operator[](int) giving a double (resp. double&):
// a double*, or a rank-1 Kokkos::View / subview of a per-block View(ngp, kNumHist).
// update() reads only h_n and writes every entry of h_np1 (trial copy during Newton;
// the caller commits h_np1 -> h_n when the step is accepted and simply discards it
// on a cut-back). h_n and h_np1 must not alias. The update is a pure function of
// (C, h_n): re-evaluating it at every global Newton iterate is the "trial" state.
//
// Units: energy and dissipation are densities per unit reference volume (Pa = J/m^3
// when the moduli are in Pa).
#pragma once
#include <type_traits>
#include <utility>

#include "stentor/tensor.hpp"

namespace stentor {

// One history variable per Gauss point.
struct HistoryVar {
  const char* name;  // column / HDF5 dataset name
  double initial;    // value at t = 0 (before any update)
  bool output;       // written to the HDF5 output (all are restart data)
};

// What one Gauss-point update returns (besides h_{n+1}).
struct PointResponse {
  Mat3 S;              // second Piola–Kirchhoff stress at t_{n+1}
  Ten4 CC;             // consistent tangent 2 dS/dC_{n+1} (minor symmetries)
  double energy;       // stored energy density Psi_{n+1}
  double dissipation;  // dissipation of the step t_n -> t_{n+1}, >= 0
  int iterations;      // local Newton iterations (0: elastic point)
  bool converged;      // false: the local solve failed; the caller must cut back
};

// Doubles of Gauss-point history a law declares: Law::kNumHist, 0 for a law without one
// (the stateless hyperelastic laws and ElasticLaw).
template <class Law, class = void>
struct LawHistorySize : std::integral_constant<int, 0> {};
template <class Law>
struct LawHistorySize<Law, std::void_t<decltype(Law::kNumHist)>> : std::integral_constant<int, Law::kNumHist> {};
template <class Law>
inline constexpr bool kHasHistory = LawHistorySize<Law>::value > 0;

// A law with history may define its own Gonzalez dynamic step (Plasticity.hpp):
//   template <bool WithTangent, class HIn, class HOut>
//   PointResponse dynamic_update(const Mat3& C_n, const Mat3& C_np1, const HIn& h_n,
//                                const HOut& h_np1, Ten4& D) const;
// (Plasticity.hpp adds an optional out-argument, the mean-value point of its step.)
// S = the stress Sigma of the momentum equation, D = dSigma/dC_np1, and
// Psi_{n+1} - Psi_n = 1/2 Sigma : (C_np1 - C_n) - dissipation. Without it the kernel takes the
// discrete gradient of frozen_potential(h_n) (HyperelasticElement.hpp, history_gonzalez).
template <class Law, class = void>
struct HasDynamicUpdate : std::false_type {};
template <class Law>
struct HasDynamicUpdate<Law, std::void_t<decltype(std::declval<const Law&>().template dynamic_update<true>(
                                 Mat3(), Mat3(), static_cast<const double*>(nullptr), static_cast<double*>(nullptr),
                                 std::declval<Ten4&>()))>> : std::true_type {};

// Fills a history row with the declared initial values.
template <class Material, class Row>
KOKKOS_INLINE_FUNCTION void init_history(const Row& h) {
  for (int i = 0; i < Material::kNumHist; ++i) h[i] = Material::kHistory[i].initial;
}

// Index of a history variable by name, -1 if absent (host side: output set-up).
template <class Material>
inline int history_index(const char* name) {
  for (int i = 0; i < Material::kNumHist; ++i) {
    const char* a = Material::kHistory[i].name;
    const char* b = name;
    while (*a && *a == *b) ++a, ++b;
    if (*a == *b) return i;
  }
  return -1;
}

// A stateless hyperelastic law (energy(C), stress_and_tangent(C, S, CC)) seen through
// the same interface with no history, so one templated element kernel serves both.
template <class Elastic>
struct HyperelasticPoint {
  Elastic law;
  static constexpr int kNumHist = 0;
  static constexpr HistoryVar kHistory[1] = {{"", 0.0, false}};  // unused (size 0)

  template <class HIn, class HOut>
  KOKKOS_INLINE_FUNCTION PointResponse update(const Mat3& C, const HIn&, const HOut&) const {
    PointResponse r;
    law.stress_and_tangent(C, r.S, r.CC);
    r.energy = law.energy(C);
    r.dissipation = 0.0;
    r.iterations = 0;
    r.converged = true;
    return r;
  }
};

}  // namespace stentor
