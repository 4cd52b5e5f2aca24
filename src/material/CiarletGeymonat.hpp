// Ciarlet–Geymonat compressible hyperelastic law (mission.md, model item 2):
//
//   W(C) = C1(I1-3) + C2(I2-3) + D(I3-1) - K ln I3,   K = C1 + 2 C2 + D,
//   I1 = tr C, I2 = ((tr C)^2 - tr C^2)/2, I3 = det C.
//
// K is chosen so that S(I) = 0. Plane strain uses the same formulas: the caller
// passes C with C(2,2) = 1 and zero out-of-plane shear.
//
// Derivatives (C symmetric, Ci = C^{-1} = cof(C)/I3):
//   dI1/dC = I,  dI2/dC = I1 I - C,  dI3/dC = I3 Ci,  d(ln I3)/dC = Ci
//   S  = 2 dW/dC = 2[(C1 + C2 I1) I - C2 C + (D I3 - K) Ci]
//   dCi_IJ/dC_KL = -1/2 (Ci_IK Ci_JL + Ci_IL Ci_JK)      (symmetrised)
//   CC = 2 dS/dC = 4 C2 (I⊗I - II) + 4 D I3 Ci⊗Ci + 4 (K - D I3) Ci⊙Ci,
//   II_IJKL = 1/2(δ_IK δ_JL + δ_IL δ_JK),  (Ci⊙Ci)_IJKL = 1/2(Ci_IK Ci_JL + Ci_IL Ci_JK).
// At C = I: CC = 4(C2+D) I⊗I + 4(C1+C2) II = λ I⊗I + 2μ II, hence
// μ = 2(C1+C2), λ = 4(C2+D).
//
// Requires det C > 0 (ln I3); the energy is NaN/inf otherwise, which callers
// (line search, step cutting) can detect.
#pragma once
#include "material/InvariantTangent.hpp"
#include "stentor/tensor.hpp"

namespace stentor {

struct CiarletGeymonat {
  double C1, C2, D;

  // Coefficient of ln I3 that makes the reference configuration stress-free.
  KOKKOS_INLINE_FUNCTION double K() const { return C1 + 2.0 * C2 + D; }

  KOKKOS_INLINE_FUNCTION double energy(const Mat3& C) const {
    const double I1 = trace(C);
    const double I2 = 0.5 * (I1 * I1 - ddot(C, transpose(C)));  // tr(C^2) = C:C^T
    const double I3 = det(C);
    return C1 * (I1 - 3.0) + C2 * (I2 - 3.0) + D * (I3 - 1.0) - K() * std::log(I3);
  }

  KOKKOS_INLINE_FUNCTION Mat3 stress(const Mat3& C) const {
    double I3;
    const Mat3 Ci = inverse_and_det(C, I3);
    return stress_from(C, Ci, I3);
  }

  KOKKOS_INLINE_FUNCTION void tangent(const Mat3& C, Ten4& CC) const {
    double I3;
    const Mat3 Ci = inverse_and_det(C, I3);
    tangent_from(Ci, I3, CC);
  }

  // One determinant/cofactor evaluation shared by S and CC (the Newton hot path).
  KOKKOS_INLINE_FUNCTION void stress_and_tangent(const Mat3& C, Mat3& S, Ten4& CC) const {
    double I3;
    const Mat3 Ci = inverse_and_det(C, I3);
    S = stress_from(C, Ci, I3);
    tangent_from(Ci, I3, CC);
  }

  KOKKOS_INLINE_FUNCTION double shear_modulus() const { return 2.0 * (C1 + C2); }
  KOKKOS_INLINE_FUNCTION double lame_lambda() const { return 4.0 * (C2 + D); }

 private:
  // S = a I + b C + c Ci and CC = p (I⊗I - II) + q Ci⊗Ci + r (Ci_IK Ci_JL + Ci_IL Ci_JK)
  // with the coefficients of the header comment (InvariantTangent.hpp fills them).
  KOKKOS_INLINE_FUNCTION Mat3 stress_from(const Mat3& C, const Mat3& Ci, double I3) const {
    return invariant_stress(C, Ci, 2.0 * (C1 + C2 * trace(C)), -2.0 * C2, 2.0 * (D * I3 - K()));
  }

  KOKKOS_INLINE_FUNCTION void tangent_from(const Mat3& Ci, double I3, Ten4& CC) const {
    // r = 4(K - D I3) * 1/2 from the symmetrisation
    invariant_tangent(Ci, 4.0 * C2, 4.0 * D * I3, 2.0 * (K() - D * I3), CC);
  }
};

}  // namespace stentor
