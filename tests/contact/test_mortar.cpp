// The dual mortar integrals of one slave facet against one master facet
// (src/contact/Mortar.hpp), element by element:
//  1. biorthogonality: a master facet that coincides with the slave facet gives
//     M_ab = int Phi_a N_b = delta_ab int N_b (line2, line3 curved, tri3, quad4 distorted);
//  2. partition of unity: sum_a Phi_a = 1, so sum_a M_ab = int over the overlap of N_b^m
//     and sum_ab M_ab = the overlap's measure, against closed forms for partial overlaps;
//  3. the derivatives carried by the Dual numbers against central differences of the
//     double evaluation, on non-matching, non-planar and curved configurations.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <random>
#include <string>

#include "contact/Mortar.hpp"

using namespace stentor;
using mortar::Face;
using mortar::PD;

namespace {

constexpr int kN = mortar::kMaxFacetNodes;
using Pos = std::array<std::array<double, 3>, kN>;

struct Pair {
  int dim = 2;
  Face s, m;
  Pos xs{}, xm{};
};

// M in double.
std::array<std::array<double, kN>, kN> integrals(const Pair& p, bool* overlap = nullptr) {
  double xs[kN][3], xm[kN][3], M[kN][kN] = {};
  for (int a = 0; a < kN; ++a)
    for (int c = 0; c < 3; ++c) xs[a][c] = p.xs[a][c], xm[a][c] = p.xm[a][c];
  const bool ov = mortar::pair_integrals(p.dim, p.s, xs, p.m, xm, M);
  if (overlap) *overlap = ov;
  std::array<std::array<double, kN>, kN> out{};
  for (int a = 0; a < kN; ++a)
    for (int b = 0; b < kN; ++b) out[a][b] = M[a][b];
  return out;
}

// Coincident facets (the master's nodes in the same places, opposite orientation).
Pair coincident(int dim, CellType t, int nn, const Pos& x) {
  Pair p;
  p.dim = dim;
  p.s = Face{t, nn, 1.0};
  p.m = Face{t, nn, -1.0};
  p.xs = x;
  p.xm = x;
  return p;
}

// int N_b over a whole facet (quadrature of its own geometry).
std::array<double, kN> facet_integrals(int dim, CellType t, int nn, const Pos& x) {
  double qp[kMaxQuadPoints][3], qw[kMaxQuadPoints];
  const int nq = quadrature(t, 5, qp, qw);
  std::array<double, kN> out{};
  for (int q = 0; q < nq; ++q) {
    double xa[kN][3];
    for (int a = 0; a < nn; ++a)
      for (int c = 0; c < 3; ++c) xa[a][c] = x[a][c];
    const double xi[2] = {qp[q][0], qp[q][1]};
    facet::Frame<double> f;
    facet::frame(t, nn, dim, 1.0, xa, xi, f);
    double J = 0.0;
    if (dim == 2) {
      J = std::hypot(f.a[0][0], f.a[0][1]);
    } else {
      const double n[3] = {f.a[0][1] * f.a[1][2] - f.a[0][2] * f.a[1][1], f.a[0][2] * f.a[1][0] - f.a[0][0] * f.a[1][2],
                           f.a[0][0] * f.a[1][1] - f.a[0][1] * f.a[1][0]};
      J = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    }
    for (int b = 0; b < nn; ++b) out[static_cast<std::size_t>(b)] += qw[q] * J * f.N[b];
  }
  return out;
}

}  // namespace

