// Input alternatives for the isotropic laws (docs/deck.md, "Materials"): Young's
// modulus E and Poisson ratio nu, or the Lame constants mu and lambda, converted to
// each law's own coefficients so that the tangent at C = I is the isotropic
// elasticity tensor CC(I) = lambda I⊗I + 2 mu II (II the symmetric identity).
//
// Small strain: sigma = lambda tr(eps) I + 2 mu eps. Uniaxial stress sigma_11 = s gives
// eps_22 = eps_33 = -nu eps_11 and s = E eps_11; inverting,
//   mu = E / (2 (1 + nu)),   lambda = E nu / ((1 + nu)(1 - 2 nu)).
//
// Ciarlet–Geymonat (CiarletGeymonat.hpp): CC(I) = 4(C2 + D) I⊗I + 4(C1 + C2) II, so
//   mu = 2 (C1 + C2),  lambda = 4 (C2 + D).
// Two equations for three coefficients: the split rule is C2 as given (default 0), then
//   C1 = mu/2 - C2,   D = lambda/4 - C2,
// both of which must be > 0 (the law's own requirement; D > 0 needs nu > 0 when C2 = 0).
//
// Mooney–Rivlin (MooneyRivlin.hpp): CC(I) = (lam + 4 C2) I⊗I + 4 (C1 + C2) II, so with
// C2 as given (default 0)
//   C1 = mu/2 - C2 (> 0),   lam = lambda - 4 C2 (>= 0).
// Neo-Hookean (NeoHookean.hpp) takes mu and lambda directly.
#pragma once

namespace stentor {

struct Lame {
  double mu, lambda;
};

// E > 0, -1 < nu < 1/2.
inline Lame lame_from_young(double E, double nu) { return {E / (2.0 * (1.0 + nu)), E * nu / ((1.0 + nu) * (1.0 - 2.0 * nu))}; }

struct CiarletGeymonatCoefficients {
  double C1, C2, D;
};

// The split rule above (C2 given, default 0); the caller checks C1 > 0, D > 0.
inline CiarletGeymonatCoefficients ciarlet_geymonat_from_lame(const Lame& l, double C2) {
  return {0.5 * l.mu - C2, C2, 0.25 * l.lambda - C2};
}

struct MooneyRivlinCoefficients {
  double C1, C2, lam;
};

// C1 = mu/2 - C2, lam = lambda - 4 C2 (C2 given, default 0); the caller checks C1 > 0, lam >= 0.
inline MooneyRivlinCoefficients mooney_rivlin_from_lame(const Lame& l, double C2) {
  return {0.5 * l.mu - C2, C2, l.lambda - 4.0 * C2};
}

}  // namespace stentor
