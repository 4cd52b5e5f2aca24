// Element residual and tangent of finite-strain hyperelasticity, one cell at a time.
// Called from the Kokkos element loop (Assembler.cpp); everything lives on the stack.
//
//   r_(a,i)        = sum_q  P_iJ dF_iJ/du_(a,i)  w_q detJ_q
//   K_(a,i),(b,k)  = sum_q  dF_jJ/du_(a,i) A_jJlL dF_lL/du_(b,k)  w_q detJ_q,   A = dP/dF
// (F is linear in u, so these are the exact derivatives of the stored energy).
// 2D meshes are read by their Kinematics (Problem->kinematics):
//   plane strain: F_33 = 1, per unit thickness; dF_iJ/du_(a,i) = dN_a/dX_J;
//   axisymmetric: (x, y) = (r, z), the third direction is the hoop one,
//     F_33 = F_thth = 1 + u_r/R at the reference radius R = sum_a N_a X_a,r of the point,
//     dF_33/du_(a,r) = N_a/R (the hoop row of B), and every volume integral carries
//     2 pi R: forces, energies and masses are those of the full revolution (docs/axisymmetric.md).
// Only in-plane dofs are assembled.
//
// F-bar (ElementTechnology::FBar, hex8; de Souza Neto, Peric, Dutko & Owen 1996, "Design of
// simple low order finite elements for large strain analysis of nearly incompressible
// solids", IJSS 33). Every Gauss point's law sees
//   Fb = s F,  s = (J0/J)^(1/3),  J = det F,  J0 = det F0,  F0 = F at the cell centre (xi = 0),
// so det Fb = J0: one volume change per cell, which removes the volumetric (and isochoric
// plastic flow) locking of the fully integrated hex8. The internal force is the Cauchy
// stress of Fb, sb = Pb Fb^T / J0, Pb = P(Fb), over the current volume:
//   r_(a,i) = int sb_ij dN_a/dx_j J dV = int Pe_iJ dN_a/dX_J dV,  Pe = s^-2 Pb
// (Pb Fb^T F^-T J/J0 = s^-2 Pb, since J/J0 = s^-3). Pe is not the derivative of a potential
// of u, so the tangent is not symmetric. With Ab = dPb/dFb (the law's tangent at Fb):
//   dFb/dF_kL  = s (I_ikJL - 1/3 F_iJ F^-1_Lk),   dFb/dF0_kL = 1/3 s F_iJ F0^-1_Lk,
//   dPe/dF     = s^-1 Ab - Q (x) F^-T,           dPe/dF0    = Q (x) F0^-T,
//   Q_iJ = 1/3 s^-2 [ (Ab : Fb)_iJ - 2 Pb_iJ ],  (Ab : Fb)_iJ = Ab_iJmN Fb_mN,
// the first term from dPb and the -2 Pb from d(s^-2) = -2/3 s^-2 (F0^-T : dF0 - F^-T : dF).
// With dF/du_(b,k) = e_k (x) dN_b/dX, F^-T : dF/du_(b,k) = dN_b/dx_k (the spatial gradient at
// the point, G) and F0^-T : dF0/du_(b,k) = dN_b/dx_k at the centre (G0), so
//   K_(a,i),(b,k) = int [ s^-1 dN_a/dX_J Ab_iJkL dN_b/dX_L + (Q_iJ dN_a/dX_J)(G0_bk - G_bk) ] dV,
// de Souza Neto's extra term. A homogeneous deformation has F0 = F, Fb = F, Pe = P(F): the
// patch test holds exactly on any hex8 mesh. Statics only (the deck refuses it in dynamics:
// with Fb the Gonzalez step's Delta C is no longer linear in the displacement increment).
#pragma once
#include "fem/CellType.hpp"
#include "fem/Geometry.hpp"
#include "fem/Quadrature.hpp"
#include "fem/Shape.hpp"
#include "material/CiarletGeymonat.hpp"
#include "material/DiscreteGradient.hpp"
#include "material/ElasticLaw.hpp"
#include "material/Kinematics.hpp"
#include "material/MaterialState.hpp"
#include "stentor/tensor.hpp"

