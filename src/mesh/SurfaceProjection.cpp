#include "mesh/SurfaceProjection.hpp"

#include <algorithm>
#include <cmath>
#include <set>

#include "fem/Quadrature.hpp"
#include "fem/Shape.hpp"
#include "mesh/MeshQuery.hpp"

namespace stentor {

namespace {

// The vertex-only facet type with the same reference coordinates (line3 -> line2, tri6 ->
// tri3), and the vertex pair of each mid-edge node (gmsh order: line3 node 2 on (0, 1);
// tri6 nodes 3, 4, 5 on (0, 1), (1, 2), (2, 0)).
CellType vertex_type(CellType t) { return t == CellType::Line3 ? CellType::Line2 : t == CellType::Tri6 ? CellType::Tri3 : t; }
constexpr int kTri6Edges[3][2] = {{0, 1}, {1, 2}, {2, 0}};

// The area element |dx/dxi| of facet f (a length in 2D) from the derivatives dN of its own
// shape functions.
double area_element(const Mesh& mesh, const CellBlock& b, std::size_t f, const double (*dN)[3]) {
  const int nn = b.nodes_per_cell;
  double t1[3] = {0, 0, 0}, t2[3] = {0, 0, 0};
  for (int a = 0; a < nn; ++a)
    for (int c = 0; c < 3; ++c) {
      const double x = mesh.coord(b.conn[f * nn + a])[c];  // a boundary node: stored in any part
      t1[c] += dN[a][0] * x;
      t2[c] += dN[a][1] * x;
    }
  if (mesh.dim == 2) return std::sqrt(t1[0] * t1[0] + t1[1] * t1[1] + t1[2] * t1[2]);
  const double n[3] = {t1[1] * t2[2] - t1[2] * t2[1], t1[2] * t2[0] - t1[0] * t2[2], t1[0] * t2[1] - t1[1] * t2[0]};
  return std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
}

}  // namespace

SurfaceProjection::SurfaceProjection(const Mesh& mesh, const std::vector<std::string>& groups, bool axisymmetric) {
  std::vector<const CellBlock*> facets;
  std::set<GId> nodes;  // of every cell of the groups
  for (const std::string& g : std::set<std::string>(groups.begin(), groups.end()))
    for (const CellBlock* b : boundary_blocks(mesh, g)) {
      nodes.insert(b->conn.begin(), b->conn.end());
      if (cell_dim(b->type) == mesh.dim - 1) facets.push_back(b);
    }
  nodes_.assign(nodes.begin(), nodes.end());
  vertex_area_.assign(nodes_.size(), 0.0);
  edge_of_.assign(nodes_.size(), {-1, -1});
  for (const CellBlock* b : facets)
    for (std::size_t f = 0; f < b->num_cells(); ++f) add_facet(mesh, *b, f, axisymmetric);
}

// Facet f's share of its vertices' areas int L_v dA (with the facet's own, possibly
// curved, geometry; degree 4 is exact on straight facets), and its mid-edge nodes' edges.
// Axisymmetric: the revolved facet, dA = 2 pi r ds (r = x at the point).
void SurfaceProjection::add_facet(const Mesh& mesh, const CellBlock& b, std::size_t f, bool axisymmetric) {
  const int nn = b.nodes_per_cell;
  const CellType vt = vertex_type(b.type);
  const int nv = cell_num_nodes(vt);
  long at[kMaxCellNodes];
  for (int a = 0; a < nn; ++a) at[a] = index(b.conn[f * nn + a]);
  double qp[kMaxQuadPoints][3], qw[kMaxQuadPoints];
  const int nq = quadrature(b.type, 4, qp, qw);
  for (int q = 0; q < nq; ++q) {
    double N[kMaxCellNodes], dN[kMaxCellNodes][3], L[kMaxCellNodes];
    shape_functions(b.type, qp[q], N, dN);
    shape_functions(vt, qp[q], L, nullptr);
    double w = qw[q] * area_element(mesh, b, f, dN);
    if (axisymmetric) {
      double r = 0.0;
      for (int a = 0; a < nn; ++a) r += N[a] * mesh.coord(b.conn[f * nn + a])[0];
      w *= 2.0 * 3.14159265358979323846 * r;
    }
    for (int v = 0; v < nv; ++v) vertex_area_[static_cast<std::size_t>(at[v])] += w * L[v];
  }
  if (b.type == CellType::Line3) edge_of_[static_cast<std::size_t>(at[2])] = {at[0], at[1]};
  if (b.type == CellType::Tri6)
    for (int e = 0; e < 3; ++e) edge_of_[static_cast<std::size_t>(at[3 + e])] = {at[kTri6Edges[e][0]], at[kTri6Edges[e][1]]};
}

long SurfaceProjection::index(GId g) const {
  const auto it = std::lower_bound(nodes_.begin(), nodes_.end(), g);
  return it != nodes_.end() && *it == g ? static_cast<long>(it - nodes_.begin()) : -1;
}

std::vector<double> SurfaceProjection::project(const std::vector<double>& f, int k) const {
  const std::size_t n = nodes_.size(), K = static_cast<std::size_t>(k);
  std::vector<double> ft(n * K, 0.0), p(n * K, 0.0);
  // f~_v: the vertex's own force plus half of each neighbouring mid-edge node's.
  for (std::size_t i = 0; i < n; ++i) {
    const auto [v, w] = edge_of_[i];
    for (std::size_t c = 0; c < K; ++c) {
      if (v < 0) {
        ft[i * K + c] += f[i * K + c];
        continue;
      }
      ft[static_cast<std::size_t>(v) * K + c] += 0.5 * f[i * K + c];
      ft[static_cast<std::size_t>(w) * K + c] += 0.5 * f[i * K + c];
    }
  }
  for (std::size_t i = 0; i < n; ++i)
    if (vertex_area_[i] > 0.0)
      for (std::size_t c = 0; c < K; ++c) p[i * K + c] = ft[i * K + c] / vertex_area_[i];
  for (std::size_t i = 0; i < n; ++i) {
    const auto [v, w] = edge_of_[i];
    if (v >= 0)
      for (std::size_t c = 0; c < K; ++c) p[i * K + c] = 0.5 * (p[static_cast<std::size_t>(v) * K + c] + p[static_cast<std::size_t>(w) * K + c]);
  }
  return p;
}

}  // namespace stentor
