// Eigen-decomposition of symmetric 3 x 3 tensors, and what the output fields derive from
// it (Assembler::cell_fields): principal values sorted, the logarithm of an SPD tensor.
//
// Cyclic Jacobi: each sweep zeroes the off-diagonal entries (0,1), (0,2), (1,2) in turn
// by a plane rotation A <- P^T A P with the smaller rotation angle (t = tan(phi) of
// |phi| <= pi/4, Golub & Van Loan 8.5.2), which converges quadratically and, unlike the
// closed-form cubic roots, keeps repeated and nearly repeated eigenvalues (a uniaxial
// stretch: two equal lateral stretches) accurate to round-off and V orthonormal. Stops
// when the off-diagonal part is below 1e-17 of the diagonal's norm (3 to 5 sweeps in
// practice; at most 32).
#pragma once
#include <cmath>

#include "stentor/tensor.hpp"

namespace stentor {

// Symmetric eigen-decomposition A = V diag(lam) V^T by cyclic Jacobi rotations
// (columns of V are the eigenvectors; robust for repeated eigenvalues).
KOKKOS_INLINE_FUNCTION void sym_eig3(const Mat3& Ain, double lam[3], Mat3& V) {
  Mat3 A = Ain;
  V = Mat3::identity();
  for (int sweep = 0; sweep < 32; ++sweep) {
    const double off = A(0, 1) * A(0, 1) + A(0, 2) * A(0, 2) + A(1, 2) * A(1, 2);
    const double dia = A(0, 0) * A(0, 0) + A(1, 1) * A(1, 1) + A(2, 2) * A(2, 2);
    if (off <= 1e-34 * dia || off == 0.0) break;
    for (int p = 0; p < 2; ++p)
      for (int q = p + 1; q < 3; ++q) {
        if (A(p, q) == 0.0) continue;
        const double th = (A(q, q) - A(p, p)) / (2.0 * A(p, q));
        const double t = (th >= 0.0 ? 1.0 : -1.0) / (std::fabs(th) + std::sqrt(th * th + 1.0));
        const double c = 1.0 / std::sqrt(t * t + 1.0), s = t * c;
        for (int k = 0; k < 3; ++k) {  // A <- A P, V <- V P
          const double akp = A(k, p), akq = A(k, q);
          A(k, p) = c * akp - s * akq, A(k, q) = s * akp + c * akq;
          const double vkp = V(k, p), vkq = V(k, q);
          V(k, p) = c * vkp - s * vkq, V(k, q) = s * vkp + c * vkq;
        }
        for (int k = 0; k < 3; ++k) {  // A <- P^T A
          const double apk = A(p, k), aqk = A(q, k);
          A(p, k) = c * apk - s * aqk, A(q, k) = s * apk + c * aqk;
        }
        A(p, q) = A(q, p) = 0.0;
      }
  }
  for (int i = 0; i < 3; ++i) lam[i] = A(i, i);
}

// Eigenvalues of a symmetric tensor, largest first.
KOKKOS_INLINE_FUNCTION void principal_values(const Mat3& A, double lam[3]) {
  Mat3 V;
  sym_eig3(A, lam, V);
  for (int i = 0; i < 2; ++i)
    for (int j = 0; j < 2 - i; ++j)
      if (lam[j] < lam[j + 1]) {
        const double t = lam[j];
        lam[j] = lam[j + 1], lam[j + 1] = t;
      }
}

// (1/2) ln B of a symmetric positive definite B = V diag(b) V^T: V diag(ln(b)/2) V^T.
// With B = F F^T this is the spatial Hencky strain ln V (V the left stretch).
KOKKOS_INLINE_FUNCTION Mat3 half_log_spd(const Mat3& B) {
  double b[3];
  Mat3 V;
  sym_eig3(B, b, V);
  Mat3 L = Mat3::zero();
  for (int a = 0; a < 3; ++a) {
    const double h = 0.5 * std::log(b[a]);
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) L(i, j) += h * V(i, a) * V(j, a);
  }
  return L;
}

}  // namespace stentor
