// Tests of the finite-element reference library: shape functions, quadrature, geometry.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <string>
#include <vector>

#include "fem/CellType.hpp"
#include "fem/Geometry.hpp"
#include "fem/Quadrature.hpp"
#include "fem/Shape.hpp"

using namespace stentor;

namespace {

const CellType kShapeTypes[] = {CellType::Line2, CellType::Line3, CellType::Tri3, CellType::Tri6, CellType::Quad4,
                                CellType::Quad8, CellType::Tet4,  CellType::Tet10, CellType::Hex8};

bool is_simplex(CellType t) {
  return t == CellType::Tri3 || t == CellType::Tri6 || t == CellType::Tet4 || t == CellType::Tet10;
}

// Reference node coordinates as reported by gmsh 4.8.4 (gmsh::model::mesh::getElementProperties,
// localNodeCoord), hardcoded here, independently of the library's reference_nodes().
std::vector<std::vector<double>> gmsh_nodes(CellType t) {
  switch (t) {
    case CellType::Line2: return {{-1}, {1}};
    case CellType::Line3: return {{-1}, {1}, {0}};
    case CellType::Tri3: return {{0, 0}, {1, 0}, {0, 1}};
    case CellType::Tri6: return {{0, 0}, {1, 0}, {0, 1}, {0.5, 0}, {0.5, 0.5}, {0, 0.5}};
    case CellType::Quad4: return {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
    case CellType::Quad8: return {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}, {0, -1}, {1, 0}, {0, 1}, {-1, 0}};
    case CellType::Tet4: return {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    case CellType::Tet10:
      return {{0, 0, 0},   {1, 0, 0},     {0, 1, 0},   {0, 0, 1},     {0.5, 0, 0},
              {0.5, 0.5, 0}, {0, 0.5, 0}, {0, 0, 0.5}, {0, 0.5, 0.5}, {0.5, 0, 0.5}};
    case CellType::Hex8:
      return {{-1, -1, -1}, {1, -1, -1}, {1, 1, -1}, {-1, 1, -1},
              {-1, -1, 1},  {1, -1, 1},  {1, 1, 1},  {-1, 1, 1}};
    default: return {};
  }
}

void to3(const std::vector<double>& v, double x[3]) {
  x[0] = x[1] = x[2] = 0.0;
  for (size_t d = 0; d < v.size(); ++d) x[d] = v[d];
}

// A few interior sample points of the reference cell.
std::vector<std::vector<double>> samples(CellType t) {
  if (is_simplex(t)) {
    if (cell_dim(t) == 2) return {{0.2, 0.3}, {0.1, 0.7}, {0.6, 0.15}, {1.0 / 3, 1.0 / 3}};
    return {{0.2, 0.3, 0.1}, {0.1, 0.1, 0.7}, {0.5, 0.15, 0.25}, {0.25, 0.25, 0.25}};
  }
  switch (cell_dim(t)) {
    case 1: return {{-0.7}, {0.1}, {0.55}};
    case 2: return {{-0.3, 0.4}, {0.8, -0.6}, {0.1, 0.9}, {0, 0}};
    default: return {{-0.3, 0.4, 0.2}, {0.8, -0.6, -0.9}, {0.1, 0.9, 0.5}, {0, 0, 0}};
  }
}

// Complete polynomial of degree `order` in dim variables (fixed random-ish coefficients).
double poly(int order, const double x[3]) {
  const double l = 0.7 - 1.3 * x[0] + 2.1 * x[1] - 0.4 * x[2];
  if (order == 1) return l;
  return l + 0.9 * x[0] * x[0] - 1.7 * x[0] * x[1] + 0.6 * x[1] * x[1] + 1.1 * x[0] * x[2] - 0.8 * x[1] * x[2] +
         1.4 * x[2] * x[2];
}

double factorial(int n) {
  double r = 1.0;
  for (int k = 2; k <= n; ++k) r *= k;
  return r;
}

double exact_monomial(CellType t, const int e[3]) {
  const int dim = cell_dim(t);
  if (is_simplex(t)) return factorial(e[0]) * factorial(e[1]) * factorial(e[2]) / factorial(e[0] + e[1] + e[2] + dim);
  double r = 1.0;
  for (int d = 0; d < dim; ++d) r *= (e[d] % 2) ? 0.0 : 2.0 / (e[d] + 1);
  return r;
}

double ref_measure(CellType t) {
  switch (t) {
    case CellType::Line2:
    case CellType::Line3: return 2.0;
    case CellType::Quad4:
    case CellType::Quad8: return 4.0;
    case CellType::Hex8: return 8.0;
    case CellType::Tri3:
    case CellType::Tri6: return 0.5;
    case CellType::Tet4:
    case CellType::Tet10: return 1.0 / 6.0;
    default: return 1.0;
  }
}

}  // namespace

TEST(CellType, Names) {
  EXPECT_STREQ(cell_name(CellType::Point1), "point1");
  EXPECT_STREQ(cell_name(CellType::Line2), "line2");
  EXPECT_STREQ(cell_name(CellType::Line3), "line3");
  EXPECT_STREQ(cell_name(CellType::Tri3), "tri3");
  EXPECT_STREQ(cell_name(CellType::Tri6), "tri6");
  EXPECT_STREQ(cell_name(CellType::Quad4), "quad4");
  EXPECT_STREQ(cell_name(CellType::Quad8), "quad8");
  EXPECT_STREQ(cell_name(CellType::Tet4), "tet4");
  EXPECT_STREQ(cell_name(CellType::Tet10), "tet10");
  EXPECT_STREQ(cell_name(CellType::Hex8), "hex8");
}

TEST(Shape, ReferenceNodesMatchGmsh) {
  for (CellType t : kShapeTypes) {
    SCOPED_TRACE(cell_name(t));
    const auto g = gmsh_nodes(t);
    ASSERT_EQ(static_cast<int>(g.size()), cell_num_nodes(t));
    double xi[kMaxCellNodes][3];
    reference_nodes(t, xi);
    for (int a = 0; a < cell_num_nodes(t); ++a) {
      double x[3];
      to3(g[a], x);
      for (int d = 0; d < 3; ++d) EXPECT_EQ(xi[a][d], x[d]) << "node " << a << " dir " << d;
    }
  }
}

TEST(Shape, KroneckerAtGmshNodes) {
  for (CellType t : kShapeTypes) {
    SCOPED_TRACE(cell_name(t));
    const auto g = gmsh_nodes(t);
    const int nn = cell_num_nodes(t);
    for (int b = 0; b < nn; ++b) {
      double x[3], N[kMaxCellNodes];
      to3(g[b], x);
      shape_functions(t, x, N, nullptr);
      for (int a = 0; a < nn; ++a) EXPECT_NEAR(N[a], a == b ? 1.0 : 0.0, 1e-14) << "N_" << a << " at node " << b;
    }
  }
}

TEST(Shape, PartitionOfUnityAndGradientSum) {
  for (CellType t : kShapeTypes) {
    SCOPED_TRACE(cell_name(t));
    const int nn = cell_num_nodes(t);
    for (const auto& s : samples(t)) {
      double x[3], N[kMaxCellNodes], dN[kMaxCellNodes][3];
      to3(s, x);
      shape_functions(t, x, N, dN);
      double sum = 0.0, dsum[3] = {0, 0, 0};
      for (int a = 0; a < nn; ++a) {
        sum += N[a];
        for (int d = 0; d < 3; ++d) dsum[d] += dN[a][d];
        for (int d = cell_dim(t); d < 3; ++d) EXPECT_EQ(dN[a][d], 0.0);
      }
      EXPECT_NEAR(sum, 1.0, 1e-14);
      for (int d = 0; d < 3; ++d) EXPECT_NEAR(dsum[d], 0.0, 1e-14);
    }
  }
}

TEST(Shape, GradientsMatchFiniteDifferences) {
  const double h = 1e-6;
  for (CellType t : kShapeTypes) {
    SCOPED_TRACE(cell_name(t));
    const int nn = cell_num_nodes(t), dim = cell_dim(t);
    for (const auto& s : samples(t)) {
      double x[3], dN[kMaxCellNodes][3];
      to3(s, x);
      shape_functions(t, x, nullptr, dN);
      for (int d = 0; d < dim; ++d) {
        double xp[3] = {x[0], x[1], x[2]}, xm[3] = {x[0], x[1], x[2]};
        xp[d] += h;
        xm[d] -= h;
        double Np[kMaxCellNodes], Nm[kMaxCellNodes];
        shape_functions(t, xp, Np, nullptr);
        shape_functions(t, xm, Nm, nullptr);
        for (int a = 0; a < nn; ++a) EXPECT_NEAR(dN[a][d], (Np[a] - Nm[a]) / (2 * h), 1e-8) << "a=" << a << " d=" << d;
      }
    }
  }
}

TEST(Shape, PolynomialReproduction) {
  for (CellType t : kShapeTypes) {
    SCOPED_TRACE(cell_name(t));
    const int nn = cell_num_nodes(t), dim = cell_dim(t), order = cell_order(t);
    const auto g = gmsh_nodes(t);
    for (const auto& s : samples(t)) {
      double x[3], N[kMaxCellNodes], dN[kMaxCellNodes][3];
      to3(s, x);
      shape_functions(t, x, N, dN);
      double v = 0.0, dv[3] = {0, 0, 0};
      for (int a = 0; a < nn; ++a) {
        double xa[3];
        to3(g[a], xa);
        const double p = poly(order, xa);
        v += p * N[a];
        for (int d = 0; d < 3; ++d) dv[d] += p * dN[a][d];
      }
      // restrict the exact polynomial to the cell's dimension (coordinates beyond dim are 0)
      EXPECT_NEAR(v, poly(order, x), 1e-13);
      const double h = 1e-6;
      for (int d = 0; d < dim; ++d) {
        double xp[3] = {x[0], x[1], x[2]}, xm[3] = {x[0], x[1], x[2]};
        xp[d] += h;
        xm[d] -= h;
        EXPECT_NEAR(dv[d], (poly(order, xp) - poly(order, xm)) / (2 * h), 1e-8);
      }
    }
  }
}

TEST(Shape, PointCell) {
  double x[3] = {0, 0, 0}, N[1], dN[1][3];
  shape_functions(CellType::Point1, x, N, dN);
  EXPECT_EQ(N[0], 1.0);
  EXPECT_EQ(dN[0][0], 0.0);
}

TEST(Quadrature, WeightsAndMonomialExactness) {
  for (CellType t : kShapeTypes) {
    SCOPED_TRACE(cell_name(t));
    const int dim = cell_dim(t);
    for (int deg = 0; deg <= kMaxQuadDegree; ++deg) {
      SCOPED_TRACE("degree " + std::to_string(deg));
      double xi[kMaxQuadPoints][3], w[kMaxQuadPoints];
      const int nq = quadrature(t, deg, xi, w);
      ASSERT_GT(nq, 0);
      ASSERT_LE(nq, kMaxQuadPoints);
      double wsum = 0.0;
      for (int q = 0; q < nq; ++q) {
        EXPECT_GT(w[q], 0.0);
        wsum += w[q];
        for (int d = dim; d < 3; ++d) EXPECT_EQ(xi[q][d], 0.0);
        // points inside the reference cell
        if (is_simplex(t)) {
          double s = 0.0;
          for (int d = 0; d < dim; ++d) {
            EXPECT_GT(xi[q][d], 0.0);
            s += xi[q][d];
          }
          EXPECT_LT(s, 1.0);
        } else {
          for (int d = 0; d < dim; ++d) EXPECT_LT(std::fabs(xi[q][d]), 1.0);
        }
      }
      EXPECT_NEAR(wsum, ref_measure(t), 1e-15 * ref_measure(t) * 4);
      const int emax1 = dim >= 2 ? deg : 0, emax2 = dim >= 3 ? deg : 0;
      for (int e0 = 0; e0 <= deg; ++e0)
        for (int e1 = 0; e1 <= emax1 && e0 + e1 <= deg; ++e1)
          for (int e2 = 0; e2 <= emax2 && e0 + e1 + e2 <= deg; ++e2) {
            const int e[3] = {e0, e1, e2};
            double s = 0.0;
            for (int q = 0; q < nq; ++q)
              s += w[q] * std::pow(xi[q][0], e0) * std::pow(xi[q][1], e1) * std::pow(xi[q][2], e2);
            EXPECT_NEAR(s, exact_monomial(t, e), 1e-14) << "x^" << e0 << " y^" << e1 << " z^" << e2;
          }
    }
    double xi[kMaxQuadPoints][3], w[kMaxQuadPoints];
    EXPECT_EQ(quadrature(t, kMaxQuadDegree + 1, xi, w), 0);
  }
}

TEST(Quadrature, PointCounts) {
  double xi[kMaxQuadPoints][3], w[kMaxQuadPoints];
  EXPECT_EQ(quadrature(CellType::Point1, 2, xi, w), 1);
  EXPECT_EQ(w[0], 1.0);
  EXPECT_EQ(quadrature(CellType::Line2, 1, xi, w), 1);
  EXPECT_EQ(quadrature(CellType::Line2, 3, xi, w), 2);
  EXPECT_EQ(quadrature(CellType::Line3, 4, xi, w), 3);
  EXPECT_EQ(quadrature(CellType::Quad4, 2, xi, w), 4);
  EXPECT_EQ(quadrature(CellType::Quad8, 4, xi, w), 9);
  EXPECT_EQ(quadrature(CellType::Hex8, 2, xi, w), 8);
  EXPECT_EQ(quadrature(CellType::Hex8, 5, xi, w), 27);
  EXPECT_EQ(quadrature(CellType::Tri3, 1, xi, w), 1);
  EXPECT_EQ(quadrature(CellType::Tri3, 2, xi, w), 3);
  EXPECT_EQ(quadrature(CellType::Tri6, 4, xi, w), 6);
  EXPECT_EQ(quadrature(CellType::Tri6, 5, xi, w), 7);
  EXPECT_EQ(quadrature(CellType::Tet4, 1, xi, w), 1);
  EXPECT_EQ(quadrature(CellType::Tet4, 2, xi, w), 4);
  EXPECT_EQ(quadrature(CellType::Tet10, 4, xi, w), 14);

  EXPECT_EQ(default_quadrature_degree(CellType::Hex8), 2);
  EXPECT_EQ(default_quadrature_degree(CellType::Quad4), 2);
  EXPECT_EQ(default_quadrature_degree(CellType::Tet4), 2);
  EXPECT_EQ(default_quadrature_degree(CellType::Tri3), 2);
  EXPECT_EQ(default_quadrature_degree(CellType::Tet10), 4);
  EXPECT_EQ(default_quadrature_degree(CellType::Tri6), 4);
  EXPECT_EQ(quadrature(CellType::Hex8, default_quadrature_degree(CellType::Hex8), xi, w), 8);
}

// Mass-matrix style check: int N_a N_b with a degree-2*order rule equals the degree-5 rule
// (exact for P1/P2 products and, per direction, for Q1 products). Quad8 products exceed
// total degree 4 and are skipped.
TEST(Quadrature, IntegratesShapeProductsExactly) {
  for (CellType t : kShapeTypes) {
    if (t == CellType::Quad8) continue;
    SCOPED_TRACE(cell_name(t));
    const int nn = cell_num_nodes(t);
    const int deg = 2 * cell_order(t);
    double xa[kMaxQuadPoints][3], wa[kMaxQuadPoints], xb[kMaxQuadPoints][3], wb[kMaxQuadPoints];
    const int na = quadrature(t, deg, xa, wa);
    const int nb = quadrature(t, kMaxQuadDegree, xb, wb);
    for (int a = 0; a < nn; ++a)
      for (int b = 0; b < nn; ++b) {
        double s1 = 0, s2 = 0, N[kMaxCellNodes];
        for (int q = 0; q < na; ++q) {
          shape_functions(t, xa[q], N, nullptr);
          s1 += wa[q] * N[a] * N[b];
        }
        for (int q = 0; q < nb; ++q) {
          shape_functions(t, xb[q], N, nullptr);
          s2 += wb[q] * N[a] * N[b];
        }
        EXPECT_NEAR(s1, s2, 1e-14);
      }
  }
}

namespace {

// Affine map X = A xi + c applied to the reference nodes of t (first dim coordinates).
void affine_nodes(CellType t, const double A[3][3], const double c[3], double X[kMaxCellNodes][3]) {
  double xi[kMaxCellNodes][3];
  reference_nodes(t, xi);
  const int dim = cell_dim(t);
  for (int a = 0; a < cell_num_nodes(t); ++a)
    for (int i = 0; i < 3; ++i) {
      X[a][i] = i < dim ? c[i] : 0.0;
      if (i < dim)
        for (int j = 0; j < dim; ++j) X[a][i] += A[i][j] * xi[a][j];
    }
}

double det(int dim, const double A[3][3]) {
  if (dim == 2) return A[0][0] * A[1][1] - A[0][1] * A[1][0];
  return A[0][0] * (A[1][1] * A[2][2] - A[1][2] * A[2][1]) - A[0][1] * (A[1][0] * A[2][2] - A[1][2] * A[2][0]) +
         A[0][2] * (A[1][0] * A[2][1] - A[1][1] * A[2][0]);
}

}  // namespace

TEST(Geometry, ReferenceGradientsOnAffineCells) {
  const double A[3][3] = {{1.7, 0.3, -0.2}, {-0.4, 1.1, 0.5}, {0.25, -0.35, 0.9}};
  const double c[3] = {0.3, -1.2, 2.5};
  const double g[3] = {0.8, -1.9, 0.45};  // u(X) = 0.6 + g . X
  const CellType types[] = {CellType::Tri3, CellType::Tri6, CellType::Quad4, CellType::Quad8,
                            CellType::Tet4, CellType::Tet10, CellType::Hex8};
  for (CellType t : types) {
    SCOPED_TRACE(cell_name(t));
    const int nn = cell_num_nodes(t), dim = cell_dim(t);
    double X[kMaxCellNodes][3];
    affine_nodes(t, A, c, X);
    for (const auto& s : samples(t)) {
      double x[3], dN[kMaxCellNodes][3], dNdX[kMaxCellNodes][3];
      to3(s, x);
      shape_functions(t, x, nullptr, dN);
      const double J = reference_gradients(dim, nn, X, dN, dNdX);
      EXPECT_NEAR(J, det(dim, A), 1e-13);
      double grad[3] = {0, 0, 0};
      for (int a = 0; a < nn; ++a) {
        double u = 0.6;
        for (int i = 0; i < dim; ++i) u += g[i] * X[a][i];
        for (int i = 0; i < 3; ++i) grad[i] += u * dNdX[a][i];
      }
      for (int i = 0; i < dim; ++i) EXPECT_NEAR(grad[i], g[i], 1e-12);
      for (int i = dim; i < 3; ++i) EXPECT_EQ(grad[i], 0.0);
      // sum_a X_a (x) dNdX_a = identity
      for (int i = 0; i < dim; ++i)
        for (int j = 0; j < dim; ++j) {
          double s2 = 0.0;
          for (int a = 0; a < nn; ++a) s2 += X[a][i] * dNdX[a][j];
          EXPECT_NEAR(s2, i == j ? 1.0 : 0.0, 1e-12);
        }
    }
  }
}

TEST(Geometry, ReferenceGradientsVolumeOfDistortedHex) {
  // Non-affine hex: volume = sum_q w_q det J. A trapezoidal prism (exact for trilinear maps).
  const double X[8][3] = {{0, 0, 0}, {2, 0, 0}, {1.5, 1, 0}, {0.5, 1, 0},
                          {0, 0, 3}, {2, 0, 3}, {1.5, 1, 3}, {0.5, 1, 3}};
  double xi[kMaxQuadPoints][3], w[kMaxQuadPoints];
  const int nq = quadrature(CellType::Hex8, 2, xi, w);
  double vol = 0.0;
  for (int q = 0; q < nq; ++q) {
    double dN[8][3], dNdX[8][3];
    shape_functions(CellType::Hex8, xi[q], nullptr, dN);
    const double J = reference_gradients(3, 8, X, dN, dNdX);
    EXPECT_GT(J, 0.0);
    vol += w[q] * J;
  }
  EXPECT_NEAR(vol, 0.5 * (2.0 + 1.0) * 1.0 * 3.0, 1e-13);
}

TEST(Geometry, ReferenceGradientsDegenerate) {
  const double X[3][3] = {{0, 0, 0}, {1, 1, 0}, {2, 2, 0}};  // collinear triangle
  double x[3] = {0.2, 0.2, 0}, dN[3][3], dNdX[3][3];
  shape_functions(CellType::Tri3, x, nullptr, dN);
  EXPECT_EQ(reference_gradients(2, 3, X, dN, dNdX), 0.0);
  for (int a = 0; a < 3; ++a)
    for (int d = 0; d < 3; ++d) EXPECT_EQ(dNdX[a][d], 0.0);
}

TEST(Geometry, FacetNormalsUnitSquare2D) {
  // Counter-clockwise boundary of [0,2]x[0,1]: outward normals, lengths/2 as Jacobian.
  const double P[4][3] = {{0, 0, 0}, {2, 0, 0}, {2, 1, 0}, {0, 1, 0}};
  const double nexp[4][2] = {{0, -1}, {1, 0}, {0, 1}, {-1, 0}};
  const double len[4] = {2, 1, 2, 1};
  for (int e = 0; e < 4; ++e) {
    const double* p0 = P[e];
    const double* p1 = P[(e + 1) % 4];
    // line2
    {
      const double X[2][3] = {{p0[0], p0[1], 0}, {p1[0], p1[1], 0}};
      double x[3] = {0.3, 0, 0}, dN[2][3], n[3];
      shape_functions(CellType::Line2, x, nullptr, dN);
      const double m = facet_measure_and_normal(2, 2, X, dN, n);
      EXPECT_NEAR(m, len[e] / 2, 1e-15);
      EXPECT_NEAR(n[0], nexp[e][0], 1e-15);
      EXPECT_NEAR(n[1], nexp[e][1], 1e-15);
      EXPECT_EQ(n[2], 0.0);
    }
    // line3 (mid node at the midpoint): integrate the length with quadrature
    {
      const double X[3][3] = {{p0[0], p0[1], 0}, {p1[0], p1[1], 0}, {0.5 * (p0[0] + p1[0]), 0.5 * (p0[1] + p1[1]), 0}};
      double xi[kMaxQuadPoints][3], w[kMaxQuadPoints];
      const int nq = quadrature(CellType::Line3, 4, xi, w);
      double L = 0.0;
      for (int q = 0; q < nq; ++q) {
        double dN[3][3], n[3];
        shape_functions(CellType::Line3, xi[q], nullptr, dN);
        L += w[q] * facet_measure_and_normal(2, 3, X, dN, n);
        EXPECT_NEAR(n[0], nexp[e][0], 1e-14);
        EXPECT_NEAR(n[1], nexp[e][1], 1e-14);
      }
      EXPECT_NEAR(L, len[e], 1e-14);
    }
  }
}

TEST(Geometry, FacetNormalsCubeFace3D) {
  // Top face z = 1 of the unit cube, nodes counter-clockwise seen from outside (+z).
  {
    const double X[4][3] = {{0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
    double xi[kMaxQuadPoints][3], w[kMaxQuadPoints];
    const int nq = quadrature(CellType::Quad4, 2, xi, w);
    double area = 0.0;
    for (int q = 0; q < nq; ++q) {
      double dN[4][3], n[3];
      shape_functions(CellType::Quad4, xi[q], nullptr, dN);
      area += w[q] * facet_measure_and_normal(3, 4, X, dN, n);
      EXPECT_NEAR(n[0], 0.0, 1e-15);
      EXPECT_NEAR(n[1], 0.0, 1e-15);
      EXPECT_NEAR(n[2], 1.0, 1e-15);
    }
    EXPECT_NEAR(area, 1.0, 1e-14);
  }
  // Bottom face z = 0 seen from outside (-z): nodes (0,0),(0,1),(1,1),(1,0); tri3 halves.
  {
    const double X[3][3] = {{0, 0, 0}, {0, 1, 0}, {1, 1, 0}};
    double x[3] = {1.0 / 3, 1.0 / 3, 0}, dN[3][3], n[3];
    shape_functions(CellType::Tri3, x, nullptr, dN);
    const double m = facet_measure_and_normal(3, 3, X, dN, n);
    EXPECT_NEAR(m * 0.5, 0.5, 1e-15);  // reference triangle area 1/2
    EXPECT_NEAR(n[2], -1.0, 1e-15);
  }
  // Face x = 1 as tri6 (straight edges), outward +x.
  {
    const double V[3][3] = {{1, 0, 0}, {1, 1, 0}, {1, 1, 1}};
    double X[6][3];
    const int e[3][2] = {{0, 1}, {1, 2}, {2, 0}};
    for (int a = 0; a < 3; ++a)
      for (int i = 0; i < 3; ++i) X[a][i] = V[a][i];
    for (int k = 0; k < 3; ++k)
      for (int i = 0; i < 3; ++i) X[3 + k][i] = 0.5 * (V[e[k][0]][i] + V[e[k][1]][i]);
    double xi[kMaxQuadPoints][3], w[kMaxQuadPoints];
    const int nq = quadrature(CellType::Tri6, 4, xi, w);
    double area = 0.0;
    for (int q = 0; q < nq; ++q) {
      double dN[6][3], n[3];
      shape_functions(CellType::Tri6, xi[q], nullptr, dN);
      area += w[q] * facet_measure_and_normal(3, 6, X, dN, n);
      EXPECT_NEAR(n[0], 1.0, 1e-14);
      EXPECT_NEAR(n[1], 0.0, 1e-14);
      EXPECT_NEAR(n[2], 0.0, 1e-14);
    }
    EXPECT_NEAR(area, 0.5, 1e-14);
  }
}
