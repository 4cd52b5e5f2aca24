// Forward-mode automatic differentiation with a fixed number of seeds, for the contact
// kernels: the local contact residual of one slave node is written once, templated on
// the scalar, and evaluated with Dual<N> to obtain its exact first derivatives with
// respect to the node's local unknowns (slave position, master facet positions, the
// slave's bulk residual). The normal, tangents, projection point and slip direction
// are then differentiated without hand-derived formulas (docs/contact.md).
//
// Header-only, callable inside Kokkos kernels (no heap, no exceptions).
#pragma once
#include <Kokkos_Macros.hpp>
#include <cmath>

namespace stentor {

template <int N>
struct Dual {
  double v = 0.0;
  double d[N] = {};
  KOKKOS_INLINE_FUNCTION Dual() = default;
  KOKKOS_INLINE_FUNCTION Dual(double x) : v(x) {}  // NOLINT: constants mix freely with duals
  // The independent variable number i (0 <= i < N) with value x.
  KOKKOS_INLINE_FUNCTION static Dual seed(double x, int i) {
    Dual r(x);
    r.d[i] = 1.0;
    return r;
  }
  KOKKOS_INLINE_FUNCTION Dual& operator+=(const Dual& b) {
    v += b.v;
    for (int i = 0; i < N; ++i) d[i] += b.d[i];
    return *this;
  }
  KOKKOS_INLINE_FUNCTION Dual& operator-=(const Dual& b) {
    v -= b.v;
    for (int i = 0; i < N; ++i) d[i] -= b.d[i];
    return *this;
  }
  KOKKOS_INLINE_FUNCTION Dual& operator*=(const Dual& b) {
    for (int i = 0; i < N; ++i) d[i] = d[i] * b.v + v * b.d[i];
    v *= b.v;
    return *this;
  }
  KOKKOS_INLINE_FUNCTION Dual& operator*=(double s) {
    v *= s;
    for (int i = 0; i < N; ++i) d[i] *= s;
    return *this;
  }
  KOKKOS_INLINE_FUNCTION Dual& operator/=(const Dual& b) {
    const double inv = 1.0 / b.v;
    v *= inv;
    for (int i = 0; i < N; ++i) d[i] = (d[i] - v * b.d[i]) * inv;
    return *this;
  }
};

template <int N>
KOKKOS_INLINE_FUNCTION Dual<N> operator-(const Dual<N>& a) {
  Dual<N> r;
  r.v = -a.v;
  for (int i = 0; i < N; ++i) r.d[i] = -a.d[i];
  return r;
}
template <int N>
KOKKOS_INLINE_FUNCTION Dual<N> operator+(Dual<N> a, const Dual<N>& b) { return a += b; }
template <int N>
KOKKOS_INLINE_FUNCTION Dual<N> operator-(Dual<N> a, const Dual<N>& b) { return a -= b; }
template <int N>
KOKKOS_INLINE_FUNCTION Dual<N> operator*(Dual<N> a, const Dual<N>& b) { return a *= b; }
template <int N>
KOKKOS_INLINE_FUNCTION Dual<N> operator/(Dual<N> a, const Dual<N>& b) { return a /= b; }
template <int N>
KOKKOS_INLINE_FUNCTION Dual<N> operator+(Dual<N> a, double b) { a.v += b; return a; }
template <int N>
KOKKOS_INLINE_FUNCTION Dual<N> operator+(double b, Dual<N> a) { a.v += b; return a; }
template <int N>
KOKKOS_INLINE_FUNCTION Dual<N> operator-(Dual<N> a, double b) { a.v -= b; return a; }
template <int N>
KOKKOS_INLINE_FUNCTION Dual<N> operator-(double b, const Dual<N>& a) { return -a + b; }
template <int N>
KOKKOS_INLINE_FUNCTION Dual<N> operator*(Dual<N> a, double b) { return a *= b; }
template <int N>
KOKKOS_INLINE_FUNCTION Dual<N> operator*(double b, Dual<N> a) { return a *= b; }
template <int N>
KOKKOS_INLINE_FUNCTION Dual<N> operator/(Dual<N> a, double b) { return a *= 1.0 / b; }
template <int N>
KOKKOS_INLINE_FUNCTION Dual<N> operator/(double a, const Dual<N>& b) { return Dual<N>(a) / b; }

template <int N>
KOKKOS_INLINE_FUNCTION Dual<N> sqrt(const Dual<N>& a) {
  Dual<N> r;
  r.v = std::sqrt(a.v);
  const double h = r.v > 0.0 ? 0.5 / r.v : 0.0;
  for (int i = 0; i < N; ++i) r.d[i] = a.d[i] * h;
  return r;
}

// Value of a scalar (double or Dual), for decisions (active sets, branches).
KOKKOS_INLINE_FUNCTION double value(double x) { return x; }
template <int N>
KOKKOS_INLINE_FUNCTION double value(const Dual<N>& x) { return x.v; }

}  // namespace stentor
