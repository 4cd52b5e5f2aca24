#include "contact/MasterSurface.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include "bc/Loads.hpp"
#include "deck/Config.hpp"

namespace stentor {

MasterSurface::MasterSurface(const Mesh& mesh, const std::string& group, const std::string& where) {
  for (const OrientedFacets& of : oriented_facets(mesh, group, where)) {
    if (!facet::supported(of.type))
      throw InputError(where + ": facets of type " + cell_name(of.type) + " in group '" + group +
                       "' are not supported as a master surface (line2, line3, tri3, tri6, quad4 are)");
    for (std::size_t f = 0; f < of.num_facets(); ++f) {
      Facet fc;
      fc.type = of.type;
      fc.nn = of.nodes_per_facet;
      fc.orient = of.orientation[f];
      for (int a = 0; a < fc.nn; ++a) {
        fc.gid[a] = of.conn[f * static_cast<std::size_t>(fc.nn) + static_cast<std::size_t>(a)];
        nodes_.push_back(fc.gid[a]);
      }
      facets_.push_back(fc);
    }
  }
  std::sort(nodes_.begin(), nodes_.end());
  nodes_.erase(std::unique(nodes_.begin(), nodes_.end()), nodes_.end());
  for (const Facet& fc : facets_) {
    double lo[3] = {1e300, 1e300, 1e300}, hi[3] = {-1e300, -1e300, -1e300};
    for (int a = 0; a < fc.nn; ++a)
      for (int c = 0; c < 3; ++c) {
        const double v = mesh.coord(fc.gid[a])[c];
        lo[c] = std::min(lo[c], v);
        hi[c] = std::max(hi[c], v);
      }
    for (int c = 0; c < 3; ++c) h_ = std::max(h_, hi[c] - lo[c]);
  }
}

void MasterSurface::index(const std::function<int(GId)>& node_pos) {
  for (auto& f : facets_)
    for (int a = 0; a < f.nn; ++a) f.node[a] = node_pos(f.gid[a]);
}

long long MasterSurface::key(const long long* i) {
  return ((i[0] & 0x1fffff) << 42) | ((i[1] & 0x1fffff) << 21) | (i[2] & 0x1fffff);
}

void MasterSurface::cell_of(const double* p, long long* i) const {
  for (int c = 0; c < 3; ++c) i[c] = static_cast<long long>(std::floor(p[c] / cell_));
}

void MasterSurface::build(const std::vector<double>& x, const std::vector<char>* present) {
  double hc = h_;
  std::vector<std::array<double, 3>> centre(facets_.size());
  std::vector<char> use(facets_.size(), 1);
  for (std::size_t f = 0; f < facets_.size(); ++f) {
    const Facet& fc = facets_[f];
    if (present)
      for (int a = 0; a < fc.nn; ++a) use[f] = use[f] && (*present)[static_cast<std::size_t>(fc.node[a])];
    if (!use[f]) continue;
    double lo[3] = {1e300, 1e300, 1e300}, hi[3] = {-1e300, -1e300, -1e300};
    for (int a = 0; a < fc.nn; ++a)
      for (int c = 0; c < 3; ++c) {
        const double v = x[3 * static_cast<std::size_t>(fc.node[a]) + static_cast<std::size_t>(c)];
        lo[c] = std::min(lo[c], v);
        hi[c] = std::max(hi[c], v);
      }
    for (int c = 0; c < 3; ++c) {
      centre[f][static_cast<std::size_t>(c)] = 0.5 * (lo[c] + hi[c]);
      hc = std::max(hc, hi[c] - lo[c]);
    }
  }
  cell_ = hc > 0.0 ? 3.0 * hc : 1.0;
  bins_.clear();
  for (std::size_t f = 0; f < facets_.size(); ++f) {
    if (!use[f]) continue;
    long long i[3];
    cell_of(centre[f].data(), i);
    bins_[key(i)].push_back(static_cast<int>(f));
  }
}

MasterSurface::Hit MasterSurface::on_facet(int f, int dim, const double xs[3], const std::vector<double>& x, double band) const {
  Hit hit;
  const Facet& fc = facets_[static_cast<std::size_t>(f)];
  double xa[facet::kMaxNodes][3];
  for (int a = 0; a < fc.nn; ++a)
    for (int c = 0; c < 3; ++c) xa[a][c] = x[3 * static_cast<std::size_t>(fc.node[a]) + static_cast<std::size_t>(c)];
  double xi[2];
  if (!facet::project(fc.type, fc.nn, dim, xa, xs, xi, band)) return hit;
  facet::Frame<double> fr;
  facet::frame(fc.type, fc.nn, dim, fc.orient, xa, xi, fr);
  double d2 = 0.0, d = 0.0;
  for (int c = 0; c < 3; ++c) {
    d2 += (xs[c] - fr.xm[c]) * (xs[c] - fr.xm[c]);
    d += fr.n[c] * (xs[c] - fr.xm[c]);
  }
  if (std::sqrt(d2) > search_radius() || d < -h_) return hit;
  hit.facet = f;
  hit.xi[0] = hit.xi_free[0] = xi[0], hit.xi[1] = hit.xi_free[1] = xi[1];
  hit.inside = true;
  hit.dist = std::sqrt(d2);
  return hit;
}

void MasterSurface::near(const double lo[3], const double hi[3], std::vector<int>& out) const {
  out.clear();
  double l[3], u[3];
  for (int c = 0; c < 3; ++c) l[c] = lo[c] - cell_, u[c] = hi[c] + cell_;
  long long a[3], b[3];
  cell_of(l, a);
  cell_of(u, b);
  for (long long i = a[0]; i <= b[0]; ++i)
    for (long long j = a[1]; j <= b[1]; ++j)
      for (long long k = a[2]; k <= b[2]; ++k) {
        const long long c[3] = {i, j, k};
        auto it = bins_.find(key(c));
        if (it != bins_.end()) out.insert(out.end(), it->second.begin(), it->second.end());
      }
}

MasterSurface::Hit MasterSurface::closest(int dim, const double xs[3], const std::vector<double>& x) const {
  Hit best;
  best.dist = 1e300;
  const double radius = search_radius();
  const int kz = dim == 3 ? 1 : 0;
  long long c0[3];
  cell_of(xs, c0);
  for (int i = -1; i <= 1; ++i)
    for (int j = -1; j <= 1; ++j)
      for (int k = -kz; k <= kz; ++k) {
        // Neighbouring bins by index (offsetting the point by one spacing can round into
        // the same bin and skip its neighbour).
        const long long c[3] = {c0[0] + i, c0[1] + j, c0[2] + k};
        auto it = bins_.find(key(c));
        if (it == bins_.end()) continue;
        for (int f : it->second) {
          const Facet& fc = facets_[static_cast<std::size_t>(f)];
          double xa[facet::kMaxNodes][3];
          for (int a = 0; a < fc.nn; ++a)
            for (int c = 0; c < 3; ++c) xa[a][c] = x[3 * static_cast<std::size_t>(fc.node[a]) + static_cast<std::size_t>(c)];
          double xi[2], xi_free[2];
          const bool inside = facet::project(fc.type, fc.nn, dim, xa, xs, xi, 0.0, xi_free);
          facet::Frame<double> fr;
          facet::frame(fc.type, fc.nn, dim, fc.orient, xa, xi, fr);
          double d2 = 0.0;
          for (int c = 0; c < 3; ++c) d2 += (xs[c] - fr.xm[c]) * (xs[c] - fr.xm[c]);
          const double dist = std::sqrt(d2);
          if (dist > radius) continue;
          // A point more than h behind the facet is on the far side of its body, not in contact.
          const double d = fr.n[0] * (xs[0] - fr.xm[0]) + fr.n[1] * (xs[1] - fr.xm[1]) + fr.n[2] * (xs[2] - fr.xm[2]);
          if (d < -h_) continue;
          // The nearest; at equal distance (a shared node) a projection inside the facet wins,
          // then the lower facet index (not the visiting order, which depends on the bins).
          const double tol = 1e-10 * h_;
          const bool tie = dist <= best.dist + tol && inside == best.inside;
          const bool better = dist < best.dist - tol || (dist <= best.dist + tol && inside && !best.inside) || (tie && f < best.facet);
          if (better) {
            best.facet = f;
            best.xi[0] = xi[0], best.xi[1] = xi[1];
            best.xi_free[0] = xi_free[0], best.xi_free[1] = xi_free[1];
            best.inside = inside;
            best.dist = dist;
          }
        }
      }
  return best;
}

}  // namespace stentor
