// Finite-strain multiplicative plasticity on an isotropic hyperelastic law: the
// Ciarlet–Geymonat law of the talk (mission.md, model item 6;
// docs/plasticity.md) and the neo-Hookean law. A stateless value type with a Gauss-point
// history (MaterialState.hpp): update(C_{n+1}, h_n, h_{n+1}) -> S, CC = 2 dS/dC, Psi, D.
// MultiplicativePlasticity<Elastic> needs of Elastic the tensor functions of a
// hyperelastic law and, in principal values, the three functions principal_moduli,
// principal_energy and principal_energy_jump below (written for CiarletGeymonat and
// NeoHookean); the formulas below are those of Ciarlet–Geymonat, and the neo-Hookean ones
// are next to its functions.
//
// Model. F = Fe Ftr, det Ftr = 1, Ce = Fe^T Fe = Ftr^-T C Ftr^-1, stored energy
//   Psi = W(Ce) + psi_h(alpha),   psi_h = 1/2 H alpha^2 + psi(alpha)   (W: CiarletGeymonat.hpp),
// H >= 0 the linear hardening, psi the stored energy of the nonlinear hardening kappa = psi'
// (Voce or a table, IsotropicHardening.hpp; none: psi = 0, linear hardening), so the yield
// stress is sigma_y(alpha) = Y + psi_h'(alpha) = Y + H alpha + kappa(alpha), non-decreasing;
// Mandel stress M = 2 Ce dW/dCe (= Ce Sbar, Sbar = 2 dW/dCe; Ce and Sbar commute for the
// isotropic W, so M is symmetric and coaxial with Ce), yield function
//   f = |M|_H - sigma_y(alpha),  |M|_H = sqrt(3/2 dev M : dev M),   Y > 0 [Pa],
// associative flow L^tr = dFtr/dt Ftr^-1 = gdot n, n = df/dM = 3/2 dev M / |M|_H
// (symmetric, trace-free, n:n = 3/2), alpha_dot = gdot (alpha is the accumulated
// Delta-gamma = equivalent plastic strain, since sqrt(2/3 n:n) = 1).
//
// Update (backward Euler + exponential map, Weber–Anand 1990, Simo 1992):
//   Ftr_{n+1} = exp(dg n_{n+1}) Ftr_n.
// This integrates L^tr = gdot n exactly for constant n. (The talk's slide writes
// Ftr_n exp(dg n), which integrates Ftr^-1 dFtr/dt = gdot n instead, i.e. n in the
// reference configuration; both coincide when Ftr_n and n commute: first yield, and
// proportional loading in a fixed principal frame.) With G = Ftr_n^-1 and the trial
// (elastic predictor) Ce^tr = G^T C G:
//   Ce_{n+1} = exp(-dg n) Ce^tr exp(-dg n).
// Because n(M(Ce_{n+1})) commutes with Ce_{n+1}, all three are coaxial with Ce^tr:
// with Ce^tr = sum_A ct_A N_A (x) N_A and log strains et_A = 1/2 ln ct_A,
//   e_A = et_A - dg n_A       (principal elastic log strains at t_{n+1}),
// and in principal space M_A = tau_A(e) = dW/de_A (e_A = 1/2 ln c_A => d/de = 2c d/dc):
//   tau_A = 2[C1 c_A + C2 c_A (c_B + c_C) + D I3 - K],
//   dtau_A/de_A = 4 c_A [C1 + C2 (c_B + c_C)] + 4 D I3,  dtau_A/de_B = 4 C2 c_A c_B + 4 D I3.
// KKT (f <= 0, dg >= 0, f dg = 0) by the elastic predictor: f(Ce^tr) <= 0 => dg = 0
// (elastic, Ftr unchanged); otherwise a local Newton on x = (e_1, e_2, e_3, dg),
//   R_A = e_A - et_A + dg n_A(e) = 0,   R_4 = |tau(e)|_H - sigma_y(alpha_n + dg) = 0,
//   J = [ I + dg (dn/dtau) G_e ,  n ;  n^T G_e ,  -h ],  dn/dtau = (3/2 P - n n^T)/|tau|_H,
// h = sigma_y'(alpha_n + dg) = H + kappa' (the right derivative at a table point); R_4 is
// evaluated as |tau|_H - sigma_y(alpha_n) - H dg - [kappa(alpha_n + dg) - kappa(alpha_n)],
// the bracket an exact 0 for linear hardening (the operations of the linear law, bit for bit);
// G_e = dtau/de, P = I - 1/3 1 (x) 1. (For the Hencky energy n is fixed and this is the
// radial return, one step; CG needs a few.) Sum n_A = 0, so sum e_A = sum et_A and
// det Ce_{n+1} = det Ce^tr: the flow is isochoric.
// Talk's complementarity form: with Mq = M + c H^-1 : dD (dD = dg n, c = c^tr > 0),
// |Mq|_H = |M|_H + c dg, and C^tr = max(Y, |Mq|_H) M - Y Mq = 0 reduces on the deviatoric
// direction to max(Y, |M|_H + c dg) |M|_H = Y (|M|_H + c dg), i.e. either dg = 0 and
// |M|_H <= Y, or |M|_H = Y and dg > 0: the same KKT set for every c > 0. The active set
// {|Mq|_H > Y} of the talk's PDAS at a converged point is {dg > 0}, which the return map
// finds by the trial test (f^tr > 0 <=> dg > 0 for this convex-in-log-strain W).
//
// Exponential: spectral, exp(dg n) = sum_A exp(dg n_A) N_A (x) N_A in the eigenbasis of
// Ce^tr (Jacobi rotations, orthonormal to round-off), then Ftr_{n+1} is scaled by
// det^(-1/3) so det Ftr = 1 to round-off after any number of steps (measured 1.3e-15
// after chains of large random steps, test_plasticity).
//
// Stress. S = Ftr_{n+1}^-1 Sbar_{n+1} Ftr_{n+1}^-T = G Z G^T with
//   Z = exp(-dg n) Sbar exp(-dg n) = sum_A z_A N_A (x) N_A,  z_A = tau_A / ct_A,
// i.e. S = sum_A z_A v_A (x) v_A with v_A = G N_A: an isotropic function of Ce^tr whose
// principal values depend on et through the return map (Simo 1992).
// Consistent tangent CC = 2 dS/dC (Ftr_n, alpha_n fixed). dCe^tr = G^T dC G gives
// N_A.dCe^tr.N_B = v_A.dC.v_B; differentiating the converged R(x; et) = 0 gives
// de/det = [J^-1]_{3x3} (R_A has -et_A), a = dtau/det = G_e [J^-1]_{3x3} (symmetric:
// associative flow), and with dz_A/dct_B = a_AB / (2 ct_A ct_B) - delta_AB tau_A / ct_A^2,
//   CC = 2 sum_AB dz_A/dct_B v_A v_A v_B v_B
//      + sum_{A != B} th_AB v_A (x) v_B (x) (v_A (x) v_B + v_B (x) v_A),
//   th_AB = (z_A - z_B)/(ct_A - ct_B), or for |ct_A - ct_B| <= 1e-8 (ct_A + ct_B) its
//   limit 1/2 (dz_A/dct_A - dz_A/dct_B + dz_B/dct_B - dz_B/dct_A) (z is symmetric in ct).
// Elastic points: S = G Sbar(Ce^tr) G^T, CC = G G G G : CCbar(Ce^tr) with the tensor
// formulas of CiarletGeymonat.hpp (identical to it, bitwise, while Ftr = I).
//
// Energy. Psi_{n+1} = W(Ce_{n+1}) + psi_h(alpha_{n+1}), and the step dissipation
//   Dp = [W(Ce^tr) - W(Ce_{n+1})] - [psi_h(alpha_{n+1}) - psi_h(alpha_n)],
//   psi_h(alpha_{n+1}) - psi_h(alpha_n) = H dg (alpha_n + dg/2) + [psi(alpha_n + dg) - psi(alpha_n)]
// (W(Ce^tr) - W(Ce_{n+1}) evaluated with expm1 on the log-strain differences, the psi
// increment in closed form, both free of cancellation). W is convex in principal log strains
// (sums of exp of linear forms and -2K sum e), so W(et) - W(e) >= tau(e).(et - e) =
// dg n.tau = dg |M|_H = dg sigma_y(alpha_{n+1}); psi_h is convex (sigma_y non-decreasing), so its
// increment is <= dg psi_h'(alpha_{n+1}) = dg (sigma_y(alpha_{n+1}) - Y), and
// Dp >= Y dg >= 0 (>= Y dg + 1/2 H dg^2 for linear hardening). Exact one-step identity (by construction):
//   Psi_{n+1} - Psi_n = [W(Ce^tr) - W(Ce_n)] - Dp,
// where the elastic-predictor work W(Ce^tr) - W(Ce_n) = 1/2 Sigma : (C_{n+1} - C_n) exactly
// with Sigma the Gonzalez discrete gradient (DiscreteGradient.hpp) of the frozen-state
// potential C -> W(G^T C G) (FrozenPlasticPotential below): the lagged dynamic step.
// The default dynamic step (dynamic_update) takes the discrete gradient of the incremental
// potential W_inc(C) = Psi(C, return map) + Y dg instead (IncrementalPotential below), whose
// gradient is the return-map stress: the plastic flow of the step is in the momentum stress
// (off the yield surface by O(|dC|^2)), and Dp = Y dg exactly. The `mean value` option takes the
// return-map stress at a mean-value point of W_inc (an admissible stress, on the surface where it
// flows), which is unique only where W_inc is convex along the step's segment.
#pragma once
#include <cmath>

