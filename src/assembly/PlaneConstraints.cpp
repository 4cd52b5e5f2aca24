// Dirichlet sets with `components` = normal: a node that may slide in a plane at any angle
// (a roller, or the symmetry plane of a sector), e . u = g(t) with e the plane's unit normal.
//
// A node on m planes (an edge: 2, a corner: 3) gets m orthonormal constraint directions
// e_i: the planes' normals with the node's Cartesian-prescribed components removed (those
// rows stay identity rows), Gram-Schmidt, a plane parallel to an earlier one dropped (the
// later set's value counts, as for Cartesian sets). With P = I - sum_i e_i e_i^T its
// equations become
//   rows j_i:          e_i . du = 0             (u itself is kept on the planes by
//                                               apply_dirichlet's projection)
//   the other rows k:  (P r)_k = 0              (no force along the planes)
// The j_i are the free components that maximise |det e_i(j_l)|: then the rows k imply the
// rows j_i of P r (a vector of range(P) that vanishes on the rows k and the prescribed
// ones vanishes), so the node's free residual is all of P r, and the supports' reaction
// is r - P r, split on the planes' normals. The tangent rows are the same projection of
// the assembled rows (inertia, viscosity, pressure included).
// Rows are projected in place: the three rows of a node share one column pattern (the
// element graph couples whole nodes), checked once.
#include <Teuchos_CommHelpers.hpp>

#include <cmath>
#include <limits>
#include <algorithm>

#include "assembly/Assembler.hpp"
#include "bc/PlaneDirections.hpp"
#include "deck/Config.hpp"

