// Small fixed-size tensors for material-point and element kernels.
// Everything is KOKKOS_INLINE_FUNCTION and lives in registers/stack so the same
// code runs in Kokkos kernels on any host backend (Serial, OpenMP).
#pragma once
#include <Kokkos_Macros.hpp>
#include <cmath>

namespace stentor {

// 3x3 second-order tensor, row-major: a[i][j].
struct Mat3 {
  double a[3][3];
  KOKKOS_INLINE_FUNCTION double& operator()(int i, int j) { return a[i][j]; }
  KOKKOS_INLINE_FUNCTION double operator()(int i, int j) const { return a[i][j]; }
  KOKKOS_INLINE_FUNCTION static Mat3 zero() {
    Mat3 m;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) m.a[i][j] = 0.0;
    return m;
  }
  KOKKOS_INLINE_FUNCTION static Mat3 identity() {
    Mat3 m = zero();
    m.a[0][0] = m.a[1][1] = m.a[2][2] = 1.0;
    return m;
  }
};

// Fourth-order tensor T[i][j][k][l] (81 doubles).
struct Ten4 {
  double a[3][3][3][3];
  KOKKOS_INLINE_FUNCTION double& operator()(int i, int j, int k, int l) { return a[i][j][k][l]; }
  KOKKOS_INLINE_FUNCTION double operator()(int i, int j, int k, int l) const { return a[i][j][k][l]; }
  KOKKOS_INLINE_FUNCTION void set_zero() {
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        for (int k = 0; k < 3; ++k)
          for (int l = 0; l < 3; ++l) a[i][j][k][l] = 0.0;
  }
};

KOKKOS_INLINE_FUNCTION Mat3 operator+(const Mat3& x, const Mat3& y) {
  Mat3 r;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) r.a[i][j] = x.a[i][j] + y.a[i][j];
  return r;
}
KOKKOS_INLINE_FUNCTION Mat3 operator-(const Mat3& x, const Mat3& y) {
  Mat3 r;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) r.a[i][j] = x.a[i][j] - y.a[i][j];
  return r;
}
KOKKOS_INLINE_FUNCTION Mat3 operator*(double s, const Mat3& x) {
  Mat3 r;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) r.a[i][j] = s * x.a[i][j];
  return r;
}
// Matrix product x*y.
KOKKOS_INLINE_FUNCTION Mat3 matmul(const Mat3& x, const Mat3& y) {
  Mat3 r;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      double s = 0.0;
      for (int k = 0; k < 3; ++k) s += x.a[i][k] * y.a[k][j];
      r.a[i][j] = s;
    }
  return r;
}
KOKKOS_INLINE_FUNCTION Mat3 transpose(const Mat3& x) {
  Mat3 r;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) r.a[i][j] = x.a[j][i];
  return r;
}
// x^T x (right Cauchy-Green from F).
KOKKOS_INLINE_FUNCTION Mat3 tmul(const Mat3& x, const Mat3& y) {
  Mat3 r;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      double s = 0.0;
      for (int k = 0; k < 3; ++k) s += x.a[k][i] * y.a[k][j];
      r.a[i][j] = s;
    }
  return r;
}
KOKKOS_INLINE_FUNCTION double trace(const Mat3& x) { return x.a[0][0] + x.a[1][1] + x.a[2][2]; }
KOKKOS_INLINE_FUNCTION double ddot(const Mat3& x, const Mat3& y) {
  double s = 0.0;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) s += x.a[i][j] * y.a[i][j];
  return s;
}
KOKKOS_INLINE_FUNCTION double det(const Mat3& x) {
  return x.a[0][0] * (x.a[1][1] * x.a[2][2] - x.a[1][2] * x.a[2][1]) -
         x.a[0][1] * (x.a[1][0] * x.a[2][2] - x.a[1][2] * x.a[2][0]) +
         x.a[0][2] * (x.a[1][0] * x.a[2][1] - x.a[1][1] * x.a[2][0]);
}
// Cofactor matrix: cof(x) = det(x) x^{-T}; well defined for singular x too.
KOKKOS_INLINE_FUNCTION Mat3 cofactor(const Mat3& x) {
  Mat3 c;
  c.a[0][0] = x.a[1][1] * x.a[2][2] - x.a[1][2] * x.a[2][1];
  c.a[0][1] = x.a[1][2] * x.a[2][0] - x.a[1][0] * x.a[2][2];
  c.a[0][2] = x.a[1][0] * x.a[2][1] - x.a[1][1] * x.a[2][0];
  c.a[1][0] = x.a[0][2] * x.a[2][1] - x.a[0][1] * x.a[2][2];
  c.a[1][1] = x.a[0][0] * x.a[2][2] - x.a[0][2] * x.a[2][0];
  c.a[1][2] = x.a[0][1] * x.a[2][0] - x.a[0][0] * x.a[2][1];
  c.a[2][0] = x.a[0][1] * x.a[1][2] - x.a[0][2] * x.a[1][1];
  c.a[2][1] = x.a[0][2] * x.a[1][0] - x.a[0][0] * x.a[1][2];
  c.a[2][2] = x.a[0][0] * x.a[1][1] - x.a[0][1] * x.a[1][0];
  return c;
}
KOKKOS_INLINE_FUNCTION Mat3 inverse(const Mat3& x) {
  const double d = det(x);
  return (1.0 / d) * transpose(cofactor(x));
}
KOKKOS_INLINE_FUNCTION Mat3 deviator(const Mat3& x) {
  Mat3 r = x;
  const double p = trace(x) / 3.0;
  for (int i = 0; i < 3; ++i) r.a[i][i] -= p;
  return r;
}

// Largest absolute entry (a norm for comparisons in tests and checks).
KOKKOS_INLINE_FUNCTION double max_abs(const Mat3& m) {
  double r = 0.0;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) r = std::fmax(r, std::fabs(m.a[i][j]));
  return r;
}
KOKKOS_INLINE_FUNCTION double max_abs(const Ten4& t) {
  double r = 0.0;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      for (int k = 0; k < 3; ++k)
        for (int l = 0; l < 3; ++l) r = std::fmax(r, std::fabs(t.a[i][j][k][l]));
  return r;
}

}  // namespace stentor
