// Holzapfel–Gasser–Ogden law for arterial layers with two fibre families (Holzapfel,
// Gasser & Ogden, J. Elasticity 61, 2000) and the fibre dispersion kappa of Gasser,
// Ogden & Holzapfel (J. R. Soc. Interface 3, 2006), compressible, with the anisotropic
// term in the *unmodified* invariants:
//
//   W(C) = mu/2 (I1 - 3) - mu ln J + lambda/2 (ln J)^2                (neo-Hookean matrix)
//        + sum_{f = 4, 6} k1/(2 k2) [exp(k2 (I_f* - 1)^2) - 1]  if I_f* > 1 (else 0),
//   I4 = a0·C a0,  I6 = g0·C g0   (a0, g0 unit fibre directions in the reference),
//   I_f* = kappa I1 + (1 - 3 kappa) I_f = H_f : C,   H_f = kappa 1 + (1 - 3 kappa) a0⊗a0,
// kappa in [0, 1/3]: 0 ideally aligned fibres (the 2000 law, evaluated bit for bit as
// before: H = A exactly), 1/3 isotropic dispersion (I* = I1/3, the fibres act as an
// isotropic exponential term). H_f is the structure tensor of a rotationally symmetric
// fibre distribution about a0 with kappa = (1/4) int rho(theta) sin^3 theta dtheta.
//
// Why not the isochoric-volumetric split with the "modified" invariants Ibar4 = J^-2/3 I4
// of the 2000/2006 papers: with a compressible penalty the split anisotropic term gives
// no volume change under the fibre stress it should carry (a sphere under pressure stays
// a sphere, Sansour 2008; Helfenstein et al. 2010), and Nolan et al. (J. Mech. Behav.
// Biomed. Mater. 39, 2014) show that the unmodified I4, I6 give the physically right
// compressible response; this is their recommended form. Nearly incompressible (lambda
// >> mu) both forms agree to O(mu/lambda).
//
// A fibre family bears load only when its generalized invariant is in tension, I_f* > 1
// (the usual switch of the 2006 paper applied to I*, not to I_f: with dispersion some
// fibres of a family are stretched even when its mean direction is not; the switch is
// the family's, not the single fibre's). At I_f* = 1 the energy and the stress are
// continuous (psi'(1) = 0) and the tangent jumps by 4 k1 H⊗H.
//
// The isotropic coupling rho of Holzapfel, Sommer, Gasser & Regitnig (Am. J. Physiol. Heart
// Circ. Physiol. 289, 2005), whose layer-specific fit of human coronary arteries uses it:
//   each family's term is k1/(2 k2) [exp(k2 E_f) - 1],  E_f = (1 - rho) (I1 - 3)^2 + rho <I_f* - 1>^2,
// <x> = max(x, 0) (the family's own part in tension only, so the energy stays C1 where it
// switches). rho = 1 (the default) is the law above, evaluated with the same operations;
// rho < 1 stiffens every direction with I1. With
//   G_f = dE_f/dC = 2 (1 - rho) (I1 - 3) 1 + 2 rho <I_f* - 1> H_f,
//   S_f = k1 e G_f,   CC_f = 2 k1 k2 e G_f⊗G_f + 4 k1 e [(1 - rho) 1⊗1 + rho [I_f* > 1] H_f⊗H_f],  e = exp(k2 E_f).
// Derivatives, psi(I) = k1/(2 k2)(exp(k2 (I-1)^2) - 1); I_f* is linear in C with
// dI_f*/dC = H_f (dI1/dC = 1, dI4/dC = A = a0⊗a0):
//   psi'(I)  = k1 (I - 1) exp(k2 (I - 1)^2),
//   psi''(I) = k1 (1 + 2 k2 (I - 1)^2) exp(k2 (I - 1)^2),
//   S  = S_NH + sum_f 2 psi'(I_f*) H_f,     CC = CC_NH + sum_f 4 psi''(I_f*) H_f⊗H_f   (I_f* > 1).
// Units: mu, lambda, k1 [Pa]; k2 [-].
//
// The directions come from a local cylindrical frame (FibreFrame): at a point X, with the
// vessel axis through `point` along the unit `axis` e_z,
//   e_r = (X - point) - ((X - point)·e_z) e_z, normalised;  e_t = e_z × e_r,
//   a0 = cos(beta) e_t + sin(beta) e_z,  g0 = cos(beta) e_t - sin(beta) e_z,
// i.e. two helices at +-beta to the circumferential direction (beta = 0: both
// circumferential, 90 deg: both axial). On the axis itself (e_r undefined) e_r is any
// unit vector normal to e_z.
#pragma once
#include "material/NeoHookean.hpp"

namespace stentor {

struct HolzapfelGasserOgden {
  NeoHookean matrix;
  double k1, k2;
  double a0[3], g0[3];
  double kappa = 0.0;  // dispersion, [0, 1/3]
  double rho = 1.0;    // isotropic coupling of Holzapfel et al. 2005, (0, 1]; 1: none

