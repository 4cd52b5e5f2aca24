// material/SymEigen.hpp: the Jacobi eigen-decomposition of symmetric 3 x 3 tensors and
// what the output fields derive from it (principal values sorted, (1/2) ln of an SPD
// tensor), against tensors built from known eigenpairs: distinct, repeated (a uniaxial
// stretch), triple, nearly repeated (1e-9 apart), zero, indefinite, badly scaled.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "material/SymEigen.hpp"

using namespace stentor;

namespace {

// A rotation from a unit quaternion (random in [-1, 1]^4, normalized).
Mat3 rotation(std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  double q[4], n = 0.0;
  for (double& x : q) x = u(rng), n += x * x;
  n = std::sqrt(n);
  const double w = q[0] / n, x = q[1] / n, y = q[2] / n, z = q[3] / n;
  Mat3 R;
  R(0, 0) = 1 - 2 * (y * y + z * z), R(0, 1) = 2 * (x * y - z * w), R(0, 2) = 2 * (x * z + y * w);
  R(1, 0) = 2 * (x * y + z * w), R(1, 1) = 1 - 2 * (x * x + z * z), R(1, 2) = 2 * (y * z - x * w);
  R(2, 0) = 2 * (x * z - y * w), R(2, 1) = 2 * (y * z + x * w), R(2, 2) = 1 - 2 * (x * x + y * y);
  return R;
}

// R diag(d) R^T.
Mat3 spectral(const Mat3& R, const double d[3]) {
  Mat3 A = Mat3::zero();
  for (int a = 0; a < 3; ++a)
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) A(i, j) += d[a] * R(i, a) * R(j, a);
  return A;
}

}  // namespace

TEST(SymEigen, DecompositionAndSortedPrincipalValues) {
  std::mt19937 rng(7);
  const double cases[][3] = {{3.0, -1.0, 0.5},  {2.0, 2.0, 5.0},      {4.0, 4.0, 4.0}, {1.0, 1.0 + 1e-9, 1.0 - 1e-9},
                             {0.0, 0.0, 0.0},   {-7.0, 1e-3, 2e-12},  {1e8, 1.0, -1e-3}};
  for (const auto& d : cases)
    for (int r = 0; r < 20; ++r) {
      const Mat3 R = rotation(rng), A = spectral(R, d);
      double lam[3];
      Mat3 V;
      sym_eig3(A, lam, V);
      const double scale = std::max({std::fabs(d[0]), std::fabs(d[1]), std::fabs(d[2]), 1e-300});
      // A V = V diag(lam), V^T V = I.
      for (int i = 0; i < 3; ++i)
        for (int a = 0; a < 3; ++a) {
          double av = 0.0, vtv = 0.0;
          for (int k = 0; k < 3; ++k) av += A(i, k) * V(k, a), vtv += V(k, i) * V(k, a);
          EXPECT_NEAR(av, lam[a] * V(i, a), 1e-14 * scale);
          EXPECT_NEAR(vtv, i == a ? 1.0 : 0.0, 1e-14);
        }
      double p[3], e[3] = {d[0], d[1], d[2]};
      principal_values(A, p);
      std::sort(e, e + 3, [](double x, double y) { return x > y; });
      for (int a = 0; a < 3; ++a) EXPECT_NEAR(p[a], e[a], 1e-14 * scale) << "case " << d[0] << " " << d[1] << " " << d[2];
      EXPECT_GE(p[0], p[1]);
      EXPECT_GE(p[1], p[2]);
    }
}

// (1/2) ln(R diag(b) R^T) = R diag(ln(b)/2) R^T; a uniaxial b = diag(lam^2, s^2, s^2) gives
// the Hencky strains ln lam, ln s exactly where the eigenvalues repeat.
TEST(SymEigen, HalfLogOfSpdTensor) {
  std::mt19937 rng(11);
  const double cases[][3] = {{1.44, 0.9, 0.9}, {1.0, 1.0, 1.0}, {2.5, 0.3, 1.7}, {1e-4, 1e4, 1.0}};
  for (const auto& b : cases)
    for (int r = 0; r < 20; ++r) {
      const Mat3 R = rotation(rng);
      const double h[3] = {0.5 * std::log(b[0]), 0.5 * std::log(b[1]), 0.5 * std::log(b[2])};
      const Mat3 L = half_log_spd(spectral(R, b)), expect = spectral(R, h);
      // Forming B rounds its smallest eigenvalue by ~eps |B|: ln of it is only as good as
      // eps times the condition number (1e8 in the last case: 1e-8), whatever the solver.
      const double cond = *std::max_element(b, b + 3) / *std::min_element(b, b + 3), tol = 1e-13 + 1e-15 * cond;
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) EXPECT_NEAR(L(i, j), expect(i, j), tol) << b[0] << " " << b[1] << " " << b[2];
    }
}
