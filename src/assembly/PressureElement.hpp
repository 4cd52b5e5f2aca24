// Follower pressure on one boundary facet, in the configuration x = X + U:
//   r_a += ps N_a n da,  K = theta dr/dU  (U is the theta-blend of u_n and u_{n+1}),
// n da = (x_,xi_y, -x_,xi_x) dxi in 2D (axisymmetric: times 2 pi x_r, the current ring),
// (x_,xi x x_,eta) dxi deta in 3D; ps = pressure times the facet's orientation.
#pragma once
#include "assembly/HyperelasticElement.hpp"

namespace stentor {

KOKKOS_INLINE_FUNCTION void pressure_element(int dim, Kinematics kin, CellType type, int nn, const double (*X)[3],
                                             const double (*U)[3], double ps, double theta, const QuadRule& q,
                                             double* re, double (*ke)[kMaxCellDofs]) {
  const int nd = nn * dim;
  for (int i = 0; i < nd; ++i) {
    re[i] = 0.0;
    for (int j = 0; j < nd; ++j) ke[i][j] = 0.0;
  }
  double N[kMaxCellNodes], dN[kMaxCellNodes][3];
  for (int g = 0; g < q.n; ++g) {
    shape_functions(type, q.xi[g], N, dN);
    double t1[3] = {0, 0, 0}, t2[3] = {0, 0, 0}, x[3] = {0, 0, 0};
    for (int a = 0; a < nn; ++a)
      for (int d = 0; d < 3; ++d) {
        t1[d] += dN[a][0] * (X[a][d] + U[a][d]);
        t2[d] += dN[a][1] * (X[a][d] + U[a][d]);
        x[d] += N[a] * (X[a][d] + U[a][d]);
      }
    const double w = q.w[g] * ps;
    const double wt = w * theta;
    if (dim == 2) {
      // Axisymmetric: n da = 2 pi x_r (t1_y, -t1_x) dxi; d(x_r)/du_(b,r) = N_b.
      const bool axi = kin == Kinematics::Axisymmetric;
      const double ring = axi ? kTwoPi * x[0] : 1.0;
      const double n[2] = {t1[1], -t1[0]};
      for (int a = 0; a < nn; ++a) {
        re[a * 2 + 0] += w * ring * N[a] * n[0];
        re[a * 2 + 1] += w * ring * N[a] * n[1];
        for (int b = 0; b < nn; ++b) {
          ke[a * 2 + 0][b * 2 + 1] += wt * ring * N[a] * dN[b][0];
          ke[a * 2 + 1][b * 2 + 0] -= wt * ring * N[a] * dN[b][0];
          if (axi) {
            ke[a * 2 + 0][b * 2 + 0] += wt * kTwoPi * N[a] * n[0] * N[b];
            ke[a * 2 + 1][b * 2 + 0] += wt * kTwoPi * N[a] * n[1] * N[b];
          }
        }
      }
    } else {
      const double n[3] = {t1[1] * t2[2] - t1[2] * t2[1], t1[2] * t2[0] - t1[0] * t2[2], t1[0] * t2[1] - t1[1] * t2[0]};
      for (int a = 0; a < nn; ++a)
        for (int i = 0; i < 3; ++i) {
          re[a * 3 + i] += w * N[a] * n[i];
          for (int b = 0; b < nn; ++b)
            for (int k = 0; k < 3; ++k) {
              // d(t1 x t2)_i/du_bk = dN_b,xi (e_k x t2)_i + dN_b,eta (t1 x e_k)_i
              double ek_x_t2 = 0.0, t1_x_ek = 0.0;
              const int i1 = (i + 1) % 3, i2 = (i + 2) % 3;
              if (k == i1) { ek_x_t2 = t2[i2]; t1_x_ek = -t1[i2]; }
              if (k == i2) { ek_x_t2 = -t2[i1]; t1_x_ek = t1[i1]; }
              ke[a * 3 + i][b * 3 + k] += wt * N[a] * (dN[b][0] * ek_x_t2 + dN[b][1] * t1_x_ek);
            }
        }
    }
  }
}

}  // namespace stentor
