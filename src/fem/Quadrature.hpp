// Quadrature rules on the gmsh reference cells (see fem/Shape.hpp), all with positive weights.
//   line/quad/hex : tensor Gauss-Legendre, n = ceil((degree+1)/2) points per direction (n <= 3),
//                   x index fastest, then y, then z
//   tri           : degree <=1: centroid (1 pt); 2: 3 pts (Strang-Fix); 3-4: 6 pts (Dunavant);
//                   5: 7 pts (Radon)
//   tet           : degree <=1: centroid (1 pt); 2: 4 pts; 3-5: 14 pts (Walkington / Keast-type)
//   point         : 1 pt, weight 1
// Weights sum to the reference measure (2, 4, 8 for [-1,1]^d; 1/2, 1/6 for simplices).
// quadrature() returns the number of points, or 0 if no rule of that degree is available
// (degree > 5) or the cell type is invalid. Header-only, callable inside Kokkos kernels.
#pragma once
#include <Kokkos_Macros.hpp>

#include "fem/CellType.hpp"

namespace stentor {

constexpr int kMaxQuadPoints = 27;
constexpr int kMaxQuadDegree = 5;

namespace quad_detail {

// 1D Gauss-Legendre on [-1,1] with n = 1..3 points.
KOKKOS_INLINE_FUNCTION void gauss1d(int n, double* x, double* w) {
  if (n == 1) {
    x[0] = 0.0;
    w[0] = 2.0;
  } else if (n == 2) {
    const double a = 0.577350269189625764509148780502;  // 1/sqrt(3)
    x[0] = -a, x[1] = a;
    w[0] = w[1] = 1.0;
  } else {
    const double a = 0.774596669241483377035853079956;  // sqrt(3/5)
    x[0] = -a, x[1] = 0.0, x[2] = a;
    w[0] = w[2] = 5.0 / 9.0;
    w[1] = 8.0 / 9.0;
  }
}

KOKKOS_INLINE_FUNCTION int tensor(int dim, int degree, double (*xi)[3], double* w) {
  const int n = (degree + 2) / 2;
  double x[3], wx[3];
  gauss1d(n, x, wx);
  const int ny = dim >= 2 ? n : 1, nz = dim >= 3 ? n : 1;
  int q = 0;
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < n; ++i, ++q) {
        xi[q][0] = x[i];
        xi[q][1] = dim >= 2 ? x[j] : 0.0;
        xi[q][2] = dim >= 3 ? x[k] : 0.0;
        w[q] = wx[i] * (dim >= 2 ? wx[j] : 1.0) * (dim >= 3 ? wx[k] : 1.0);
      }
  return q;
}

// Triangle orbit (a,a),(1-2a,a),(a,1-2a) with weight w, appended at q.
KOKKOS_INLINE_FUNCTION int tri_orbit3(int q, double a, double wt, double (*xi)[3], double* w) {
  const double b = 1.0 - 2.0 * a;
  const double p[3][2] = {{a, a}, {b, a}, {a, b}};
  for (int k = 0; k < 3; ++k, ++q) {
    xi[q][0] = p[k][0];
    xi[q][1] = p[k][1];
    xi[q][2] = 0.0;
    w[q] = wt;
  }
  return q;
}

// Tet orbit (a,a,a) and permutations of (1-3a,a,a), weight w.
KOKKOS_INLINE_FUNCTION int tet_orbit4(int q, double a, double wt, double (*xi)[3], double* w) {
  const double b = 1.0 - 3.0 * a;
  const double p[4][3] = {{a, a, a}, {b, a, a}, {a, b, a}, {a, a, b}};
  for (int k = 0; k < 4; ++k, ++q) {
    for (int d = 0; d < 3; ++d) xi[q][d] = p[k][d];
    w[q] = wt;
  }
  return q;
}

// Tet orbit: permutations of (a,a,1/2-a,1/2-a) in barycentrics (6 points), weight w.
KOKKOS_INLINE_FUNCTION int tet_orbit6(int q, double a, double wt, double (*xi)[3], double* w) {
  const double b = 0.5 - a;
  const double p[6][3] = {{a, a, b}, {a, b, a}, {b, a, a}, {b, b, a}, {b, a, b}, {a, b, b}};
  for (int k = 0; k < 6; ++k, ++q) {
    for (int d = 0; d < 3; ++d) xi[q][d] = p[k][d];
    w[q] = wt;
  }
  return q;
}

}  // namespace quad_detail

