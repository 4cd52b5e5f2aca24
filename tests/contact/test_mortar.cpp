// The dual mortar integrals of one slave facet against one master facet
// (src/contact/Mortar.hpp), element by element:
//  1. biorthogonality: a master facet that coincides with the slave facet gives
//     M_ab = int Phi_a N_b = delta_ab int N_b (line2, line3 curved, tri3, quad4 distorted);
//  2. partition of unity: sum_a Phi_a = 1, so sum_a M_ab = int over the overlap of N_b^m
//     and sum_ab M_ab = the overlap's measure, against closed forms for partial overlaps;
//  3. the derivatives carried by the Dual numbers against central differences of the
//     double evaluation, on non-matching, non-planar and curved configurations;
//  4. axisymmetric (2D, dA = 2 pi r ds): a segment at constant r gives 2 pi r times the
//     plane-strain integrals, a sloped one the closed forms of the weighted dual basis
//     (Simpson's rule, exact for the cubic integrands), the weighted biorthogonality, and
//     the derivatives (the weight's included) against central differences.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <random>
#include <string>
#include <utility>

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
  bool axi = false;
};

// M in double.
std::array<std::array<double, kN>, kN> integrals(const Pair& p, bool* overlap = nullptr) {
  double xs[kN][3], xm[kN][3], M[kN][kN] = {};
  for (int a = 0; a < kN; ++a)
    for (int c = 0; c < 3; ++c) xs[a][c] = p.xs[a][c], xm[a][c] = p.xm[a][c];
  const bool ov = mortar::pair_integrals(p.dim, p.s, xs, p.m, xm, M, p.axi);
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

// The largest |dM/dx - central difference| over both facets' coordinates (h = 1e-6) and
// the largest |dM/dx|, after noise on every coordinate (keeps the clip topology generic).
std::pair<double, double> derivative_error(Pair& p, std::mt19937& gen) {
  std::uniform_real_distribution<double> U(-0.05, 0.05);
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
  EXPECT_TRUE(mortar::pair_integrals(p.dim, p.s, xs, p.m, xm, M, p.axi));
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
  return {worst, scale};
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
    const auto [worst, scale] = derivative_error(c.p, gen);
    std::printf("%s: max |dM - FD| = %.2e of %.3f\n", c.name, worst, scale);
    EXPECT_LT(worst, 1e-6 * scale) << c.name;
  }
}

// ---------------------------------------------------------------------------------------
// Axisymmetric: dA = 2 pi r ds, r = x of the slave point (contact/Mortar.hpp, axi).
namespace {

constexpr double kTwoPi = 2.0 * 3.14159265358979323846;

Pair axi_pair(CellType ts, int ns, const Pos& xs, CellType tm, int nm, const Pos& xm) {
  Pair p;
  p.dim = 2;
  p.s = Face{ts, ns, 1.0};
  p.m = Face{tm, nm, 1.0};
  p.xs = xs;
  p.xm = xm;
  p.axi = true;
  return p;
}

// Simpson's rule on [a, b]: exact for cubics.
template <class F>
double simpson(double a, double b, const F& f) {
  return (b - a) / 6.0 * (f(a) + 4.0 * f(0.5 * (a + b)) + f(b));
}

// The weighted dual basis of a line2 segment with end radii r0, r1 in closed form:
// A = D M^-1, M = L/12 [[3 r0 + r1, r0 + r1], [r0 + r1, r0 + 3 r1]] 2 pi, D = L/6 (2 r0 + r1, r0 + 2 r1) 2 pi.
std::array<std::array<double, 2>, 2> line2_axi_dual(double r0, double r1) {
  const double m00 = 3 * r0 + r1, m01 = r0 + r1, m11 = r0 + 3 * r1, det = m00 * m11 - m01 * m01;
  const double d0 = 2.0 * (2 * r0 + r1), d1 = 2.0 * (r0 + 2 * r1);  // D / (M scale): (L/6) / (L/12) = 2
  return {{{d0 * m11 / det, -d0 * m01 / det}, {-d1 * m01 / det, d1 * m00 / det}}};
}

}  // namespace

