// Compressible Mooney–Rivlin law (the coupled form of Bonet & Wood, Nonlinear
// Continuum Mechanics, section 6.4.4, with a (ln J)^2 volumetric term):
//
//   W(C) = C1 (I1 - 3) + C2 (I2 - 3) - 2 (C1 + 2 C2) ln J + lam/2 (ln J)^2,
//   I1 = tr C,  I2 = ((tr C)^2 - tr C^2)/2,  J = sqrt(det C).
//
// The -2(C1 + 2C2) ln J term makes the reference configuration stress-free (at C = I,
// dI1/dC = I, dI2/dC = 2I, d ln J/dC = I/2). C1 > 0, C2 >= 0, lam >= 0 [Pa]; polyconvex
// (I1, I2 convex in F and cof F, -ln J and (ln J)^2 convex in J for J < e, and the sum
// -2(C1+2C2) ln J + lam/2 (ln J)^2 is convex in J where lam (1 - ln J) + 2(C1+2C2) > 0).
// Nearly incompressible (lam >> C1, C2) it tends to the incompressible Mooney–Rivlin
// solid W = C1 (I1 - 3) + C2 (I2 - 3) (Rivlin 1948; Treloar), whose uniaxial nominal
// stress is P = 2 (l - l^-2)(C1 + C2/l) and equibiaxial P = 2 (l - l^-5)(C1 + C2 l^2).
//
// Derivatives (InvariantTangent.hpp):
//   S  = 2(C1 + C2 I1) I - 2 C2 C + (lam ln J - 2(C1 + 2C2)) Ci,
//   CC = 4 C2 (I⊗I - II) + lam Ci⊗Ci + (2(C1 + 2C2) - lam ln J)(Ci_IK Ci_JL + Ci_IL Ci_JK).
// At C = I: CC = (lam + 4 C2) I⊗I + 4 (C1 + C2) II, so the small-strain constants are
//   mu = 2 (C1 + C2),  lambda = lam + 4 C2
// (ElasticConstants.hpp: from E/nu or mu/lambda with C2 given, C1 = mu/2 - C2,
// lam = lambda - 4 C2). C2 = 0 is the neo-Hookean law with mu = 2 C1 (NeoHookean.hpp).
#pragma once
#include "material/InvariantTangent.hpp"

namespace stentor {

struct MooneyRivlin {
  double C1, C2, lam;

  KOKKOS_INLINE_FUNCTION double energy(const Mat3& C) const {
    const double I1 = trace(C);
    const double I2 = 0.5 * (I1 * I1 - ddot(C, transpose(C)));
    const double lnJ = 0.5 * std::log(det(C));
    return C1 * (I1 - 3.0) + C2 * (I2 - 3.0) - 2.0 * (C1 + 2.0 * C2) * lnJ + 0.5 * lam * lnJ * lnJ;
  }

  KOKKOS_INLINE_FUNCTION Mat3 stress(const Mat3& C) const {
    double I3;
    const Mat3 Ci = inverse_and_det(C, I3);
    return invariant_stress(C, Ci, 2.0 * (C1 + C2 * trace(C)), -2.0 * C2, ci_coefficient(I3));
  }

  KOKKOS_INLINE_FUNCTION void stress_and_tangent(const Mat3& C, Mat3& S, Ten4& CC) const {
    double I3;
    const Mat3 Ci = inverse_and_det(C, I3);
    const double c = ci_coefficient(I3);
    S = invariant_stress(C, Ci, 2.0 * (C1 + C2 * trace(C)), -2.0 * C2, c);
    invariant_tangent(Ci, 4.0 * C2, lam, -c, CC);
  }

  KOKKOS_INLINE_FUNCTION void tangent(const Mat3& C, Ten4& CC) const {
    Mat3 S;
    stress_and_tangent(C, S, CC);
  }

  KOKKOS_INLINE_FUNCTION double shear_modulus() const { return 2.0 * (C1 + C2); }
  KOKKOS_INLINE_FUNCTION double lame_lambda() const { return lam + 4.0 * C2; }

 private:
  // Coefficient of Ci in S: lam ln J - 2(C1 + 2 C2).
  KOKKOS_INLINE_FUNCTION double ci_coefficient(double I3) const { return lam * 0.5 * std::log(I3) - 2.0 * (C1 + 2.0 * C2); }
};

}  // namespace stentor
