// Radial reference for a pressurised tube of compressible Holzapfel-Gasser-Ogden layers
// (material/HolzapfelGasserOgden.hpp, fibres and dispersion included) at a uniform axial
// stretch (plane strain by default), solved independently of the finite elements. Used by
// test_artery_inflation.cpp (the layered artery, docs/artery.md) and
// test_balloon_inflation.cpp (the stent's deformable balloon, docs/stent.md);
// docs/verification.md.
//
// Axial symmetry, r = r(R), uniform axial stretch lambda_z (1: plane strain): in the
// cylindrical basis C = diag(r'^2, (r/R)^2, lambda_z^2), the fibres a0, g0 = (0, cos beta,
// +-sin beta) (their theta-z parts cancel), S = law.stress(C) with the material functions
// of the FE code. The nominal stresses P_rR = r' S_RR, P_tT = (r/R) S_TT satisfy the
// radial equilibrium
//   dP_rR/dR = (P_tT - P_rR) / R,
// with P_rR continuous across the layer interfaces (traction), P_rR(Ri) = -p lambda_z r(Ri)/Ri
// (the follower pressure: sigma_rr = -p on the deformed lumen, P_rR = J sigma_rr / r'
// = sigma_rr lambda_z r/R) and P_rR(Ro) = 0. State (r, P_rR) integrated by RK4 (r' from
// P_rR by Newton with the law's tangent), shooting on r(Ri) by bisection. This is the
// compressible problem itself: no incompressibility approximation.
#pragma once
#include <cmath>
#include <vector>

#include "material/HolzapfelGasserOgden.hpp"

namespace stentor::testing::radial {

// One layer R0 <= R <= R1 of the law (its fibres in the cylindrical basis (r, theta, z)).
struct Layer {
  HolzapfelGasserOgden law;
  double R0, R1;
};

// The law with both fibre families at +-beta (radians) to the circumferential direction,
// in the basis (r, theta, z) of the reference.
inline HolzapfelGasserOgden cylindrical_law(double mu, double lambda, double k1, double k2, double beta,
                                            double kappa = 0.0, double rho = 1.0) {
  return HolzapfelGasserOgden{NeoHookean{mu, lambda}, k1, k2, {0.0, std::cos(beta), std::sin(beta)},
                              {0.0, std::cos(beta), -std::sin(beta)}, kappa, rho};
}

// r' with P_rR(r', r/R, lz) = P (Newton from the guess d, halving a step that would leave
// r' > 0; P_rR increases with r'). NaN when it does not converge.
inline double stretch_r(const HolzapfelGasserOgden& law, double lt, double P, double d, double lz = 1.0) {
  for (int it = 0; it < 100; ++it) {
    Mat3 C = Mat3::identity(), S;
    C(0, 0) = d * d;
    C(1, 1) = lt * lt;
    C(2, 2) = lz * lz;
    Ten4 CC;
    law.stress_and_tangent(C, S, CC);
    const double f = d * S(0, 0) - P, df = S(0, 0) + d * d * CC(0, 0, 0, 0);  // CC = 2 dS/dC
    double step = f / df;
    while (d - step <= 0.0) step *= 0.5;
    d -= step;
    if (!std::isfinite(d)) break;
    if (std::fabs(step) < 1e-15 * d) return d;
  }
  return std::nan("");
}

// (dr/dR, dP/dR) at R; d: the last r' (Newton's guess, updated).
inline void rhs(const HolzapfelGasserOgden& law, double R, double r, double P, double& d, double& dr, double& dP,
                double lz = 1.0) {
  const double lt = r / R;
  d = stretch_r(law, lt, P, d, lz);
  Mat3 C = Mat3::identity();
  C(0, 0) = d * d;
  C(1, 1) = lt * lt;
  C(2, 2) = lz * lz;
  const Mat3 S = law.stress(C);
  dr = d;
  dP = (lt * S(1, 1) - P) / R;
}

// P_rR at the outer surface for the lumen radius ri; ro: the outer radius reached.
inline double outer_traction(const std::vector<Layer>& L, double p, double ri, double& ro, double lz = 1.0) {
  double r = ri, P = -p * lz * ri / L[0].R0, d = 1.0;
  for (const Layer& l : L) {
    const int n = 400;
    const double h = (l.R1 - l.R0) / n;
    for (int i = 0; i < n; ++i) {
      const double R = l.R0 + i * h;
      double k1r, k1p, k2r, k2p, k3r, k3p, k4r, k4p;
      rhs(l.law, R, r, P, d, k1r, k1p, lz);
      rhs(l.law, R + 0.5 * h, r + 0.5 * h * k1r, P + 0.5 * h * k1p, d, k2r, k2p, lz);
      rhs(l.law, R + 0.5 * h, r + 0.5 * h * k2r, P + 0.5 * h * k2p, d, k3r, k3p, lz);
      rhs(l.law, R + h, r + h * k3r, P + h * k3p, d, k4r, k4p, lz);
      r += h / 6.0 * (k1r + 2.0 * k2r + 2.0 * k3r + k4r);
      P += h / 6.0 * (k1p + 2.0 * k2p + 2.0 * k3p + k4p);
    }
  }
  ro = r;
  return P;
}

// Deformed (lumen, outer) radii at pressure p: bisection on r(Ri) for P_rR(Ro) = 0 (it
// grows with r(Ri); a lumen radius too large for the integration to finish counts as
// above the root).
inline void reference_radii(const std::vector<Layer>& L, double p, double& ri, double& ro, double lz = 1.0) {
  auto above = [&](double a) {
    const double f = outer_traction(L, p, a, ro, lz);
    return !(f < 0.0);
  };
  double lo = L[0].R0, hi = 1.1 * lo;
  while (!above(hi)) lo = hi, hi *= 1.1;
  for (int it = 0; it < 100 && hi - lo > 1e-15 * hi; ++it) {
    const double mid = 0.5 * (lo + hi);
    (above(mid) ? hi : lo) = mid;
  }
  ri = 0.5 * (lo + hi);
  outer_traction(L, p, ri, ro, lz);
}

// The incompressible semi-inverse solution of one HGO layer (kappa = 0), plane strain:
// r^2 = R^2 + a^2 - ri^2, lt = r/R, p(a) = int (sigma_tt - sigma_rr) R dR / r^2 with
// sigma_tt - sigma_rr = mu (lt^2 - lt^-2) + 4 cos^2(beta) lt^2 psi'(I4) (Simpson, 4000 panels).
inline double incompressible_pressure(double a, double mu, double k1, double k2, double beta, double ri, double ro) {
  const double c2 = std::cos(beta) * std::cos(beta), s2 = 1.0 - c2;
  auto f = [&](double R) {
    const double r = std::sqrt(R * R + a * a - ri * ri), lt = r / R;
    const double x = c2 * lt * lt + s2 - 1.0, dpsi = x > 0.0 ? k1 * x * std::exp(k2 * x * x) : 0.0;
    return (mu * (lt * lt - 1.0 / (lt * lt)) + 4.0 * c2 * lt * lt * dpsi) * R / (r * r);
  };
  const int n = 4000;
  const double h = (ro - ri) / n;
  double sum = f(ri) + f(ro);
  for (int i = 1; i < n; ++i) sum += (i % 2 ? 4.0 : 2.0) * f(ri + i * h);
  return sum * h / 3.0;
}

}  // namespace stentor::testing::radial