TEST(MortarIntegrals, CoincidentFacetsAreBiorthogonal) {
  struct Case {
    const char* name;
    int dim;
    CellType t;
    int nn;
    Pos x;
  };
  const Case cases[] = {
      {"line2", 2, CellType::Line2, 2, {{{0.1, 0.2, 0}, {1.3, 0.5, 0}}}},
      // A curved line3 (the mid-node off the chord): its geometric dual basis.
      {"line3", 2, CellType::Line3, 3, {{{0.0, 0.0, 0}, {1.0, 0.1, 0}, {0.5, 0.12, 0}}}},
      {"tri3", 3, CellType::Tri3, 3, {{{0.0, 0.0, 0.3}, {1.2, 0.1, 0.3}, {0.3, 0.9, 0.3}}}},
      {"quad4 parallelogram", 3, CellType::Quad4, 4, {{{0.0, 0.0, 0.0}, {1.0, 0.2, 0.0}, {1.3, 1.0, 0.0}, {0.3, 0.8, 0.0}}}},
      // A distorted (non-parallelogram) flat quad4: its dual basis depends on the geometry,
      // and the inverse of its bilinear map is not polynomial, so the triangle rules on the
      // clip polygon integrate Phi_a N_b only approximately (measured 1.6e-5 relative).
      {"quad4 distorted", 3, CellType::Quad4, 4, {{{0.0, 0.0, 0.0}, {1.0, 0.0, 0.0}, {1.3, 0.8, 0.0}, {-0.1, 1.1, 0.0}}}},
  };
  for (const Case& c : cases) {
    const auto M = integrals(coincident(c.dim, c.t, c.nn, c.x));
    const auto D = facet_integrals(c.dim, c.t, c.nn, c.x);
    double worst = 0.0, scale = 0.0;
    for (int a = 0; a < c.nn; ++a) scale = std::max(scale, D[static_cast<std::size_t>(a)]);
    for (int a = 0; a < c.nn; ++a)
      for (int b = 0; b < c.nn; ++b)
        worst = std::max(worst, std::abs(M[static_cast<std::size_t>(a)][static_cast<std::size_t>(b)] - (a == b ? D[static_cast<std::size_t>(b)] : 0.0)));
    std::printf("%s: max |M_ab - delta_ab int N_b| = %.2e of %.3f\n", c.name, worst, scale);
    EXPECT_LT(worst, (std::string(c.name) == "quad4 distorted" ? 1e-4 : 1e-12) * scale) << c.name;
  }
}

TEST(MortarIntegrals, PartialOverlapsAgainstClosedForms) {
  // 2D: slave [0, 1] x {0}, master [0.3, 1.7] x {0} (facing): overlap 0.7; the master's
  // N_0 = (1.7 - x)/1.4 over [0.3, 1] integrates to (1.4^2 - 0.7^2)/2.8 = 0.525, N_1 to 0.175.
  {
    Pair p;
    p.dim = 2;
    p.s = Face{CellType::Line2, 2, 1.0};
    p.m = Face{CellType::Line2, 2, 1.0};
    p.xs = {{{0, 0, 0}, {1, 0, 0}}};
    p.xm = {{{1.7, 0, 0}, {0.3, 0, 0}}};  // reversed: outward normals face each other
    const auto M = integrals(p);
    const double col0 = M[0][0] + M[1][0], col1 = M[0][1] + M[1][1];
    std::printf("line2 partial overlap: sum_a M_a0 %.15f (0.175), sum_a M_a1 %.15f (0.525)\n", col0, col1);
    EXPECT_NEAR(col0, 0.175, 1e-14);
    EXPECT_NEAR(col1, 0.525, 1e-14);
  }
  // 3D: slave unit square, master square [0.4, 1.6] x [-0.2, 0.5] above it: overlap
  // 0.6 x 0.5 = 0.3; a master tri3 inside the slave: sum_a M_ab = its area / 3 each.
  {
    Pair p;
    p.dim = 3;
    p.s = Face{CellType::Quad4, 4, 1.0};
    p.m = Face{CellType::Quad4, 4, 1.0};
    p.xs = {{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}}};
    p.xm = {{{0.4, -0.2, 0.01}, {0.4, 0.5, 0.01}, {1.6, 0.5, 0.01}, {1.6, -0.2, 0.01}}};  // clockwise: facing
    auto M = integrals(p);
    double total = 0.0;
    for (const auto& row : M)
      for (double v : row) total += v;
    std::printf("quad4 partial overlap: sum M %.15f (0.3)\n", total);
    EXPECT_NEAR(total, 0.3, 1e-13);
    p.m = Face{CellType::Tri3, 3, 1.0};
    p.xm = {{{0.2, 0.1, 0.0}, {0.3, 0.8, 0.0}, {0.9, 0.3, 0.0}}};
    M = integrals(p);
    const double area = 0.5 * std::abs((0.3 - 0.2) * (0.3 - 0.1) - (0.8 - 0.1) * (0.9 - 0.2));
    for (int b = 0; b < 3; ++b) {
      double col = 0.0;
      for (int a = 0; a < 4; ++a) col += M[static_cast<std::size_t>(a)][static_cast<std::size_t>(b)];
      EXPECT_NEAR(col, area / 3.0, 1e-14) << b;
    }
  }
}

