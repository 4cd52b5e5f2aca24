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
#include "material/Kinematics.hpp"
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

enum ElementStatus : int { kElementOk = 0, kElementInverted = 1, kElementDegenerate = 2 };

// Deformation gradient at a point: F = I + sum_a U_a (x) dN_a/dX.
KOKKOS_INLINE_FUNCTION Mat3 deformation_gradient(int dim, int nn, const double (*U)[3], const double (*dNdX)[3]) {
  Mat3 F = Mat3::identity();
  for (int a = 0; a < nn; ++a)
    for (int i = 0; i < dim; ++i)
      for (int J = 0; J < dim; ++J) F(i, J) += U[a][i] * dNdX[a][J];
  return F;
}

template <bool WithTangent>
KOKKOS_INLINE_FUNCTION int hyperelastic_element(int dim, CellType type, int nn, const double (*X)[3], const double (*U)[3],
                                                const CiarletGeymonat& mat, const QuadRule& q, double* re,
                                                double (*ke)[kMaxCellDofs], double& energy) {
  const int nd = nn * dim;
  for (int i = 0; i < nd; ++i) {
    re[i] = 0.0;
    if (WithTangent)
      for (int j = 0; j < nd; ++j) ke[i][j] = 0.0;
  }
  energy = 0.0;
  double N[kMaxCellNodes], dN[kMaxCellNodes][3], dNdX[kMaxCellNodes][3];
  for (int g = 0; g < q.n; ++g) {
    shape_functions(type, q.xi[g], N, dN);
    const double detJ = reference_gradients(dim, nn, X, dN, dNdX);
    if (!(detJ > 0.0)) return kElementDegenerate;
    const double wq = q.w[g] * detJ;
    const Mat3 F = deformation_gradient(dim, nn, U, dNdX);
    if (!(det(F) > 0.0)) return kElementInverted;
    const Mat3 C = tmul(F, F);
    Mat3 S;
    Ten4 CC;
    if (WithTangent)
      mat.stress_and_tangent(C, S, CC);
    else
      S = mat.stress(C);
    energy += wq * mat.energy(C);
    const Mat3 P = matmul(F, S);
    for (int a = 0; a < nn; ++a)
      for (int i = 0; i < dim; ++i) {
        double s = 0.0;
        for (int J = 0; J < dim; ++J) s += P(i, J) * dNdX[a][J];
        re[a * dim + i] += wq * s;
      }
    if (WithTangent) {
      Ten4 A;
      spatial_tangent_dPdF(F, S, CC, A);
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

}  // namespace stentor