  // I_f = a·C a (the classical fibre invariant, no dispersion).
  KOKKOS_INLINE_FUNCTION static double invariant(const Mat3& C, const double* a) {
    double s = 0.0;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) s += a[i] * C(i, j) * a[j];
    return s;
  }

  // I_f* = kappa I1 + (1 - 3 kappa) I_f (= I_f for kappa = 0, bit for bit).
  KOKKOS_INLINE_FUNCTION double generalized_invariant(const Mat3& C, const double* a) const {
    if (kappa == 0.0) return invariant(C, a);
    return kappa * (C(0, 0) + C(1, 1) + C(2, 2)) + (1.0 - 3.0 * kappa) * invariant(C, a);
  }

  // H_f = kappa 1 + (1 - 3 kappa) a⊗a.
  KOKKOS_INLINE_FUNCTION void structure(const double* a, Mat3& H) const {
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) H(i, j) = (1.0 - 3.0 * kappa) * a[i] * a[j] + (i == j ? kappa : 0.0);
  }

  KOKKOS_INLINE_FUNCTION double fibre_energy(double I) const {
    const double x = I - 1.0;
    return x > 0.0 ? k1 / (2.0 * k2) * std::expm1(k2 * x * x) : 0.0;
  }

  // E_f = (1 - rho) (I1 - 3)^2 + rho <I_f* - 1>^2 (rho < 1).
  KOKKOS_INLINE_FUNCTION double coupled_argument(double j, double x) const {
    const double xp = x > 0.0 ? x : 0.0;
    return (1.0 - rho) * j * j + rho * xp * xp;
  }

  KOKKOS_INLINE_FUNCTION double energy(const Mat3& C) const {
    if (rho != 1.0) {
      const double j = C(0, 0) + C(1, 1) + C(2, 2) - 3.0;
      const double Ea = coupled_argument(j, generalized_invariant(C, a0) - 1.0);
      const double Eg = coupled_argument(j, generalized_invariant(C, g0) - 1.0);
      return matrix.energy(C) + k1 / (2.0 * k2) * (std::expm1(k2 * Ea) + std::expm1(k2 * Eg));
    }
    return matrix.energy(C) + fibre_energy(generalized_invariant(C, a0)) + fibre_energy(generalized_invariant(C, g0));
  }

  KOKKOS_INLINE_FUNCTION Mat3 stress(const Mat3& C) const {
    Mat3 S = matrix.stress(C);
    add_fibre(C, a0, S, nullptr);
    add_fibre(C, g0, S, nullptr);
    return S;
  }

  KOKKOS_INLINE_FUNCTION void stress_and_tangent(const Mat3& C, Mat3& S, Ten4& CC) const {
    matrix.stress_and_tangent(C, S, CC);
    add_fibre(C, a0, S, &CC);
    add_fibre(C, g0, S, &CC);
  }

  KOKKOS_INLINE_FUNCTION void tangent(const Mat3& C, Ten4& CC) const {
    Mat3 S;
    stress_and_tangent(C, S, CC);
  }

  // True when neither fibre switches between tension and compression on the segment
  // C0 -> C1 (I_f* is linear along it, so the end points decide): the energy is then
  // smooth there (DiscreteGradient.hpp uses Simpson's rule for g only then).
  KOKKOS_INLINE_FUNCTION bool smooth_between(const Mat3& C0, const Mat3& C1) const {
    return ((generalized_invariant(C0, a0) > 1.0) == (generalized_invariant(C1, a0) > 1.0)) &&
           ((generalized_invariant(C0, g0) > 1.0) == (generalized_invariant(C1, g0) > 1.0));
  }

 private:
  KOKKOS_INLINE_FUNCTION void add_fibre(const Mat3& C, const double* a, Mat3& S, Ten4* CC) const {
    if (rho != 1.0) {
      add_coupled_fibre(C, a, S, CC);
      return;
    }
    const double x = generalized_invariant(C, a) - 1.0;
    if (!(x > 0.0)) return;
    const double e = std::exp(k2 * x * x);
    const double s = 2.0 * k1 * x * e;                         // 2 psi'
    const double t = 4.0 * k1 * (1.0 + 2.0 * k2 * x * x) * e;  // 4 psi''
    if (kappa == 0.0) {  // the 2000 law, in its original order of operations
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) S(i, j) += s * a[i] * a[j];
      if (CC)
        for (int i = 0; i < 3; ++i)
          for (int j = 0; j < 3; ++j)
            for (int k = 0; k < 3; ++k)
              for (int l = 0; l < 3; ++l) (*CC)(i, j, k, l) += t * a[i] * a[j] * a[k] * a[l];
      return;
    }
    Mat3 H;
    structure(a, H);
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) S(i, j) += s * H(i, j);
    if (CC)
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
          for (int k = 0; k < 3; ++k)
            for (int l = 0; l < 3; ++l) (*CC)(i, j, k, l) += t * H(i, j) * H(k, l);
  }

  // One family with the isotropic coupling rho < 1 (header: S_f, CC_f).
  KOKKOS_INLINE_FUNCTION void add_coupled_fibre(const Mat3& C, const double* a, Mat3& S, Ten4* CC) const {
    const double j = C(0, 0) + C(1, 1) + C(2, 2) - 3.0, x = generalized_invariant(C, a) - 1.0;
    const double xp = x > 0.0 ? x : 0.0;
    const double e = std::exp(k2 * coupled_argument(j, x));
    Mat3 H, G;
    structure(a, H);
    for (int i = 0; i < 3; ++i)
      for (int k = 0; k < 3; ++k) G(i, k) = 2.0 * rho * xp * H(i, k) + (i == k ? 2.0 * (1.0 - rho) * j : 0.0);
    for (int i = 0; i < 3; ++i)
      for (int k = 0; k < 3; ++k) S(i, k) += k1 * e * G(i, k);
    if (!CC) return;
    const double g = 2.0 * k1 * k2 * e, iso = 4.0 * k1 * e * (1.0 - rho), fib = x > 0.0 ? 4.0 * k1 * e * rho : 0.0;
    for (int i = 0; i < 3; ++i)
      for (int k = 0; k < 3; ++k)
        for (int l = 0; l < 3; ++l)
          for (int m = 0; m < 3; ++m)
            (*CC)(i, k, l, m) += g * G(i, k) * G(l, m) + fib * H(i, k) * H(l, m) + (i == k && l == m ? iso : 0.0);
  }
};

