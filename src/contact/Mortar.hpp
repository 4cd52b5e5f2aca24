// Dual mortar coupling of a slave and a master surface: the integrals
//   M_jk = int_{slave} Phi_j N_k^m dA
// of one slave facet against one master facet, templated on the scalar so that Dual
// numbers carry their exact derivatives with respect to the two facets' node positions
// (docs/contact.md, "Mortar").
//
// Phi_j are the dual shape functions of the slave facet, biorthogonal to its own shape
// functions: int Phi_j N_l dA = delta_jl int N_l dA. With them the weighted gap of slave
// node j, int Phi_j (x^s - x^m) . n_j dA, is S_j n_j . (x_j - sum_k w_jk x_k) with
// w_jk = M_jk / S_j and S_j = sum_k M_jk: a slave node's conditions stay local (the
// condensed multiplier is its bulk residual, as in node-to-segment) and only the master
// side changes: the reaction goes to the master nodes by w_jk instead of by the shape
// functions at one projection point. A uniform pressure then gives the consistent master
// forces sum_j w_jk p A_j = p int N_k^m dA (the patch test), since sum_j Phi_j = 1.
//
// Integration follows the segment-based scheme of Puso & Laursen (2004) and Popp et al.
// (2010): 2D, the master facet's end points projected on the slave segment bound the
// overlap (Gauss points on it); 3D, both facets projected on the auxiliary plane of the
// slave facet (its centre and unit normal), the master polygon clipped by the slave
// polygon (Sutherland-Hodgman), the clip polygon split into triangles around its centroid
// (Gauss points on each). A point of the plane maps back to a facet's parameters by
// inverting the facet's projected (planar) map, which is exact for the projection along
// the plane's normal. Facets: line2, line3, tri3, quad4 (the dual functions of quad4 and
// line3 are computed from the facet's geometry, A = D M^-1; tri6 would need a modified
// basis, its corner integrals int N_a vanish). A curved (line3) pair: the master's end
// nodes projected on the slave bound the overlap, and a Gauss point maps to the master
// along the slave's normal.
//
// Axisymmetric (2D, `axi`): the section's lines are revolved about the y axis, dA = 2 pi r ds
// with r = x of the slave point in the current configuration (where the integrals are
// taken), so M carries the derivative of the weight as well. The dual basis is then built
// from the weighted mass matrix, A = D M^-1 with M_ac = int N_a N_c 2 pi r ds and
// D_a = int N_a 2 pi r ds, so that it stays biorthogonal in the revolved measure (the
// constant line2 coefficients are those of ds only). A slave facet on the axis (r = 0 at
// both ends) has no area and couples to nothing.
//
// Branches (which side of an edge a vertex lies on, min/max of the overlap bounds) use
// the values only: M is piecewise smooth in the positions, and its derivatives are exact
// on each piece. Header-only, callable inside Kokkos kernels (no heap, no exceptions).
#pragma once
#include <Kokkos_Macros.hpp>
#include <cmath>
#include <type_traits>

#include "contact/Dual.hpp"
#include "contact/FacetGeometry.hpp"
#include "fem/Quadrature.hpp"

