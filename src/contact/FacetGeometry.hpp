// Geometry of one master facet in the current configuration, templated on the scalar
// (double, or Dual for exact derivatives): shape functions of the facet types a 2D or
// 3D boundary has (line2, line3, tri3, tri6, quad4), the point x_m(xi), the covariant
// tangents a_k = dx_m/dxi_k and the unit outward normal
//   2D: n = o (a_1y, -a_1x) / |a_1|,   3D: n = o (a_1 x a_2) / |a_1 x a_2|,
// o = +-1 the facet's orientation (mesh boundaries are not oriented consistently), and
// the closest-point projection of a slave point x_s: xi with a_k(xi) . (x_s - x_m(xi)) = 0,
// found by Newton in double precision. Header-only, callable inside Kokkos kernels.
#pragma once
#include <Kokkos_Macros.hpp>
#include <cmath>

#include "contact/Dual.hpp"
#include "fem/CellType.hpp"

namespace stentor::facet {

constexpr int kMaxNodes = 6;  // tri6

// N_a(xi) and dN_a/dxi_k (k < 2) of a facet type.
template <class T>
KOKKOS_INLINE_FUNCTION void shape(CellType t, const T xi[2], T* N, T (*dN)[2]) {
  const T x = xi[0], y = xi[1];
  switch (t) {
    case CellType::Line2:
      N[0] = 0.5 * (1.0 - x), N[1] = 0.5 * (1.0 + x);
      dN[0][0] = T(-0.5), dN[1][0] = T(0.5);
      dN[0][1] = dN[1][1] = T(0.0);
      return;
    case CellType::Line3:
      N[0] = 0.5 * x * (x - 1.0), N[1] = 0.5 * x * (x + 1.0), N[2] = 1.0 - x * x;
      dN[0][0] = x - 0.5, dN[1][0] = x + 0.5, dN[2][0] = -2.0 * x;
      dN[0][1] = dN[1][1] = dN[2][1] = T(0.0);
      return;
    case CellType::Tri3:
      N[0] = 1.0 - x - y, N[1] = x, N[2] = y;
      dN[0][0] = T(-1.0), dN[0][1] = T(-1.0), dN[1][0] = T(1.0), dN[1][1] = T(0.0), dN[2][0] = T(0.0), dN[2][1] = T(1.0);
      return;
    case CellType::Tri6: {
      const T L[3] = {1.0 - x - y, x, y};
      const double dL[3][2] = {{-1.0, -1.0}, {1.0, 0.0}, {0.0, 1.0}};
      for (int a = 0; a < 3; ++a) {
        N[a] = L[a] * (2.0 * L[a] - 1.0);
        for (int k = 0; k < 2; ++k) dN[a][k] = (4.0 * L[a] - 1.0) * dL[a][k];
      }
      const int e[3][2] = {{0, 1}, {1, 2}, {2, 0}};
      for (int m = 0; m < 3; ++m) {
        const int i = e[m][0], j = e[m][1];
        N[3 + m] = 4.0 * L[i] * L[j];
        for (int k = 0; k < 2; ++k) dN[3 + m][k] = 4.0 * (L[j] * dL[i][k] + L[i] * dL[j][k]);
      }
      return;
    }
    case CellType::Quad4: {
      const double sx[4] = {-1.0, 1.0, 1.0, -1.0}, sy[4] = {-1.0, -1.0, 1.0, 1.0};
      for (int a = 0; a < 4; ++a) {
        const T fx = 1.0 + sx[a] * x, fy = 1.0 + sy[a] * y;
        N[a] = 0.25 * fx * fy;
        dN[a][0] = 0.25 * sx[a] * fy;
        dN[a][1] = 0.25 * sy[a] * fx;
      }
      return;
    }
    default: return;
  }
}

KOKKOS_INLINE_FUNCTION bool supported(CellType t) {
  return t == CellType::Line2 || t == CellType::Line3 || t == CellType::Tri3 || t == CellType::Tri6 || t == CellType::Quad4;
}

// Parametric centre, and the nearest point of the reference facet to xi (in place);
// returns true when xi was inside (within tol).
KOKKOS_INLINE_FUNCTION void centre(CellType t, double xi[2]) {
  const bool tri = t == CellType::Tri3 || t == CellType::Tri6;
  xi[0] = xi[1] = tri ? 1.0 / 3.0 : 0.0;
}
KOKKOS_INLINE_FUNCTION bool clamp(CellType t, double xi[2], double tol) {
  bool inside = true;
  if (t == CellType::Tri3 || t == CellType::Tri6) {
    if (xi[0] < -tol || xi[1] < -tol || xi[0] + xi[1] > 1.0 + tol) inside = false;
    if (xi[0] < 0.0) xi[0] = 0.0;
    if (xi[1] < 0.0) xi[1] = 0.0;
    const double s = xi[0] + xi[1];
    if (s > 1.0) xi[0] /= s, xi[1] /= s;
    return inside;
  }
  const int nk = cell_dim(t);
  for (int k = 0; k < nk; ++k) {
    if (xi[k] < -1.0 - tol || xi[k] > 1.0 + tol) inside = false;
    xi[k] = xi[k] < -1.0 ? -1.0 : (xi[k] > 1.0 ? 1.0 : xi[k]);
  }
  return inside;
}

// The same nearest-point map in any scalar (Dual numbers carry its derivative: clamped
// parameters are constants, the free ones pass through, a triangle's third edge scales
// both by 1 / (xi_0 + xi_1)). Branches use the values only.
template <class T>
KOKKOS_INLINE_FUNCTION void clamp_t(CellType t, T xi[2]) {
  if (t == CellType::Tri3 || t == CellType::Tri6) {
    if (value(xi[0]) < 0.0) xi[0] = T(0.0);
    if (value(xi[1]) < 0.0) xi[1] = T(0.0);
    const T s = xi[0] + xi[1];
    if (value(s) > 1.0) xi[0] = xi[0] / s, xi[1] = xi[1] / s;
    return;
  }
  const int nk = cell_dim(t);
  for (int k = 0; k < nk; ++k) {
    if (value(xi[k]) < -1.0) xi[k] = T(-1.0);
    if (value(xi[k]) > 1.0) xi[k] = T(1.0);
  }
}

// Point, tangents and unit normal at xi. x[a][c]: current node positions.
template <class T>
struct Frame {
  T N[kMaxNodes];
  T xm[3], a[2][3], n[3];
};
template <class T>
KOKKOS_INLINE_FUNCTION void frame(CellType t, int nn, int dim, double orient, const T (*x)[3], const T xi[2], Frame<T>& f) {
  using std::sqrt;
  T dN[kMaxNodes][2];
  shape(t, xi, f.N, dN);
  for (int c = 0; c < 3; ++c) {
    f.xm[c] = T(0.0);
    f.a[0][c] = T(0.0);
    f.a[1][c] = T(0.0);
    for (int b = 0; b < nn; ++b) {
      f.xm[c] += f.N[b] * x[b][c];
      f.a[0][c] += dN[b][0] * x[b][c];
      f.a[1][c] += dN[b][1] * x[b][c];
    }
  }
  if (dim == 2) {
    f.n[0] = orient * f.a[0][1], f.n[1] = -orient * f.a[0][0], f.n[2] = T(0.0);
  } else {
    f.n[0] = orient * (f.a[0][1] * f.a[1][2] - f.a[0][2] * f.a[1][1]);
    f.n[1] = orient * (f.a[0][2] * f.a[1][0] - f.a[0][0] * f.a[1][2]);
    f.n[2] = orient * (f.a[0][0] * f.a[1][1] - f.a[0][1] * f.a[1][0]);
  }
  const T len = sqrt(f.n[0] * f.n[0] + f.n[1] * f.n[1] + f.n[2] * f.n[2]);
  for (int c = 0; c < 3; ++c) f.n[c] = f.n[c] / len;
}

// Closest-point projection of xs on the facet: Gauss-Newton on the tangential equations
// g_k = a_k . (x_s - x_m) = 0 with the matrix a_k . a_l (exact for flat facets; for curved
// ones it converges to the same root). Returns whether the projection lies inside the
// facet; xi is clamped to the facet otherwise. band > 0: a projection past the facet's
// edge by at most `band` (parametric) also counts as inside and keeps its xi (the facet
// extended; Contact's facet hysteresis). xi_free (if given): the parameters before clamping
// (the root of g_k = 0 on the facet's extension), from which a clamped projection's
// derivatives follow (NodeLaw's projection_parameters).
KOKKOS_INLINE_FUNCTION bool project(CellType t, int nn, int dim, const double (*x)[3], const double xs[3], double xi[2],
                                    double band = 0.0, double* xi_free = nullptr) {
  centre(t, xi);
  const int nk = dim - 1;
  for (int it = 0; it < 20; ++it) {
    Frame<double> f;
    frame(t, nn, dim, 1.0, x, xi, f);
    double r[3] = {xs[0] - f.xm[0], xs[1] - f.xm[1], xs[2] - f.xm[2]};
    double g[2] = {0.0, 0.0}, H[2][2] = {{0.0, 0.0}, {0.0, 0.0}};
    for (int k = 0; k < nk; ++k) {
      for (int c = 0; c < 3; ++c) g[k] += f.a[k][c] * r[c];
      for (int l = 0; l < nk; ++l)
        for (int c = 0; c < 3; ++c) H[k][l] += f.a[k][c] * f.a[l][c];
    }
    double dxi[2] = {0.0, 0.0};
    if (nk == 1) {
      dxi[0] = g[0] / H[0][0];
    } else {
      const double det = H[0][0] * H[1][1] - H[0][1] * H[1][0];
      dxi[0] = (H[1][1] * g[0] - H[0][1] * g[1]) / det;
      dxi[1] = (H[0][0] * g[1] - H[1][0] * g[0]) / det;
    }
    xi[0] += dxi[0];
    xi[1] += dxi[1];
    // Far outside: stop early (the facet is not the closest one).
    if (std::abs(xi[0]) > 10.0 || std::abs(xi[1]) > 10.0) break;
    if (std::abs(dxi[0]) + std::abs(dxi[1]) < 1e-14) break;
  }
  if (xi_free) xi_free[0] = xi[0], xi_free[1] = xi[1];
  if (band > 0.0) {
    double c[2] = {xi[0], xi[1]};
    if (clamp(t, c, band)) return true;
  }
  return clamp(t, xi, 1e-10);
}

}  // namespace stentor::facet