TEST(MortarIntegrals, AxisymmetricConstantRadiusIsTwoPiRTimesPlaneStrain) {
  // A slave segment on the cylinder r = 1.7 against a non-matching master on it (overlap
  // z in [0.5, 1.1]); line2 and straight line3 (mid-node in the middle).
  const double r = 1.7;
  const Pair cases[] = {
      axi_pair(CellType::Line2, 2, {{{r, 0.2, 0}, {r, 1.1, 0}}}, CellType::Line2, 2, {{{r, 1.3, 0}, {r, 0.5, 0}}}),
      axi_pair(CellType::Line3, 3, {{{r, 0.2, 0}, {r, 1.1, 0}, {r, 0.65, 0}}}, CellType::Line3, 3,
               {{{r, 1.3, 0}, {r, 0.5, 0}, {r, 0.9, 0}}}),
      axi_pair(CellType::Line2, 2, {{{r, 0.2, 0}, {r, 1.1, 0}}}, CellType::Line3, 3, {{{r, 1.3, 0}, {r, 0.5, 0}, {r, 0.9, 0}}}),
  };
  for (const Pair& a : cases) {
    Pair plane = a;
    plane.axi = false;
    bool ov_a = false, ov_p = false;
    const auto Ma = integrals(a, &ov_a), Mp = integrals(plane, &ov_p);
    ASSERT_TRUE(ov_a && ov_p);
    double worst = 0.0, scale = 0.0;
    for (int i = 0; i < a.s.nn; ++i)
      for (int j = 0; j < a.m.nn; ++j) {
        const double ref = kTwoPi * r * Mp[static_cast<std::size_t>(i)][static_cast<std::size_t>(j)];
        worst = std::max(worst, std::abs(Ma[static_cast<std::size_t>(i)][static_cast<std::size_t>(j)] - ref));
        scale = std::max(scale, std::abs(ref));
      }
    std::printf("axi %s/%s at r = %.1f: max |M_axi - 2 pi r M_plane| = %.2e of %.3f\n", cell_name(a.s.type),
                cell_name(a.m.type), r, worst, scale);
    EXPECT_LT(worst, 1e-14 * scale);
  }
}

TEST(MortarIntegrals, AxisymmetricSlopedSegmentsAgainstClosedForms) {
  // Slave line2 P(s) = P0 + s (P1 - P0), s in [0, 1]; a collinear master from P(s_a) to P(s_b)
  // (reversed: facing). M_ab = 2 pi L int_overlap Phi_a(s) N_b^m(s) r(s) ds with the closed-form
  // weighted dual basis, by Simpson's rule (the integrand is cubic in s).
  struct Case {
    const char* name;
    double P0[2], P1[2], sa, sb;
  };
  const Case cases[] = {
      {"sloped", {0.3, 0.2}, {1.4, 0.9}, 1.25, 0.4},
      {"radial, from the axis", {0.0, 0.5}, {1.2, 0.5}, 0.7, -0.3},
      {"radial, inward", {1.5, 0.4}, {0.2, 0.4}, 1.4, 0.35},
  };
  for (const Case& c : cases) {
    auto P = [&](double s, int k) { return c.P0[k] + s * (c.P1[k] - c.P0[k]); };
    const Pair p = axi_pair(CellType::Line2, 2, {{{c.P0[0], c.P0[1], 0}, {c.P1[0], c.P1[1], 0}}}, CellType::Line2, 2,
                            {{{P(c.sa, 0), P(c.sa, 1), 0}, {P(c.sb, 0), P(c.sb, 1), 0}}});
    const auto M = integrals(p);
    const double L = std::hypot(c.P1[0] - c.P0[0], c.P1[1] - c.P0[1]);
    const auto A = line2_axi_dual(c.P0[0], c.P1[0]);
    const double lo = std::max(0.0, std::min(c.sa, c.sb)), hi = std::min(1.0, std::max(c.sa, c.sb));
    double worst = 0.0, scale = 0.0;
    for (int a = 0; a < 2; ++a)
      for (int b = 0; b < 2; ++b) {
        const auto f = [&](double s) {
          const double phi = A[static_cast<std::size_t>(a)][0] * (1 - s) + A[static_cast<std::size_t>(a)][1] * s;
          const double nm = b == 0 ? (c.sb - s) / (c.sb - c.sa) : (s - c.sa) / (c.sb - c.sa);
          return phi * nm * P(s, 0);
        };
        const double ref = kTwoPi * L * simpson(lo, hi, f);
        worst = std::max(worst, std::abs(M[static_cast<std::size_t>(a)][static_cast<std::size_t>(b)] - ref));
        scale = std::max(scale, std::abs(ref));
      }
    std::printf("axi line2 %s: max |M - closed form| = %.2e of %.3f\n", c.name, worst, scale);
    EXPECT_LT(worst, 1e-14 * scale) << c.name;
  }
}

