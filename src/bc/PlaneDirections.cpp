#include "bc/PlaneDirections.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

namespace stentor {
namespace {

// The rows j_0..j_{m-1} among the free components that maximise |det e_i(j_l)|.
void choose_rows(int dim, const bool* fixed, int m, const double (*e)[3], int* j) {
  double best = -1.0;
  int free_c[3], nf = 0;
  for (int c = 0; c < dim; ++c)
    if (!fixed[c]) free_c[nf++] = c;
  auto det = [&](const int* r) {
    if (m == 1) return std::abs(e[0][r[0]]);
    if (m == 2) return std::abs(e[0][r[0]] * e[1][r[1]] - e[0][r[1]] * e[1][r[0]]);
    return std::abs(e[0][r[0]] * (e[1][r[1]] * e[2][r[2]] - e[1][r[2]] * e[2][r[1]]) -
                    e[0][r[1]] * (e[1][r[0]] * e[2][r[2]] - e[1][r[2]] * e[2][r[0]]) +
                    e[0][r[2]] * (e[1][r[0]] * e[2][r[1]] - e[1][r[1]] * e[2][r[0]]));
  };
  // Ordered choices of m distinct free components (at most 3! = 6).
  int r[3];
  for (int a = 0; a < nf; ++a)
    for (int b = 0; b < (m > 1 ? nf : 1); ++b)
      for (int c = 0; c < (m > 2 ? nf : 1); ++c) {
        if ((m > 1 && b == a) || (m > 2 && (c == a || c == b))) continue;
        r[0] = free_c[a], r[1] = free_c[b], r[2] = free_c[c];
        const double d = det(r);
        if (d > best) best = d, j[0] = r[0], j[1] = r[1], j[2] = r[2];
      }
}

}  // namespace

PlaneDirections plane_directions(const Loads& loads, GId g, const bool fixed[3], int dim) {
  std::vector<int> sets;
  for (std::size_t s = 0; s < loads.dirichlet.size(); ++s) {
    const DirichletSet& d = loads.dirichlet[s];
    if (!d.normal || !std::binary_search(d.nodes.begin(), d.nodes.end(), g)) continue;
    for (auto it = sets.begin(); it != sets.end(); ++it) {
      const auto& o = loads.dirichlet[static_cast<std::size_t>(*it)].n;
      if (std::abs(o[0] * d.n[0] + o[1] * d.n[1] + o[2] * d.n[2]) > 1.0 - 1e-9) {
        sets.erase(it);
        break;
      }
    }
    sets.push_back(static_cast<int>(s));
  }
  PlaneDirections p;
  for (int s : sets) {
    const DirichletSet& d = loads.dirichlet[static_cast<std::size_t>(s)];
    double v[3] = {0, 0, 0};
    for (int c = 0; c < dim; ++c) v[c] = fixed[c] ? 0.0 : d.n[static_cast<std::size_t>(c)];
    for (int i = 0; i < p.m; ++i) {
      const double a = v[0] * p.e[i][0] + v[1] * p.e[i][1] + v[2] * p.e[i][2];
      for (int c = 0; c < 3; ++c) v[c] -= a * p.e[i][c];
    }
    const double len = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    if (!(len > 1e-6)) continue;  // prescribed already by the Cartesian components or the other planes
    for (int c = 0; c < 3; ++c) p.e[p.m][c] = v[c] / len, p.n[p.m][c] = d.n[static_cast<std::size_t>(c)];
    p.set[p.m++] = s;
  }
  if (p.m > 0) choose_rows(dim, fixed, p.m, p.e, p.j);
  return p;
}

}  // namespace stentor
