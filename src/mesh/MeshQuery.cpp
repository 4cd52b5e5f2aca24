#include "mesh/MeshQuery.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

#include "deck/Config.hpp"
#include "fem/Quadrature.hpp"
#include "fem/Shape.hpp"

namespace stentor {
namespace {

std::string join(const std::vector<std::string>& v) {
  if (v.empty()) return "(none)";
  std::string s;
  for (std::size_t i = 0; i < v.size(); ++i) s += (i ? ", " : "") + v[i];
  return s;
}

std::vector<const CellBlock*> blocks_named(const std::vector<CellBlock>& blocks, const std::string& g) {
  std::vector<const CellBlock*> out;
  for (const auto& b : blocks)
    if (b.name == g) out.push_back(&b);
  return out;
}

[[noreturn]] void not_found(const Mesh& m, const std::string& group, bool boundary, const std::string& prefix = "") {
  std::string msg = prefix + "physical group '" + group + "' not found in mesh " + m.source + "; available " +
                    (boundary ? "boundary" : "volume") + " groups: " +
                    join(boundary ? m.boundary_group_names() : m.volume_group_names());
  const bool other = boundary ? has_volume_group(m, group) : has_boundary_group(m, group);
  if (other) msg += std::string(" ('") + group + "' is a " + (boundary ? "body (volume) group" : "boundary group") + ")";
  throw InputError(msg);
}

std::vector<GId> nodes_of(const std::vector<const CellBlock*>& blocks) {
  std::vector<GId> n;
  for (const auto* b : blocks) n.insert(n.end(), b->conn.begin(), b->conn.end());
  std::sort(n.begin(), n.end());
  n.erase(std::unique(n.begin(), n.end()), n.end());
  return n;
}

}  // namespace

void require_group(const Mesh& m, const std::string& group, bool boundary, const std::string& parameter) {
  if (boundary ? has_boundary_group(m, group) : has_volume_group(m, group)) return;
  not_found(m, group, boundary, "'" + parameter + "' = '" + group + "': ");
}

bool has_volume_group(const Mesh& m, const std::string& group) { return !blocks_named(m.volumes, group).empty(); }
bool has_boundary_group(const Mesh& m, const std::string& group) {
  return !blocks_named(m.boundaries, group).empty();
}

std::vector<const CellBlock*> volume_blocks(const Mesh& m, const std::string& group) {
  auto b = blocks_named(m.volumes, group);
  if (b.empty()) not_found(m, group, false);
  return b;
}

std::vector<const CellBlock*> boundary_blocks(const Mesh& m, const std::string& group) {
  auto b = blocks_named(m.boundaries, group);
  if (b.empty()) not_found(m, group, true);
  return b;
}

std::vector<GId> boundary_nodes(const Mesh& m, const std::string& group) {
  return nodes_of(boundary_blocks(m, group));
}

std::vector<GId> volume_nodes(const Mesh& m, const std::string& group) { return nodes_of(volume_blocks(m, group)); }

namespace {
// tributary_areas(_by): the facets' HRZ shares, each facet's into the map of its class.
void add_tributary_areas(const Mesh& mesh, const std::string& group, bool axisymmetric,
                         const std::function<int(const double*)>& classify, std::vector<std::map<GId, double>>& area) {
  for (const CellBlock* b : boundary_blocks(mesh, group)) {
    if (cell_dim(b->type) != mesh.dim - 1) continue;
    const int nn = b->nodes_per_cell;
    // Degree 4: N_a^2 of a quadratic facet, exactly (3 Gauss points per direction, 6 on a triangle).
    double qp[kMaxQuadPoints][3], qw[kMaxQuadPoints];
    const int nq = quadrature(b->type, 4, qp, qw);
    for (std::size_t f = 0; f < b->num_cells(); ++f) {
      double centroid[3] = {0, 0, 0};
      for (int a = 0; a < nn; ++a)
        for (int c = 0; c < 3; ++c) centroid[c] += mesh.coord(b->conn[f * nn + a])[c] / nn;
      const int cls = classify ? classify(centroid) : 0;
      if (cls < 0 || cls >= static_cast<int>(area.size())) continue;
      std::vector<double> m2(static_cast<std::size_t>(nn), 0.0);
      double A = 0.0;
      for (int q = 0; q < nq; ++q) {
        double N[kMaxCellNodes], dN[kMaxCellNodes][3];
        shape_functions(b->type, qp[q], N, dN);
        double t1[3] = {0, 0, 0}, t2[3] = {0, 0, 0};
        for (int a = 0; a < nn; ++a)
          for (int c = 0; c < 3; ++c) {
            const double x = mesh.coord(b->conn[f * nn + a])[c];
            t1[c] += dN[a][0] * x;
            t2[c] += dN[a][1] * x;
          }
        double J = std::sqrt(t1[0] * t1[0] + t1[1] * t1[1] + t1[2] * t1[2]);
        if (axisymmetric) {
          double r = 0.0;
          for (int a = 0; a < nn; ++a) r += N[a] * mesh.coord(b->conn[f * nn + a])[0];
          J *= 2.0 * 3.14159265358979323846 * r;
        }
        if (mesh.dim == 3) {
          const double cr[3] = {t1[1] * t2[2] - t1[2] * t2[1], t1[2] * t2[0] - t1[0] * t2[2], t1[0] * t2[1] - t1[1] * t2[0]};
          J = std::sqrt(cr[0] * cr[0] + cr[1] * cr[1] + cr[2] * cr[2]);
        }
        A += qw[q] * J;
        for (int a = 0; a < nn; ++a) m2[static_cast<std::size_t>(a)] += qw[q] * J * N[a] * N[a];
      }
      double s = 0.0;
      for (double v : m2) s += v;
      for (int a = 0; a < nn; ++a) area[static_cast<std::size_t>(cls)][b->conn[f * nn + a]] += A * m2[static_cast<std::size_t>(a)] / s;
    }
  }
}
}  // namespace

std::map<GId, double> tributary_areas(const Mesh& mesh, const std::string& group, bool axisymmetric) {
  std::vector<std::map<GId, double>> area(1);
  add_tributary_areas(mesh, group, axisymmetric, nullptr, area);
  return area[0];
}

std::vector<std::map<GId, double>> tributary_areas_by(const Mesh& mesh, const std::string& group, int classes,
                                                      const std::function<int(const double*)>& classify) {
  std::vector<std::map<GId, double>> area(static_cast<std::size_t>(std::max(classes, 0)));
  add_tributary_areas(mesh, group, false, classify, area);
  return area;
}

std::map<GId, int> surface_parts(const Mesh& mesh, const std::string& group) {
  std::map<GId, GId> up;  // union-find over node ids
  auto root = [&up](GId g) {
    GId r = g;
    while (up[r] != r) r = up[r];
    while (up[g] != r) g = std::exchange(up[g], r);
    return r;
  };
  for (const CellBlock* b : boundary_blocks(mesh, group)) {
    if (cell_dim(b->type) != mesh.dim - 1) continue;
    const auto nn = static_cast<std::size_t>(b->nodes_per_cell);
    for (std::size_t f = 0; f < b->num_cells(); ++f)
      for (std::size_t a = 0; a < nn; ++a) {
        const GId g = b->conn[f * nn + a];
        up.emplace(g, g);
        const GId r0 = root(b->conn[f * nn]), r1 = root(g);
        if (r0 != r1) up[std::max(r0, r1)] = std::min(r0, r1);  // a part's root is its smallest node
      }
  }
  std::map<GId, int> index, part;
  for (const auto& [g, parent] : up) {
    const GId r = root(g);
    part[g] = index.emplace(r, static_cast<int>(index.size())).first->second;  // roots meet in increasing order
  }
  return part;
}

}  // namespace stentor