TEST(MortarIntegrals, AxisymmetricDualBasisIsBiorthogonal) {
  // (a) The weighted dual basis itself: int Phi_a N_c 2 pi r ds = delta_ac int N_c 2 pi r ds
  // by an independent rule (3 Gauss points on each of 8 sub-intervals: exact for the
  // line2's cubic and the straight line3's quintic integrand); (b) coincident facets:
  // M_ab = delta_ab D_b, D_b the closed form 2 pi L (2 r_b + r_other) / 6 of a line2.
  struct Case {
    const char* name;
    CellType t;
    int nn;
    Pos x;
  };
  const Case cases[] = {
      {"line2 sloped", CellType::Line2, 2, {{{0.3, 0.2, 0}, {1.4, 0.9, 0}}}},
      {"line2 on the axis", CellType::Line2, 2, {{{0.0, 0.5, 0}, {1.2, 0.6, 0}}}},
      {"line2 cylinder", CellType::Line2, 2, {{{2.0, 0.1, 0}, {2.0, 0.9, 0}}}},
      {"line3 straight", CellType::Line3, 3, {{{0.1, 0.2, 0}, {1.3, 0.8, 0}, {0.7, 0.5, 0}}}},
  };
  double qp[kMaxQuadPoints][3], qw[kMaxQuadPoints];
  const int nq = quadrature(CellType::Line2, 5, qp, qw);
  for (const Case& c : cases) {
    double x[kN][3], A[kN][kN];
    for (int a = 0; a < kN; ++a)
      for (int k = 0; k < 3; ++k) x[a][k] = c.x[static_cast<std::size_t>(a)][static_cast<std::size_t>(k)];
    ASSERT_TRUE(mortar::dual_coefficients_2d(c.t, c.nn, x, true, A)) << c.name;
    double B[kN][kN] = {}, D[kN] = {};
    const int nsub = 8;
    for (int e = 0; e < nsub; ++e)
      for (int q = 0; q < nq; ++q) {
        const double xi = -1.0 + (2.0 * e + 1.0 + qp[q][0]) / nsub, w = qw[q] / nsub;
        double pt[2], tg[2];
        mortar::curve(c.t, c.nn, x, xi, pt, tg);
        const double dA = w * std::hypot(tg[0], tg[1]) * kTwoPi * pt[0];
        double N[facet::kMaxNodes], dN[facet::kMaxNodes][2], Phi[kN];
        const double z[2] = {xi, 0.0};
        facet::shape(c.t, z, N, dN);
        mortar::dual_values(c.nn, A, N, Phi);
        for (int a = 0; a < c.nn; ++a) {
          D[a] += dA * N[a];
          for (int b = 0; b < c.nn; ++b) B[a][b] += dA * Phi[a] * N[b];
        }
      }
    double worst = 0.0, scale = 0.0;
    for (int a = 0; a < c.nn; ++a) scale = std::max(scale, D[a]);
    for (int a = 0; a < c.nn; ++a)
      for (int b = 0; b < c.nn; ++b) worst = std::max(worst, std::abs(B[a][b] - (a == b ? D[b] : 0.0)));
    // Coincident master facet (opposite orientation).
    Pair p = coincident(2, c.t, c.nn, c.x);
    p.axi = true;
    const auto M = integrals(p);
    double worst_m = 0.0;
    for (int a = 0; a < c.nn; ++a)
      for (int b = 0; b < c.nn; ++b)
        worst_m = std::max(worst_m, std::abs(M[static_cast<std::size_t>(a)][static_cast<std::size_t>(b)] - (a == b ? D[b] : 0.0)));
    if (c.t == CellType::Line2) {
      const double L = std::hypot(c.x[1][0] - c.x[0][0], c.x[1][1] - c.x[0][1]);
      for (int b = 0; b < 2; ++b) {
        const double Db = kTwoPi * L * (2 * c.x[static_cast<std::size_t>(b)][0] + c.x[static_cast<std::size_t>(1 - b)][0]) / 6.0;
        EXPECT_NEAR(D[b], Db, 1e-14 * scale) << c.name;
      }
    }
    std::printf("axi %s: max |int Phi_a N_c dA - delta_ac D_c| = %.2e, coincident max |M_ab - delta_ab D_b| = %.2e, of %.3f\n", c.name,
                worst, worst_m, scale);
    EXPECT_LT(worst, 1e-14 * scale) << c.name;
    EXPECT_LT(worst_m, 1e-14 * scale) << c.name;
  }
  // A facet on the axis has no revolved area: no dual basis, no coupling.
  double x[kN][3] = {{0.0, 0.0, 0.0}, {0.0, 1.0, 0.0}}, A[kN][kN];
  EXPECT_FALSE(mortar::dual_coefficients_2d(CellType::Line2, 2, x, true, A));
  Pair p = coincident(2, CellType::Line2, 2, {{{0.0, 0.0, 0}, {0.0, 1.0, 0}}});
  p.axi = true;
  bool ov = true;
  integrals(p, &ov);
  EXPECT_FALSE(ov);
}

