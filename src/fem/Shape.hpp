// Lagrange / serendipity shape functions on gmsh reference cells.
//
// Node ordering and reference coordinates are exactly gmsh's (checked against
// gmsh::model::mesh::getElementProperties, gmsh 4.8):
//   line2/line3 : xi in [-1,1]; nodes -1, +1, (0)
//   tri3/tri6   : vertices (0,0),(1,0),(0,1); mid-edges (0,1),(1,2),(2,0)
//   quad4/quad8 : [-1,1]^2; vertices (-1,-1),(1,-1),(1,1),(-1,1);
//                 mid-edges (0,1),(1,2),(2,3),(3,0)
//   tet4/tet10  : vertices 0, e_x, e_y, e_z; mid-edges (0,1),(1,2),(2,0),(3,0),(3,2),(3,1)
//   hex8        : [-1,1]^3; bottom (z=-1) like quad4, then top (z=+1) like quad4
// Header-only, callable inside Kokkos kernels: no heap, no exceptions.
#pragma once
#include <Kokkos_Macros.hpp>

#include "fem/CellType.hpp"

namespace stentor {

namespace shape_detail {

// Simplex of dimension `dim` (2 or 3), order 1 or 2. Barycentrics L0 = 1 - sum xi, Lk = xi_{k-1}.
KOKKOS_INLINE_FUNCTION void simplex(int dim, int order, const double xi[3], double* N, double (*dN)[3]) {
  double L[4];
  double dL[4][3] = {{-1.0, -1.0, -1.0}, {1.0, 0.0, 0.0}, {0.0, 1.0, 0.0}, {0.0, 0.0, 1.0}};
  L[0] = 1.0;
  for (int d = 0; d < dim; ++d) {
    L[d + 1] = xi[d];
    L[0] -= xi[d];
  }
  for (int a = 0; a <= dim; ++a)
    for (int d = dim; d < 3; ++d) dL[a][d] = 0.0;
  const int nv = dim + 1;
  if (order == 1) {
    for (int a = 0; a < nv; ++a) {
      if (N) N[a] = L[a];
      if (dN)
        for (int d = 0; d < 3; ++d) dN[a][d] = dL[a][d];
    }
    return;
  }
  for (int a = 0; a < nv; ++a) {
    if (N) N[a] = L[a] * (2.0 * L[a] - 1.0);
    if (dN)
      for (int d = 0; d < 3; ++d) dN[a][d] = (4.0 * L[a] - 1.0) * dL[a][d];
  }
  // gmsh edge order: tri (0,1),(1,2),(2,0); tet additionally (3,0),(3,2),(3,1).
  const int edges[6][2] = {{0, 1}, {1, 2}, {2, 0}, {3, 0}, {3, 2}, {3, 1}};
  const int ne = dim == 2 ? 3 : 6;
  for (int e = 0; e < ne; ++e) {
    const int i = edges[e][0], j = edges[e][1], a = nv + e;
    if (N) N[a] = 4.0 * L[i] * L[j];
    if (dN)
      for (int d = 0; d < 3; ++d) dN[a][d] = 4.0 * (L[j] * dL[i][d] + L[i] * dL[j][d]);
  }
}

}  // namespace shape_detail

// Reference coordinates of the nodes of `t` (unused components set to 0).
KOKKOS_INLINE_FUNCTION void reference_nodes(CellType t, double (*xi)[3]) {
  const int n = cell_num_nodes(t);
  for (int a = 0; a < n; ++a) xi[a][0] = xi[a][1] = xi[a][2] = 0.0;
  switch (t) {
    case CellType::Point1: break;
    case CellType::Line3:
      xi[2][0] = 0.0;
      [[fallthrough]];
    case CellType::Line2:
      xi[0][0] = -1.0;
      xi[1][0] = 1.0;
      break;
    case CellType::Tri6:
      xi[3][0] = 0.5;
      xi[4][0] = 0.5;
      xi[4][1] = 0.5;
      xi[5][1] = 0.5;
      [[fallthrough]];
    case CellType::Tri3:
      xi[1][0] = 1.0;
      xi[2][1] = 1.0;
      break;
    case CellType::Quad8:
      xi[4][0] = 0.0, xi[4][1] = -1.0;
      xi[5][0] = 1.0, xi[5][1] = 0.0;
      xi[6][0] = 0.0, xi[6][1] = 1.0;
      xi[7][0] = -1.0, xi[7][1] = 0.0;
      [[fallthrough]];
    case CellType::Quad4:
      xi[0][0] = -1.0, xi[0][1] = -1.0;
      xi[1][0] = 1.0, xi[1][1] = -1.0;
      xi[2][0] = 1.0, xi[2][1] = 1.0;
      xi[3][0] = -1.0, xi[3][1] = 1.0;
      break;
    case CellType::Tet10:
      xi[4][0] = 0.5;                  // (0,1)
      xi[5][0] = 0.5, xi[5][1] = 0.5;  // (1,2)
      xi[6][1] = 0.5;                  // (2,0)
      xi[7][2] = 0.5;                  // (3,0)
      xi[8][1] = 0.5, xi[8][2] = 0.5;  // (3,2)
      xi[9][0] = 0.5, xi[9][2] = 0.5;  // (3,1)
      [[fallthrough]];
    case CellType::Tet4:
      xi[1][0] = 1.0;
      xi[2][1] = 1.0;
      xi[3][2] = 1.0;
      break;
    case CellType::Hex8:
      for (int a = 0; a < 8; ++a) {
        const int q = a % 4;
        xi[a][0] = (q == 1 || q == 2) ? 1.0 : -1.0;
        xi[a][1] = (q >= 2) ? 1.0 : -1.0;
        xi[a][2] = a >= 4 ? 1.0 : -1.0;
      }
      break;
    default: break;
  }
}

// N[a] = N_a(xi), dN[a][d] = dN_a/dxi_d (d = 0..2; components beyond cell_dim are 0).
// Either N or dN may be nullptr. Unknown types write nothing.
KOKKOS_INLINE_FUNCTION void shape_functions(CellType t, const double xi[3], double* N, double (*dN)[3]) {
  switch (t) {
    case CellType::Point1:
      if (N) N[0] = 1.0;
      if (dN) dN[0][0] = dN[0][1] = dN[0][2] = 0.0;
      return;
    case CellType::Line2: {
      const double x = xi[0];
      if (N) {
        N[0] = 0.5 * (1.0 - x);
        N[1] = 0.5 * (1.0 + x);
      }
      if (dN) {
        dN[0][0] = -0.5;
        dN[1][0] = 0.5;
        for (int a = 0; a < 2; ++a) dN[a][1] = dN[a][2] = 0.0;
      }
      return;
    }
    case CellType::Line3: {
      const double x = xi[0];
      if (N) {
        N[0] = 0.5 * x * (x - 1.0);
        N[1] = 0.5 * x * (x + 1.0);
        N[2] = 1.0 - x * x;
      }
      if (dN) {
        dN[0][0] = x - 0.5;
        dN[1][0] = x + 0.5;
        dN[2][0] = -2.0 * x;
        for (int a = 0; a < 3; ++a) dN[a][1] = dN[a][2] = 0.0;
      }
      return;
    }
    case CellType::Tri3: shape_detail::simplex(2, 1, xi, N, dN); return;
    case CellType::Tri6: shape_detail::simplex(2, 2, xi, N, dN); return;
    case CellType::Tet4: shape_detail::simplex(3, 1, xi, N, dN); return;
    case CellType::Tet10: shape_detail::simplex(3, 2, xi, N, dN); return;
    case CellType::Quad4: {
      const double sx[4] = {-1.0, 1.0, 1.0, -1.0}, sy[4] = {-1.0, -1.0, 1.0, 1.0};
      for (int a = 0; a < 4; ++a) {
        const double fx = 1.0 + sx[a] * xi[0], fy = 1.0 + sy[a] * xi[1];
        if (N) N[a] = 0.25 * fx * fy;
        if (dN) {
          dN[a][0] = 0.25 * sx[a] * fy;
          dN[a][1] = 0.25 * fx * sy[a];
          dN[a][2] = 0.0;
        }
      }
      return;
    }
    case CellType::Quad8: {
      const double x = xi[0], y = xi[1];
      const double sx[4] = {-1.0, 1.0, 1.0, -1.0}, sy[4] = {-1.0, -1.0, 1.0, 1.0};
      for (int a = 0; a < 4; ++a) {  // corners: (1+x sx)(1+y sy)(x sx + y sy - 1)/4
        const double fx = 1.0 + sx[a] * x, fy = 1.0 + sy[a] * y, g = sx[a] * x + sy[a] * y - 1.0;
        if (N) N[a] = 0.25 * fx * fy * g;
        if (dN) {
          dN[a][0] = 0.25 * sx[a] * fy * (g + fx);
          dN[a][1] = 0.25 * sy[a] * fx * (g + fy);
          dN[a][2] = 0.0;
        }
      }
      // mid-edges 4: y=-1, 6: y=+1 (bubble in x); 5: x=+1, 7: x=-1 (bubble in y)
      const double my[2] = {-1.0, 1.0};
      for (int k = 0; k < 2; ++k) {
        const int a = 4 + 2 * k;
        const double fy = 1.0 + my[k] * y;
        if (N) N[a] = 0.5 * (1.0 - x * x) * fy;
        if (dN) {
          dN[a][0] = -x * fy;
          dN[a][1] = 0.5 * (1.0 - x * x) * my[k];
          dN[a][2] = 0.0;
        }
      }
      const double mx[2] = {1.0, -1.0};
      for (int k = 0; k < 2; ++k) {
        const int a = 5 + 2 * k;
        const double fx = 1.0 + mx[k] * x;
        if (N) N[a] = 0.5 * fx * (1.0 - y * y);
        if (dN) {
          dN[a][0] = 0.5 * mx[k] * (1.0 - y * y);
          dN[a][1] = -fx * y;
          dN[a][2] = 0.0;
        }
      }
      return;
    }
    case CellType::Hex8: {
      const double sx[4] = {-1.0, 1.0, 1.0, -1.0}, sy[4] = {-1.0, -1.0, 1.0, 1.0};
      for (int a = 0; a < 8; ++a) {
        const double ax = sx[a % 4], ay = sy[a % 4], az = a < 4 ? -1.0 : 1.0;
        const double fx = 1.0 + ax * xi[0], fy = 1.0 + ay * xi[1], fz = 1.0 + az * xi[2];
        if (N) N[a] = 0.125 * fx * fy * fz;
        if (dN) {
          dN[a][0] = 0.125 * ax * fy * fz;
          dN[a][1] = 0.125 * fx * ay * fz;
          dN[a][2] = 0.125 * fx * fy * az;
        }
      }
      return;
    }
    default: return;
  }
}

}  // namespace stentor
