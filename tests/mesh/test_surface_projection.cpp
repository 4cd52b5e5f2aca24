// mesh/SurfaceProjection.hpp: nodal forces to a traction (lumped projection onto the
// facets' piecewise-linear vertex field). On tri3 and tri6 facets in 3D (an irregular
// triangulation: the facets differ in size) and line2 and line3 facets in 2D (a curve):
//   - a uniform traction comes back exactly at every node from its consistent nodal forces;
//   - on P2 facets the result equals the P1 facets' of the same vertices (f~_v = the P1
//     consistent forces), for a traction linear in x;
//   - a traction that stops abruptly (>= 0) gives no negative value anywhere;
//   - a lone point of the group gets 0; k components are kept apart.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <utility>

#include "fem/Quadrature.hpp"
#include "fem/Shape.hpp"
#include "mesh/SurfaceProjection.hpp"

using namespace stentor;

namespace {

double linear(const double* x) { return 3.0 + 2.0 * x[0] - 1.5 * x[1] + 0.5 * x[2]; }
double uniform(const double*) { return 7.0; }
double step(const double* x) { return x[0] < 1.45 ? 2.0 : 0.0; }

// Facets of P1 cells (tri3 in 3D: a 3 x 2 grid of squares in the plane z = 0.1 x, split
// into triangles, one vertex moved; line2 in 2D: 5 segments of different lengths), raised
// to P2 by mid-edge nodes when order = 2; and a lone point (node `lone`) in the same group.
Mesh surface(int dim, int order, GId& lone) {
  Mesh m;
  m.dim = dim;
  std::vector<std::vector<GId>> cells;
  auto add_node = [&](double x, double y, double z) {
    m.x.insert(m.x.end(), {x, y, z});
    return static_cast<GId>(m.num_nodes() - 1);
  };
  if (dim == 3) {
    for (int j = 0; j <= 2; ++j)
      for (int i = 0; i <= 3; ++i) {
        const double x = i + (i == 1 && j == 1 ? 0.3 : 0.0), y = j + (i == 1 && j == 1 ? -0.2 : 0.0);
        add_node(x, y, 0.1 * x);
      }
    for (int j = 0; j < 2; ++j)
      for (int i = 0; i < 3; ++i) {
        const GId a = j * 4 + i, b = a + 1, c = a + 5, d = a + 4;
        cells.push_back({a, b, c});
        cells.push_back({a, c, d});
      }
  } else {
    const double xs[6] = {0.0, 0.4, 1.0, 1.3, 2.2, 2.5};
    for (double x : xs) add_node(x, 0.2 * x * x, 0.0);
    for (GId a = 0; a < 5; ++a) cells.push_back({a, a + 1});
  }
  CellBlock b;
  b.name = "surf";
  const int nv = dim == 3 ? 3 : 2;
  b.type = dim == 3 ? (order == 2 ? CellType::Tri6 : CellType::Tri3) : (order == 2 ? CellType::Line3 : CellType::Line2);
  b.nodes_per_cell = cell_num_nodes(b.type);
  std::map<std::pair<GId, GId>, GId> mid;
  for (const auto& c : cells) {
    b.conn.insert(b.conn.end(), c.begin(), c.end());
    if (order == 1) continue;
    // gmsh order: tri6 edges (0,1), (1,2), (2,0); line3 the middle node last.
    for (int e = 0; e < (nv == 3 ? 3 : 1); ++e) {
      const GId p = c[static_cast<std::size_t>(e)], q = c[static_cast<std::size_t>((e + 1) % nv)];
      const auto key = std::minmax(p, q);
      auto it = mid.find(key);
      if (it == mid.end()) {
        const double* xp = &m.x[3 * static_cast<std::size_t>(p)];
        const double* xq = &m.x[3 * static_cast<std::size_t>(q)];
        it = mid.emplace(key, add_node(0.5 * (xp[0] + xq[0]), 0.5 * (xp[1] + xq[1]), 0.5 * (xp[2] + xq[2]))).first;
      }
      b.conn.push_back(it->second);
    }
  }
  m.boundaries.push_back(b);
  CellBlock pt;
  pt.name = "surf";
  pt.type = CellType::Point1;
  pt.nodes_per_cell = 1;
  lone = add_node(9.0, 9.0, 0.0);
  pt.conn = {lone};
  m.boundaries.push_back(pt);
  return m;
}

// f_a = int N_a t dA over the group's facets (degree 4: exact for N_a t, t linear, on
// straight facets; for `step` a quadrature of the step like any other).
std::vector<double> consistent_forces(const Mesh& m, const SurfaceProjection& s, double (*traction)(const double*)) {
  std::vector<double> f(s.nodes().size(), 0.0);
  const CellBlock& b = m.boundaries[0];
  const int nn = b.nodes_per_cell;
  double qp[kMaxQuadPoints][3], qw[kMaxQuadPoints];
  const int nq = quadrature(b.type, 4, qp, qw);
  for (std::size_t c = 0; c < b.num_cells(); ++c)
    for (int q = 0; q < nq; ++q) {
      double N[kMaxCellNodes], dN[kMaxCellNodes][3], x[3] = {0, 0, 0}, t1[3] = {0, 0, 0}, t2[3] = {0, 0, 0};
      shape_functions(b.type, qp[q], N, dN);
      for (int a = 0; a < nn; ++a)
        for (int k = 0; k < 3; ++k) {
          const double xa = m.x[3 * static_cast<std::size_t>(b.conn[c * nn + a]) + k];
          x[k] += N[a] * xa, t1[k] += dN[a][0] * xa, t2[k] += dN[a][1] * xa;
        }
      const double n[3] = {t1[1] * t2[2] - t1[2] * t2[1], t1[2] * t2[0] - t1[0] * t2[2], t1[0] * t2[1] - t1[1] * t2[0]};
      const double J = m.dim == 2 ? std::sqrt(t1[0] * t1[0] + t1[1] * t1[1]) : std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
      for (int a = 0; a < nn; ++a) f[static_cast<std::size_t>(s.index(b.conn[c * nn + a]))] += qw[q] * J * N[a] * traction(x);
    }
  return f;
}

// Projects `traction` on the group's facets (order 1 or 2), two components (t and 2 t);
// returns the first, per node of the mesh (0 at the lone point, which is checked here).
std::vector<double> project(int dim, int order, double (*traction)(const double*)) {
  GId lone = -1;
  const Mesh m = surface(dim, order, lone);
  const SurfaceProjection s(m, {"surf", "surf"});
  EXPECT_EQ(s.nodes().size(), m.num_nodes());
  EXPECT_EQ(s.index(1000), -1);
  std::vector<double> f2;
  for (double v : consistent_forces(m, s, traction)) f2.insert(f2.end(), {v, 2.0 * v});
  const std::vector<double> p2 = s.project(f2, 2);
  std::vector<double> p(m.num_nodes());
  for (GId g : s.nodes()) {
    const auto i = static_cast<std::size_t>(s.index(g));
    EXPECT_EQ(p2[2 * i + 1], 2.0 * p2[2 * i]);
    p[static_cast<std::size_t>(g)] = p2[2 * i];
  }
  EXPECT_EQ(p[static_cast<std::size_t>(lone)], 0.0);
  p.pop_back();  // the lone point, last
  return p;
}

}  // namespace