TEST(MortarIntegrals, AxisymmetricDerivativesMatchFiniteDifferences) {
  // The weight 2 pi r of the current slave point and the weighted dual basis both depend
  // on the positions: the Dual derivatives against central differences.
  std::mt19937 gen(7);
  struct Case {
    const char* name;
    Pair p;
  };
  std::vector<Case> cases = {
      {"line2/line2 sloped",
       axi_pair(CellType::Line2, 2, {{{0.3, 0.2, 0}, {1.4, 0.9, 0}}}, CellType::Line2, 2, {{{1.65, 1.03, 0}, {0.7, 0.47, 0}}})},
      {"line2/line2 near the axis",
       axi_pair(CellType::Line2, 2, {{{0.1, 0.5, 0}, {1.2, 0.52, 0}}}, CellType::Line2, 2, {{{0.9, 0.49, 0}, {-0.2, 0.51, 0}}})},
      {"line3/line3 curved",
       axi_pair(CellType::Line3, 3, {{{1.0, 0.0, 0}, {1.1, 1.0, 0}, {1.12, 0.5, 0}}}, CellType::Line3, 3,
                {{{1.11, 1.3, 0}, {1.08, 0.35, 0}, {1.13, 0.8, 0}}})},
      {"line2/line3",
       axi_pair(CellType::Line2, 2, {{{1.0, 0.0, 0}, {1.05, 1.0, 0}}}, CellType::Line3, 3, {{{1.06, 1.3, 0}, {1.02, 0.35, 0}, {1.07, 0.8, 0}}})},
  };
  for (Case& c : cases) {
    const auto [worst, scale] = derivative_error(c.p, gen);
    std::printf("axi %s: max |dM - FD| = %.2e of %.3f\n", c.name, worst, scale);
    EXPECT_LT(worst, 1e-6 * scale) << c.name;
  }
}