#include "material/CiarletGeymonat.hpp"
#include "material/DiscreteGradient.hpp"
#include "material/IsotropicHardening.hpp"
#include "material/MaterialState.hpp"
#include "material/NeoHookean.hpp"
#include "material/SymEigen.hpp"
#include "stentor/tensor.hpp"

namespace stentor {
namespace plasticity_detail {

// sym_eig3: material/SymEigen.hpp (shared with the output fields).
using stentor::sym_eig3;

// Principal Mandel stresses tau_A = dW/de_A (split as shape part s_A + common p) and
// the Hessian Ge_AB = dtau_A/de_B, for principal values c_A of Ce.
KOKKOS_INLINE_FUNCTION void principal_moduli(const CiarletGeymonat& m, const double c[3], double s[3],
                                             double& p, double Ge[3][3]) {
  const double I3 = c[0] * c[1] * c[2];
  p = 2.0 * (m.D * I3 - m.K());
  for (int A = 0; A < 3; ++A) {
    const int B = (A + 1) % 3, Cc = (A + 2) % 3;
    s[A] = 2.0 * c[A] * (m.C1 + m.C2 * (c[B] + c[Cc]));
    for (int Bb = 0; Bb < 3; ++Bb)
      Ge[A][Bb] = (A == Bb) ? 4.0 * c[A] * (m.C1 + m.C2 * (c[B] + c[Cc])) + 4.0 * m.D * I3
                            : 4.0 * m.C2 * c[A] * c[Bb] + 4.0 * m.D * I3;
  }
}

// Hill norm q = |tau|_H and flow direction n = 3/2 dev tau / q (from the shape part s,
// which has the deviator of tau).
KOKKOS_INLINE_FUNCTION double hill(const double s[3], double n[3]) {
  const double mean = (s[0] + s[1] + s[2]) / 3.0;
  const double d[3] = {s[0] - mean, s[1] - mean, s[2] - mean};
  const double q = std::sqrt(1.5 * (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]));
  for (int A = 0; A < 3; ++A) n[A] = q > 0.0 ? 1.5 * d[A] / q : 0.0;
  return q;
}

// W(c) from principal values of Ce.
KOKKOS_INLINE_FUNCTION double principal_energy(const CiarletGeymonat& m, const double c[3]) {
  const double I1 = c[0] + c[1] + c[2], I2 = c[0] * c[1] + c[1] * c[2] + c[2] * c[0];
  const double I3 = c[0] * c[1] * c[2];
  return m.C1 * (I1 - 3.0) + m.C2 * (I2 - 3.0) + m.D * (I3 - 1.0) - m.K() * std::log(I3);
}

// W(c exp(2 d)) - W(c) without cancellation (d: log-strain differences).
KOKKOS_INLINE_FUNCTION double principal_energy_jump(const CiarletGeymonat& m, const double c[3],
                                                    const double d[3]) {
  const double sd = d[0] + d[1] + d[2];
  double r = m.D * c[0] * c[1] * c[2] * std::expm1(2.0 * sd) - 2.0 * m.K() * sd;
  for (int A = 0; A < 3; ++A) {
    const int B = (A + 1) % 3;
    r += m.C1 * c[A] * std::expm1(2.0 * d[A]) + m.C2 * c[A] * c[B] * std::expm1(2.0 * (d[A] + d[B]));
  }
  return r;
}

// The same three for the neo-Hookean law, W = mu/2 (I1 - 3) - mu ln J + lambda/2 (ln J)^2
// with ln J = 1/2 ln(c_1 c_2 c_3) = e_1 + e_2 + e_3:
//   tau_A = mu c_A + lambda ln J - mu   (s_A = mu c_A, p = lambda ln J - mu),
//   Ge_AB = 2 mu c_A delta_AB + lambda,
//   W(c exp(2 d)) - W(c) = mu/2 sum c_A expm1(2 d_A) - mu sum d + lambda/2 sd (2 ln J + sd),
// sd = sum d. W is convex in the e_A (exponentials, a linear and a square of a linear form),
// so the dissipation bound of the header holds as for Ciarlet–Geymonat.
KOKKOS_INLINE_FUNCTION void principal_moduli(const NeoHookean& m, const double c[3], double s[3], double& p,
                                             double Ge[3][3]) {
  p = m.lambda * 0.5 * std::log(c[0] * c[1] * c[2]) - m.mu;
  for (int A = 0; A < 3; ++A) {
    s[A] = m.mu * c[A];
    for (int B = 0; B < 3; ++B) Ge[A][B] = (A == B ? 2.0 * m.mu * c[A] : 0.0) + m.lambda;
  }
}

KOKKOS_INLINE_FUNCTION double principal_energy(const NeoHookean& m, const double c[3]) {
  const double lnJ = 0.5 * std::log(c[0] * c[1] * c[2]);
  return 0.5 * m.mu * (c[0] + c[1] + c[2] - 3.0) - m.mu * lnJ + 0.5 * m.lambda * lnJ * lnJ;
}

KOKKOS_INLINE_FUNCTION double principal_energy_jump(const NeoHookean& m, const double c[3], const double d[3]) {
  const double sd = d[0] + d[1] + d[2], lnJ = 0.5 * std::log(c[0] * c[1] * c[2]);
  double r = -m.mu * sd + 0.5 * m.lambda * sd * (2.0 * lnJ + sd);
  for (int A = 0; A < 3; ++A) r += 0.5 * m.mu * c[A] * std::expm1(2.0 * d[A]);
  return r;
}

// Solves J x = b (4x4, partial pivoting); J and b are overwritten. False if singular.
KOKKOS_INLINE_FUNCTION bool solve4(double J[4][4], double b[4]) {
  for (int k = 0; k < 4; ++k) {
    int piv = k;
    for (int i = k + 1; i < 4; ++i)
      if (std::fabs(J[i][k]) > std::fabs(J[piv][k])) piv = i;
    if (J[piv][k] == 0.0) return false;
    if (piv != k) {
      for (int j = 0; j < 4; ++j) {
        const double t = J[k][j];
        J[k][j] = J[piv][j], J[piv][j] = t;
      }
      const double t = b[k];
      b[k] = b[piv], b[piv] = t;
    }
    for (int i = k + 1; i < 4; ++i) {
      const double f = J[i][k] / J[k][k];
      for (int j = k; j < 4; ++j) J[i][j] -= f * J[k][j];
      b[i] -= f * b[k];
    }
  }
  for (int k = 3; k >= 0; --k) {
    double s = b[k];
    for (int j = k + 1; j < 4; ++j) s -= J[k][j] * b[j];
    b[k] = s / J[k][k];
  }
  return true;
}

// CC = G G G G : CCbar, CC_ijkl = G_ia G_jb G_kc G_ld CCbar_abcd (4 one-index passes).
KOKKOS_INLINE_FUNCTION void push_tangent(const Mat3& G, const Ten4& CCbar, Ten4& CC) {
  Ten4 T;
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b)
      for (int c = 0; c < 3; ++c)
        for (int l = 0; l < 3; ++l)
          T(a, b, c, l) = G(l, 0) * CCbar(a, b, c, 0) + G(l, 1) * CCbar(a, b, c, 1) + G(l, 2) * CCbar(a, b, c, 2);
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b)
      for (int k = 0; k < 3; ++k)
        for (int l = 0; l < 3; ++l)
          CC(a, b, k, l) = G(k, 0) * T(a, b, 0, l) + G(k, 1) * T(a, b, 1, l) + G(k, 2) * T(a, b, 2, l);
  for (int a = 0; a < 3; ++a)
    for (int j = 0; j < 3; ++j)
      for (int k = 0; k < 3; ++k)
        for (int l = 0; l < 3; ++l)
          T(a, j, k, l) = G(j, 0) * CC(a, 0, k, l) + G(j, 1) * CC(a, 1, k, l) + G(j, 2) * CC(a, 2, k, l);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      for (int k = 0; k < 3; ++k)
        for (int l = 0; l < 3; ++l)
          CC(i, j, k, l) = G(i, 0) * T(0, j, k, l) + G(i, 1) * T(1, j, k, l) + G(i, 2) * T(2, j, k, l);
}

