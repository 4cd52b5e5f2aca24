// The mortar discretization of a master-surface pair (`discretization = mortar`,
// docs/contact.md "Mortar"): per slave facet, the dual mortar integrals against the master
// facets that overlap it (contact/Mortar.hpp, exact derivatives by Dual numbers); per slave
// node p, from those of its facets:
//   S_p = sum_k M_pk, w_pk = M_pk / S_p, xbar_p = sum_k w_pk x_k,
//   n_p = -(sum over its facets of their outward unit normals at p), normalized,
//   d = n_p . (x_p - xbar_p),   rel = (x_p - x_p,n) - sum_k w_pk (x_k - x_k,n),
// and then the same law as node-to-segment (contact/NodeLaw.hpp, law()) with the reaction
// r_k += w_pk r_p on the master nodes. Axisymmetric: M, S and the dual basis in the
// revolved measure 2 pi r ds (contact/Mortar.hpp), r_p the bulk residual of the whole ring. The derivatives of M, S, the dual basis and the
// nodal normal are carried to the node's rows by the chain rule through (x_p, n_p, xbar_p,
// the relative master motion, r_p). The facets' integrals and the nodes are Kokkos kernels
// over the host execution space (OpenMP threads where Kokkos has them). A node whose facets are covered by less than half
// (S_p < A_p / 2, A_p its tributary area) has no master: it is free.
#include <Teuchos_CommHelpers.hpp>

#include <algorithm>
#include <cmath>
#include <array>
#include <map>

#include "contact/Contact.hpp"
#include "contact/MasterSurface.hpp"
#include "contact/Mortar.hpp"
#include "contact/MortarNode.hpp"