TEST(SurfaceProjection, UniformTractionExactAtEveryNode) {
  for (int dim : {2, 3})
    for (int order : {1, 2}) {
      double worst = 0.0;
      for (double v : project(dim, order, uniform)) worst = std::max(worst, std::abs(v - 7.0));
      std::printf("dim %d order %d: max |p - t| %.2e\n", dim, order, worst);
      EXPECT_LT(worst, 1e-13) << "dim " << dim << " order " << order;
    }
}

TEST(SurfaceProjection, P2FacetsGiveTheP1VertexValuesInterpolated) {
  for (int dim : {2, 3}) {
    const std::vector<double> p1 = project(dim, 1, linear), p2 = project(dim, 2, linear);
    GId lone = -1;
    const Mesh m2 = surface(dim, 2, lone);
    ASSERT_LT(p1.size(), p2.size());
    // The vertices come first in both meshes: the same values.
    for (std::size_t v = 0; v < p1.size(); ++v) EXPECT_NEAR(p2[v], p1[v], 1e-13 * std::abs(p1[v])) << "dim " << dim << " vertex " << v;
    // Each mid-edge node: the mean of its edge's two vertices.
    const CellBlock& b = m2.boundaries[0];
    const int nn = b.nodes_per_cell;
    const int tri6[3][3] = {{3, 0, 1}, {4, 1, 2}, {5, 2, 0}}, line3[3] = {2, 0, 1};  // (mid, v, w)
    for (std::size_t c = 0; c < b.num_cells(); ++c)
      for (int e = 0; e < (dim == 3 ? 3 : 1); ++e) {
        const int* E = dim == 3 ? tri6[e] : line3;
        const auto at = [&](int a) { return static_cast<std::size_t>(b.conn[c * nn + a]); };
        EXPECT_NEAR(p2[at(E[0])], 0.5 * (p2[at(E[1])] + p2[at(E[2])]), 1e-13 * std::abs(p2[at(E[0])])) << "dim " << dim;
      }
  }
}

TEST(SurfaceProjection, NoNegativeValueNextToAStep) {
  for (int dim : {2, 3})
    for (int order : {1, 2}) {
      const std::vector<double> p = project(dim, order, step);
      double lo = 1e300, hi = 0.0;
      for (double v : p) lo = std::min(lo, v), hi = std::max(hi, v);
      std::printf("dim %d order %d, step 2 -> 0: p in [%g, %g]\n", dim, order, lo, hi);
      EXPECT_GE(lo, 0.0);
      EXPECT_LE(hi, 2.0 + 1e-12);
    }
}
