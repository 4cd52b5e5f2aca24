// Compressible neo-Hookean law (Ciarlet 1988, Simo & Pister 1984 form; the one in
// FEBio's "neo-Hookean" and in Bonet & Wood, Nonlinear Continuum Mechanics, eq. 6.28):
//
//   W(C) = mu/2 (I1 - 3) - mu ln J + lambda/2 (ln J)^2,   I1 = tr C,  J = sqrt(det C).
//
// mu, lambda [Pa] are the small-strain Lame constants (or from E, nu:
// ElasticConstants.hpp). W(I) = 0, S(I) = 0; W -> +inf as J -> 0. Polyconvex (I1 convex in
// F; f(J) = -mu ln J + lambda/2 (ln J)^2 has f'' = (mu + lambda (1 - ln J))/J^2) wherever
// ln J < 1 + mu/lambda, i.e. in every state short of a volume growth by e = 2.7. This is Mooney–Rivlin (MooneyRivlin.hpp) with C1 = mu/2,
// C2 = 0, lam = lambda (a test checks that they agree).
//
// Derivatives (InvariantTangent.hpp: dI1/dC = I, d(ln J)/dC = Ci/2, Ci = C^{-1}):
//   S  = 2 dW/dC = mu I + (lambda ln J - mu) Ci,
//   CC = 2 dS/dC = lambda Ci⊗Ci + (mu - lambda ln J)(Ci_IK Ci_JL + Ci_IL Ci_JK).
// At C = I: CC = lambda I⊗I + 2 mu II, the isotropic elasticity tensor.
// Principal stretches l_i (C = diag(l_i^2)): S_ii = mu (1 - 1/l_i^2) + lambda ln J / l_i^2.
#pragma once
#include "material/InvariantTangent.hpp"

namespace stentor {

struct NeoHookean {
  double mu, lambda;

  KOKKOS_INLINE_FUNCTION double energy(const Mat3& C) const {
    const double lnJ = 0.5 * std::log(det(C));
    return 0.5 * mu * (trace(C) - 3.0) - mu * lnJ + 0.5 * lambda * lnJ * lnJ;
  }

  KOKKOS_INLINE_FUNCTION Mat3 stress(const Mat3& C) const {
    double I3;
    const Mat3 Ci = inverse_and_det(C, I3);
    return invariant_stress(C, Ci, mu, 0.0, lambda * 0.5 * std::log(I3) - mu);
  }

  KOKKOS_INLINE_FUNCTION void stress_and_tangent(const Mat3& C, Mat3& S, Ten4& CC) const {
    double I3;
    const Mat3 Ci = inverse_and_det(C, I3);
    const double c = lambda * 0.5 * std::log(I3) - mu;
    S = invariant_stress(C, Ci, mu, 0.0, c);
    invariant_tangent(Ci, 0.0, lambda, -c, CC);
  }

  KOKKOS_INLINE_FUNCTION void tangent(const Mat3& C, Ten4& CC) const {
    Mat3 S;
    stress_and_tangent(C, S, CC);
  }
};

}  // namespace stentor