// Converged local return map in principal log strains.
struct ReturnMap {
  double e[3];      // elastic log strains at t_{n+1}
  double tau[3];    // principal Mandel stresses
  double n[3];      // flow direction
  double dgamma;    // plastic multiplier of the step
  double q;         // |M_{n+1}|_H
  double a[3][3];   // algorithmic moduli d tau / d et
  int iterations;
  bool converged;
};

}  // namespace plasticity_detail

// Plastic Gauss-point state (the part that evolves; see kHistory for its flat layout).
struct PlasticState {
  Mat3 Ftr;      // plastic (inelastic) deformation, det = 1
  double alpha;  // accumulated dg = equivalent plastic strain
};

// Elastic potential at a frozen plastic state, C -> W(G^T C G), G = Ftr_n^-1: the
// elastic predictor of a step, with the energy/stress/stress_and_tangent interface of
// a hyperelastic law so DiscreteGradient.hpp (Gonzalez) applies to it directly.
template <class Elastic>
struct FrozenPotential {
  Elastic law;
  Mat3 G;
  KOKKOS_INLINE_FUNCTION Mat3 elastic_C(const Mat3& C) const { return tmul(G, matmul(C, G)); }
  KOKKOS_INLINE_FUNCTION double energy(const Mat3& C) const { return law.energy(elastic_C(C)); }
  KOKKOS_INLINE_FUNCTION Mat3 stress(const Mat3& C) const {
    return matmul(G, matmul(law.stress(elastic_C(C)), transpose(G)));
  }
  KOKKOS_INLINE_FUNCTION void stress_and_tangent(const Mat3& C, Mat3& S, Ten4& CC) const {
    Mat3 Sb;
    Ten4 CCb;
    law.stress_and_tangent(elastic_C(C), Sb, CCb);
    S = matmul(G, matmul(Sb, transpose(G)));
    plasticity_detail::push_tangent(G, CCb, CC);
  }
};

