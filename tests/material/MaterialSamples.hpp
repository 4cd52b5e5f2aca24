// Shared samples for material-point tests: parameter sets and random deformations.
#pragma once
#include <random>

#include "material/CiarletGeymonat.hpp"
#include "stentor/tensor.hpp"

namespace stentor::testing {

// Two parameter sets: moderate, and nearly incompressible (D >> C1, C2) with C2 = 0.
inline const CiarletGeymonat kMats[] = {{0.8, 0.3, 1.5}, {50.0, 0.0, 2000.0}};

// Random deformation gradient with det F >= 0.3 (3D) or a plane-strain one
// (F_33 = 1, no out-of-plane shear) when plane = true.
inline Mat3 random_F(std::mt19937& rng, bool plane = false) {
  std::uniform_real_distribution<double> u(-0.4, 0.4);
  for (;;) {
    Mat3 F = Mat3::identity();
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) F(i, j) += u(rng);
    if (plane) {
      F(0, 2) = F(1, 2) = F(2, 0) = F(2, 1) = 0.0;
      F(2, 2) = 1.0;
    }
    if (det(F) >= 0.3) return F;
  }
}

// diag(x, y, z), and the symmetric unit direction (e_I e_J + e_J e_I) / 2 for finite
// differences in C.
inline Mat3 diag(double x, double y, double z) {
  Mat3 m = Mat3::zero();
  m(0, 0) = x, m(1, 1) = y, m(2, 2) = z;
  return m;
}

inline Mat3 sym_unit(int I, int J) {
  Mat3 E = Mat3::zero();
  E(I, J) += 0.5;
  E(J, I) += 0.5;
  return E;
}

// max |S - 2 dW/dC (central differences of step h)| / (max |S| + modulus).
template <class Law>
double stress_fd_error(const Law& m, const Mat3& C, double modulus, double h = 1e-5) {
  const Mat3 S = m.stress(C);
  Mat3 Sfd;
  for (int I = 0; I < 3; ++I)
    for (int J = 0; J < 3; ++J) {
      const Mat3 E = sym_unit(I, J);
      Sfd(I, J) = (m.energy(C + h * E) - m.energy(C - h * E)) / h;
    }
  return max_abs(S - Sfd) / (max_abs(S) + modulus);
}

// max |CC - 2 dS/dC (central differences of step h)| / max |CC|.
template <class Law>
double tangent_fd_error(const Law& m, const Mat3& C, double h = 1e-6) {
  Mat3 S;
  Ten4 CC, diff;
  m.stress_and_tangent(C, S, CC);
  for (int K = 0; K < 3; ++K)
    for (int L = 0; L < 3; ++L) {
      const Mat3 E = sym_unit(K, L);
      const Mat3 dS = (1.0 / h) * (m.stress(C + h * E) - m.stress(C - h * E));
      for (int I = 0; I < 3; ++I)
        for (int J = 0; J < 3; ++J) diff(I, J, K, L) = CC(I, J, K, L) - dS(I, J);
    }
  return max_abs(diff) / max_abs(CC);
}

}  // namespace stentor::testing
