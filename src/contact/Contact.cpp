#include "contact/Contact.hpp"

#include <Teuchos_CommHelpers.hpp>

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "mesh/MeshQuery.hpp"

namespace stentor {
namespace {

const char* kAxes[3] = {"x", "y", "z"};

double dot3(const double* a, const double* b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

// Orthonormal tangents of the unit normal n (dim - 1 of them).
void tangents(int dim, const double* n, double t[2][3]) {
  if (dim == 2) {
    t[0][0] = -n[1];
    t[0][1] = n[0];
    t[0][2] = 0.0;
    return;
  }
  // e: the axis least aligned with n.
  int k = 0;
  for (int c = 1; c < 3; ++c)
    if (std::abs(n[c]) < std::abs(n[k])) k = c;
  double e[3] = {0, 0, 0};
  e[k] = 1.0;
  double a[3] = {n[1] * e[2] - n[2] * e[1], n[2] * e[0] - n[0] * e[2], n[0] * e[1] - n[1] * e[0]};
  const double an = std::sqrt(dot3(a, a));
  for (int c = 0; c < 3; ++c) t[0][c] = a[c] / an;
  t[1][0] = n[1] * t[0][2] - n[2] * t[0][1];
  t[1][1] = n[2] * t[0][0] - n[0] * t[0][2];
  t[1][2] = n[0] * t[0][1] - n[1] * t[0][0];
}

}  // namespace

std::unique_ptr<Contact> Contact::create(const Config& cfg, const Mesh& mesh, const Distribution& dist, const Assembler& assembler) {
  if (cfg.contact.empty()) return nullptr;
  return std::make_unique<Contact>(cfg, mesh, dist, assembler);
}

Contact::Contact(const Config& cfg, const Mesh& mesh, const Distribution& dist, const Assembler& assembler)
    : dim_(mesh.dim), end_time_(cfg.stepping.end_time), dist_(dist) {
  // Length scale of the mesh, for the leapfrog test tolerance.
  double lo[3] = {1e300, 1e300, 1e300}, hi[3] = {-1e300, -1e300, -1e300};
  for (std::size_t n = 0; n < mesh.num_nodes(); ++n)
    for (int c = 0; c < 3; ++c) {
      lo[c] = std::min(lo[c], mesh.x[3 * n + c]);
      hi[c] = std::max(hi[c], mesh.x[3 * n + c]);
    }
  double diag = 0.0;
  for (int c = 0; c < 3; ++c) diag += (hi[c] - lo[c]) * (hi[c] - lo[c]);
  gap_tol_ = 1e-12 * std::sqrt(diag);

  const auto& colmap = assembler.matrix()->getColMap();
  for (const auto& pc : cfg.contact) {
    const std::string where = "'Contact->" + pc.name + "'";
    const int want = dim_;
    if (pc.point_len != want) throw InputError(where + "->point must have " + std::to_string(want) + " values (the mesh is " + std::to_string(want) + "D)");
    if (pc.obstacle == "plane" && pc.normal_len != want)
      throw InputError(where + "->normal must have " + std::to_string(want) + " values (the mesh is " + std::to_string(want) + "D)");
    if (pc.obstacle == "circle" && dim_ != 2) throw InputError(where + "->obstacle = circle is 2D only; use cylinder or sphere in 3D");
    if ((pc.obstacle == "cylinder" || pc.obstacle == "sphere") && dim_ != 3)
      throw InputError(where + "->obstacle = " + pc.obstacle + " is 3D only; use circle in 2D");
    Pair p;
    p.cfg = pc;
    p.persistence = pc.formulation == "persistence" || (pc.formulation == "auto" && cfg.problem.dynamic());
    if (pc.formulation == "persistence" && !cfg.problem.dynamic())
      throw InputError(where + "->formulation = persistence needs a dynamic analysis ('Problem->analysis' = dynamic); use gap in statics");
    const std::vector<GId> nodes = boundary_nodes(mesh, pc.slave);  // throws InputError naming the group
    long excluded = 0;
    for (GId g : nodes) {
      if (!dist.owns_node(g)) continue;
      const la::LO l = dist.local_node(g);
      bool prescribed = false;
      for (int c = 0; c < dim_; ++c) prescribed = prescribed || assembler.is_dirichlet(l * dim_ + c);
      if (prescribed) {
        ++excluded;
        continue;
      }
      Node nd;
      nd.lid = l;
      for (int c = 0; c < 3; ++c) nd.X[c] = mesh.x[3 * static_cast<std::size_t>(g) + c];
      for (int c = 0; c < dim_; ++c) nd.col[static_cast<std::size_t>(c)] = colmap->getLocalElement(static_cast<la::GO>(g) * dim_ + c);
      p.nodes.push_back(nd);
    }
    Teuchos::reduceAll(*dist.comm(), Teuchos::REDUCE_SUM, 1, &excluded, &p.excluded);
    pairs_.push_back(std::move(p));
  }
}

std::string Contact::description() const {
  std::ostringstream os;
  for (std::size_t i = 0; i < pairs_.size(); ++i) {
    const auto& p = pairs_[i];
    long loc = static_cast<long>(p.nodes.size()), glob = 0;
    Teuchos::reduceAll(*dist_.comm(), Teuchos::REDUCE_SUM, 1, &loc, &glob);
    os << (i ? "\n           " : "") << p.cfg.name << ": " << glob << " nodes of '" << p.cfg.slave << "' vs " << p.cfg.obstacle << ", "
       << (p.persistence ? "persistence (leapfrog)" : "gap") << ", mu " << p.cfg.friction;
    if (p.excluded) os << " (" << p.excluded << " slave nodes with a prescribed displacement left out)";
  }
  return os.str();
}

std::array<double, 3> Contact::translation(const Pair& p, double t) const {
  const double f = p.cfg.translation_ramp(t, end_time_);
  return {p.cfg.translation[0] * f, p.cfg.translation[1] * f, p.cfg.translation[2] * f};
}

double Contact::gap(const Pair& p, const double* x, double t, double* n) const {
  const auto w = translation(p, t);
  const auto& c = p.cfg;
  double r[3];
  for (int k = 0; k < 3; ++k) r[k] = x[k] - (c.point[static_cast<std::size_t>(k)] + w[static_cast<std::size_t>(k)]);
  if (c.obstacle == "plane") {
    for (int k = 0; k < 3; ++k) n[k] = c.normal[static_cast<std::size_t>(k)];
    return dot3(n, r);
  }
  if (c.obstacle == "cylinder") {
    const double a = r[0] * c.axis[0] + r[1] * c.axis[1] + r[2] * c.axis[2];
    for (int k = 0; k < 3; ++k) r[k] -= a * c.axis[static_cast<std::size_t>(k)];
  }
  const double R = c.radius + c.radius_change * c.radius_ramp(t, end_time_);
  const double rho = std::sqrt(dot3(r, r));
  if (rho > 0.0) {
    for (int k = 0; k < 3; ++k) n[k] = r[k] / rho;
  } else {
    n[0] = 1.0, n[1] = 0.0, n[2] = 0.0;
  }
  if (c.side == "inside") {
    for (int k = 0; k < 3; ++k) n[k] = -n[k];
    return R - rho;
  }
  return rho - R;
}

void Contact::initialize(const la::Vector& u0, double end_time) {
  end_time_ = end_time;
  auto uh = u0.getLocalViewHost(Tpetra::Access::ReadOnly);
  for (auto& p : pairs_)
    for (auto& nd : p.nodes) {
      double x[3] = {nd.X[0], nd.X[1], nd.X[2]}, n[3];
      for (int c = 0; c < dim_; ++c) x[c] += uh(nd.lid * dim_ + c, 0);
      nd.d_n = nd.d_prev = gap(p, x, 0.0, n);
    }
}

void Contact::begin_step(double t_n, double dt, const la::Vector& u_n) {
  t0_ = t_n;
  t1_ = t_n + dt;
  dt_ = dt;
  auto uh = u_n.getLocalViewHost(Tpetra::Access::ReadOnly);
  for (auto& p : pairs_)
    for (auto& nd : p.nodes)
      for (int c = 0; c < 3; ++c) nd.x_n[c] = nd.X[c] + (c < dim_ ? uh(nd.lid * dim_ + c, 0) : 0.0);
}

void Contact::apply(const la::Vector& u, la::Vector& r, la::CrsMatrix* K) {
  // One Kokkos kernel per pair over its slave nodes: each node reads and rewrites only its
  // own dim residual entries and tangent rows, so nodes are independent (no atomics). The
  // node records and the obstacle description live in host memory, which the execution
  // spaces Stentor is built for (Serial, OpenMP) can read.
  static_assert(Kokkos::SpaceAccessibility<la::ExecSpace, Kokkos::HostSpace>::accessible,
                "contact kernels read host-side node records");
  const int dim = dim_;
  auto uh = u.getLocalViewHost(Tpetra::Access::ReadOnly);
  auto rh = r.getLocalViewHost(Tpetra::Access::ReadWrite);
  // fillComplete is collective: every rank reopens and closes the tangent, whether or not
  // it has candidate nodes this time.
  if (K) K->resumeFill();
  using LocalMatrix = la::CrsMatrix::local_matrix_device_type;
  LocalMatrix Kl;
  if (K) Kl = K->getLocalMatrixDevice();
  Kokkos::View<int, la::ExecSpace> bad_pattern("contact_bad_pattern");
  for (auto& p : pairs_) {
    const double mu = p.cfg.friction;
    const auto w0 = translation(p, t0_), w1 = translation(p, t1_);
    const double lf = dt_last_ > 0.0 ? 0.5 * dt_ / dt_last_ : 0.5;
    Node* nodes = p.nodes.data();
    const Pair* pp = &p;
    const bool with_k = K != nullptr;
    const double t1 = t1_, dt = dt_, gap_tol = gap_tol_;
    Kokkos::parallel_for(
        "stentor::contact_nodes", Kokkos::RangePolicy<la::ExecSpace>(0, p.nodes.size()), [=](const std::size_t i) {
          Node& nd = nodes[i];
          const Pair& pr = *pp;
          double x[3] = {nd.X[0], nd.X[1], nd.X[2]}, n[3], t[2][3], rp[3] = {0, 0, 0};
          for (int c = 0; c < dim; ++c) {
            x[c] += uh(nd.lid * dim + c, 0);
            rp[c] = rh(nd.lid * dim + c, 0);
          }
          for (int c = 0; c < 3; ++c) nd.f[c] = rp[c];
          nd.state = 0;
          // Leapfrog: free this step, unless the node ended the last step in contact (then
          // the persistence condition itself decides whether it separates).
          if (pr.persistence && !nd.was_active && nd.d_n + lf * (nd.d_n - nd.d_prev) > gap_tol) return;
          const double d = gap(pr, x, t1, n);
          tangents(dim, n, t);
          // The node's dim rows of the tangent share one column pattern: row c is
          // values(b[c] .. b[c] + len - 1) with the columns of row 0.
          std::size_t b[3] = {0, 0, 0}, len = 0;
          if (with_k) {
            const la::LO row0 = nd.lid * dim;
            len = static_cast<std::size_t>(Kl.graph.row_map(row0 + 1) - Kl.graph.row_map(row0));
            for (int c = 0; c < dim; ++c) {
              b[c] = static_cast<std::size_t>(Kl.graph.row_map(row0 + c));
              const auto lc = static_cast<std::size_t>(Kl.graph.row_map(row0 + c + 1)) - b[c];
              bool same = lc == len;
              for (std::size_t k = 0; same && k < len; ++k) same = Kl.graph.entries(b[c] + k) == Kl.graph.entries(b[0] + k);
              if (!same) {
                Kokkos::atomic_increment(&bad_pattern());
                return;
              }
            }
            double s = 0.0;
            for (int c = 0; c < dim; ++c)
              for (std::size_t k = 0; k < len; ++k)
                if (Kl.graph.entries(b[0] + k) == nd.col[static_cast<std::size_t>(c)]) s = std::max(s, std::abs(Kl.values(b[c] + k)));
            if (s > 0.0) nd.scale = s;
          }
          const double sp = nd.scale;
          const double rn = dot3(n, rp);
          const double lam_n = -rn;
          double lam_t[3];
          for (int c = 0; c < 3; ++c) lam_t[c] = -(rp[c] - rn * n[c]);
          const double cn = pr.cfg.c_normal > 0.0 ? pr.cfg.c_normal : sp * (pr.persistence ? dt : 1.0);
          const double g = pr.persistence ? (d - nd.d_n) / dt : d;
          if (lam_n + cn * g > 0.0) {
            // Inactive: lambda = 0, bulk rows unchanged. (A node touching with zero force,
            // lambda + c g = 0, counts as active: it keeps a body that only rests on the
            // obstacle from being a free rigid body at the first iteration.)
            nd.state = 1;
            return;
          }
          // Active. Relative tangential motion over the step (obstacle translation removed).
          double du[3], dtau[3];
          for (int c = 0; c < 3; ++c) du[c] = x[c] - nd.x_n[c] - (w1[static_cast<std::size_t>(c)] - w0[static_cast<std::size_t>(c)]);
          const double dun = dot3(du, n);
          for (int c = 0; c < 3; ++c) dtau[c] = du[c] - dun * n[c];
          bool stick = false;
          double sdir[3] = {0, 0, 0};
          if (mu > 0.0) {
            const double ct = pr.cfg.c_tangent > 0.0 ? pr.cfg.c_tangent : sp * dt;
            double q[3];
            for (int c = 0; c < 3; ++c) q[c] = lam_t[c] + ct * dtau[c] / dt;
            const double qn = std::sqrt(dot3(q, q));
            if (qn + mu * lam_n >= 0.0 && qn > 0.0) {
              for (int c = 0; c < 3; ++c) sdir[c] = q[c] / qn;
            } else {
              stick = true;
            }
          }
          nd.state = stick ? 2 : 3;
          // Row slots: the normal row goes to the component most aligned with n.
          int slot_n = 0;
          for (int c = 1; c < dim; ++c)
            if (std::abs(n[c]) > std::abs(n[slot_n])) slot_n = c;
          int slot_t[2] = {0, 0}, nt = 0;
          for (int c = 0; c < dim; ++c)
            if (c != slot_n) slot_t[nt++] = c;
          double res[3];
          res[slot_n] = sp * (d - (pr.persistence ? nd.d_n : 0.0));
          double comb[2][3];  // slip/frictionless: row combination of the bulk rows
          for (int k = 0; k < dim - 1; ++k) {
            const double st = dot3(sdir, t[k]);
            for (int c = 0; c < 3; ++c) comb[k][c] = t[k][c] + mu * st * n[c];
            res[slot_t[k]] = stick ? sp * dot3(t[k], dtau) : dot3(comb[k], rp);
          }
          for (int c = 0; c < dim; ++c) rh(nd.lid * dim + c, 0) = res[c];
          if (!with_k) return;
          // Rewrite the rows column by column (each new entry needs the old entries of the
          // same column only): normal row = sp n on the node's own dofs; stick rows = sp t;
          // slip rows = comb . (bulk rows).
          for (std::size_t k = 0; k < len; ++k) {
            const la::LO col = Kl.graph.entries(b[0] + k);
            double old[3] = {0, 0, 0}, out[3] = {0, 0, 0};
            for (int c = 0; c < dim; ++c) old[c] = Kl.values(b[c] + k);
            for (int c = 0; c < dim; ++c)
              if (col == nd.col[static_cast<std::size_t>(c)]) {
                out[slot_n] = sp * n[c];
                if (stick)
                  for (int j = 0; j < dim - 1; ++j) out[slot_t[j]] = sp * t[j][c];
              }
            if (!stick)
              for (int j = 0; j < dim - 1; ++j) {
                double v = 0.0;
                for (int c = 0; c < dim; ++c) v += comb[j][c] * old[c];
                out[slot_t[j]] = v;
              }
            for (int c = 0; c < dim; ++c) Kl.values(b[c] + k) = out[c];
          }
        });
  }
  Kokkos::fence();
  auto bad = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), bad_pattern);
  if (bad() > 0) throw std::logic_error("stentor contact: the rows of a node do not share one column pattern");
  if (K) K->fillComplete(dist_.owned_map(), dist_.owned_map());
}