namespace stentor {

namespace {

constexpr double kMinCover = 0.5;  // S_p / A_p below which a slave node has no master

mortar::Face face_of(const MasterSurface::Facet& f) { return mortar::Face{f.type, f.nn, f.orient}; }

int corner_of(const MasterSurface::Facet& f, int pos) {
  for (int a = 0; a < f.nn; ++a)
    if (f.node[a] == pos) return a;
  return -1;
}

}  // namespace

void Contact::setup_mortar(Pair& p) {
  const std::string where = "'Contact->" + p.cfg.name + "->discretization' = mortar: ";
  auto check = [&](const MasterSurface& s, const std::string& group) {
    for (const auto& f : s.facets())
      if (!mortar::supported(f.type))
        throw InputError(where + "group '" + group + "' has " + cell_name(f.type) +
                         " facets; mortar supports line2, line3, tri3 and quad4 facets (use node-to-segment for tri6)");
  };
  check(*p.master, p.cfg.master);
  check(*p.slave_faces, p.cfg.slave);
  p.slave_faces->index([this](GId g) { return master_pos(g); });
  std::map<int, std::vector<int>> faces_of;  // surface position -> slave facets
  const auto& sf = p.slave_faces->facets();
  for (std::size_t e = 0; e < sf.size(); ++e)
    for (int a = 0; a < sf[e].nn; ++a) faces_of[sf[e].node[a]].push_back(static_cast<int>(e));
  p.node_faces.assign(p.nodes.size(), {});
  for (std::size_t i = 0; i < p.nodes.size(); ++i) p.node_faces[i] = faces_of[master_pos(p.nodes[i].gid)];
  p.mortar_out.assign(p.nodes.size(), contact::MortarRows{});
}

// The integrals of every needed slave facet against the master facets near it: those with
// their centre within the bins around the slave facet's box, in front of its plane by at
// most 2h or behind it by at most h (h: the largest master facet extent), facing it.
std::vector<std::vector<Contact::FaceCoupling>> Contact::couple_faces(const Pair& p, const std::vector<char>& needed) const {
  const auto& sf = p.slave_faces->facets();
  const auto& mf = p.master->facets();
  const double h = 0.5 * p.master->search_radius();
  std::vector<std::vector<FaceCoupling>> out(sf.size());
  std::vector<std::size_t> list;
  for (std::size_t e = 0; e < sf.size(); ++e)
    if (needed[e]) list.push_back(e);
  // One slave facet per kernel iteration (host execution space: Serial or OpenMP threads).
  Kokkos::parallel_for("stentor::mortar_faces", Kokkos::RangePolicy<la::ExecSpace>(0, list.size()), [&](const std::size_t li) {
    const std::size_t e = list[li];
    std::vector<int> near;
    const auto& f = sf[e];
    double xs[mortar::kMaxFacetNodes][3], lo[3] = {1e300, 1e300, 1e300}, hi[3] = {-1e300, -1e300, -1e300};
    for (int a = 0; a < f.nn; ++a)
      for (int c = 0; c < 3; ++c) {
        xs[a][c] = master_x_[3 * static_cast<std::size_t>(f.node[a]) + static_cast<std::size_t>(c)];
        lo[c] = std::min(lo[c], xs[a][c]);
        hi[c] = std::max(hi[c], xs[a][c]);
      }
    double cen[2];
    facet::centre(f.type, cen);
    facet::Frame<double> fs;
    facet::frame(f.type, f.nn, dim_, f.orient, xs, cen, fs);
    p.master->near(lo, hi, near);
    for (int m : near) {
      const auto& g = mf[static_cast<std::size_t>(m)];
      double xm[mortar::kMaxFacetNodes][3], mc[3] = {0, 0, 0};
      for (int b = 0; b < g.nn; ++b)
        for (int c = 0; c < 3; ++c) {
          xm[b][c] = master_x_[3 * static_cast<std::size_t>(g.node[b]) + static_cast<std::size_t>(c)];
          mc[c] += xm[b][c] / g.nn;
        }
      const double ahead = (mc[0] - fs.xm[0]) * fs.n[0] + (mc[1] - fs.xm[1]) * fs.n[1] + (mc[2] - fs.xm[2]) * fs.n[2];
      if (ahead > 2.0 * h || ahead < -h) continue;
      using PD = mortar::PD;
      PD xsd[mortar::kMaxFacetNodes][3], xmd[mortar::kMaxFacetNodes][3];
      for (int a = 0; a < f.nn; ++a)
        for (int c = 0; c < 3; ++c) xsd[a][c] = c < dim_ ? PD::seed(xs[a][c], 3 * a + c) : PD(xs[a][c]);
      for (int b = 0; b < g.nn; ++b)
        for (int c = 0; c < 3; ++c) xmd[b][c] = c < dim_ ? PD::seed(xm[b][c], 12 + 3 * b + c) : PD(xm[b][c]);
      PD M[mortar::kMaxFacetNodes][mortar::kMaxFacetNodes];
      if (!mortar::pair_integrals(dim_, face_of(f), xsd, face_of(g), xmd, M, axi_)) continue;
      FaceCoupling cp;
      cp.master = m;
      for (int a = 0; a < f.nn; ++a)
        for (int b = 0; b < g.nn; ++b) {
          cp.M[a][b] = M[a][b].v;
          for (int v = 0; v < mortar::kPairVars; ++v) cp.dM[a][b][v] = M[a][b].d[v];
        }
      out[e].push_back(cp);
    }
  });
  Kokkos::fence();
  return out;
}

namespace contact {

std::size_t Stencil::var(int pos) {
  const auto it = std::find(vars.begin(), vars.end(), pos);
  if (it != vars.end()) return static_cast<std::size_t>(it - vars.begin());
  vars.push_back(pos);
  return vars.size() - 1;
}

std::size_t Stencil::slot(int pos) {
  const auto it = std::find(masters.begin(), masters.end(), pos);
  if (it != masters.end()) return static_cast<std::size_t>(it - masters.begin());
  masters.push_back(pos);
  M.emplace_back(nv());
  return masters.size() - 1;
}

Stencil gather_stencil(int dim, int j, const std::vector<int>& faces, const Facets& sf, const Facets& mf,
                       const std::vector<std::vector<FaceCoupling>>& cpl) {
  Stencil st;
  st.dim = dim;
  st.vars = {j};
  for (int e : faces)
    for (int a = 0; a < sf[static_cast<std::size_t>(e)].nn; ++a) st.var(sf[static_cast<std::size_t>(e)].node[a]);
  for (int e : faces)
    for (const auto& c : cpl[static_cast<std::size_t>(e)])
      for (int b = 0; b < mf[static_cast<std::size_t>(c.master)].nn; ++b) st.var(mf[static_cast<std::size_t>(c.master)].node[b]);
  const auto D = static_cast<std::size_t>(dim);
  for (int e : faces) {
    const auto& f = sf[static_cast<std::size_t>(e)];
    const int aj = corner_of(f, j);
    for (const auto& c : cpl[static_cast<std::size_t>(e)]) {
      const auto& g = mf[static_cast<std::size_t>(c.master)];
      for (int b = 0; b < g.nn; ++b) {
        Grad& Mk = st.M[st.slot(g.node[b])];
        Mk.v += c.M[aj][b];
        for (int cc = 0; cc < dim; ++cc) {
          const auto C = static_cast<std::size_t>(cc);
          for (int a = 0; a < f.nn; ++a) Mk.d[st.var(f.node[a]) * D + C] += c.dM[aj][b][3 * a + cc];
          for (int b2 = 0; b2 < g.nn; ++b2) Mk.d[st.var(g.node[b2]) * D + C] += c.dM[aj][b][12 + 3 * b2 + cc];
        }
      }
    }
  }
  return st;
}

std::array<Grad, 3> nodal_normal(Stencil& st, int j, const std::vector<int>& faces, const Facets& sf, const std::vector<double>& x) {
  const std::size_t nv = st.nv();
  const int dim = st.dim;
  std::array<Grad, 3> v{Grad(nv), Grad(nv), Grad(nv)};
  for (int e : faces) {
    const auto& f = sf[static_cast<std::size_t>(e)];
    using ND = Dual<3 * mortar::kMaxFacetNodes>;
    ND xs[mortar::kMaxFacetNodes][3], ne[3];
    for (int a = 0; a < f.nn; ++a)
      for (int c = 0; c < 3; ++c) {
        const double xv = x[3 * static_cast<std::size_t>(f.node[a]) + static_cast<std::size_t>(c)];
        xs[a][c] = c < dim ? ND::seed(xv, 3 * a + c) : ND(xv);
      }
    mortar::corner_normal(dim, face_of(f), xs, corner_of(f, j), ne);
    for (std::size_t c = 0; c < 3; ++c) {
      v[c].v -= ne[c].v;
      for (int a = 0; a < f.nn; ++a)
        for (int cc = 0; cc < dim; ++cc)
          v[c].d[st.var(f.node[a]) * static_cast<std::size_t>(dim) + static_cast<std::size_t>(cc)] -= ne[c].d[3 * a + cc];
    }
  }
  const double len = std::sqrt(v[0].v * v[0].v + v[1].v * v[1].v + v[2].v * v[2].v);
  std::array<Grad, 3> n{Grad(nv), Grad(nv), Grad(nv)};
  for (std::size_t c = 0; c < 3; ++c) n[c].v = v[c].v / len;
  for (std::size_t c = 0; c < 3; ++c)
    for (std::size_t e = 0; e < 3; ++e) {
      const double P = ((c == e) ? 1.0 : 0.0) - n[c].v * n[e].v;
      for (std::size_t l = 0; l < nv; ++l) n[c].d[l] += P * v[e].d[l] / len;
    }
  return n;
}

MortarPoint mortar_point(Stencil& st, const std::vector<double>& x, const std::vector<double>& xn) {
  const std::size_t nv = st.nv(), nk = st.masters.size();
  const auto D = static_cast<std::size_t>(st.dim);
  MortarPoint mp;
  mp.S = Grad(nv);
  for (const Grad& Mk : st.M) {
    mp.S.v += Mk.v;
    for (std::size_t l = 0; l < nv; ++l) mp.S.d[l] += Mk.d[l];
  }
  mp.w.assign(nk, Grad(nv));
  mp.xbar = {Grad(nv), Grad(nv), Grad(nv)};
  mp.mbar = {Grad(nv), Grad(nv), Grad(nv)};
  if (nk == 0 || mp.S.v <= 0.0) return mp;
  for (std::size_t k = 0; k < nk; ++k) {
    Grad& w = mp.w[k];
    w.v = st.M[k].v / mp.S.v;
    for (std::size_t l = 0; l < nv; ++l) w.d[l] = (st.M[k].d[l] - w.v * mp.S.d[l]) / mp.S.v;
    const std::size_t vk = st.var(st.masters[k]);
    for (std::size_t c = 0; c < D; ++c) {
      const std::size_t q = 3 * static_cast<std::size_t>(st.masters[k]) + c;
      const double xk = x[q], mk = x[q] - xn[q];
      mp.xbar[c].v += w.v * xk;
      mp.mbar[c].v += w.v * mk;
      for (std::size_t l = 0; l < nv; ++l) mp.xbar[c].d[l] += xk * w.d[l], mp.mbar[c].d[l] += mk * w.d[l];
      mp.xbar[c].d[vk * D + c] += w.v;
      mp.mbar[c].d[vk * D + c] += w.v;
    }
  }
  return mp;
}

int mortar_law(int dim, const bool fixed[3], const double r[3], const LawParams& law, const double xp[3], const double xpn[3],
               const std::array<Grad, 3>& n, const MortarPoint& mp, std::size_t nv, MortarRows& out) {
  using ZD = Dual<15>;
  ZD xz[3], nz[3], bz[3], mz[3], rz[3];
  double nv3[3];
  for (int c = 0; c < 3; ++c) {
    const auto C = static_cast<std::size_t>(c);
    nv3[c] = n[C].v;
    xz[c] = c < dim ? ZD::seed(xp[c], c) : ZD(xp[c]);
    nz[c] = ZD::seed(n[C].v, 3 + c);
    bz[c] = c < dim ? ZD::seed(mp.xbar[C].v, 6 + c) : ZD(mp.xbar[C].v);
    mz[c] = c < dim ? ZD::seed(mp.mbar[C].v, 9 + c) : ZD(mp.mbar[C].v);
    rz[c] = c < dim && !fixed[c] ? ZD::seed(r[c], 12 + c) : ZD(0.0);
  }
  ZD relz[3], gap(0.0), nrel(0.0);
  for (int c = 0; c < 3; ++c) {
    relz[c] = xz[c] - xpn[c] - mz[c];
    gap += nz[c] * (xz[c] - bz[c]);
    nrel += nz[c] * relz[c];
  }
  ZD res[3];
  const int state = contact::law(dim, fixed, law, law.persistence ? nrel : gap, nz, relz, static_cast<const ZD*>(nullptr), rz, res, nv3);
  if (state == Inactive) return state;
  out.nvar = static_cast<int>(nv) + dim;
  const auto nvar = static_cast<std::size_t>(out.nvar);
  // dz/dy, rows of length nvar.
  std::vector<double> dz(15 * nvar, 0.0);
  for (std::size_t c = 0; c < 3; ++c) {
    if (c < static_cast<std::size_t>(dim)) {
      dz[c * nvar + c] = 1.0;  // x_p: vars[0]
      dz[(12 + c) * nvar + nv + c] = fixed[c] ? 0.0 : 1.0;
    }
    for (std::size_t l = 0; l < nv; ++l) {
      dz[(3 + c) * nvar + l] = n[c].d[l];
      dz[(6 + c) * nvar + l] = mp.xbar[c].d[l];
      dz[(9 + c) * nvar + l] = mp.mbar[c].d[l];
    }
  }
  out.dres.assign(static_cast<std::size_t>(dim) * nvar, 0.0);
  for (int k = 0; k < dim; ++k) {
    out.res[k] = res[k].v;
    if (fixed[k]) continue;
    for (std::size_t z = 0; z < 15; ++z) {
      const double a = res[k].d[z];
      if (a == 0.0) continue;
      for (std::size_t l = 0; l < nvar; ++l) out.dres[static_cast<std::size_t>(k) * nvar + l] += a * dz[z * nvar + l];
    }
  }
  // Master rows: w_k r_p.
  const std::size_t nk = mp.w.size(), D = static_cast<std::size_t>(dim);
  out.add.assign(nk * D, 0.0);
  out.dadd.assign(nk * D * nvar, 0.0);
  for (std::size_t k = 0; k < nk; ++k)
    for (std::size_t c = 0; c < D; ++c) {
      const std::size_t row = k * D + c;
      const double rc = fixed[c] ? 0.0 : r[c];
      out.add[row] = mp.w[k].v * rc;
      for (std::size_t l = 0; l < nv; ++l) out.dadd[row * nvar + l] = rc * mp.w[k].d[l];
      if (!fixed[c]) out.dadd[row * nvar + nv + c] = mp.w[k].v;
    }
  return state;
}

}  // namespace contact

int Contact::mortar_node(Pair& p, std::size_t i, const std::vector<std::vector<FaceCoupling>>& cpl, const contact::LawParams* law,
                         double* dout, double* nout, double* relout) {
  const Slave& nd = p.nodes[i];
  const int j = master_pos(nd.gid);
  const auto& faces = p.node_faces[i];
  contact::Stencil st = contact::gather_stencil(dim_, j, faces, p.slave_faces->facets(), p.master->facets(), cpl);
  const contact::MortarPoint mp = contact::mortar_point(st, master_x_, master_xn_);
  double xp[3], xpn[3];
  for (std::size_t c = 0; c < 3; ++c) xp[c] = master_x_[3 * static_cast<std::size_t>(j) + c], xpn[c] = master_xn_[3 * static_cast<std::size_t>(j) + c];
  if (st.masters.empty() || mp.S.v <= kMinCover * nd.area || mp.S.v <= 0.0) {
    p.mortar_out[i].masters.clear();
    p.mortar_out[i].w.clear();
    *dout = p.master->search_radius();
    for (int c = 0; c < 3; ++c) nout[c] = 0.0, relout[c] = xp[c] - xpn[c];
    return contact::Free;
  }
  const std::array<contact::Grad, 3> n = contact::nodal_normal(st, j, faces, p.slave_faces->facets(), master_x_);
  *dout = 0.0;
  for (std::size_t c = 0; c < 3; ++c) {
    *dout += n[c].v * (xp[c] - mp.xbar[c].v);
    nout[c] = n[c].v;
    relout[c] = xp[c] - xpn[c] - mp.mbar[c].v;
  }
  contact::MortarRows& mo = p.mortar_out[i];
  mo.vars = st.vars;
  mo.masters = st.masters;
  mo.w.resize(st.masters.size());
  for (std::size_t k = 0; k < mo.w.size(); ++k) mo.w[k] = mp.w[k].v;
  if (!law) return contact::Free;
  return contact::mortar_law(dim_, nd.fixed, nd.f, *law, xp, xpn, n, mp, st.nv(), mo);
}

void Contact::mortar_rows(const Pair& p, std::size_t i, std::vector<Row>& q, std::vector<Row>& g, std::map<la::GO, Row>& q_far,
                          std::map<la::GO, Row>& g_far) const {
  const auto& map = dist_.owned_map();
  auto row_of = [&](la::GO gid, std::vector<Row>& loc, std::map<la::GO, Row>& far) -> Row& {
    const la::LO l = map->getLocalElement(gid);
    return l >= 0 ? loc[static_cast<std::size_t>(l)] : far[gid];
  };
  const Slave& nd = p.nodes[i];
  const contact::MortarRows& mo = p.mortar_out[i];
  const auto nvar = static_cast<std::size_t>(mo.nvar);
  const int nv = mo.nvar - dim_;
  auto ydof = [&](int l) -> la::GO {
    const GId node = l < nv ? master_nodes_[static_cast<std::size_t>(mo.vars[static_cast<std::size_t>(l / dim_)])] : nd.gid;
    return static_cast<la::GO>(node) * dim_ + l % dim_;
  };
  const la::GO r0 = static_cast<la::GO>(nd.gid) * dim_;
  for (int k = 0; k < dim_; ++k) {
    if (nd.fixed[k]) continue;  // Dirichlet rows stay identity rows of Q
    Row& qr = q[static_cast<std::size_t>(nd.lid * dim_ + k)];
    Row& gr = g[static_cast<std::size_t>(nd.lid * dim_ + k)];
    const double* dr = &mo.dres[static_cast<std::size_t>(k) * nvar];
    for (int j = 0; j < dim_; ++j) qr.push_back({r0 + j, dr[nv + j] - (j == k ? 1.0 : 0.0)});
    for (int l = 0; l < nv; ++l)
      if (dr[l] != 0.0) gr.push_back({ydof(l), dr[l]});
  }
  for (std::size_t k = 0; k < mo.masters.size(); ++k)
    for (int c = 0; c < dim_; ++c) {
      const auto pos = static_cast<std::size_t>(mo.masters[k]);
      if (master_fixed_[pos * static_cast<std::size_t>(dim_) + static_cast<std::size_t>(c)]) continue;
      const la::GO row = static_cast<la::GO>(master_nodes_[pos]) * dim_ + c;
      Row& qr = row_of(row, q, q_far);
      Row& gr = row_of(row, g, g_far);
      const double* da = &mo.dadd[(k * static_cast<std::size_t>(dim_) + static_cast<std::size_t>(c)) * nvar];
      for (int j = 0; j < dim_; ++j) qr.push_back({r0 + j, da[nv + j]});
      for (int l = 0; l < nv; ++l)
        if (da[l] != 0.0) gr.push_back({ydof(l), da[l]});
    }
}

void Contact::evaluate_mortar(Pair& p, const contact::LawParams& lp, double lf, const double* u, double* r) {
  (void)u;
  p.slave_faces->build(master_x_, &present_);
  std::vector<char> cand(p.nodes.size(), 0), needed(p.slave_faces->facets().size(), 0);
  for (std::size_t i = 0; i < p.nodes.size(); ++i) {
    Slave& nd = p.nodes[i];
    for (int c = 0; c < dim_; ++c) nd.f[c] = r[nd.lid * dim_ + c];
    nd.state = p.out[i].state = contact::Free;
    nd.inside = true;
    // Leapfrog, as for node-to-segment.
    if (p.persistence && !nd.was_active && nd.d_n + lf * (nd.d_n - nd.d_prev) > gap_tol_) continue;
    cand[i] = 1;
    for (int e : p.node_faces[i]) needed[static_cast<std::size_t>(e)] = 1;
  }
  const auto cpl = couple_faces(p, needed);
  // One slave node per kernel iteration (each writes its own record and rows).
  Kokkos::parallel_for("stentor::mortar_nodes", Kokkos::RangePolicy<la::ExecSpace>(0, p.nodes.size()), [&](const std::size_t i) {
    if (!cand[i]) return;
    Slave& nd = p.nodes[i];
    const contact::LawParams q = node_params(p, nd, lp);
    double d = 0.0, n[3], rel[3];
    const int st = mortar_node(p, i, cpl, &q, &d, n, rel);
    nd.state = p.out[i].state = st;
    nd.gap = d;
    for (int c = 0; c < 3; ++c) nd.normal[c] = n[c], nd.rel[c] = rel[c];
    nd.facet = n[0] == 0.0 && n[1] == 0.0 && n[2] == 0.0 ? -1 : 0;
    if (st >= contact::Stick)
      for (int c = 0; c < dim_; ++c)
        if (!nd.fixed[c]) r[nd.lid * dim_ + c] = p.mortar_out[i].res[c];
  });
  Kokkos::fence();
}

void Contact::mortar_geometry(Pair& p) {
  p.slave_faces->build(master_x_, &present_);
  if (p.master) p.master->build(master_x_, &present_);
  std::vector<char> needed(p.slave_faces->facets().size(), 0);
  for (const auto& faces : p.node_faces)
    for (int e : faces) needed[static_cast<std::size_t>(e)] = 1;
  const auto cpl = couple_faces(p, needed);
  Kokkos::parallel_for("stentor::mortar_geometry", Kokkos::RangePolicy<la::ExecSpace>(0, p.nodes.size()), [&](const std::size_t i) {
    Slave& nd = p.nodes[i];
    double d = 0.0, n[3], rel[3];
    mortar_node(p, i, cpl, nullptr, &d, n, rel);
    nd.gap = d;
    for (int c = 0; c < 3; ++c) nd.normal[c] = n[c], nd.rel[c] = rel[c];
  });
  Kokkos::fence();
}

}  // namespace stentor