namespace stentor {

// A quadrature rule by value (captured by kernels).
struct QuadRule {
  int n = 0;
  double xi[kMaxQuadPoints][3];
  double w[kMaxQuadPoints];
};

inline QuadRule make_rule(CellType t, int degree) {
  QuadRule q;
  q.n = quadrature(t, degree, q.xi, q.w);
  return q;
}

// kElementLocalFailure: a Gauss point's local (return-map) solve did not converge; like an
// inverted cell, the state is inadmissible (Newton line search, then step cut-back).
enum ElementStatus : int { kElementOk = 0, kElementInverted = 1, kElementDegenerate = 2, kElementLocalFailure = 3 };

// Gauss-point history of one cell for solid_element. NoHistory: a stateless law (the
// kernel is then exactly the hyperelastic one). CellHistory: rows g of the committed
// (h_n, read) and trial (h_{n+1}, written) per-block Views, kNumHist doubles per point.
struct NoHistory {
  static constexpr bool kActive = false;
};
struct CellHistory {
  static constexpr bool kActive = true;
  const double* hn;  // row of Gauss point 0 of this cell, committed
  double* h1;        // same, trial
  int stride;        // doubles per Gauss point
  KOKKOS_INLINE_FUNCTION const double* n(int g) const { return hn + g * stride; }
  KOKKOS_INLINE_FUNCTION double* np1(int g) const { return h1 + g * stride; }
};

// Deformation gradient at a point: F = I + sum_a U_a (x) dN_a/dX.
KOKKOS_INLINE_FUNCTION Mat3 deformation_gradient(int dim, int nn, const double (*U)[3], const double (*dNdX)[3]) {
  Mat3 F = Mat3::identity();
  for (int a = 0; a < nn; ++a)
    for (int i = 0; i < dim; ++i)
      for (int J = 0; J < dim; ++J) F(i, J) += U[a][i] * dNdX[a][J];
  return F;
}

// The element formulation of a block (Bodies-><body>->element technology): the standard
// displacement element, or F-bar (hex8 only, see the header).
enum class ElementTechnology : int { Full = 0, FBar = 1 };

// How a cell's fields are read: Cartesian (3D, or 2D plane strain) or Axisymmetric (a 2D
// mesh in the (r, z) half plane, x = r >= 0, y = z; the third direction is the hoop one).
enum class Kinematics : int { Cartesian = 0, Axisymmetric = 1 };

constexpr double kTwoPi = 6.283185307179586476925286766559005768;

// Reference radius R = sum_a N_a X_a,r at a point (0 for Cartesian kinematics). Positive at
// the interior (Gauss) points of a cell of positive area in r >= 0, nodes on the axis
// included: nothing divides by a nodal radius.
KOKKOS_INLINE_FUNCTION double reference_radius(Kinematics kin, int nn, const double* N, const double (*X)[3]) {
  double R = 0.0;
  if (kin == Kinematics::Axisymmetric)
    for (int a = 0; a < nn; ++a) R += N[a] * X[a][0];
  return R;
}

// Volume measure of a point with quadrature weight times detJ `wdetJ`: axisymmetric, the
// ring it sweeps about the axis (2 pi R wdetJ); Cartesian, wdetJ (per unit thickness in 2D).
KOKKOS_INLINE_FUNCTION double volume_weight(Kinematics kin, double wdetJ, double R) {
  return kin == Kinematics::Axisymmetric ? kTwoPi * R * wdetJ : wdetJ;
}

// F at a point: deformation_gradient, and axisymmetric the hoop stretch F_33 = 1 + u_r/R.
KOKKOS_INLINE_FUNCTION Mat3 point_deformation_gradient(int dim, Kinematics kin, int nn, const double* N, double R,
                                                       const double (*U)[3], const double (*dNdX)[3]) {
  Mat3 F = deformation_gradient(dim, nn, U, dNdX);
  if (kin == Kinematics::Axisymmetric) {
    double ur = 0.0;
    for (int a = 0; a < nn; ++a) ur += N[a] * U[a][0];
    F(2, 2) += ur / R;
  }
  return F;
}

// How the element's stress depends on the step's end states (u_n, u_{n+1}).
enum class StressEval : int {
  EndPoint = 0,  // P(F_{n+1}): statics, Newmark, HHT
  Midpoint = 1,  // P(F_{n+1/2}), F_{n+1/2} = (F_n + F_{n+1})/2: the plain midpoint rule
  Gonzalez = 2   // F_{n+1/2} Sigma_algo(C_n, C_{n+1}): Gonzalez's energy-consistent discrete gradient
};

struct ElementTime {
  StressEval eval = StressEval::EndPoint;
  bool has_old = false;  // U0 (u_n) is given: needed by Midpoint/Gonzalez and by viscosity
  double dt = 0.0;
  double eta = 0.0;      // Curnier viscosity; 0 skips all viscous work
};

// Stress and (WithTangent) A = dP/dF of a law with Gauss-point history at F1 (end point):
// the update reads h_n and writes h_{n+1} (trial); adds Psi_{n+1} and the step's plastic
// dissipation (times wq). False if the local solve failed. A residual-only call
// (WithTangent = false) takes the law's stress-only update: the same P bit for bit.
template <bool WithTangent, class Law>
KOKKOS_INLINE_FUNCTION bool history_point(const Law& law, const Mat3& F1, const double* hn, double* h1, double wq, Mat3& P,
                                          Ten4& A, double& energy, double& plastic) {
  const PointResponse pr = law.template update<WithTangent>(tmul(F1, F1), hn, h1);
  if (!pr.converged) return false;
  energy += wq * pr.energy;
  plastic += wq * pr.dissipation;
  P = matmul(F1, pr.S);
  if (WithTangent) spatial_tangent_dPdF(F1, pr.S, pr.CC, A);
  return true;
}

// dP/dF_{n+1} of P = F_{n+1/2} Sigma(C_n, C_{n+1}), D = dSigma/dC_{n+1}:
//   A_iJkL = 1/2 delta_ik Sigma_LJ + 2 sum_{I,N} Fm_iI D_IJLN F1_kN.
KOKKOS_INLINE_FUNCTION void gonzalez_dPdF(const Mat3& Fv, const Mat3& F1, const Mat3& Sig, const Ten4& D, Ten4& A) {
  for (int I = 0; I < 3; ++I)
    for (int J = 0; J < 3; ++J)
      for (int L = 0; L < 3; ++L)
        for (int k = 0; k < 3; ++k) {
          double t = 0.0;
          for (int Nn = 0; Nn < 3; ++Nn) t += D(I, J, L, Nn) * F1(k, Nn);
          A(I, J, L, k) = t;  // temporarily T[I][J][L][k]
        }
  Ten4 T = A;
  for (int i = 0; i < 3; ++i)
    for (int J = 0; J < 3; ++J)
      for (int k = 0; k < 3; ++k)
        for (int L = 0; L < 3; ++L) {
          double v = 2.0 * (Fv(i, 0) * T(0, J, L, k) + Fv(i, 1) * T(1, J, L, k) + Fv(i, 2) * T(2, J, L, k));
          if (i == k) v += 0.5 * Sig(L, J);
          A(i, J, k, L) = v;
        }
}

// Energy-dissipative midpoint step of a law with history (docs/plasticity.md, "Dynamics"):
// the law's own dynamic_update (plasticity: the discrete gradient of the step's incremental
// potential, the return map inside the step) or, for a law without one, the update at
// C_{n+1} (state h_{n+1}, Psi_{n+1}, D) with Gonzalez's discrete gradient Sigma(C_n, C_{n+1})
// of the frozen-state potential C -> Psi(C, h_n). Either way
// Psi_{n+1} - Psi_n = 1/2 Sigma : (C_{n+1} - C_n) - D, P = F_{n+1/2} Sigma and A from
// D = dSigma/dC_{n+1}.
template <bool WithTangent, class Law>
KOKKOS_INLINE_FUNCTION bool history_gonzalez(const Law& law, const Mat3& Fv, const Mat3& F1, const Mat3& C0, const Mat3& C1,
                                             const double* hn, double* h1, double wq, Mat3& P, Ten4& A, double& energy,
                                             double& plastic) {
  Ten4 D;
  PointResponse pr;
  if constexpr (HasDynamicUpdate<Law>::value) {
    pr = law.template dynamic_update<WithTangent>(C0, C1, hn, h1, D);
  } else {
    pr = law.template update<false>(C1, hn, h1);  // CC unused: stress-only
    const auto frozen = law.frozen_potential(hn);
    if (WithTangent)
      gonzalez_stress_and_tangent(frozen, C0, C1, pr.S, D);
    else
      pr.S = gonzalez_stress(frozen, C0, C1);
  }
  if (!pr.converged) return false;
  energy += wq * pr.energy;
  plastic += wq * pr.dissipation;
  P = matmul(Fv, pr.S);
  if (WithTangent) gonzalez_dPdF(Fv, F1, pr.S, D, A);
  return true;
}

// Curnier viscosity at the evaluation configuration Fv: P^v = Fv S^v, S^v = 2 eta (C1 - C0)/dt,
// added to P (and its derivative with respect to F1 to A); the dissipation times wq to `dissipation`.
template <bool WithTangent>
KOKKOS_INLINE_FUNCTION void add_viscous_stress(const ElementTime& et, const Mat3& Fv, const Mat3& F1, const Mat3& C0,
                                               const Mat3& C1, double wq, Mat3& P, Ten4& A, double& dissipation) {
  const Mat3 Sv = curnier_viscous_stress(et.eta, C0, C1, et.dt);
  dissipation += wq * curnier_dissipation(et.eta, C0, C1, et.dt);
  P = P + matmul(Fv, Sv);
  if (!WithTangent) return;
  // dP^v_iJ/dF1_kL = c delta_ik Sv_LJ + (2 eta/dt) (Fv_iL F1_kJ + (Fv F1^T)_ik delta_JL), c = dFv/dF1.
  const double c = (et.eval == StressEval::EndPoint) ? 1.0 : 0.5;
  const double e2 = 2.0 * et.eta / et.dt;
  Mat3 FvF1t;
  for (int i = 0; i < 3; ++i)
    for (int k = 0; k < 3; ++k) FvF1t(i, k) = Fv(i, 0) * F1(k, 0) + Fv(i, 1) * F1(k, 1) + Fv(i, 2) * F1(k, 2);
  for (int i = 0; i < 3; ++i)
    for (int J = 0; J < 3; ++J)
      for (int k = 0; k < 3; ++k)
        for (int L = 0; L < 3; ++L) {
          double v = e2 * Fv(i, L) * F1(k, J);
          if (J == L) v += e2 * FvF1t(i, k);
          if (i == k) v += c * Sv(L, J);
          A(i, J, k, L) += v;
        }
}

// Hyperelastic P at the evaluation configuration (F_{n+1}, or F_{n+1/2} for Midpoint) or by
// Gonzalez's discrete gradient, and (WithTangent) A = dP/dF_{n+1}. False if Fv is inverted.
template <bool WithTangent, class Law>
KOKKOS_INLINE_FUNCTION bool elastic_point(const Law& matq, const ElementTime& et, const Mat3& Fv, const Mat3& F1,
                                          const Mat3& C0, const Mat3& C1, Mat3& P, Ten4& A) {
  if (et.eval == StressEval::EndPoint || et.eval == StressEval::Midpoint) {
    if (!(det(Fv) > 0.0)) return false;
    const Mat3 Cv = tmul(Fv, Fv);
    Mat3 S;
    Ten4 CC;
    if (WithTangent)
      matq.stress_and_tangent(Cv, S, CC);
    else
      S = matq.stress(Cv);
    P = matmul(Fv, S);
    if (WithTangent) {
      spatial_tangent_dPdF(Fv, S, CC, A);
      if (et.eval == StressEval::Midpoint)  // dF_{n+1/2}/dF_{n+1} = 1/2
        for (int i = 0; i < 3; ++i)
          for (int J = 0; J < 3; ++J)
            for (int k = 0; k < 3; ++k)
              for (int L = 0; L < 3; ++L) A(i, J, k, L) *= 0.5;
    }
    return true;
  }
  // Gonzalez: P = F_{n+1/2} Sigma, Sigma = Sigma_algo(C_n, C_{n+1}), D = dSigma/dC_{n+1}.
  Mat3 Sig;
  Ten4 D;
  if (WithTangent)
    gonzalez_stress_and_tangent(matq, C0, C1, Sig, D);
  else
    Sig = gonzalez_stress(matq, C0, C1);
  P = matmul(Fv, Sig);
  if (WithTangent) gonzalez_dPdF(Fv, F1, Sig, D, A);
  return true;
}

// P and A of one Gauss point g from F_n (F0, used when et.has_old) and F_{n+1} (F1): the
// law's scheme (with history: end point or history_gonzalez), then viscosity. Adds the
// point's energy, viscous and (history) plastic dissipation times wq. Returns kElementOk
// or the failure.
template <bool WithTangent, class Law, class Hist>
KOKKOS_INLINE_FUNCTION int point_stress(const Law& matq, const ElementTime& et, const Mat3& F0, const Mat3& F1,
                                        const Hist& hist, int g, double wq, Mat3& P, Ten4& A, double& energy,
                                        double& dissipation, double* plastic) {
  if (!(det(F1) > 0.0)) return kElementInverted;
  const Mat3 C1 = tmul(F1, F1);
  Mat3 Fv = F1, C0 = C1;
  if constexpr (!Hist::kActive) energy += wq * matq.energy(C1);
  if (et.has_old) {
    C0 = tmul(F0, F0);
    if (et.eval != StressEval::EndPoint) Fv = 0.5 * (F0 + F1);
  }
  if constexpr (Hist::kActive) {
    // End point (statics, Newmark, HHT) or the energy-dissipative Gonzalez step; the deck
    // refuses the plain midpoint rule with history.
    const bool ok = et.eval == StressEval::Gonzalez
                        ? history_gonzalez<WithTangent>(matq, Fv, F1, C0, C1, hist.n(g), hist.np1(g), wq, P, A, energy, *plastic)
                        : history_point<WithTangent>(matq, F1, hist.n(g), hist.np1(g), wq, P, A, energy, *plastic);
    if (!ok) return kElementLocalFailure;
  } else if (!elastic_point<WithTangent>(matq, et, Fv, F1, C0, C1, P, A)) {
    return kElementInverted;
  }
  if (et.eta > 0.0) add_viscous_stress<WithTangent>(et, Fv, F1, C0, C1, wq, P, A, dissipation);
  return kElementOk;
}

// Adds one point's r_(a,i) = wq P : dF/du_(a,i) and K = wq dF/du_(a,i) : A : dF/du_(b,k).
// dF_iJ/du_(a,k) = delta_ik dN_a/dX_J, plus axisymmetric the hoop entry dF_33/du_(a,r) = N_a/R.
template <bool WithTangent>
KOKKOS_INLINE_FUNCTION void add_point(int dim, Kinematics kin, int nn, const double* N, const double (*dNdX)[3], double R,
                                      double wq, const Mat3& P, const Ten4& A, double* re, double (*ke)[kMaxCellDofs]) {
  const bool axi = kin == Kinematics::Axisymmetric;
  double h[kMaxCellNodes];  // N_a/R: the hoop row of B
  for (int a = 0; a < nn; ++a) h[a] = axi ? N[a] / R : 0.0;
  for (int a = 0; a < nn; ++a)
    for (int i = 0; i < dim; ++i) {
      double s = 0.0;
      for (int J = 0; J < dim; ++J) s += P(i, J) * dNdX[a][J];
      if (axi && i == 0) s += P(2, 2) * h[a];
      re[a * dim + i] += wq * s;
    }
  if (!WithTangent) return;
  // G[i][k][L] = wq dF_jJ/du_(a,i) A_jJkL, then K += G dN_b/dX_L; axisymmetric also
  // Gh[i] = wq dF_jJ/du_(a,i) A_jJ33 and K_(a,i),(b,r) += Gh[i] N_b/R (the hoop column).
  for (int a = 0; a < nn; ++a) {
    double G[3][3][3], Gh[3] = {0.0, 0.0, 0.0};
    for (int i = 0; i < dim; ++i) {
      for (int k = 0; k < dim; ++k)
        for (int L = 0; L < dim; ++L) {
          double s = 0.0;
          for (int J = 0; J < dim; ++J) s += dNdX[a][J] * A(i, J, k, L);
          if (axi && i == 0) s += h[a] * A(2, 2, k, L);
          G[i][k][L] = wq * s;
        }
      if (axi) {
        double s = 0.0;
        for (int J = 0; J < dim; ++J) s += dNdX[a][J] * A(i, J, 2, 2);
        if (i == 0) s += h[a] * A(2, 2, 2, 2);
        Gh[i] = wq * s;
      }
    }
    for (int b = 0; b < nn; ++b)
      for (int i = 0; i < dim; ++i)
        for (int k = 0; k < dim; ++k) {
          double s = 0.0;
          for (int L = 0; L < dim; ++L) s += G[i][k][L] * dNdX[b][L];
          if (axi && k == 0) s += Gh[i] * h[b];
          ke[a * dim + i][b * dim + k] += s;
        }
  }
}

// F-bar data of a cell: J0 = det F at the centre (xi = 0) and G0_(b,k) = dN_b/dx_k there.
struct FBarCentre {
  double J0 = 1.0;
  double G0[kMaxCellNodes][3];
};

// The centre data of F-bar for displacements U; false if the cell is degenerate or inverted
// at its centre.
KOKKOS_INLINE_FUNCTION bool fbar_centre(int dim, CellType type, int nn, const double (*X)[3], const double (*U)[3],
                                        FBarCentre& c) {
  const double xi0[3] = {0.0, 0.0, 0.0};
  double dN[kMaxCellNodes][3], dNdX[kMaxCellNodes][3];
  shape_functions(type, xi0, nullptr, dN);
  if (!(reference_gradients(dim, nn, X, dN, dNdX) > 0.0)) return false;
  const Mat3 F0 = deformation_gradient(dim, nn, U, dNdX);
  c.J0 = det(F0);
  if (!(c.J0 > 0.0)) return false;
  const Mat3 Fi = inverse(F0);
  for (int b = 0; b < nn; ++b)
    for (int k = 0; k < 3; ++k) c.G0[b][k] = dNdX[b][0] * Fi(0, k) + dNdX[b][1] * Fi(1, k) + dNdX[b][2] * Fi(2, k);
  return true;
}

// s = (J0/J)^(1/3) of Fb = s F at a point with J = det F > 0.
KOKKOS_INLINE_FUNCTION double fbar_scale(double J0, const Mat3& F) { return std::cbrt(J0 / det(F)); }

// Adds one F-bar point (header): Pb = P(Fb), Ab = dPb/dFb from point_stress, s of the point,
// F the point's (unmodified) deformation gradient. The residual and the s^-1 Ab part go
// through add_point with Pe = s^-2 Pb; then K_(a,i),(b,k) += wq (Q_iJ dN_a/dX_J)(G0_bk - G_bk).
template <bool WithTangent>
KOKKOS_INLINE_FUNCTION void add_fbar_point(int nn, const double (*dNdX)[3], double wq, double s, const Mat3& F,
                                           const Mat3& Pb, Ten4& Ab, const FBarCentre& c, double* re,
                                           double (*ke)[kMaxCellDofs]) {
  const double s2 = 1.0 / (s * s);
  const Mat3 Pe = s2 * Pb;
  Mat3 Q;
  if (WithTangent) {
    const Mat3 Fb = s * F;
    for (int i = 0; i < 3; ++i)
      for (int J = 0; J < 3; ++J) {
        double t = 0.0;
        for (int m = 0; m < 3; ++m)
          for (int Nn = 0; Nn < 3; ++Nn) t += Ab(i, J, m, Nn) * Fb(m, Nn);
        Q(i, J) = s2 * (t - 2.0 * Pb(i, J)) / 3.0;
      }
    const double si = 1.0 / s;
    for (int i = 0; i < 3; ++i)
      for (int J = 0; J < 3; ++J)
        for (int k = 0; k < 3; ++k)
          for (int L = 0; L < 3; ++L) Ab(i, J, k, L) *= si;
  }
  const double none[1] = {0.0};
  add_point<WithTangent>(3, Kinematics::Cartesian, nn, none, dNdX, 0.0, wq, Pe, Ab, re, ke);
  if (!WithTangent) return;
  const Mat3 Fi = inverse(F);
  double dG[kMaxCellNodes][3];  // G0 - G
  for (int b = 0; b < nn; ++b)
    for (int k = 0; k < 3; ++k) dG[b][k] = c.G0[b][k] - (dNdX[b][0] * Fi(0, k) + dNdX[b][1] * Fi(1, k) + dNdX[b][2] * Fi(2, k));
  for (int a = 0; a < nn; ++a)
    for (int i = 0; i < 3; ++i) {
      const double g = wq * (Q(i, 0) * dNdX[a][0] + Q(i, 1) * dNdX[a][1] + Q(i, 2) * dNdX[a][2]);
      for (int b = 0; b < nn; ++b)
        for (int k = 0; k < 3; ++k) ke[a * 3 + i][b * 3 + k] += g * dG[b][k];
    }
}

// Element internal force (and its derivative with respect to u_{n+1}):
//   r_(a,i) = sum_q P : dF/du_(a,i) dV,  K = dr/du_{n+1} = sum_q dF/du_(a,i) : A : dF/du_(b,k) dV,
// dV = w detJ (axisymmetric: 2 pi R w detJ).
// `energy` = int W(C_{n+1}) (with history: int Psi_{n+1}); `dissipation` = int S^v : (C_{n+1} - C_n)/2
// = int eta |dC|^2/dt; `plastic` += int D_p of the step (laws with history only).
// Mat is a hyperelastic law (ElasticLaw: the dispatch over every law, or one law such as
// CiarletGeymonat) with Hist = NoHistory, or any law with history (MaterialState.hpp,
// e.g. CiarletGeymonatPlasticity, NeoHookeanDamage) with Hist = CellHistory; with history
// the stress is evaluated at the end point, or by history_gonzalez for the Gonzalez scheme.
// tech = FBar (3D Cartesian hex8, statics): every law sees Fb (header); energy = int W(Cb).
template <bool WithTangent, class Mat = CiarletGeymonat, class Hist = NoHistory>
KOKKOS_INLINE_FUNCTION int solid_element(int dim, Kinematics kin, ElementTechnology tech, CellType type, int nn,
                                         const double (*X)[3],
                                         const double (*U)[3], const double (*U0)[3], const Mat& mat,
                                         const ElementTime& et, const QuadRule& q, double* re, double (*ke)[kMaxCellDofs],
                                         double& energy, double& dissipation, const Hist& hist = Hist{},
                                         double* plastic = nullptr) {
  const int nd = nn * dim;
  for (int i = 0; i < nd; ++i) {
    re[i] = 0.0;
    if (WithTangent)
      for (int j = 0; j < nd; ++j) ke[i][j] = 0.0;
  }
  energy = 0.0;
  dissipation = 0.0;
  const bool fbar = tech == ElementTechnology::FBar;
  FBarCentre c1, c0;  // F-bar: centre data of u_{n+1} and u_n
  if (fbar) {
    if (!fbar_centre(dim, type, nn, X, U, c1)) return kElementInverted;
    if (et.has_old && !fbar_centre(dim, type, nn, X, U0, c0)) return kElementInverted;
  }
  double N[kMaxCellNodes], dN[kMaxCellNodes][3], dNdX[kMaxCellNodes][3];
  for (int g = 0; g < q.n; ++g) {
    shape_functions(type, q.xi[g], N, dN);
    const double detJ = reference_gradients(dim, nn, X, dN, dNdX);
    if (!(detJ > 0.0)) return kElementDegenerate;
    const double R = reference_radius(kin, nn, N, X);
    if (kin == Kinematics::Axisymmetric && !(R > 0.0)) return kElementDegenerate;
    const double wq = volume_weight(kin, q.w[g] * detJ, R);
    const Mat matq = law_at_point(mat, nn, N, X);  // fibre directions at this point, if the law has them
    Mat3 F1 = point_deformation_gradient(dim, kin, nn, N, R, U, dNdX);
    Mat3 F0 = et.has_old ? point_deformation_gradient(dim, kin, nn, N, R, U0, dNdX) : F1;
    const Mat3 F = F1;  // F-bar: the point's own F (F1 becomes Fb)
    double s = 1.0;
    if (fbar) {
      if (!(det(F1) > 0.0) || (et.has_old && !(det(F0) > 0.0))) return kElementInverted;
      s = fbar_scale(c1.J0, F1);
      F0 = et.has_old ? fbar_scale(c0.J0, F0) * F0 : s * F1;
      F1 = s * F1;
    }
    Mat3 P;
    Ten4 A;
    const int status = point_stress<WithTangent>(matq, et, F0, F1, hist, g, wq, P, A, energy, dissipation, plastic);
    if (status != kElementOk) return status;
    if (fbar)
      add_fbar_point<WithTangent>(nn, dNdX, wq, s, F, P, A, c1, re, ke);
    else
      add_point<WithTangent>(dim, kin, nn, N, dNdX, R, wq, P, A, re, ke);
  }
  return kElementOk;
}

// Consistent mass of one cell: M_(a,i),(b,k) = delta_ik int rho N_a N_b dV (axisymmetric dV = 2 pi R dA).
KOKKOS_INLINE_FUNCTION void mass_element(int dim, Kinematics kin, CellType type, int nn, const double (*X)[3], double rho,
                                         const QuadRule& q, double (*ke)[kMaxCellDofs]) {
  const int nd = nn * dim;
  for (int i = 0; i < nd; ++i)
    for (int j = 0; j < nd; ++j) ke[i][j] = 0.0;
  double N[kMaxCellNodes], dN[kMaxCellNodes][3], dNdX[kMaxCellNodes][3];
  for (int g = 0; g < q.n; ++g) {
    shape_functions(type, q.xi[g], N, dN);
    double w = rho * q.w[g] * reference_gradients(dim, nn, X, dN, dNdX);
    if (kin == Kinematics::Axisymmetric) w *= kTwoPi * reference_radius(kin, nn, N, X);
    for (int a = 0; a < nn; ++a)
      for (int b = 0; b < nn; ++b)
        for (int i = 0; i < dim; ++i) ke[a * dim + i][b * dim + i] += w * N[a] * N[b];
  }
}

}  // namespace stentor