std::string Contact::iteration_summary() const {
  std::vector<long> loc, glob;
  for (const auto& p : pairs_) {
    long a = 0, st = 0, sl = 0;
    for (const auto& nd : p.nodes) {
      a += nd.state >= 2;
      st += nd.state == 2;
      sl += nd.state == 3;
    }
    loc.insert(loc.end(), {a, st, sl});
  }
  glob.resize(loc.size());
  Teuchos::reduceAll(*dist_.comm(), Teuchos::REDUCE_SUM, static_cast<int>(loc.size()), loc.data(), glob.data());
  std::ostringstream os;
  os << "      contact";
  for (std::size_t i = 0; i < pairs_.size(); ++i)
    os << "  " << pairs_[i].cfg.name << ": active " << glob[3 * i] << " (stick " << glob[3 * i + 1] << ", slip " << glob[3 * i + 2] << ")";
  return os.str();
}

Contact::StepStats Contact::accept(const la::Vector& u_np1) {
  auto uh = u_np1.getLocalViewHost(Tpetra::Access::ReadOnly);
  const std::size_t np = pairs_.size();
  std::vector<double> loc(np * 6 + 2, 0.0), glob(loc.size(), 0.0), mloc(np, 1e300), mglob(np, 0.0);
  for (std::size_t i = 0; i < np; ++i) {
    auto& p = pairs_[i];
    const auto w0 = translation(p, t0_), w1 = translation(p, t1_);
    for (auto& nd : p.nodes) {
      double x[3] = {nd.X[0], nd.X[1], nd.X[2]}, n[3];
      for (int c = 0; c < dim_; ++c) x[c] += uh(nd.lid * dim_ + c, 0);
      const double d = gap(p, x, t1_, n);
      mloc[i] = std::min(mloc[i], d);
      if (nd.state >= 2) {
        loc[6 * i] += 1;
        loc[6 * i + 1] += nd.state == 2;
        loc[6 * i + 2] += nd.state == 3;
        for (int c = 0; c < 3; ++c) loc[6 * i + 3 + static_cast<std::size_t>(c)] += nd.f[c];
        // f = r_bulk,p is the contact force on the body; split into normal and tangential parts.
        const double fn = dot3(nd.f, n);
        double ft[3], du[3], dw[3];
        for (int c = 0; c < 3; ++c) {
          ft[c] = nd.f[c] - fn * n[c];
          du[c] = x[c] - nd.x_n[c];
          dw[c] = w1[static_cast<std::size_t>(c)] - w0[static_cast<std::size_t>(c)];
        }
        double rel[3];
        for (int c = 0; c < 3; ++c) rel[c] = du[c] - dw[c];
        const double reln = dot3(rel, n), dwn = dot3(dw, n);
        double relt[3], dwt[3];
        for (int c = 0; c < 3; ++c) {
          relt[c] = rel[c] - reln * n[c];
          dwt[c] = dw[c] - dwn * n[c];
        }
        loc[6 * np] += fn * dot3(du, n) + dot3(ft, dwt);
        loc[6 * np + 1] += -dot3(ft, relt);
      }
      nd.d_prev = nd.d_n;
      nd.d_n = d;
      nd.was_active = nd.state >= 2;
    }
  }
  Teuchos::reduceAll(*dist_.comm(), Teuchos::REDUCE_SUM, static_cast<int>(loc.size()), loc.data(), glob.data());
  Teuchos::reduceAll(*dist_.comm(), Teuchos::REDUCE_MIN, static_cast<int>(np), mloc.data(), mglob.data());
  dt_last_ = dt_;
  StepStats s;
  for (std::size_t i = 0; i < np; ++i) {
    PairStats ps;
    ps.active = static_cast<long>(glob[6 * i]);
    ps.stick = static_cast<long>(glob[6 * i + 1]);
    ps.slip = static_cast<long>(glob[6 * i + 2]);
    ps.force = {glob[6 * i + 3], glob[6 * i + 4], glob[6 * i + 5]};
    ps.min_gap = mglob[i];
    s.pairs.push_back(ps);
  }
  s.work = glob[6 * np];
  s.friction_dissipation = glob[6 * np + 1];
  return s;
}