// Cylindrical fibre frame of a material (see above); beta in radians.
struct FibreFrame {
  double point[3], axis[3];  // axis: unit
  double beta;
  // A curved vessel: its centreline a circular arc of radius `bend` (0: the straight axis)
  // through `point`, tangent to `axis` there, curving towards the unit direction `towards`
  // (normal to `axis`); the frame at X is that of the arc's point nearest X, with the arc's
  // tangent as the axis (a torus' meridian frame).
  double bend = 0.0;
  double towards[3] = {0.0, 0.0, 0.0};

  // The centreline's point nearest X and its unit tangent there (bend > 0).
  KOKKOS_INLINE_FUNCTION void on_centreline(const double* X, double* q, double* t) const {
    const double nb[3] = {axis[1] * towards[2] - axis[2] * towards[1], axis[2] * towards[0] - axis[0] * towards[2],
                          axis[0] * towards[1] - axis[1] * towards[0]};  // the bend plane's normal
    double d[3], dn = 0.0;
    for (int i = 0; i < 3; ++i) {
      d[i] = X[i] - point[i] - bend * towards[i];  // from the bend's centre
      dn += d[i] * nb[i];
    }
    double n2 = 0.0;
    for (int i = 0; i < 3; ++i) {
      d[i] -= dn * nb[i];
      n2 += d[i] * d[i];
    }
    if (!(n2 > 1e-300)) {  // on the bend's axis: the arc's point at `point`
      for (int i = 0; i < 3; ++i) d[i] = -towards[i], n2 = 1.0;
    }
    const double inv = 1.0 / std::sqrt(n2);
    for (int i = 0; i < 3; ++i) {
      d[i] *= inv;
      q[i] = point[i] + bend * (towards[i] + d[i]);
    }
    t[0] = nb[1] * d[2] - nb[2] * d[1];
    t[1] = nb[2] * d[0] - nb[0] * d[2];
    t[2] = nb[0] * d[1] - nb[1] * d[0];
  }

  // a0, g0 at the reference point X.
  KOKKOS_INLINE_FUNCTION void directions(const double* X, double* a, double* g) const {
    double p[3] = {point[0], point[1], point[2]}, ax[3] = {axis[0], axis[1], axis[2]};
    if (bend > 0.0) on_centreline(X, p, ax);
    directions_about(X, p, ax, a, g);
  }

  // The same about the straight axis through p along the unit ax.
  KOKKOS_INLINE_FUNCTION void directions_about(const double* X, const double* p, const double* ax, double* a, double* g) const {
    double r[3], d = 0.0;
    for (int i = 0; i < 3; ++i) d += (X[i] - p[i]) * ax[i];
    double n2 = 0.0;
    for (int i = 0; i < 3; ++i) {
      r[i] = X[i] - p[i] - d * ax[i];
      n2 += r[i] * r[i];
    }
    if (!(n2 > 1e-300)) {  // on the axis: any normal to it
      const int k = std::fabs(ax[0]) < 0.9 ? 0 : 1;
      for (int i = 0; i < 3; ++i) r[i] = (i == k ? 1.0 : 0.0) - ax[k] * ax[i];
      n2 = r[0] * r[0] + r[1] * r[1] + r[2] * r[2];
    }
    const double inv = 1.0 / std::sqrt(n2);
    for (int i = 0; i < 3; ++i) r[i] *= inv;
    const double t[3] = {ax[1] * r[2] - ax[2] * r[1], ax[2] * r[0] - ax[0] * r[2], ax[0] * r[1] - ax[1] * r[0]};
    const double c = std::cos(beta), s = std::sin(beta);
    for (int i = 0; i < 3; ++i) {
      a[i] = c * t[i] + s * ax[i];
      g[i] = c * t[i] - s * ax[i];
    }
  }
};

}  // namespace stentor
