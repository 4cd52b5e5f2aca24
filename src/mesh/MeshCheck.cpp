#include "mesh/MeshCheck.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <sstream>

#include "deck/Config.hpp"
#include "fem/Geometry.hpp"
#include "fem/Shape.hpp"

namespace stentor {
namespace {

// Is cell c of block b inverted or degenerate? Evaluates det J at every
// reference node and at the reference centroid.
bool cell_inverted(const Mesh& m, const CellBlock& b, std::size_t c) {
  const int nn = b.nodes_per_cell;
  double X[kMaxCellNodes][3], xi[kMaxCellNodes + 1][3];
  double dN[kMaxCellNodes][3], dNdX[kMaxCellNodes][3];
  double lo[3] = {1e300, 1e300, 1e300}, hi[3] = {-1e300, -1e300, -1e300};
  for (int a = 0; a < nn; ++a) {
    const GId n = b.conn[c * nn + a];
    for (int d = 0; d < 3; ++d) {
      X[a][d] = m.x[3 * n + d];
      lo[d] = std::min(lo[d], X[a][d]);
      hi[d] = std::max(hi[d], X[a][d]);
    }
  }
  double h2 = 0;
  for (int d = 0; d < m.dim; ++d) h2 += (hi[d] - lo[d]) * (hi[d] - lo[d]);
  const double tol = 1e-12 * std::pow(std::sqrt(h2), m.dim);

  reference_nodes(b.type, xi);
  // centroid of the reference cell
  double* cen = xi[nn];
  cen[0] = cen[1] = cen[2] = 0.0;
  switch (b.type) {
    case CellType::Tri3:
    case CellType::Tri6: cen[0] = cen[1] = 1.0 / 3.0; break;
    case CellType::Tet4:
    case CellType::Tet10: cen[0] = cen[1] = cen[2] = 0.25; break;
    default: break;  // quads/hexes: origin
  }
  for (int q = 0; q <= nn; ++q) {
    shape_functions(b.type, xi[q], nullptr, dN);
    const double det = reference_gradients(m.dim, nn, X, dN, dNdX);
    if (!(det > tol)) return true;  // also catches NaN
  }
  return false;
}

struct GroupReport {
  std::size_t bad = 0, total = 0;
  GId first_cell = -1;
  double at[3] = {0, 0, 0};
};

}  // namespace

std::size_t count_inverted_cells(const Mesh& m) {
  std::size_t n = 0;
  for (const auto& b : m.volumes)
    for (std::size_t c = 0; c < b.num_cells(); ++c) n += cell_inverted(m, b, c) ? 1 : 0;
  return n;
}

void check_mesh(const Mesh& m) {
  std::vector<std::string> order;  // group names in block order
  std::map<std::string, GroupReport> rep;
  for (const auto& b : m.volumes) {
    if (!rep.count(b.name)) order.push_back(b.name);
    auto& r = rep[b.name];
    const int nn = b.nodes_per_cell;
    for (std::size_t c = 0; c < b.num_cells(); ++c) {
      ++r.total;
      if (!cell_inverted(m, b, c)) continue;
      if (r.bad++ == 0) {
        r.first_cell = c < b.cell_id.size() ? b.cell_id[c] : static_cast<GId>(c);
        for (int a = 0; a < nn; ++a)
          for (int d = 0; d < 3; ++d) r.at[d] += m.x[3 * b.conn[c * nn + a] + d] / nn;
      }
    }
  }
  std::vector<std::string> problems;
  for (const auto& name : order) {
    const auto& r = rep[name];
    if (!r.bad) continue;
    std::ostringstream os;
    os << r.bad << " inverted or degenerate element" << (r.bad > 1 ? "s" : "") << " (det J <= 0) in group '"
       << name << "', e.g. cell " << r.first_cell << " at (" << r.at[0] << ", " << r.at[1] << ", " << r.at[2]
       << ")";
    if (m.dim == 2 && r.bad == r.total)
      os << "; all " << r.total << " cells are inverted: the surface is probably oriented clockwise"
         << " (reverse its curve loop, e.g. 'Reverse Surface' in the .geo)";
    problems.push_back(os.str());
  }
  if (!problems.empty()) {
    std::string msg = m.source + ": ";
    for (std::size_t i = 0; i < problems.size(); ++i) msg += (i ? "; " : "") + problems[i];
    throw InputError(msg);
  }

  // Every boundary node must belong to a body cell (otherwise its dofs are free-floating).
  std::vector<char> in_body(m.num_nodes(), 0);
  for (const auto& b : m.volumes)
    for (GId n : b.conn) in_body[n] = 1;
  for (const auto& b : m.boundaries) {
    std::size_t orphans = 0;
    GId example = -1;
    for (GId n : b.conn)
      if (!in_body[n]) {
        if (orphans++ == 0) example = n;
      }
    if (orphans) {
      std::ostringstream os;
      os << m.source << ": boundary group '" << b.name << "' has nodes that belong to no body (physical "
         << (m.dim == 2 ? "surface" : "volume") << "), e.g. node " << example << " at (" << m.x[3 * example]
         << ", " << m.x[3 * example + 1] << ", " << m.x[3 * example + 2] << ")";
      throw InputError(os.str());
    }
  }
}

}  // namespace stentor