Contact::NodalFields Contact::nodal_fields(const la::Vector& u) const {
  NodalFields out;
  auto uh = u.getLocalViewHost(Tpetra::Access::ReadOnly);
  for (const Pair& p : pairs_)
    for (const Node& nd : p.nodes) {
      double x[3] = {nd.X[0], nd.X[1], nd.X[2]}, n[3] = {0, 0, 0};
      for (int c = 0; c < dim_; ++c) x[c] += uh(nd.lid * dim_ + c, 0);
      const double d = gap(p, x, t1_, n);
      const bool active = nd.state >= 2;
      // Condensed multipliers (talk's signs): lambda_nu = -n . f, lambda_tau = -(I - n n) f.
      double fn = 0.0;
      for (int c = 0; c < 3; ++c) fn += n[c] * nd.f[c];
      out.nodes.push_back(static_cast<long long>(dist_.global_node(nd.lid)));
      out.values.push_back(static_cast<double>(nd.state));
      out.values.push_back(d);
      out.values.push_back(active ? -fn : 0.0);
      for (int c = 0; c < 3; ++c) out.values.push_back(active ? -(nd.f[c] - fn * n[c]) : 0.0);
    }
  return out;
}

std::vector<std::string> Contact::history_columns() const {
  std::vector<std::string> c;
  for (const auto& p : pairs_) {
    const std::string b = "contact_" + p.cfg.name + "_";
    c.push_back(b + "active");
    c.push_back(b + "stick");
    c.push_back(b + "slip");
    for (int k = 0; k < dim_; ++k) c.push_back(b + "force_" + kAxes[k]);
    c.push_back(b + "min_gap");
  }
  return c;
}

std::vector<double> Contact::history_values(const StepStats& s) const {
  std::vector<double> v;
  for (const auto& ps : s.pairs) {
    v.push_back(static_cast<double>(ps.active));
    v.push_back(static_cast<double>(ps.stick));
    v.push_back(static_cast<double>(ps.slip));
    for (int k = 0; k < dim_; ++k) v.push_back(ps.force[static_cast<std::size_t>(k)]);
    v.push_back(ps.min_gap);
  }
  return v;
}

std::string Contact::progress(const StepStats& s) const {
  std::ostringstream os;
  os << "  contact";
  for (const auto& ps : s.pairs) os << " " << ps.active << "/" << ps.stick << "/" << ps.slip;
  return os.str();
}

}  // namespace stentor