TEST(MortarIntegrals, DerivativesMatchFiniteDifferences) {
  std::mt19937 gen(3);
  std::uniform_real_distribution<double> U(-0.05, 0.05);
  struct Case {
    const char* name;
    Pair p;
  };
  std::vector<Case> cases;
  {
    Pair p;
    p.dim = 2;
    p.s = Face{CellType::Line2, 2, 1.0};
    p.m = Face{CellType::Line2, 2, 1.0};
    p.xs = {{{0, 0, 0}, {1, 0.05, 0}}};
    p.xm = {{{1.3, 0.01, 0}, {0.35, -0.02, 0}}};
    cases.push_back({"line2/line2", p});
    p.s = Face{CellType::Line3, 3, 1.0};
    p.m = Face{CellType::Line3, 3, 1.0};
    p.xs = {{{0, 0, 0}, {1, 0.05, 0}, {0.5, 0.06, 0}}};
    p.xm = {{{1.3, 0.01, 0}, {0.35, -0.02, 0}, {0.8, 0.03, 0}}};
    cases.push_back({"line3/line3", p});
  }
  {
    Pair p;
    p.dim = 3;
    p.s = Face{CellType::Quad4, 4, 1.0};
    p.m = Face{CellType::Quad4, 4, 1.0};
    p.xs = {{{0, 0, 0}, {1, 0.1, 0.02}, {1.1, 0.9, -0.03}, {-0.1, 1, 0.01}}};  // warped
    p.xm = {{{0.35, -0.2, 0.01}, {0.3, 0.55, 0.02}, {1.55, 0.6, 0.0}, {1.6, -0.25, 0.015}}};
    cases.push_back({"quad4/quad4", p});
    p.m = Face{CellType::Tri3, 3, 1.0};
    p.xm = {{{0.2, -0.3, 0.01}, {0.4, 1.3, 0.0}, {1.4, 0.3, 0.02}}};
    cases.push_back({"quad4/tri3", p});
    p.s = Face{CellType::Tri3, 3, 1.0};
    p.xs = {{{0, 0, 0}, {1.2, 0.1, 0.02}, {0.3, 1.0, -0.01}}};
    p.m = Face{CellType::Quad4, 4, 1.0};
    p.xm = {{{0.35, -0.2, 0.01}, {0.3, 0.55, 0.02}, {1.55, 0.6, 0.0}, {1.6, -0.25, 0.015}}};
    cases.push_back({"tri3/quad4", p});
  }
  for (Case& c : cases) {
    Pair& p = c.p;
    // Noise on every coordinate (keeps the clip topology generic).
    for (int a = 0; a < kN; ++a)
      for (int k = 0; k < p.dim; ++k) {
        if (a < p.s.nn) p.xs[static_cast<std::size_t>(a)][static_cast<std::size_t>(k)] += U(gen);
        if (a < p.m.nn) p.xm[static_cast<std::size_t>(a)][static_cast<std::size_t>(k)] += U(gen);
      }
    PD xs[kN][3], xm[kN][3], M[kN][kN];
    for (int a = 0; a < kN; ++a)
      for (int k = 0; k < 3; ++k) {
        xs[a][k] = k < p.dim ? PD::seed(p.xs[static_cast<std::size_t>(a)][static_cast<std::size_t>(k)], 3 * a + k) : PD(p.xs[static_cast<std::size_t>(a)][static_cast<std::size_t>(k)]);
        xm[a][k] = k < p.dim ? PD::seed(p.xm[static_cast<std::size_t>(a)][static_cast<std::size_t>(k)], 12 + 3 * a + k) : PD(p.xm[static_cast<std::size_t>(a)][static_cast<std::size_t>(k)]);
      }
    ASSERT_TRUE(mortar::pair_integrals(p.dim, p.s, xs, p.m, xm, M)) << c.name;
    double worst = 0.0, scale = 0.0;
    const double h = 1e-6;
    for (int side = 0; side < 2; ++side)
      for (int a = 0; a < (side ? p.m.nn : p.s.nn); ++a)
        for (int k = 0; k < p.dim; ++k) {
          Pair pp = p, pm = p;
          auto& xp = side ? pp.xm : pp.xs;
          auto& xn = side ? pm.xm : pm.xs;
          xp[static_cast<std::size_t>(a)][static_cast<std::size_t>(k)] += h;
          xn[static_cast<std::size_t>(a)][static_cast<std::size_t>(k)] -= h;
          const auto Mp = integrals(pp), Mm = integrals(pm);
          const int v = 12 * side + 3 * a + k;
          for (int i = 0; i < p.s.nn; ++i)
            for (int j = 0; j < p.m.nn; ++j) {
              const double fd = (Mp[static_cast<std::size_t>(i)][static_cast<std::size_t>(j)] - Mm[static_cast<std::size_t>(i)][static_cast<std::size_t>(j)]) / (2 * h);
              worst = std::max(worst, std::abs(fd - M[i][j].d[v]));
              scale = std::max(scale, std::abs(M[i][j].d[v]));
            }
        }
    std::printf("%s: max |dM - FD| = %.2e of %.3f\n", c.name, worst, scale);
    EXPECT_LT(worst, 1e-6 * scale) << c.name;
  }
}