// Points xi[q][0..2] (unused components 0) and weights w[q]; arrays must hold kMaxQuadPoints.
KOKKOS_INLINE_FUNCTION int quadrature(CellType t, int degree, double (*xi)[3], double* w) {
  if (degree < 0) degree = 0;
  if (degree > kMaxQuadDegree) return 0;
  switch (t) {
    case CellType::Point1:
      xi[0][0] = xi[0][1] = xi[0][2] = 0.0;
      w[0] = 1.0;
      return 1;
    case CellType::Line2:
    case CellType::Line3: return quad_detail::tensor(1, degree, xi, w);
    case CellType::Quad4:
    case CellType::Quad8: return quad_detail::tensor(2, degree, xi, w);
    case CellType::Hex8: return quad_detail::tensor(3, degree, xi, w);
    case CellType::Tri3:
    case CellType::Tri6: {
      if (degree <= 1) {
        xi[0][0] = xi[0][1] = 1.0 / 3.0;
        xi[0][2] = 0.0;
        w[0] = 0.5;
        return 1;
      }
      if (degree == 2) return quad_detail::tri_orbit3(0, 1.0 / 6.0, 1.0 / 6.0, xi, w);
      if (degree <= 4) {  // Dunavant degree 4, 6 points
        int q = quad_detail::tri_orbit3(0, 0.445948490915964886318329, 0.5 * 0.223381589678011465944827, xi, w);
        return quad_detail::tri_orbit3(q, 0.091576213509770743459571, 0.5 * 0.109951743655321867388506, xi, w);
      }
      // Radon degree 5, 7 points: centroid 9/80; a = (6 -+ sqrt15)/21, w = (155 -+ sqrt15)/2400
      xi[0][0] = xi[0][1] = 1.0 / 3.0;
      xi[0][2] = 0.0;
      w[0] = 9.0 / 80.0;
      int q = quad_detail::tri_orbit3(1, 0.101286507323456338800987361915, 0.06296959027241357629784197275, xi, w);
      return quad_detail::tri_orbit3(q, 0.470142064105115089770441209513, 0.0661970763942530903688246939167, xi, w);
    }
    case CellType::Tet4:
    case CellType::Tet10: {
      if (degree <= 1) {
        xi[0][0] = xi[0][1] = xi[0][2] = 0.25;
        w[0] = 1.0 / 6.0;
        return 1;
      }
      if (degree == 2)  // a = (5 - sqrt5)/20
        return quad_detail::tet_orbit4(0, 0.138196601125010515179541316564, 1.0 / 24.0, xi, w);
      // degree 5, 14 points (Walkington), positive weights
      int q = quad_detail::tet_orbit4(0, 0.092735250310891082, 0.012248840519393621, xi, w);
      q = quad_detail::tet_orbit4(q, 0.31088591926330073, 0.018781320953002573, xi, w);
      return quad_detail::tet_orbit6(q, 0.045503704125650281, 0.0070910034628469806, xi, w);
    }
    default: return 0;
  }
}

// Default degree for a volume cell: 2 for order-1 cells (hex8 -> 2x2x2 Gauss, tet4 -> 4 pts),
// 4 for order-2 cells (tet10 -> 14 pts, tri6 -> 6 pts).
KOKKOS_INLINE_FUNCTION int default_quadrature_degree(CellType volume_cell) {
  return cell_order(volume_cell) == 2 ? 4 : 2;
}

// Degree for the internal force, stiffness and stored energy. On linear simplices (tri3,
// tet4) the deformation gradient is constant per cell, so the integrand (stress times
// constant shape gradients, W(C), the Gonzalez and viscous stresses) is constant and one
// point is exact: 4x less work on tet4 than the default rule, same result to round-off.
// Mass and body forces (products of shape functions) keep default_quadrature_degree.
KOKKOS_INLINE_FUNCTION int stiffness_quadrature_degree(CellType volume_cell) {
  return (volume_cell == CellType::Tri3 || volume_cell == CellType::Tet4) ? 1 : default_quadrature_degree(volume_cell);
}

}  // namespace stentor
