// Geometric helpers for element kernels (header-only, callable inside Kokkos kernels).
//
// Nodal coordinates are passed as X[a][0..2] for a = 0..nn-1 and reference gradients as
// dN[a][0..2] (from shape_functions()).
#pragma once
#include <Kokkos_Macros.hpp>
#include <cmath>

namespace stentor {

// J_ij = dX_i/dxi_j = sum_a X[a][i] dN[a][j] (i, j < dim, dim = 1, 2 or 3, using the first `dim`
// coordinates). Writes dNdX[a][i] = dN_a/dX_i = sum_j dN[a][j] (J^-1)_ji for i < dim (components
// i >= dim are set to 0) and returns det J. If det J == 0, dNdX is set to 0 and 0 is returned.
// det J < 0 (inverted or mis-oriented cell) is returned as is: callers check the sign.
KOKKOS_INLINE_FUNCTION double reference_gradients(int dim, int nn, const double (*X)[3], const double (*dN)[3],
                                                  double (*dNdX)[3]) {
  double J[3][3] = {{0.0, 0.0, 0.0}, {0.0, 0.0, 0.0}, {0.0, 0.0, 0.0}};
  for (int a = 0; a < nn; ++a)
    for (int i = 0; i < dim; ++i)
      for (int j = 0; j < dim; ++j) J[i][j] += X[a][i] * dN[a][j];
  double det = 0.0;
  double Ji[3][3] = {{0.0, 0.0, 0.0}, {0.0, 0.0, 0.0}, {0.0, 0.0, 0.0}};
  if (dim == 1) {
    det = J[0][0];
    if (det != 0.0) Ji[0][0] = 1.0 / det;
  } else if (dim == 2) {
    det = J[0][0] * J[1][1] - J[0][1] * J[1][0];
    if (det != 0.0) {
      const double r = 1.0 / det;
      Ji[0][0] = J[1][1] * r;
      Ji[0][1] = -J[0][1] * r;
      Ji[1][0] = -J[1][0] * r;
      Ji[1][1] = J[0][0] * r;
    }
  } else if (dim == 3) {
    const double c00 = J[1][1] * J[2][2] - J[1][2] * J[2][1];
    const double c01 = J[1][2] * J[2][0] - J[1][0] * J[2][2];
    const double c02 = J[1][0] * J[2][1] - J[1][1] * J[2][0];
    det = J[0][0] * c00 + J[0][1] * c01 + J[0][2] * c02;
    if (det != 0.0) {
      const double r = 1.0 / det;
      Ji[0][0] = c00 * r;
      Ji[1][0] = c01 * r;
      Ji[2][0] = c02 * r;
      Ji[0][1] = (J[0][2] * J[2][1] - J[0][1] * J[2][2]) * r;
      Ji[1][1] = (J[0][0] * J[2][2] - J[0][2] * J[2][0]) * r;
      Ji[2][1] = (J[0][1] * J[2][0] - J[0][0] * J[2][1]) * r;
      Ji[0][2] = (J[0][1] * J[1][2] - J[0][2] * J[1][1]) * r;
      Ji[1][2] = (J[0][2] * J[1][0] - J[0][0] * J[1][2]) * r;
      Ji[2][2] = (J[0][0] * J[1][1] - J[0][1] * J[1][0]) * r;
    }
  }
  for (int a = 0; a < nn; ++a)
    for (int i = 0; i < 3; ++i) {
      double s = 0.0;
      if (i < dim)
        for (int j = 0; j < dim; ++j) s += dN[a][j] * Ji[j][i];
      dNdX[a][i] = s;
    }
  return det;
}

// Boundary (facet) cell of a body of spatial dimension `dim`:
//   dim == 2: a line cell (Line2/Line3) in the xy-plane. With t = dX/dxi (tangent from node 0
//             towards node 1), returns |t| (length Jacobian: ds = |t| dxi) and
//             n = (t_y, -t_x, 0)/|t|, the right-hand normal: for a boundary traversed
//             counter-clockwise this is the outward normal.
//   dim == 3: a surface cell (Tri*/Quad*). With a = dX/dxi, b = dX/deta, returns |a x b|
//             (area Jacobian: dA = |a x b| dxi deta) and n = (a x b)/|a x b|, i.e. the normal
//             given by the right-hand rule on the node order (outward when the facet's nodes
//             run counter-clockwise seen from outside).
// A degenerate facet returns 0 and n = 0.
KOKKOS_INLINE_FUNCTION double facet_measure_and_normal(int dim, int nn, const double (*X)[3], const double (*dN)[3],
                                                       double n[3]) {
  n[0] = n[1] = n[2] = 0.0;
  if (dim == 2) {
    double t[2] = {0.0, 0.0};
    for (int a = 0; a < nn; ++a)
      for (int i = 0; i < 2; ++i) t[i] += X[a][i] * dN[a][0];
    const double m = std::sqrt(t[0] * t[0] + t[1] * t[1]);
    if (m > 0.0) {
      n[0] = t[1] / m;
      n[1] = -t[0] / m;
    }
    return m;
  }
  if (dim == 3) {
    double g0[3] = {0.0, 0.0, 0.0}, g1[3] = {0.0, 0.0, 0.0};
    for (int a = 0; a < nn; ++a)
      for (int i = 0; i < 3; ++i) {
        g0[i] += X[a][i] * dN[a][0];
        g1[i] += X[a][i] * dN[a][1];
      }
    const double c[3] = {g0[1] * g1[2] - g0[2] * g1[1], g0[2] * g1[0] - g0[0] * g1[2], g0[0] * g1[1] - g0[1] * g1[0]};
    const double m = std::sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
    if (m > 0.0)
      for (int i = 0; i < 3; ++i) n[i] = c[i] / m;
    return m;
  }
  return 0.0;
}

}  // namespace stentor
