// Finite-strain kinematics at a material point: first Piola stress, its
// derivative with respect to F, Cauchy stress and von Mises measure.
#pragma once
#include "stentor/tensor.hpp"

namespace stentor {

// Right Cauchy–Green tensor C = F^T F.
KOKKOS_INLINE_FUNCTION Mat3 right_cauchy_green(const Mat3& F) { return tmul(F, F); }

// First Piola–Kirchhoff stress P = F S.
KOKKOS_INLINE_FUNCTION Mat3 first_piola(const Mat3& F, const Mat3& S) { return matmul(F, S); }

// A_iJkL = dP_iJ / dF_kL for P = F S(C), C = F^T F, CC = 2 dS/dC (minor-symmetric).
//   dP_iJ = dF_iI S_IJ + F_iI dS_IJ,  dS_IJ = 1/2 CC_IJMN dC_MN,
//   dC_MN = dF_kM F_kN + F_kM dF_kN  (sum over k)
//   => dS_IJ/dF_kL = 1/2 (CC_IJLN F_kN + CC_IJML F_kM) = CC_IJLN F_kN   (minor symmetry)
//   => A_iJkL = δ_ik S_JL + F_iI CC_IJLN F_kN.
// Done as two 3-term contractions (T = CC·F^T, then F·T): 2·243 multiply-adds
// instead of 9 per entry.
KOKKOS_INLINE_FUNCTION void spatial_tangent_dPdF(const Mat3& F, const Mat3& S, const Ten4& CC,
                                                 Ten4& A) {
  double T[3][3][3][3];  // T[I][J][L][k] = sum_N CC_IJLN F_kN
  for (int I = 0; I < 3; ++I)
    for (int J = 0; J < 3; ++J)
      for (int L = 0; L < 3; ++L)
        for (int k = 0; k < 3; ++k)
          T[I][J][L][k] = CC(I, J, L, 0) * F(k, 0) + CC(I, J, L, 1) * F(k, 1) + CC(I, J, L, 2) * F(k, 2);
  for (int i = 0; i < 3; ++i)
    for (int J = 0; J < 3; ++J)
      for (int k = 0; k < 3; ++k)
        for (int L = 0; L < 3; ++L) {
          double v = F(i, 0) * T[0][J][L][k] + F(i, 1) * T[1][J][L][k] + F(i, 2) * T[2][J][L][k];
          if (i == k) v += S(J, L);
          A(i, J, k, L) = v;
        }
}

// Cauchy stress sigma = P F^T / det F.
KOKKOS_INLINE_FUNCTION Mat3 cauchy_stress(const Mat3& F, const Mat3& P) {
  Mat3 r;
  const double invJ = 1.0 / det(F);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      r(i, j) = invJ * (P(i, 0) * F(j, 0) + P(i, 1) * F(j, 1) + P(i, 2) * F(j, 2));
  return r;
}

// von Mises equivalent stress sqrt(3/2 s:s), s = dev(sigma).
KOKKOS_INLINE_FUNCTION double von_mises(const Mat3& sigma) {
  const Mat3 s = deviator(sigma);
  return std::sqrt(1.5 * ddot(s, s));
}

}  // namespace stentor