namespace stentor::mortar {

constexpr int kMaxFacetNodes = 4;                  // line2, tri3, quad4
constexpr int kPairVars = 3 * 2 * kMaxFacetNodes;  // positions of one slave and one master facet
using PD = Dual<kPairVars>;
constexpr int kMaxPoly = 16;                       // clip polygon vertices (at most 4 + 4)
constexpr double kTwoPi = 2.0 * 3.14159265358979323846;  // the ring weight of axisymmetric facets

KOKKOS_INLINE_FUNCTION bool supported(CellType t) {
  return t == CellType::Line2 || t == CellType::Line3 || t == CellType::Tri3 || t == CellType::Quad4;
}

// Generic direction that breaks ties of the segmentation: a master vertex exactly on a slave
// facet's edge (matching meshes) counts as inside or outside as it would after an
// infinitesimal shift of the master along it. Each slave facet on either side of the edge
// then decides alike, the integrals keep one consistent one-sided derivative (of a real
// neighbouring configuration), and the zero-area slivers on the other side keep theirs.
// Without it, matching quad4 meshes gave a singular first tangent (measured: the patch
// test's KLU2 factorization failed, then 7 Newton iterations at a linear rate).
constexpr double kTieDir[3] = {0.40824829046386302, 0.57735026918962573, 0.70710678118654752};  // (1, sqrt2, sqrt3)/sqrt6

struct Face {
  CellType type = CellType::Invalid;
  int nn = 0;
  double orient = 1.0;
};

template <class T>
KOKKOS_INLINE_FUNCTION T cross2(const T* a, const T* b) { return a[0] * b[1] - a[1] * b[0]; }

// Parameters xi of the point p under the planar map p(xi) = sum_a N_a(xi) P_a: Newton in
// double to the root, then one step in T (exact first derivatives, F = 0 in value).
template <class T>
KOKKOS_INLINE_FUNCTION void planar_inverse(CellType t, int nn, const T (*P)[2], const T p[2], T xi[2]) {
  double x[2];
  facet::centre(t, x);
  double J[2][2] = {{1, 0}, {0, 1}};
  auto jac = [&](const double* at, double* F) {
    double N[facet::kMaxNodes], dN[facet::kMaxNodes][2];
    facet::shape(t, at, N, dN);
    F[0] = -value(p[0]), F[1] = -value(p[1]);
    J[0][0] = J[0][1] = J[1][0] = J[1][1] = 0.0;
    for (int a = 0; a < nn; ++a)
      for (int k = 0; k < 2; ++k) {
        F[k] += N[a] * value(P[a][k]);
        for (int l = 0; l < 2; ++l) J[k][l] += dN[a][l] * value(P[a][k]);
      }
  };
  for (int it = 0; it < 30; ++it) {
    double F[2];
    jac(x, F);
    const double det = J[0][0] * J[1][1] - J[0][1] * J[1][0];
    const double d0 = (J[1][1] * F[0] - J[0][1] * F[1]) / det, d1 = (J[0][0] * F[1] - J[1][0] * F[0]) / det;
    x[0] -= d0, x[1] -= d1;
    if (std::abs(d0) + std::abs(d1) < 1e-15) break;
  }
  double F0[2];
  jac(x, F0);
  double N[facet::kMaxNodes], dN[facet::kMaxNodes][2];
  facet::shape(t, x, N, dN);
  T F[2] = {-p[0], -p[1]};
  for (int a = 0; a < nn; ++a)
    for (int k = 0; k < 2; ++k) F[k] += N[a] * P[a][k];
  const double det = J[0][0] * J[1][1] - J[0][1] * J[1][0];
  xi[0] = x[0] - (J[1][1] * F[0] - J[0][1] * F[1]) / det;
  xi[1] = x[1] - (J[0][0] * F[1] - J[1][0] * F[0]) / det;
}

// A = D M^-1 from a facet's mass matrix M_ac = int N_a N_c dA and D_a = int N_a dA:
// Gauss-Jordan on [M | I] (M is symmetric positive definite: no pivoting).
template <class T>
KOKKOS_INLINE_FUNCTION void dual_from_mass(int nn, const T M[kMaxFacetNodes][kMaxFacetNodes], const T* D,
                                           T A[kMaxFacetNodes][kMaxFacetNodes]) {
  T W[kMaxFacetNodes][2 * kMaxFacetNodes];
  for (int a = 0; a < nn; ++a)
    for (int c = 0; c < nn; ++c) W[a][c] = M[a][c], W[a][nn + c] = T(a == c ? 1.0 : 0.0);
  for (int k = 0; k < nn; ++k) {
    const T piv = W[k][k];
    for (int c = 0; c < 2 * nn; ++c) W[k][c] = W[k][c] / piv;
    for (int r = 0; r < nn; ++r) {
      if (r == k) continue;
      const T f = W[r][k];
      for (int c = 0; c < 2 * nn; ++c) W[r][c] = W[r][c] - f * W[k][c];
    }
  }
  for (int a = 0; a < nn; ++a)
    for (int c = 0; c < nn; ++c) A[a][c] = D[a] * W[a][nn + c];
}

// Dual coefficients A (Phi_a = sum_c A[a][c] N_c) of a slave facet whose projected corners
// are P (3D; 2D line2 has constant ones).
template <class T>
KOKKOS_INLINE_FUNCTION void dual_coefficients(CellType t, int nn, const T (*P)[2], T A[kMaxFacetNodes][kMaxFacetNodes]) {
  if (t != CellType::Quad4) {
    // line2: Phi_a = (1 -+ 3 xi)/2 = 3 N_a - 1 = 2 N_a - N_b; tri3: Phi_a = 4 N_a - 1 = 3 N_a - sum_{b != a} N_b.
    const double diag = t == CellType::Line2 ? 2.0 : 3.0;
    for (int a = 0; a < nn; ++a)
      for (int c = 0; c < nn; ++c) A[a][c] = T(a == c ? diag : -1.0);
    return;
  }
  // Quad4: M_ac = int N_a N_c dA, D_a = int N_a dA over the projected facet (3 x 3 Gauss).
  double qp[kMaxQuadPoints][3], qw[kMaxQuadPoints];
  const int nq = quadrature(CellType::Quad4, 5, qp, qw);
  T M[kMaxFacetNodes][kMaxFacetNodes], D[kMaxFacetNodes];
  for (int a = 0; a < 4; ++a) {
    D[a] = T(0.0);
    for (int c = 0; c < 4; ++c) M[a][c] = T(0.0);
  }
  for (int q = 0; q < nq; ++q) {
    double N[facet::kMaxNodes], dN[facet::kMaxNodes][2];
    facet::shape(CellType::Quad4, qp[q], N, dN);
    T g[2][2] = {{T(0.0), T(0.0)}, {T(0.0), T(0.0)}};
    for (int a = 0; a < 4; ++a)
      for (int k = 0; k < 2; ++k)
        for (int l = 0; l < 2; ++l) g[k][l] += dN[a][l] * P[a][k];
    T det = g[0][0] * g[1][1] - g[0][1] * g[1][0];
    if (value(det) < 0.0) det = -det;
    for (int a = 0; a < 4; ++a) {
      D[a] += qw[q] * det * N[a];
      for (int c = 0; c < 4; ++c) M[a][c] += qw[q] * det * N[a] * N[c];
    }
  }
  dual_from_mass(4, M, D, A);
}

template <class T>
KOKKOS_INLINE_FUNCTION void dual_values(int nn, const T A[kMaxFacetNodes][kMaxFacetNodes], const T* N, T* Phi) {
  for (int a = 0; a < nn; ++a) {
    Phi[a] = T(0.0);
    for (int c = 0; c < nn; ++c) Phi[a] += A[a][c] * N[c];
  }
}

// 2D: the overlap [lo, hi] of the slave parameter range [-1, 1] with the master's end
// points projected at xi[0], xi[1]; false when they do not overlap. Ties (a master node
// over a slave node: matching meshes) are decided as for the master shifted by an
// infinitesimal generic offset (kTieDir) along the slave's chord (tx, ty); a zero-length
// overlap that this shift would open is kept (it carries the derivative of its growth).
template <class T>
KOKKOS_INLINE_FUNCTION bool overlap_bounds(const T xi[2], double tx, double ty, T& lo, T& hi) {
  const T lo_xi = value(xi[0]) < value(xi[1]) ? xi[0] : xi[1];
  const T hi_xi = value(xi[0]) < value(xi[1]) ? xi[1] : xi[0];
  const double sd = kTieDir[0] * tx + kTieDir[1] * ty > 0.0 ? 1.0 : -1.0;
  const double tol = 1e-12;
  const bool lo_is_xi = std::abs(value(lo_xi) + 1.0) <= tol ? sd > 0.0 : value(lo_xi) > -1.0;
  const bool hi_is_xi = std::abs(value(hi_xi) - 1.0) <= tol ? sd < 0.0 : value(hi_xi) < 1.0;
  lo = lo_is_xi ? lo_xi : T(-1.0);
  hi = hi_is_xi ? hi_xi : T(1.0);
  const double len = value(hi) - value(lo);
  if (len < -tol) return false;
  return len > tol || sd * (double(hi_is_xi) - double(lo_is_xi)) > 0.0;
}

// A 2D facet (line2, line3) at xi: the point p and the tangent a = dp/dxi.
template <class T, class S>
KOKKOS_INLINE_FUNCTION void curve(CellType t, int nn, const T (*x)[3], const S& xi, T p[2], T a[2]) {
  S N[facet::kMaxNodes], dN[facet::kMaxNodes][2];
  const S z[2] = {xi, S(0.0)};
  facet::shape(t, z, N, dN);
  p[0] = p[1] = a[0] = a[1] = T(0.0);
  for (int b = 0; b < nn; ++b)
    for (int c = 0; c < 2; ++c) {
      p[c] += N[b] * x[b][c];
      a[c] += dN[b][0] * x[b][c];
    }
}

// Dual coefficients of a 2D slave facet (line2, line3) from its geometry: A = D M^-1 with
// M_ac = int N_a N_c dA and D_a = int N_a dA, dA = |a| dxi, times 2 pi r (r = x of the
// point) when axi (D > 0 for line3, unlike tri6's corners). False when the facet has no
// area (axi: a facet on the axis). 3 Gauss points: exact for a line2 (N_a N_c r is cubic)
// and a straight line3 with its mid-node in the middle.
template <class T>
KOKKOS_INLINE_FUNCTION bool dual_coefficients_2d(CellType t, int nn, const T (*x)[3], bool axi, T A[kMaxFacetNodes][kMaxFacetNodes]) {
  using std::sqrt;
  double qp[kMaxQuadPoints][3], qw[kMaxQuadPoints];
  const int nq = quadrature(CellType::Line2, 5, qp, qw);
  T M[kMaxFacetNodes][kMaxFacetNodes], D[kMaxFacetNodes];
  for (int a = 0; a < nn; ++a) {
    D[a] = T(0.0);
    for (int c = 0; c < nn; ++c) M[a][c] = T(0.0);
  }
  double total = 0.0;
  for (int q = 0; q < nq; ++q) {
    T p[2], tg[2];
    curve(t, nn, x, qp[q][0], p, tg);
    T J = sqrt(tg[0] * tg[0] + tg[1] * tg[1]);
    if (axi) J = J * (kTwoPi * p[0]);
    total += qw[q] * value(J);
    double N[facet::kMaxNodes], dN[facet::kMaxNodes][2];
    const double z[2] = {qp[q][0], 0.0};
    facet::shape(t, z, N, dN);
    for (int a = 0; a < nn; ++a) {
      D[a] += qw[q] * J * N[a];
      for (int c = 0; c < nn; ++c) M[a][c] += qw[q] * J * N[a] * N[c];
    }
  }
  if (!(total > 0.0)) return false;
  dual_from_mass(nn, M, D, A);
  return true;
}

// 2D: line2 slave segment xs against line2 master segment xm; M[a][b] += int Phi_a N_b.
// Returns whether they overlap (and face each other).
// Axisymmetric (axi): the weight 2 pi r of the slave point and the dual basis of the
// weighted measure (dual_coefficients_2d).
template <class T>
KOKKOS_INLINE_FUNCTION bool pair_integrals_2d(const Face& s, const T (*xs)[3], const Face& m, const T (*xm)[3], T M[kMaxFacetNodes][kMaxFacetNodes],
                                              bool axi = false) {
  using std::sqrt;
  const T t[2] = {xs[1][0] - xs[0][0], xs[1][1] - xs[0][1]};
  const T L = sqrt(t[0] * t[0] + t[1] * t[1]);
  const T tm[2] = {xm[1][0] - xm[0][0], xm[1][1] - xm[0][1]};
  // Outward normals (FacetGeometry's convention: o (a_y, -a_x)); facing: ns . nm < 0.
  const double facing = s.orient * m.orient * value(t[1] * tm[1] + t[0] * tm[0]);
  if (facing >= 0.0) return false;
  T xi[2];
  for (int b = 0; b < 2; ++b) xi[b] = 2.0 * ((xm[b][0] - xs[0][0]) * t[0] + (xm[b][1] - xs[0][1]) * t[1]) / (L * L) - 1.0;
  T lo, hi;
  if (!overlap_bounds(xi, value(t[0]), value(t[1]), lo, hi)) return false;
  T A[kMaxFacetNodes][kMaxFacetNodes];
  if (axi && !dual_coefficients_2d(CellType::Line2, 2, xs, true, A)) return false;
  double qp[kMaxQuadPoints][3], qw[kMaxQuadPoints];
  const int nq = quadrature(CellType::Line2, 5, qp, qw);
  const T half = 0.5 * (hi - lo), mid = 0.5 * (hi + lo);
  for (int q = 0; q < nq; ++q) {
    const T x = mid + half * qp[q][0];
    const T eta = (2.0 * x - xi[0] - xi[1]) / (xi[1] - xi[0]);
    const T Nm[2] = {0.5 * (1.0 - eta), 0.5 * (1.0 + eta)};
    if (axi) {
      // Ring weight 2 pi r(x), r linear along the slave segment; Phi from the weighted basis.
      const T Ns[2] = {0.5 * (1.0 - x), 0.5 * (1.0 + x)};
      const T w = qw[q] * half * 0.5 * L * kTwoPi * (Ns[0] * xs[0][0] + Ns[1] * xs[1][0]);
      T Phi[kMaxFacetNodes];
      dual_values(2, A, Ns, Phi);
      for (int a = 0; a < 2; ++a)
        for (int b = 0; b < 2; ++b) M[a][b] += w * Phi[a] * Nm[b];
      continue;
    }
    const T w = qw[q] * half * 0.5 * L;
    const T Phi[2] = {0.5 * (1.0 - 3.0 * x), 0.5 * (1.0 + 3.0 * x)};
    for (int a = 0; a < 2; ++a)
      for (int b = 0; b < 2; ++b) M[a][b] += w * Phi[a] * Nm[b];
  }
  return true;
}

// The root xi of g(xi) = 0 near xi0 (g(T or double, xi) and its derivative in xi, gd):
// Newton in double, then one step in T, which gives the exact first derivatives.
template <class T, class G, class GD>
KOKKOS_INLINE_FUNCTION T root_1d(double xi0, const G& g, const GD& gd) {
  double x = xi0;
  for (int it = 0; it < 30; ++it) {
    const double dx = value(g(x)) / gd(x);
    x -= dx;
    if (std::abs(dx) < 1e-15 || std::abs(x) > 10.0) break;
  }
  return T(x) - g(x) / gd(x);
}

// 2D with a curved (line3) facet on either side: the master's end nodes projected on the
// slave (closest point) bound the overlap; a Gauss point x^s(xi) maps to the master point
// on the slave's normal there, x^m(eta) - x^s(xi) parallel to n^s(xi) (so the overlap's ends
// map to the master's end nodes). Ties as in pair_integrals_2d.
// Axisymmetric (axi): the weight 2 pi r of the slave point, the dual basis of the weighted
// measure (line2 as well).
template <class T>
KOKKOS_INLINE_FUNCTION bool pair_integrals_2d_curved(const Face& s, const T (*xs)[3], const Face& m, const T (*xm)[3],
                                                     T M[kMaxFacetNodes][kMaxFacetNodes], bool axi = false) {
  using std::sqrt;
  {
    T p[2], as[2], am[2];
    curve(s.type, s.nn, xs, 0.0, p, as);
    curve(m.type, m.nn, xm, 0.0, p, am);
    if (s.orient * m.orient * value(as[1] * am[1] + as[0] * am[0]) >= 0.0) return false;
  }
  // Master end nodes (0, 1) on the slave: a(xi) . (x_m - p(xi)) = 0.
  T xi[2];
  for (int b = 0; b < 2; ++b) {
    const auto g = [&](const auto& z) {
      using Z = std::decay_t<decltype(z)>;
      T p[2], a[2];
      curve(s.type, s.nn, xs, Z(z), p, a);
      return a[0] * (xm[b][0] - p[0]) + a[1] * (xm[b][1] - p[1]);
    };
    const auto gd = [&](double z) {  // a' . (x_m - p) - a . a, a' = sum N_b'' x_b (line3: 1, 1, -2)
      double p[2], a[2], xv[kMaxFacetNodes][3];
      for (int c = 0; c < s.nn; ++c)
        for (int k = 0; k < 3; ++k) xv[c][k] = value(xs[c][k]);
      curve(s.type, s.nn, xv, z, p, a);
      double a2[2] = {0.0, 0.0};
      if (s.type == CellType::Line3)
        for (int k = 0; k < 2; ++k) a2[k] = xv[0][k] + xv[1][k] - 2.0 * xv[2][k];
      return a2[0] * (value(xm[b][0]) - p[0]) + a2[1] * (value(xm[b][1]) - p[1]) - a[0] * a[0] - a[1] * a[1];
    };
    const double chord = value(xs[1][0] - xs[0][0]) * value(xs[1][0] - xs[0][0]) + value(xs[1][1] - xs[0][1]) * value(xs[1][1] - xs[0][1]);
    const double guess =
        2.0 * (value(xm[b][0] - xs[0][0]) * value(xs[1][0] - xs[0][0]) + value(xm[b][1] - xs[0][1]) * value(xs[1][1] - xs[0][1])) / chord - 1.0;
    xi[b] = root_1d<T>(guess, g, gd);
  }
  T lo, hi;
  if (!overlap_bounds(xi, value(xs[1][0] - xs[0][0]), value(xs[1][1] - xs[0][1]), lo, hi)) return false;
  T A[kMaxFacetNodes][kMaxFacetNodes];
  if (axi || s.type == CellType::Line3) {
    if (!dual_coefficients_2d(s.type, s.nn, xs, axi, A)) return false;
  } else {
    dual_coefficients(s.type, s.nn, static_cast<const T(*)[2]>(nullptr), A);  // line2: constants
  }
  double qp[kMaxQuadPoints][3], qw[kMaxQuadPoints];
  const int nq = quadrature(CellType::Line2, 5, qp, qw);
  const T half = 0.5 * (hi - lo), mid = 0.5 * (hi + lo);
  const double x0 = value(xi[0]), x1 = value(xi[1]);
  for (int q = 0; q < nq; ++q) {
    const T z = mid + half * qp[q][0];
    T p[2], a[2];
    curve(s.type, s.nn, xs, z, p, a);
    const T J = sqrt(a[0] * a[0] + a[1] * a[1]);
    // The master point on the slave normal (parallel to (a_y, -a_x)): cross(x^m - p, n) = 0,
    // i.e. a . (x^m(eta) - p) = 0.
    const auto h = [&](const auto& e) {
      using E = std::decay_t<decltype(e)>;
      T pm[2], am[2];
      curve(m.type, m.nn, xm, E(e), pm, am);
      return a[0] * (pm[0] - p[0]) + a[1] * (pm[1] - p[1]);
    };
    const auto hd = [&](double e) {  // a^s . a^m(eta)
      double pm[2], am[2], xv[kMaxFacetNodes][3];
      for (int c = 0; c < m.nn; ++c)
        for (int k = 0; k < 3; ++k) xv[c][k] = value(xm[c][k]);
      curve(m.type, m.nn, xv, e, pm, am);
      return value(a[0]) * am[0] + value(a[1]) * am[1];
    };
    const T eta = root_1d<T>(-1.0 + 2.0 * (value(z) - x0) / (x1 - x0), h, hd);
    T Ns[facet::kMaxNodes], Nm[facet::kMaxNodes], dN[facet::kMaxNodes][2], Phi[kMaxFacetNodes];
    const T zs[2] = {z, T(0.0)}, zm[2] = {eta, T(0.0)};
    facet::shape(s.type, zs, Ns, dN);
    facet::shape(m.type, zm, Nm, dN);
    dual_values(s.nn, A, Ns, Phi);
    const T w = axi ? qw[q] * half * J * (kTwoPi * p[0]) : qw[q] * half * J;
    for (int a2 = 0; a2 < s.nn; ++a2)
      for (int b = 0; b < m.nn; ++b) M[a2][b] += w * Phi[a2] * Nm[b];
  }
  return true;
}

// 3D: tri3/quad4 slave facet against a tri3/quad4 master facet, on the slave's auxiliary plane.
template <class T>
KOKKOS_INLINE_FUNCTION bool pair_integrals_3d(const Face& s, const T (*xs)[3], const Face& m, const T (*xm)[3], T M[kMaxFacetNodes][kMaxFacetNodes]) {
  using std::sqrt;
  double c0[2];
  facet::centre(s.type, c0);
  const T xc[2] = {T(c0[0]), T(c0[1])};
  facet::Frame<T> fs;
  facet::frame(s.type, s.nn, 3, s.orient, xs, xc, fs);
  // Facing: the master facet's centre normal against the slave's.
  {
    double cm[2];
    facet::centre(m.type, cm);
    double xmv[kMaxFacetNodes][3];
    for (int b = 0; b < m.nn; ++b)
      for (int c = 0; c < 3; ++c) xmv[b][c] = value(xm[b][c]);
    facet::Frame<double> fm;
    facet::frame(m.type, m.nn, 3, m.orient, xmv, cm, fm);
    if (fm.n[0] * value(fs.n[0]) + fm.n[1] * value(fs.n[1]) + fm.n[2] * value(fs.n[2]) >= 0.0) return false;
  }
  const T* n0 = fs.n;
  T e1[3], e2[3];
  const T an = fs.a[0][0] * n0[0] + fs.a[0][1] * n0[1] + fs.a[0][2] * n0[2];
  for (int c = 0; c < 3; ++c) e1[c] = fs.a[0][c] - an * n0[c];
  const T l1 = sqrt(e1[0] * e1[0] + e1[1] * e1[1] + e1[2] * e1[2]);
  for (int c = 0; c < 3; ++c) e1[c] = e1[c] / l1;
  e2[0] = n0[1] * e1[2] - n0[2] * e1[1];
  e2[1] = n0[2] * e1[0] - n0[0] * e1[2];
  e2[2] = n0[0] * e1[1] - n0[1] * e1[0];
  auto plane = [&](const T* x, T* p) {
    const T d[3] = {x[0] - fs.xm[0], x[1] - fs.xm[1], x[2] - fs.xm[2]};
    p[0] = d[0] * e1[0] + d[1] * e1[1] + d[2] * e1[2];
    p[1] = d[0] * e2[0] + d[1] * e2[1] + d[2] * e2[2];
  };
  T Ps[kMaxFacetNodes][2], Pm[kMaxFacetNodes][2];
  for (int a = 0; a < s.nn; ++a) plane(xs[a], Ps[a]);
  for (int b = 0; b < m.nn; ++b) plane(xm[b], Pm[b]);
  // Clip polygon: the slave corners counter-clockwise.
  int ord[kMaxFacetNodes];
  T area(0.0);
  for (int a = 0; a < s.nn; ++a) area += cross2(Ps[a], Ps[(a + 1) % s.nn]);
  for (int a = 0; a < s.nn; ++a) ord[a] = value(area) > 0.0 ? a : s.nn - 1 - a;
  // The tie-breaking direction in the plane; the master polygon's orientation there.
  const double dplane[2] = {kTieDir[0] * value(e1[0]) + kTieDir[1] * value(e1[1]) + kTieDir[2] * value(e1[2]),
                            kTieDir[0] * value(e2[0]) + kTieDir[1] * value(e2[1]) + kTieDir[2] * value(e2[2])};
  double morient = 0.0;
  for (int b = 0; b < m.nn; ++b) morient += value(cross2(Pm[b], Pm[(b + 1) % m.nn]));
  morient = morient > 0.0 ? 1.0 : -1.0;
  T poly[kMaxPoly][2], next[kMaxPoly][2];
  int np = m.nn;
  for (int b = 0; b < m.nn; ++b) poly[b][0] = Pm[b][0], poly[b][1] = Pm[b][1];
  for (int e = 0; e < s.nn && np > 0; ++e) {
    const T* A = Ps[ord[e]];
    const T* B = Ps[ord[(e + 1) % s.nn]];
    const T ab[2] = {B[0] - A[0], B[1] - A[1]};
    int nn2 = 0;
    const double tol = 1e-12 * (value(ab[0]) * value(ab[0]) + value(ab[1]) * value(ab[1]));
    const bool tie_in = value(ab[0]) * dplane[1] - value(ab[1]) * dplane[0] > 0.0;
    const auto inside = [&](const T& sv) { return std::abs(value(sv)) <= tol ? tie_in : value(sv) > 0.0; };
    for (int i = 0; i < np; ++i) {
      const T* P = poly[i];
      const T* Q = poly[(i + 1) % np];
      const T ap[2] = {P[0] - A[0], P[1] - A[1]}, aq[2] = {Q[0] - A[0], Q[1] - A[1]};
      const T sp = cross2(ab, ap), sq = cross2(ab, aq);
      const bool pin = inside(sp), qin = inside(sq);
      if (pin && nn2 < kMaxPoly) next[nn2][0] = P[0], next[nn2][1] = P[1], ++nn2;
      if (pin != qin && nn2 < kMaxPoly) {
        const T f = sp / (sp - sq);
        next[nn2][0] = P[0] + f * (Q[0] - P[0]);
        next[nn2][1] = P[1] + f * (Q[1] - P[1]);
        ++nn2;
      }
    }
    np = nn2;
    for (int i = 0; i < np; ++i) poly[i][0] = next[i][0], poly[i][1] = next[i][1];
  }
  if (np < 3) return false;
  T A[kMaxFacetNodes][kMaxFacetNodes];
  dual_coefficients(s.type, s.nn, Ps, A);
  T cen[2] = {T(0.0), T(0.0)};
  for (int i = 0; i < np; ++i) cen[0] += poly[i][0] / double(np), cen[1] += poly[i][1] / double(np);
  // Triangles around the centroid, their areas signed by the clip polygon's orientation (the
  // master's): a sliver of zero area keeps the derivative of its growth.
  double qp[kMaxQuadPoints][3], qw[kMaxQuadPoints];
  const int nq = quadrature(CellType::Tri3, 4, qp, qw);
  for (int i = 0; i < np; ++i) {
    const T u[2] = {poly[i][0] - cen[0], poly[i][1] - cen[1]};
    const T v[2] = {poly[(i + 1) % np][0] - cen[0], poly[(i + 1) % np][1] - cen[1]};
    const T twice = morient * cross2(u, v);
    for (int q = 0; q < nq; ++q) {
      const T p[2] = {cen[0] + qp[q][0] * u[0] + qp[q][1] * v[0], cen[1] + qp[q][0] * u[1] + qp[q][1] * v[1]};
      const T w = qw[q] * twice;
      T xi[2], eta[2];
      planar_inverse(s.type, s.nn, Ps, p, xi);
      planar_inverse(m.type, m.nn, Pm, p, eta);
      T Ns[facet::kMaxNodes], Nm[facet::kMaxNodes], dN[facet::kMaxNodes][2], Phi[kMaxFacetNodes];
      facet::shape(s.type, xi, Ns, dN);
      facet::shape(m.type, eta, Nm, dN);
      dual_values(s.nn, A, Ns, Phi);
      for (int a = 0; a < s.nn; ++a)
        for (int b = 0; b < m.nn; ++b) M[a][b] += w * Phi[a] * Nm[b];
    }
  }
  return true;
}

// axi: 2D axisymmetric (the section's facets revolved about the y axis, dA = 2 pi r ds).
template <class T>
KOKKOS_INLINE_FUNCTION bool pair_integrals(int dim, const Face& s, const T (*xs)[3], const Face& m, const T (*xm)[3], T M[kMaxFacetNodes][kMaxFacetNodes],
                                           bool axi = false) {
  if (dim == 3) return pair_integrals_3d(s, xs, m, xm, M);
  if (s.type == CellType::Line2 && m.type == CellType::Line2) return pair_integrals_2d(s, xs, m, xm, M, axi);
  return pair_integrals_2d_curved(s, xs, m, xm, M, axi);
}

// The outward unit normal of a slave facet at its corner a (line2: -1, +1; tri3, quad4: the corners).
template <class T>
KOKKOS_INLINE_FUNCTION void corner_normal(int dim, const Face& s, const T (*xs)[3], int a, T n[3]) {
  double c[2] = {0.0, 0.0};
  if (s.type == CellType::Line2) c[0] = a == 0 ? -1.0 : 1.0;
  if (s.type == CellType::Line3) c[0] = a == 0 ? -1.0 : (a == 1 ? 1.0 : 0.0);  // gmsh: ends, then the mid-node
  if (s.type == CellType::Tri3) c[0] = a == 1 ? 1.0 : 0.0, c[1] = a == 2 ? 1.0 : 0.0;
  if (s.type == CellType::Quad4) c[0] = (a == 1 || a == 2) ? 1.0 : -1.0, c[1] = a >= 2 ? 1.0 : -1.0;
  const T xi[2] = {T(c[0]), T(c[1])};
  facet::Frame<T> f;
  facet::frame(s.type, s.nn, dim, s.orient, xs, xi, f);
  for (int k = 0; k < 3; ++k) n[k] = f.n[k];
}

}  // namespace stentor::mortar
