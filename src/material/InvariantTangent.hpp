// Building blocks shared by the isotropic laws written in the invariants of C
// (CiarletGeymonat.hpp, NeoHookean.hpp, MooneyRivlin.hpp, HolzapfelGasserOgden.hpp).
//
// With Ci = C^{-1}, J = sqrt(det C):
//   dI1/dC = I,  dI2/dC = I1 I - C,  d(ln J)/dC = 1/2 Ci,
//   dCi_IJ/dC_KL = -1/2 (Ci_IK Ci_JL + Ci_IL Ci_JK)   (symmetrised).
// Every law here has S = a I + b C + c Ci and
//   CC = 2 dS/dC = p (I⊗I - II) + q Ci⊗Ci + r (Ci_IK Ci_JL + Ci_IL Ci_JK),
//   II_IJKL = 1/2 (δ_IK δ_JL + δ_IL δ_JK),
// so one routine fills CC from (p, q, r).
#pragma once
#include "stentor/tensor.hpp"

namespace stentor {

// C^{-1} via the cofactor (symmetric for symmetric C), and I3 = det C.
KOKKOS_INLINE_FUNCTION Mat3 inverse_and_det(const Mat3& C, double& I3) {
  const Mat3 cof = cofactor(C);
  I3 = C(0, 0) * cof(0, 0) + C(0, 1) * cof(0, 1) + C(0, 2) * cof(0, 2);  // row expansion
  return (1.0 / I3) * cof;
}

// S = a I + b C + c Ci.
KOKKOS_INLINE_FUNCTION Mat3 invariant_stress(const Mat3& C, const Mat3& Ci, double a, double b, double c) {
  Mat3 S;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) S(i, j) = b * C(i, j) + c * Ci(i, j);
  for (int i = 0; i < 3; ++i) S(i, i) += a;
  return S;
}

// CC = p (I⊗I - II) + q Ci⊗Ci + r (Ci_IK Ci_JL + Ci_IL Ci_JK); the 36 distinct entries
// (I<=J, K<=L) are evaluated and copied to their minor-symmetric permutations.
KOKKOS_INLINE_FUNCTION void invariant_tangent(const Mat3& Ci, double p, double q, double r, Ten4& CC) {
  for (int I = 0; I < 3; ++I)
    for (int J = I; J < 3; ++J)
      for (int K = 0; K < 3; ++K)
        for (int L = K; L < 3; ++L) {
          double v = q * Ci(I, J) * Ci(K, L) + r * (Ci(I, K) * Ci(J, L) + Ci(I, L) * Ci(J, K));
          if (I == J && K == L) v += p;
          if (I == K && J == L) v -= (I == J) ? p : 0.5 * p;  // II: 1 on the diagonal, 1/2 off
          CC(I, J, K, L) = v;
          CC(J, I, K, L) = v;
          CC(I, J, L, K) = v;
          CC(J, I, L, K) = v;
        }
}

}  // namespace stentor