namespace stentor {
namespace {

// Solves the m x m system A x = b (m <= 3, A nonsingular) by elimination with pivoting.
void solve_small(int m, double A[3][3], double b[3], double x[3]) {
  int piv[3] = {0, 1, 2};
  for (int k = 0; k < m; ++k) {
    int p = k;
    for (int i = k + 1; i < m; ++i)
      if (std::abs(A[piv[i]][k]) > std::abs(A[piv[p]][k])) p = i;
    std::swap(piv[k], piv[p]);
    for (int i = k + 1; i < m; ++i) {
      const double f = A[piv[i]][k] / A[piv[k]][k];
      for (int c = k; c < m; ++c) A[piv[i]][c] -= f * A[piv[k]][c];
      b[piv[i]] -= f * b[piv[k]];
    }
  }
  for (int k = m - 1; k >= 0; --k) {
    double v = b[piv[k]];
    for (int c = k + 1; c < m; ++c) v -= A[piv[k]][c] * x[c];
    x[k] = v / A[piv[k]][k];
  }
}

}  // namespace

void Assembler::setup_planes() {
  const la::LO nown = dist_.num_owned_nodes();
  std::vector<GId> candidates;  // the owned nodes of the `normal` sets
  for (const DirichletSet& d : loads_.dirichlet)
    if (d.normal)
      for (GId g : d.nodes) {
        const la::LO l = dist_.local_node(g);
        if (l >= 0 && l < nown) candidates.push_back(g);
      }
  std::sort(candidates.begin(), candidates.end());
  candidates.erase(std::unique(candidates.begin(), candidates.end()), candidates.end());
  for (GId g : candidates) {
    const la::LO l = dist_.local_node(g);
    bool fixed[3] = {false, false, false};
    for (int c = 0; c < dim_; ++c) fixed[c] = owned_dirichlet_flag_[static_cast<std::size_t>(l * dim_ + c)] != 0;
    const PlaneDirections d = plane_directions(loads_, g, fixed, dim_);
    if (d.m == 0) continue;
    PlaneNode p;
    static_cast<PlaneDirections&>(p) = d;
    p.lid = l;
    for (int c = 0; c < dim_; ++c) p.self[c] = K_->getColMap()->getLocalElement(dist_.owned_map()->getGlobalElement(l * dim_ + c));
    for (int i = 0; i < p.m; ++i) owned_dirichlet_flag_[static_cast<std::size_t>(l * dim_ + p.j[i])] = 1;
    planes_.push_back(p);
  }
  plane_r_.assign(planes_.size(), {0.0, 0.0, 0.0});
  // The projection rewrites a node's rows entry by entry: they must share one column pattern.
  auto Kl = K_->getLocalMatrixHost();
  for (const PlaneNode& p : planes_) {
    const la::LO row0 = p.lid * dim_;
    const std::size_t b0 = Kl.graph.row_map(row0), len = Kl.graph.row_map(row0 + 1) - b0;
    for (int c = 1; c < dim_; ++c) {
      const std::size_t bc = Kl.graph.row_map(row0 + c);
      bool same = Kl.graph.row_map(row0 + c + 1) - bc == len;
      for (std::size_t k = 0; same && k < len; ++k) same = Kl.graph.entries(bc + k) == Kl.graph.entries(b0 + k);
      if (!same) throw std::logic_error("Assembler: the rows of a node on a 'normal' plane do not share one column pattern");
    }
  }
  planes_dev_ = Kokkos::View<PlaneNode*, la::ExecSpace>("planes", planes_.size());
  auto h = Kokkos::create_mirror_view(planes_dev_);
  for (std::size_t k = 0; k < planes_.size(); ++k) h(k) = planes_[k];
  Kokkos::deep_copy(planes_dev_, h);
}

int Assembler::plane_normals(la::LO owned_node, double e[3][3], int j[3]) const {
  for (const PlaneNode& p : planes_)  // few nodes; contact setup only
    if (p.lid == owned_node) {
      for (int i = 0; i < 3; ++i) {
        j[i] = p.j[i];
        for (int c = 0; c < 3; ++c) e[i][c] = p.e[i][c];
      }
      return p.m;
    }
  return 0;
}

void Assembler::apply_planes(la::Vector& u, double t, double end_time) const {
  if (planes_.empty()) return;
  auto uh = u.getLocalViewHost(Tpetra::Access::ReadWrite);
  for (const PlaneNode& p : planes_) {
    // The closest point of the planes n_i . u = g_i: u += sum_k c_k e_k with A c = g - N u,
    // A_ik = n_i . e_k (the node's prescribed components already hold their values).
    double A[3][3] = {}, b[3] = {0, 0, 0}, c[3] = {0, 0, 0};
    for (int i = 0; i < p.m; ++i) {
      const DirichletSet& d = loads_.dirichlet[static_cast<std::size_t>(p.set[i])];
      b[i] = d.normal_value * d.ramp(t, end_time);
      for (int a = 0; a < dim_; ++a) b[i] -= p.n[i][a] * uh(p.lid * dim_ + a, 0);
      for (int k = 0; k < p.m; ++k)
        for (int a = 0; a < dim_; ++a) A[i][k] += p.n[i][a] * p.e[k][a];
    }
    solve_small(p.m, A, b, c);
    for (int k = 0; k < p.m; ++k)
      for (int a = 0; a < dim_; ++a) uh(p.lid * dim_ + a, 0) += c[k] * p.e[k][a];
  }
}

void Assembler::project_plane_rows(la::Vector& r, std::vector<double>& loc) {
  if (planes_.empty()) return;
  auto rh = r.getLocalViewHost(Tpetra::Access::ReadWrite);
  for (std::size_t k = 0; k < planes_.size(); ++k) {
    const PlaneNode& p = planes_[k];
    double rho[3] = {0, 0, 0};
    for (int i = 0; i < p.m; ++i) {
      for (int c = 0; c < dim_; ++c) rho[i] += p.e[i][c] * rh(p.lid * dim_ + c, 0);
      plane_r_[k][static_cast<std::size_t>(i)] = rho[i];
    }
    for (int i = 0; i < p.m; ++i)
      for (int c = 0; c < dim_; ++c) rh(p.lid * dim_ + c, 0) -= rho[i] * p.e[i][c];
    for (int i = 0; i < p.m; ++i) rh(p.lid * dim_ + p.j[i], 0) = 0.0;
    // The reaction sum_k rho_k e_k on the planes' normals (restricted to the free
    // components, which span the e_k): sum_i a_i n_i' = sum_k rho_k e_k, A^T a = rho.
    double At[3][3] = {}, a[3] = {0, 0, 0};
    for (int i = 0; i < p.m; ++i)
      for (int l = 0; l < p.m; ++l)
        for (int c = 0; c < dim_; ++c) At[l][i] += p.n[i][c] * p.e[l][c];
    solve_small(p.m, At, rho, a);
    for (int i = 0; i < p.m; ++i)
      for (int l = 0; l < p.m; ++l)
        for (int c = 0; c < dim_; ++c)  // n_i' = sum_l (n_i . e_l) e_l
          loc[3 * static_cast<std::size_t>(p.set[i]) + static_cast<std::size_t>(c)] +=
              a[i] * (p.n[i][0] * p.e[l][0] + p.n[i][1] * p.e[l][1] + p.n[i][2] * p.e[l][2]) * p.e[l][c];
  }
}

void Assembler::project_plane_vector(la::Vector& v) const {
  if (planes_.empty()) return;
  auto vh = v.getLocalViewHost(Tpetra::Access::ReadWrite);
  for (const PlaneNode& p : planes_) {
    double rho[3] = {0, 0, 0};
    for (int i = 0; i < p.m; ++i)
      for (int c = 0; c < dim_; ++c) rho[i] += p.e[i][c] * vh(p.lid * dim_ + c, 0);
    for (int i = 0; i < p.m; ++i)
      for (int c = 0; c < dim_; ++c) vh(p.lid * dim_ + c, 0) -= rho[i] * p.e[i][c];
    for (int i = 0; i < p.m; ++i) vh(p.lid * dim_ + p.j[i], 0) = 0.0;
  }
}

void Assembler::project_plane_matrix() {
  if (planes_.empty()) return;
  project_plane_rows_of(planes_dev_, dim_, K_->getLocalMatrixDevice());
}

void Assembler::project_plane_rows_of(const Kokkos::View<PlaneNode*, la::ExecSpace>& planes, int dim,
                                      const la::CrsMatrix::local_matrix_device_type& Kl) {
  Kokkos::parallel_for(
      "stentor::plane_rows", Kokkos::RangePolicy<la::ExecSpace>(0, planes.extent(0)), KOKKOS_LAMBDA(const int i) {
        const PlaneNode& p = planes(i);
        const la::LO row0 = p.lid * dim;
        const std::size_t len = Kl.graph.row_map(row0 + 1) - Kl.graph.row_map(row0);
        for (std::size_t m = 0; m < len; ++m) {
          double rho[3] = {0, 0, 0};
          for (int k = 0; k < p.m; ++k)
            for (int c = 0; c < dim; ++c) rho[k] += p.e[k][c] * Kl.values(Kl.graph.row_map(row0 + c) + m);
          for (int k = 0; k < p.m; ++k)
            for (int c = 0; c < dim; ++c) Kl.values(Kl.graph.row_map(row0 + c) + m) -= rho[k] * p.e[k][c];
          const la::LO col = Kl.graph.entries(Kl.graph.row_map(row0) + m);
          for (int k = 0; k < p.m; ++k) {
            double v = 0.0;
            for (int c = 0; c < dim; ++c)
              if (col == p.self[c]) v = p.e[k][c];
            Kl.values(Kl.graph.row_map(row0 + p.j[k]) + m) = v;
          }
        }
      });
  Kokkos::fence();
}

void Assembler::project_on_planes(la::Vector& v) const {
  if (planes_.empty()) return;
  auto vh = v.getLocalViewHost(Tpetra::Access::ReadWrite);
  for (const PlaneNode& p : planes_) {
    double w[3] = {0, 0, 0};
    for (int c = 0; c < dim_; ++c) w[c] = vh(p.lid * dim_ + c, 0);
    stentor::project_on_planes(p, dim_, w);
    for (int c = 0; c < dim_; ++c) vh(p.lid * dim_ + c, 0) = w[c];
  }
}

void Assembler::constrain_planes(la::CrsMatrix& M, la::Vector& b) const {
  if (planes_.empty()) return;
  if (M.getNodeNumEntries() != K_->getNodeNumEntries() || !M.getColMap()->isSameAs(*K_->getColMap()))
    throw std::logic_error("Assembler::constrain_planes: the matrix does not have the tangent's graph");
  project_plane_rows_of(planes_dev_, dim_, M.getLocalMatrixDevice());
  project_on_planes(b);
  auto bh = b.getLocalViewHost(Tpetra::Access::ReadWrite);
  for (const PlaneNode& p : planes_)
    for (int i = 0; i < p.m; ++i) bh(p.lid * dim_ + p.j[i], 0) = 0.0;
}

}  // namespace stentor