using FrozenPlasticPotential = FrozenPotential<CiarletGeymonat>;

template <class Elastic>
struct IncrementalPotential;

// The stress of the momentum equation in the Gonzalez dynamic step of the plasticity laws
// (docs/plasticity.md, "Dynamics"): the discrete gradient of the incremental potential W_inc of
// the step (the return map inside the step; the default), the return-map stress at a
// mean-value point of W_inc on the step's segment, or the discrete gradient of the elastic
// potential at the plastic state of the step's start (lagged).
enum class PlasticDynamicStep : int { kIncrementalPotential = 0, kMeanValue = 1, kLagged = 2 };

// Isotropic elasticity (Elastic: CiarletGeymonat or NeoHookean) with von Mises (Hill-norm)
// multiplicative plasticity and isotropic hardening sigma_y(alpha) = Y + H alpha + kappa(alpha)
// (kappa: IsotropicHardening.hpp, none by default). Y, H and the moduli in the same stress
// unit (Pa).
template <class Elastic>
struct MultiplicativePlasticity {
  Elastic elastic;
  double Y;        // initial yield stress, > 0 [Pa]
  double H = 0.0;  // linear isotropic hardening modulus, >= 0 [Pa]; 0: perfect plasticity
  // The stress of the Gonzalez dynamic step (dynamic_update). Deck: `plastic dynamic step`.
  PlasticDynamicStep dynamic_step = PlasticDynamicStep::kIncrementalPotential;
  // Nonlinear part kappa of the hardening (Voce or a table; none: linear hardening).
  NonlinearHardening nonlinear = {};

  // Yield stress sigma_y(alpha) and hardening energy psi_h(alpha) = 1/2 H alpha^2 + psi(alpha).
  KOKKOS_INLINE_FUNCTION double yield_stress(double alpha) const { return Y + H * alpha + nonlinear.kappa(alpha); }
  KOKKOS_INLINE_FUNCTION double hardening_energy(double alpha) const {
    return 0.5 * H * alpha * alpha + nonlinear.energy(alpha);
  }

  // History layout: Ftr row-major (9), alpha, then output-only values of the last update.
  enum : int { kFtr = 0, kAlpha = 9, kMandelHill = 10, kYielding = 11, kDissipation = 12 };
  static constexpr int kNumHist = 13;
  static constexpr HistoryVar kHistory[kNumHist] = {
      {"Ftr_11", 1.0, false}, {"Ftr_12", 0.0, false}, {"Ftr_13", 0.0, false},
      {"Ftr_21", 0.0, false}, {"Ftr_22", 1.0, false}, {"Ftr_23", 0.0, false},
      {"Ftr_31", 0.0, false}, {"Ftr_32", 0.0, false}, {"Ftr_33", 1.0, false},
      {"equivalent_plastic_strain", 0.0, true},   // alpha = sum of dg
      {"mandel_hill_norm", 0.0, true},            // |M_{n+1}|_H [Pa]
      {"yielding", 0.0, true},                    // 1 if dg > 0 in the last step
      {"plastic_dissipation", 0.0, true}};        // accumulated Dp [Pa = J/m^3]

  static constexpr int kMaxLocalIterations = 50;

  // Full result of one update in structured form (what update() flattens).
  struct Step {
    PlasticState state;  // at t_{n+1}
    double dgamma;       // plastic multiplier of the step (0: elastic)
    double mandel_hill;  // |M_{n+1}|_H
  };

  // WithTangent = false: the stress-only update for residual-only calls. The same S, state,
  // energy and dissipation bit for bit (the same operations), but no CC (left unset): no
  // algorithmic moduli (three 4x4 solves), no spectral CC (81 x 9 terms), no pushed
  // elastic tangent. Measured in docs/performance.md ("Plastic assembly").
  template <bool WithTangent = true, class HIn, class HOut>
  KOKKOS_INLINE_FUNCTION PointResponse update(const Mat3& C, const HIn& hn, const HOut& h1) const {
    Step st;
    const PointResponse r = update_state<WithTangent>(C, read_state(hn), st);
    write_state(st, hn, r.dissipation, h1);
    return r;
  }

  // Energy-dissipative dynamic step from C0 = C_n to C1 = C_{n+1} (docs/plasticity.md,
  // "Dynamics"): the state h_{n+1} of the return map at C1, Psi_{n+1} and the step's dissipation,
  // with r.S = Sigma the stress of the momentum equation (P = F_{n+1/2} Sigma) and, WithTangent,
  // D = dSigma/dC1 (r.CC unset). Default (kIncrementalPotential): Gonzalez's discrete gradient of
  // the incremental potential W_inc(C; h_n) (= that of the frozen elastic potential, bit for bit
  // the lagged step's, where the three samples C0, Cm, C1 are elastic and |dC| < 1e-3).
  // kMeanValue: Sigma = S(C0 + s dC), the return-map stress from h_n at a mean-value point s of
  // W_inc on the segment (IncrementalPotential::mean_value_stress), Gonzalez's form where the
  // three samples are elastic, |dC| < kGonzalezGuard or no root is bracketed. kLagged: Gonzalez's
  // discrete gradient of the frozen elastic potential W(G^T C G) (FrozenPotential). All close
  //   Psi_{n+1} - Psi_n = 1/2 Sigma : (C1 - C0) - Dp,  Dp >= 0;
  // the first two with Dp = Y dg (+ a gap >= 0 that is 0 when h_n is admissible at C0).
  // mean_point (if given) receives s, or -1 where Gonzalez's form was taken.
  template <bool WithTangent, class HIn, class HOut>
  KOKKOS_INLINE_FUNCTION PointResponse dynamic_update(const Mat3& C0, const Mat3& C1, const HIn& hn,
                                                      const HOut& h1, Ten4& D,
                                                      double* mean_point = nullptr) const {
    if (dynamic_step == PlasticDynamicStep::kLagged) {
      PointResponse r = update<false>(C1, hn, h1);
      const FrozenPotential<Elastic> frozen = frozen_potential(hn);
      if constexpr (WithTangent)
        gonzalez_stress_and_tangent(frozen, C0, C1, r.S, D);
      else
        r.S = gonzalez_stress(frozen, C0, C1);
      return r;
    }
    const PlasticState s0 = read_state(hn);
    Step st;
    PointResponse r = update_state<false>(C1, s0, st);
    IncrementalPotential<Elastic> pot{*this, s0, inverse(s0.Ftr)};
    pot.remember(C1, r, st.dgamma);
    r.dissipation = Y * st.dgamma + pot.start_gap(C0);
    double s = -1.0;  // the mean-value point, -1 where Gonzalez's form is taken
    if (dynamic_step != PlasticDynamicStep::kMeanValue || !(std::sqrt(ddot(C1 - C0, C1 - C0)) >= kGonzalezGuard) ||
        pot.smooth_between(C0, C1) ||
        !pot.template mean_value_stress<WithTangent>(C0, C1, r.S, D, s)) {
      if constexpr (WithTangent)
        gonzalez_stress_and_tangent(pot, C0, C1, r.S, D);
      else
        r.S = gonzalez_stress(pot, C0, C1);
    }
    if (mean_point) *mean_point = s;
    r.converged = r.converged && pot.converged;
    write_state(st, hn, r.dissipation, h1);
    return r;
  }

