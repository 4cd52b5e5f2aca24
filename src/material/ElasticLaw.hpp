// The one material dispatch of the element kernels (docs/deck.md, "Materials"): a small
// value type holding the law of a block, copied into the Kokkos kernels like each law.
// Every hyperelastic law is a stateless value type with energy(C), stress(C) and
// stress_and_tangent(C, S, CC) (S = 2 dW/dC, CC = 2 dS/dC); ElasticLaw forwards to the
// one chosen by `kind`, so solid_element, the Gonzalez discrete gradient
// (DiscreteGradient.hpp, which needs only W, S, CC of a law) and the cell fields are
// compiled once for all laws. The branch on `kind` is the same for every Gauss point of
// a block (no divergence on a GPU).
//
// A law with a position-dependent fibre frame (Holzapfel–Gasser–Ogden) gets its fibre
// directions at each Gauss point from at(X): the kernels call it with the reference
// position of the point; for the other laws it returns the law unchanged.
#pragma once
#include "material/CiarletGeymonat.hpp"
#include "material/HolzapfelGasserOgden.hpp"
#include "material/MooneyRivlin.hpp"
#include "material/NeoHookean.hpp"

namespace stentor {

struct ElasticLaw {
  enum Kind : int { kCiarletGeymonat = 0, kNeoHookean = 1, kMooneyRivlin = 2, kHolzapfelGasserOgden = 3 };
  int kind = kCiarletGeymonat;
  CiarletGeymonat cg{1.0, 0.0, 1.0};
  NeoHookean nh{1.0, 0.0};
  MooneyRivlin mr{1.0, 0.0, 0.0};
  HolzapfelGasserOgden hgo{{1.0, 0.0}, 0.0, 1.0, {1.0, 0.0, 0.0}, {1.0, 0.0, 0.0}};
  FibreFrame frame{{0.0, 0.0, 0.0}, {0.0, 0.0, 1.0}, 0.0};

  static ElasticLaw ciarlet_geymonat(const CiarletGeymonat& m) {
    ElasticLaw l;
    l.kind = kCiarletGeymonat;
    l.cg = m;
    return l;
  }
  static ElasticLaw neo_hookean(const NeoHookean& m) {
    ElasticLaw l;
    l.kind = kNeoHookean;
    l.nh = m;
    return l;
  }
  static ElasticLaw mooney_rivlin(const MooneyRivlin& m) {
    ElasticLaw l;
    l.kind = kMooneyRivlin;
    l.mr = m;
    return l;
  }

  static ElasticLaw holzapfel_gasser_ogden(const HolzapfelGasserOgden& m, const FibreFrame& f) {
    ElasticLaw l;
    l.kind = kHolzapfelGasserOgden;
    l.hgo = m;
    l.frame = f;
    return l;
  }

  KOKKOS_INLINE_FUNCTION bool needs_position() const { return kind == kHolzapfelGasserOgden; }

  // The law at reference point X (fibre directions of the frame there).
  KOKKOS_INLINE_FUNCTION ElasticLaw at(const double* X) const {
    ElasticLaw l = *this;
    if (kind == kHolzapfelGasserOgden) frame.directions(X, l.hgo.a0, l.hgo.g0);
    return l;
  }

  // For DiscreteGradient.hpp (see there): false where a fibre switches on along C0 -> C1.
  KOKKOS_INLINE_FUNCTION bool smooth_between(const Mat3& C0, const Mat3& C1) const {
    return kind != kHolzapfelGasserOgden || hgo.smooth_between(C0, C1);
  }

  KOKKOS_INLINE_FUNCTION double energy(const Mat3& C) const {
    switch (kind) {
      case kNeoHookean: return nh.energy(C);
      case kMooneyRivlin: return mr.energy(C);
      case kHolzapfelGasserOgden: return hgo.energy(C);
      default: return cg.energy(C);
    }
  }
  KOKKOS_INLINE_FUNCTION Mat3 stress(const Mat3& C) const {
    switch (kind) {
      case kNeoHookean: return nh.stress(C);
      case kMooneyRivlin: return mr.stress(C);
      case kHolzapfelGasserOgden: return hgo.stress(C);
      default: return cg.stress(C);
    }
  }
  KOKKOS_INLINE_FUNCTION void stress_and_tangent(const Mat3& C, Mat3& S, Ten4& CC) const {
    switch (kind) {
      case kNeoHookean: nh.stress_and_tangent(C, S, CC); return;
      case kMooneyRivlin: mr.stress_and_tangent(C, S, CC); return;
      case kHolzapfelGasserOgden: hgo.stress_and_tangent(C, S, CC); return;
      default: cg.stress_and_tangent(C, S, CC); return;
    }
  }
};

// The law at the reference point X = sum_a N_a X_a of an element (kernels); a law without
// a frame is returned as it is.
template <class Law>
KOKKOS_INLINE_FUNCTION Law law_at_point(const Law& m, int, const double*, const double (*)[3]) {
  return m;
}
KOKKOS_INLINE_FUNCTION ElasticLaw law_at_point(const ElasticLaw& m, int nn, const double* N, const double (*X)[3]) {
  if (!m.needs_position()) return m;
  double x[3] = {0.0, 0.0, 0.0};
  for (int a = 0; a < nn; ++a)
    for (int i = 0; i < 3; ++i) x[i] += N[a] * X[a][i];
  return m.at(x);
}

}  // namespace stentor
