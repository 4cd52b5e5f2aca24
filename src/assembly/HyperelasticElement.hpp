// Element residual and tangent of finite-strain hyperelasticity, one cell at a time.
// Called from the Kokkos element loop (Assembler.cpp); everything lives on the stack.
//
//   r_(a,i)        = sum_q  P_iJ dN_a/dX_J  w_q detJ_q
//   K_(a,i),(b,k)  = sum_q  dN_a/dX_J A_iJkL dN_b/dX_L  w_q detJ_q,   A = dP/dF
// 2D is plane strain: F_33 = 1, per unit thickness; only in-plane dofs are assembled.
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
// the law's own dynamic_update (plasticity: the discrete gradient of the incremental potential,
// the stress from the return map inside the step) or, for a law without one, the update at
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

// Element internal force (and its derivative with respect to u_{n+1}):
//   r_(a,i) = sum_q P_iJ dN_a/dX_J w detJ,  K = dr/du_{n+1} = sum_q dN_a/dX_J A_iJkL dN_b/dX_L w detJ.
// `energy` = int W(C_{n+1}) (with history: int Psi_{n+1}); `dissipation` = int S^v : (C_{n+1} - C_n)/2
// = int eta |dC|^2/dt; `plastic` += int D_p of the step (laws with history only).
// Mat is a hyperelastic law (ElasticLaw: the dispatch over every law, or one law such as
// CiarletGeymonat) with Hist = NoHistory, or any law with history (MaterialState.hpp,
// e.g. CiarletGeymonatPlasticity, NeoHookeanDamage) with Hist = CellHistory; with history
// the stress is evaluated at the end point, or by history_gonzalez for the Gonzalez scheme.
template <bool WithTangent, class Mat = CiarletGeymonat, class Hist = NoHistory>
KOKKOS_INLINE_FUNCTION int solid_element(int dim, CellType type, int nn, const double (*X)[3], const double (*U)[3],
                                         const double (*U0)[3], const Mat& mat, const ElementTime& et,
                                         const QuadRule& q, double* re, double (*ke)[kMaxCellDofs], double& energy,
                                         double& dissipation, const Hist& hist = Hist{}, double* plastic = nullptr) {
  const int nd = nn * dim;
  for (int i = 0; i < nd; ++i) {
    re[i] = 0.0;
    if (WithTangent)
      for (int j = 0; j < nd; ++j) ke[i][j] = 0.0;
  }
  energy = 0.0;
  dissipation = 0.0;
  double N[kMaxCellNodes], dN[kMaxCellNodes][3], dNdX[kMaxCellNodes][3];
  for (int g = 0; g < q.n; ++g) {
    shape_functions(type, q.xi[g], N, dN);
    const double detJ = reference_gradients(dim, nn, X, dN, dNdX);
    if (!(detJ > 0.0)) return kElementDegenerate;
    const double wq = q.w[g] * detJ;
    const Mat matq = law_at_point(mat, nn, N, X);  // fibre directions at this point, if the law has them
    const Mat3 F1 = deformation_gradient(dim, nn, U, dNdX);
    if (!(det(F1) > 0.0)) return kElementInverted;
    const Mat3 C1 = tmul(F1, F1);
    Mat3 P, Fv = F1, C0 = C1;
    Ten4 A;
    if constexpr (!Hist::kActive) energy += wq * matq.energy(C1);
    if (et.has_old) {
      const Mat3 F0 = deformation_gradient(dim, nn, U0, dNdX);
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
    } else if (et.eval == StressEval::EndPoint || et.eval == StressEval::Midpoint) {
      // Stress of the evaluation configuration Fv (F_{n+1} or F_{n+1/2}).
      if (!(det(Fv) > 0.0)) return kElementInverted;
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
    } else {
      // Gonzalez: P = F_{n+1/2} Sigma, Sigma = Sigma_algo(C_n, C_{n+1}), D = dSigma/dC_{n+1}.
      //   A_iJkL = 1/2 delta_ik Sigma_LJ + 2 sum_{I,N} Fm_iI D_IJLN F1_kN.
      Mat3 Sig;
      Ten4 D;
      if (WithTangent)
        gonzalez_stress_and_tangent(matq, C0, C1, Sig, D);
      else
        Sig = gonzalez_stress(matq, C0, C1);
      P = matmul(Fv, Sig);
      if (WithTangent) gonzalez_dPdF(Fv, F1, Sig, D, A);
    }
    if (et.eta > 0.0) {
      // Curnier viscosity at the evaluation configuration: P^v = Fv S^v, S^v = 2 eta (C1 - C0)/dt.
      const Mat3 Sv = curnier_viscous_stress(et.eta, C0, C1, et.dt);
      dissipation += wq * curnier_dissipation(et.eta, C0, C1, et.dt);
      P = P + matmul(Fv, Sv);
      if (WithTangent) {
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
    }
    for (int a = 0; a < nn; ++a)
      for (int i = 0; i < dim; ++i) {
        double s = 0.0;
        for (int J = 0; J < dim; ++J) s += P(i, J) * dNdX[a][J];
        re[a * dim + i] += wq * s;
      }
    if (WithTangent) {
      // G[a][i][k][L] = dN_a/dX_J A_iJkL, then K += G dN_b/dX_L.
      for (int a = 0; a < nn; ++a) {
        double G[3][3][3];
        for (int i = 0; i < dim; ++i)
          for (int k = 0; k < dim; ++k)
            for (int L = 0; L < dim; ++L) {
              double s = 0.0;
              for (int J = 0; J < dim; ++J) s += dNdX[a][J] * A(i, J, k, L);
              G[i][k][L] = wq * s;
            }
        for (int b = 0; b < nn; ++b)
          for (int i = 0; i < dim; ++i)
            for (int k = 0; k < dim; ++k) {
              double s = 0.0;
              for (int L = 0; L < dim; ++L) s += G[i][k][L] * dNdX[b][L];
              ke[a * dim + i][b * dim + k] += s;
            }
      }
    }
  }
  return kElementOk;
}

// Consistent mass of one cell: M_(a,i),(b,k) = delta_ik int rho N_a N_b dV.
KOKKOS_INLINE_FUNCTION void mass_element(int dim, CellType type, int nn, const double (*X)[3], double rho, const QuadRule& q,
                                         double (*ke)[kMaxCellDofs]) {
  const int nd = nn * dim;
  for (int i = 0; i < nd; ++i)
    for (int j = 0; j < nd; ++j) ke[i][j] = 0.0;
  double N[kMaxCellNodes], dN[kMaxCellNodes][3], dNdX[kMaxCellNodes][3];
  for (int g = 0; g < q.n; ++g) {
    shape_functions(type, q.xi[g], N, dN);
    const double w = rho * q.w[g] * reference_gradients(dim, nn, X, dN, dNdX);
    for (int a = 0; a < nn; ++a)
      for (int b = 0; b < nn; ++b)
        for (int i = 0; i < dim; ++i) ke[a * dim + i][b * dim + i] += w * N[a] * N[b];
  }
}

}  // namespace stentor