  template <class HIn>
  KOKKOS_INLINE_FUNCTION static PlasticState read_state(const HIn& hn) {
    PlasticState s0;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) s0.Ftr(i, j) = hn[kFtr + 3 * i + j];
    s0.alpha = hn[kAlpha];
    return s0;
  }

  template <class HIn, class HOut>
  KOKKOS_INLINE_FUNCTION static void write_state(const Step& st, const HIn& hn, double dissipation, const HOut& h1) {
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) h1[kFtr + 3 * i + j] = st.state.Ftr(i, j);
    h1[kAlpha] = st.state.alpha;
    h1[kMandelHill] = st.mandel_hill;
    h1[kYielding] = st.dgamma > 0.0 ? 1.0 : 0.0;
    h1[kDissipation] = hn[kDissipation] + dissipation;
  }

  // The elastic potential at the frozen state of history row hn: C -> W(G^T C G),
  // G = Ftr_n^-1 (for the Gonzalez stress of the energy-dissipative dynamic step).
  template <class HIn>
  KOKKOS_INLINE_FUNCTION FrozenPotential<Elastic> frozen_potential(const HIn& hn) const {
    Mat3 Ftr;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) Ftr(i, j) = hn[kFtr + 3 * i + j];
    return FrozenPotential<Elastic>{elastic, inverse(Ftr)};
  }

  // The trial test's tolerance: a trial point outside the yield surface by at most this
  // fraction of the yield stress is elastic. A converged plastic point ends on the surface
  // to round-off, so at the next step's start (C = C_n) its trial point can fall outside by
  // round-off; there the return map gave dg = 0 with the elastoplastic tangent (the
  // stiffness of the hardening modulus) where the next step may unload elastically. That
  // round-off grows with E / Y: 316L (E / Y ~ 1000) lands up to 8.8e-12 Y outside, so 1e-12
  // was too tight (the S6 ring's recoil with F-bar failed on it); 1e-10 Y leaves a factor
  // 10 and is the accuracy asked of the yield condition itself (docs/plasticity.md).
  static constexpr double kYieldTolerance = 1e-10;

  // Same on structured state (C = F^T F at t_{n+1}; s0 at t_n is not modified).
  template <bool WithTangent = true>
  KOKKOS_INLINE_FUNCTION PointResponse update_state(const Mat3& C, const PlasticState& s0,
                                                    Step& out) const {
    const Mat3 G = inverse(s0.Ftr);
    const Mat3 Ct = tmul(G, matmul(C, G));  // Ce^tr = Ftr_n^-T C Ftr_n^-1
    const double Yn = yield_stress(s0.alpha);
    const double q_tr = mandel_hill_norm(Ct);
    if (q_tr - Yn <= kYieldTolerance * Yn) return elastic_branch<WithTangent>(Ct, G, s0, q_tr, out);
    return plastic_branch<WithTangent>(Ct, G, s0, out);
  }

  // |M|_H for M = Ce Sbar(Ce) by the tensor route (independent of the spectral one).
  KOKKOS_INLINE_FUNCTION double mandel_hill_norm(const Mat3& Ce) const {
    const Mat3 M = matmul(Ce, elastic.stress(Ce));
    const Mat3 d = deviator(0.5 * (M + transpose(M)));
    return std::sqrt(1.5 * ddot(d, d));
  }

 private:
  // (The law's stress() and stress_and_tangent() compute S by the same code.)
  template <bool WithTangent>
  KOKKOS_INLINE_FUNCTION PointResponse elastic_branch(const Mat3& Ct, const Mat3& G,
                                                      const PlasticState& s0, double q,
                                                      Step& out) const {
    PointResponse r;
    Mat3 Sb;
    if constexpr (WithTangent) {
      Ten4 CCb;
      elastic.stress_and_tangent(Ct, Sb, CCb);
      plasticity_detail::push_tangent(G, CCb, r.CC);
    } else {
      Sb = elastic.stress(Ct);
    }
    r.S = matmul(G, matmul(Sb, transpose(G)));
    r.energy = elastic.energy(Ct) + hardening_energy(s0.alpha);
    r.dissipation = 0.0;
    r.iterations = 0;
    r.converged = true;
    out.state = s0;
    out.dgamma = 0.0;
    out.mandel_hill = q;
    return r;
  }

  template <bool WithTangent>
  KOKKOS_INLINE_FUNCTION PointResponse plastic_branch(const Mat3& Ct, const Mat3& G,
                                                      const PlasticState& s0, Step& out) const {
    using namespace plasticity_detail;
    double ct[3], et[3];
    Mat3 N;
    sym_eig3(Ct, ct, N);
    for (int A = 0; A < 3; ++A) et[A] = 0.5 * std::log(ct[A]);
    ReturnMap rm;
    return_map(et, yield_stress(s0.alpha), s0.alpha, rm, WithTangent);
    PointResponse r;
    r.converged = rm.converged;
    r.iterations = rm.iterations;
    const Mat3 V = matmul(G, N);
    r.S = spectral_stress(ct, V, rm);
    if constexpr (WithTangent) spectral_tangent(ct, V, rm, r.CC);
    // Ftr_{n+1} = exp(dg n) Ftr_n, spectral exponential, then det normalisation.
    const double dg = rm.dgamma;
    Mat3 E = Mat3::zero();
    for (int A = 0; A < 3; ++A) {
      const double ex = std::exp(dg * rm.n[A]);
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) E(i, j) += ex * N(i, A) * N(j, A);
    }
    const Mat3 F1 = matmul(E, s0.Ftr);
    out.state.Ftr = std::cbrt(1.0 / det(F1)) * F1;
    out.state.alpha = s0.alpha + dg;
    out.dgamma = dg;
    out.mandel_hill = rm.q;
    double c[3], d[3];
    for (int A = 0; A < 3; ++A) c[A] = std::exp(2.0 * rm.e[A]), d[A] = et[A] - rm.e[A];
    r.energy = principal_energy(elastic, c) + hardening_energy(out.state.alpha);
    r.dissipation = principal_energy_jump(elastic, c, d) - H * dg * (s0.alpha + 0.5 * dg) -
                    nonlinear.energy_increment(s0.alpha, dg);
    return r;
  }

  // Residual R(x) and Jacobian J of the local problem at x = (e, dg), Yn = sigma_y(alpha_n);
  // fills rm.tau, rm.n, rm.q and the elastic Hessian Ge = dtau/de. Returns max |s_A|
  // (tolerance scale).
  KOKKOS_INLINE_FUNCTION double local_system(const double x[4], const double et[3], double Yn, double alpha_n,
                                             double R[4], double J[4][4], double Ge[3][3],
                                             plasticity_detail::ReturnMap& rm) const {
    double c[3], s[3], p;
    for (int A = 0; A < 3; ++A) c[A] = std::exp(2.0 * x[A]);
    plasticity_detail::principal_moduli(elastic, c, s, p, Ge);
    const double q = plasticity_detail::hill(s, rm.n);
    rm.q = q;
    const double dg = x[3];
    double Nn[3][3], smax = 0.0;  // dn/dtau = (3/2 P - n n^T) / q
    for (int A = 0; A < 3; ++A) {
      rm.tau[A] = s[A] + p;
      smax = std::fmax(smax, std::fabs(s[A]));
      for (int B = 0; B < 3; ++B)
        Nn[A][B] = (1.5 * ((A == B ? 1.0 : 0.0) - 1.0 / 3.0) - rm.n[A] * rm.n[B]) / q;
    }
    for (int A = 0; A < 3; ++A) {
      R[A] = x[A] - et[A] + dg * rm.n[A];
      J[A][3] = rm.n[A];
      J[3][A] = rm.n[0] * Ge[0][A] + rm.n[1] * Ge[1][A] + rm.n[2] * Ge[2][A];
      for (int B = 0; B < 3; ++B)
        J[A][B] = (A == B ? 1.0 : 0.0) +
                  dg * (Nn[A][0] * Ge[0][B] + Nn[A][1] * Ge[1][B] + Nn[A][2] * Ge[2][B]);
    }
    R[3] = q - Yn - H * dg - nonlinear.kappa_increment(alpha_n, dg);
    J[3][3] = -H - nonlinear.slope(alpha_n + dg);
    return smax;
  }

  // Local Newton on x = (e_1, e_2, e_3, dg) from the trial point (e = et, dg = 0);
  // converged when |R_4| <= 1e-12 (Yn + max|s|) and |R_A| <= 1e-14 (1 + max|et|).
  // A step that would make dg negative is shortened to halve dg instead. rm.a (the
  // algorithmic moduli) only with `moduli`.
  KOKKOS_INLINE_FUNCTION void return_map(const double et[3], double Yn, double alpha_n,
                                         plasticity_detail::ReturnMap& rm, bool moduli) const {
    double x[4] = {et[0], et[1], et[2], 0.0}, R[4], J[4][4], Ge[3][3];
    const double emax = std::fmax(std::fabs(et[0]), std::fmax(std::fabs(et[1]), std::fabs(et[2])));
    rm.converged = false;
    for (int k = 0;; ++k) {
      const double smax = local_system(x, et, Yn, alpha_n, R, J, Ge, rm);
      const double rA = std::fmax(std::fabs(R[0]), std::fmax(std::fabs(R[1]), std::fabs(R[2])));
      rm.iterations = k;
      if (!(rm.q > 0.0)) break;
      if (std::fabs(R[3]) <= 1e-12 * (Yn + smax) && rA <= 1e-14 * (1.0 + emax)) {
        rm.converged = true;
        break;
      }
      if (k == kMaxLocalIterations) break;
      double Jc[4][4], dx[4] = {-R[0], -R[1], -R[2], -R[3]};
      for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) Jc[i][j] = J[i][j];
      if (!plasticity_detail::solve4(Jc, dx)) break;
      const double t = (x[3] + dx[3] < 0.0) ? -0.5 * x[3] / dx[3] : 1.0;
      for (int i = 0; i < 4; ++i) x[i] += t * dx[i];
    }
    for (int A = 0; A < 3; ++A) rm.e[A] = x[A];
    rm.dgamma = x[3];
    if (moduli) algorithmic_moduli(J, Ge, rm);
  }

  // a = dtau/det = Ge [J^-1]_{3x3} (J dx = (det, 0)), symmetrised (exact a is symmetric).
  KOKKOS_INLINE_FUNCTION static void algorithmic_moduli(const double J[4][4], const double Ge[3][3],
                                                        plasticity_detail::ReturnMap& rm) {
    double X[3][3];
    for (int B = 0; B < 3; ++B) {
      double Jc[4][4], b[4] = {0.0, 0.0, 0.0, 0.0};
      for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) Jc[i][j] = J[i][j];
      b[B] = 1.0;
      plasticity_detail::solve4(Jc, b);
      for (int A = 0; A < 3; ++A) X[A][B] = b[A];
    }
    double a[3][3];
    for (int A = 0; A < 3; ++A)
      for (int B = 0; B < 3; ++B) a[A][B] = Ge[A][0] * X[0][B] + Ge[A][1] * X[1][B] + Ge[A][2] * X[2][B];
    for (int A = 0; A < 3; ++A)
      for (int B = 0; B < 3; ++B) rm.a[A][B] = 0.5 * (a[A][B] + a[B][A]);
  }

  // S = sum z_A v_A v_A^T, z_A = tau_A / ct_A, v_A = columns of V = G N.
  KOKKOS_INLINE_FUNCTION static Mat3 spectral_stress(const double ct[3], const Mat3& V,
                                                     const plasticity_detail::ReturnMap& rm) {
    double z[3];
    for (int A = 0; A < 3; ++A) z[A] = rm.tau[A] / ct[A];
    Mat3 S;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) S(i, j) = z[0] * V(i, 0) * V(j, 0) + z[1] * V(i, 1) * V(j, 1) + z[2] * V(i, 2) * V(j, 2);
    return S;
  }

  // CC = 2 dS/dC (header comment) from the algorithmic moduli rm.a.
  KOKKOS_INLINE_FUNCTION static void spectral_tangent(const double ct[3], const Mat3& V,
                                                      const plasticity_detail::ReturnMap& rm, Ten4& CC) {
    double z[3], dz[3][3], th[3][3];
    for (int A = 0; A < 3; ++A) z[A] = rm.tau[A] / ct[A];
    for (int A = 0; A < 3; ++A)
      for (int B = 0; B < 3; ++B)
        dz[A][B] = rm.a[A][B] / (2.0 * ct[A] * ct[B]) - (A == B ? rm.tau[A] / (ct[A] * ct[A]) : 0.0);
    for (int A = 0; A < 3; ++A)
      for (int B = 0; B < 3; ++B) {
        if (A == B) continue;
        th[A][B] = std::fabs(ct[A] - ct[B]) > 1e-8 * (ct[A] + ct[B])
                       ? (z[A] - z[B]) / (ct[A] - ct[B])
                       : 0.5 * (dz[A][A] - dz[A][B] + dz[B][B] - dz[B][A]);
      }
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        for (int k = 0; k < 3; ++k)
          for (int l = 0; l < 3; ++l) {
            double v = 0.0;
            for (int A = 0; A < 3; ++A)
              for (int B = 0; B < 3; ++B) {
                v += 2.0 * dz[A][B] * V(i, A) * V(j, A) * V(k, B) * V(l, B);
                if (A != B) v += th[A][B] * V(i, A) * V(j, B) * (V(k, A) * V(l, B) + V(k, B) * V(l, A));
              }
            CC(i, j, k, l) = v;
          }
  }
};

