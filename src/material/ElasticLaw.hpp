// The one material dispatch of the element kernels (docs/deck.md, "Materials"): a small
// value type holding the law of a block, copied into the Kokkos kernels like each law.
// Every hyperelastic law is a stateless value type with energy(C), stress(C) and
// stress_and_tangent(C, S, CC) (S = 2 dW/dC, CC = 2 dS/dC); ElasticLaw forwards to the
// one chosen by `kind`, so solid_element, the Gonzalez discrete gradient
// (DiscreteGradient.hpp, which needs only W, S, CC of a law) and the cell fields are
// compiled once for all laws. The branch on `kind` is the same for every Gauss point of
// a block (no divergence on a GPU).
#pragma once
#include "material/CiarletGeymonat.hpp"
#include "material/MooneyRivlin.hpp"
#include "material/NeoHookean.hpp"

namespace stentor {

struct ElasticLaw {
  enum Kind : int { kCiarletGeymonat = 0, kNeoHookean = 1, kMooneyRivlin = 2 };
  int kind = kCiarletGeymonat;
  CiarletGeymonat cg{1.0, 0.0, 1.0};
  NeoHookean nh{1.0, 0.0};
  MooneyRivlin mr{1.0, 0.0, 0.0};

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

  KOKKOS_INLINE_FUNCTION double energy(const Mat3& C) const {
    switch (kind) {
      case kNeoHookean: return nh.energy(C);
      case kMooneyRivlin: return mr.energy(C);
      default: return cg.energy(C);
    }
  }
  KOKKOS_INLINE_FUNCTION Mat3 stress(const Mat3& C) const {
    switch (kind) {
      case kNeoHookean: return nh.stress(C);
      case kMooneyRivlin: return mr.stress(C);
      default: return cg.stress(C);
    }
  }
  KOKKOS_INLINE_FUNCTION void stress_and_tangent(const Mat3& C, Mat3& S, Ten4& CC) const {
    switch (kind) {
      case kNeoHookean: nh.stress_and_tangent(C, S, CC); return;
      case kMooneyRivlin: mr.stress_and_tangent(C, S, CC); return;
      default: cg.stress_and_tangent(C, S, CC); return;
    }
  }
};

}  // namespace stentor