// Incremental potential of the return map from the state s0 = h_n (the variational form of the
// update, Ortiz–Stainier 1999; its discrete gradient is the energy-momentum step of Noels,
// Stainier & Ponthot 2006; docs/plasticity.md, "Dynamics"):
//   W_inc(C) = min_{p trace-free} W(et(C) - p) + psi_h(alpha_n + |p|') + Y |p|',
// |p|' = sqrt(2/3) |p| = dg, et(C) the principal log strains of Ce^tr = G^T C G. The
// functional is convex in p (W convex in principal log strains, psi_h convex and
// non-decreasing), and its minimiser is the return map (the stationarity condition is
// |tau(e)|_H = Y + psi_h'(alpha) = sigma_y(alpha), p = dg n), so
//   W_inc(C) = Psi(C, return map) + Y dg(C),
// and by the envelope theorem dW_inc/det = tau(e_{n+1}) (tau . dn = 0, tau . n = sigma_y):
// 2 dW_inc/dC is the return-map stress S(C) and 4 d2W_inc/dC2 its consistent tangent CC. So
// gonzalez_stress / gonzalez_stress_and_tangent (DiscreteGradient.hpp) apply to it:
// 1/2 Sigma : (C1 - C0) = W_inc(C1) - W_inc(C0) with Sigma a discrete mean of return-mapped
// (admissible) stresses along the segment. W_inc is C^1 only where the segment crosses the
// yield surface (CC jumps there), so Simpson's form of the discrete gradient (which assumes a
// smooth W) is taken only where Ce^tr of the three samples C0, Cm, C1 is inside the yield surface;
// otherwise g is the energy difference itself. `converged` records a failed return map at any
// sample.
//
// Mean-value stress (mean_value_stress; the default step where the segment flows). Gonzalez's
// Sigma = S(Cm) + 2 g dC/|dC|^2 is an admissible stress plus a correction of O(|dC|^2), which
// can put it that far outside the yield surface. Instead: w(s) = W_inc(C0 + s dC) is C^1 on
// [0, 1] with w'(s) = 1/2 S(C0 + s dC):dC, so by the mean-value theorem some s* in (0, 1) has
//   phi(s*) = 1/2 S(C0 + s* dC):dC - [W_inc(C1) - W_inc(C0)] = 0,
// and Sigma = S(C0 + s* dC) closes the energy identity exactly while being itself a return-mapped
// stress from h_n (the state of a point of the step's path): its Mandel stress satisfies the
// yield condition and the flow rule there, to the return map's tolerance. phi'(s) =
// 1/4 dC:CC(C0 + s dC):dC (CC the consistent tangent; > 0 where W_inc is strictly convex along
// the segment, then s* is unique); for a quadratic W_inc, s* = 1/2 and Sigma = S(Cm). The root
// is found by Newton safeguarded by bisection in a sign-change bracket of phi (phi(0) and
// phi(1) have opposite signs where w is convex; otherwise phi(1/2) is tried; no bracket:
// Gonzalez's form instead, never met in the tests), to |phi| <= 1e-15 (|W_inc(C0)| +
// |W_inc(C1)| + |phi(0)| + |phi(1)|) or a Newton step |phi/phi_s| <= 1e-13 (then the identity
// holds to 1e-13 phi_s = 1e-13 dC:CC:dC/4, an energy of the step's own increment). Tangent, C0 fixed: phi(s*(C1), C1) = 0 gives
//   phi_s ds* = -dphi/dC1 : dC1,  dphi/dC1 = 1/2 (S* - S1) + 1/4 s* CC*:dC,
// (S1 = S(C1) = 2 dW_inc/dC1, major symmetry of CC), so with A = 1/2 CC*:dC = dS/ds and
// B = 1/2 (S1 - S*) - 1/2 s* A,
//   D = dSigma/dC1 = 1/2 s* CC* + A (x) B / phi_s,   phi_s = 1/2 A:dC.
// D has the minor symmetries, not the major one (A (x) B), like Gonzalez's tangent.
template <class Elastic>
struct IncrementalPotential {
  using Law = MultiplicativePlasticity<Elastic>;
  Law law;
  PlasticState s0;  // h_n
  Mat3 G;           // Ftr_n^-1
  mutable bool converged = true;
  // The stress-only result at one point (C_{n+1}: dynamic_update's own update), reused by
  // energy() and stress() there (the same operations: bit for bit what they would compute).
  Mat3 Ck = Mat3::zero(), Sk = Mat3::zero();
  double Wk = 0.0;
  bool cached = false;

  KOKKOS_INLINE_FUNCTION void remember(const Mat3& C, const PointResponse& r, double dg) {
    Ck = C, Sk = r.S, Wk = r.energy + law.Y * dg, cached = true, in1 = dg == 0.0;
  }
  // S(C) and W_inc(C) by the stress-only return map from s0.
  KOKKOS_INLINE_FUNCTION void evaluate(const Mat3& C, Mat3& S, double& W) const {
    if (cached && same(C, Ck)) {
      S = Sk, W = Wk;
      return;
    }
    typename Law::Step st;
    const PointResponse r = law.template update_state<false>(C, s0, st);
    converged = converged && r.converged;
    S = r.S, W = r.energy + law.Y * st.dgamma;
  }
  KOKKOS_INLINE_FUNCTION double energy(const Mat3& C) const {
    Mat3 S;
    double W;
    evaluate(C, S, W);
    return W;
  }
  KOKKOS_INLINE_FUNCTION Mat3 stress(const Mat3& C) const {
    Mat3 S;
    double W;
    evaluate(C, S, W);
    return S;
  }
  KOKKOS_INLINE_FUNCTION void stress_and_tangent(const Mat3& C, Mat3& S, Ten4& CC) const {
    typename Law::Step st;
    const PointResponse r = law.template update_state<true>(C, s0, st);
    converged = converged && r.converged;
    S = r.S;
    CC = r.CC;
  }
  // Ce^tr of C inside the yield surface (the trial test of update_state, f^tr <= 0); the
  // answers at C_n (start_gap) and C_{n+1} (remember: dg = 0, which also counts a trial point
  // outside by less than kYieldTolerance, where it does not flow) are reused.
  Mat3 C0k = Mat3::zero();
  int in0 = -1;  // trial test at C0k: 1 inside, 0 outside, -1 not evaluated
  bool in1 = false;      // at Ck
  KOKKOS_INLINE_FUNCTION static bool same(const Mat3& a, const Mat3& b) {
    bool e = true;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) e = e && a(i, j) == b(i, j);
    return e;
  }
  KOKKOS_INLINE_FUNCTION bool inside(const Mat3& C) const {
    if (cached && same(C, Ck)) return in1;
    if (in0 >= 0 && same(C, C0k)) return in0 == 1;
    const double Y = law.yield_stress(s0.alpha);
    return law.mandel_hill_norm(tmul(G, matmul(C, G))) - Y <= Law::kYieldTolerance * Y;
  }
  // True where the three samples are elastic (W_inc = the smooth frozen potential there).
  KOKKOS_INLINE_FUNCTION bool smooth_between(const Mat3& C0, const Mat3& C1) const {
    return inside(C0) && inside(0.5 * (C0 + C1)) && inside(C1);
  }
  // The mean-value stress Sigma = S(C0 + s dC) (docs/plasticity.md, "Dynamics"): s in [0, 1]
  // the root of phi(s) = 1/2 S(C0 + s dC):dC - [W_inc(C1) - W_inc(C0)], dC = C1 - C0, by Newton
  // (phi' = 1/4 dC:CC:dC) safeguarded by bisection in a sign-change bracket, started from the
  // secant of phi(0), phi(1). WithTangent, D = dSigma/dC1 = 1/2 s CC + A (x) B / phi' with
  // A = 1/2 CC:dC and B = 1/2 (S(C1) - Sigma) - 1/2 s A. False (Sigma, D untouched) where
  // phi(0), phi(1/2), phi(1) have one sign: no bracket found.
  template <bool WithTangent>
  KOKKOS_INLINE_FUNCTION bool mean_value_stress(const Mat3& C0, const Mat3& C1, Mat3& Sigma, Ten4& D,
                                                double& s_out) const {
    Mat3 dC;  // symmetric part, so that D is symmetric in KL for any input
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) dC(i, j) = 0.5 * ((C1(i, j) - C0(i, j)) + (C1(j, i) - C0(j, i)));
    Mat3 S0, S1;
    double W0, W1;
    evaluate(C0, S0, W0);
    evaluate(C1, S1, W1);
    const double dW = W1 - W0;
    double lo = 0.0, hi = 1.0;
    double flo = 0.5 * ddot(S0, dC) - dW, fhi = 0.5 * ddot(S1, dC) - dW;
    const double tol = 1e-15 * (std::fabs(W0) + std::fabs(W1) + std::fabs(flo) + std::fabs(fhi));
    double s = flo != fhi ? flo / (flo - fhi) : 0.5;
    if (flo * fhi > 0.0) s = 0.5;  // no sign change at the ends: try the middle first
    typename Law::Step st;
    PointResponse r;
    double f = 0.0, fs = 0.0;
    Mat3 A;
    for (int it = 0; it < kMaxMeanValueIterations; ++it) {
      r = law.template update_state<true>(C0 + s * dC, s0, st);
      converged = converged && r.converged;
      f = 0.5 * ddot(r.S, dC) - dW;
      for (int i = 0; i < 3; ++i)  // A = 1/2 CC:dC = dS/ds
        for (int j = 0; j < 3; ++j) {
          double v = 0.0;
          for (int k = 0; k < 3; ++k)
            for (int l = 0; l < 3; ++l) v += r.CC(i, j, k, l) * dC(k, l);
          A(i, j) = 0.5 * v;
        }
      fs = 0.5 * ddot(A, dC);
      if (std::fabs(f) <= tol || std::fabs(f) <= 1e-13 * fs) break;  // or a Newton step in s below 1e-13
      if (flo * fhi > 0.0) {  // first evaluation at s = 1/2 without a bracket
        if (f * flo > 0.0) return false;
        hi = s, fhi = f;
      } else if ((f < 0.0) == (flo < 0.0)) {
        lo = s, flo = f;
      } else {
        hi = s, fhi = f;
      }
      if (hi - lo <= 4e-16) break;
      const double sn = s - f / fs;
      s = sn > lo && sn < hi ? sn : 0.5 * (lo + hi);
    }
    s_out = s;
    Sigma = r.S;
    if constexpr (WithTangent) {
      const Mat3 B = 0.5 * (S1 - r.S) - (0.5 * s) * A;
      const double c = fs != 0.0 ? 1.0 / fs : 0.0;
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
          for (int k = 0; k < 3; ++k)
            for (int l = 0; l < 3; ++l) D(i, j, k, l) = 0.5 * s * r.CC(i, j, k, l) + c * A(i, j) * B(k, l);
    }
    return true;
  }
  static constexpr int kMaxMeanValueIterations = 60;
  // Psi(C0, h_n) - W_inc(C0) >= 0: 0 when h_n is admissible at C0 (always after a converged step,
  // whose state satisfies the yield condition at C_n); otherwise the algorithmic dissipation of
  // the return map at C0 minus Y dg, >= 0 (Plasticity.hpp header). Call it once.
  KOKKOS_INLINE_FUNCTION double start_gap(const Mat3& C0) {
    in0 = inside(C0) ? 1 : 0;
    C0k = C0;
    if (in0 == 1) return 0.0;
    typename Law::Step st;
    const PointResponse r = law.template update_state<false>(C0, s0, st);
    converged = converged && r.converged;
    return st.dgamma > 0.0 ? std::fmax(0.0, r.dissipation - law.Y * st.dgamma) : 0.0;
  }
};

using CiarletGeymonatPlasticity = MultiplicativePlasticity<CiarletGeymonat>;
using NeoHookeanPlasticity = MultiplicativePlasticity<NeoHookean>;

}  // namespace stentor
