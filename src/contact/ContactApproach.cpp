// Contact::approach: how far the next step may go before a slave node that is out of
// contact now is predicted to end it deep inside its obstacle or master surface
// (Stepping->contact approach; docs/contact.md, "Steps that land on the contact").
#include <algorithm>
#include <array>
#include <cmath>

#include "contact/Contact.hpp"
#include "contact/MasterSurface.hpp"
#include "parallel/GatherBest.hpp"

namespace stentor {

namespace {
// fraction, gid, pair, gap now, predicted gap, allowed depth: gather_best's record.
constexpr std::size_t kRecord = 6;
}  // namespace

Contact::Approach Contact::approach(const la::Vector& u_n, const la::Vector& u_pred, double t_n, double dt, double depth) const {
  std::vector<double> xm;
  if (has_master_) update_master_positions(u_pred, xm);
  auto un = u_n.getLocalViewHost(Tpetra::Access::ReadOnly);
  auto up = u_pred.getLocalViewHost(Tpetra::Access::ReadOnly);
  std::vector<std::array<double, kRecord>> mine;
  for (std::size_t ip = 0; ip < pairs_.size(); ++ip) {
    const Pair& p = pairs_[ip];
    if (!p.active || p.mortar) continue;
    const contact::Obstacle now = obstacle(p, t_n), next = obstacle(p, t_n + dt);
    // The parts of the slave surface that touch now (an active node on any rank).
    std::vector<int> touching_here(static_cast<std::size_t>(p.parts), 0), touching(touching_here.size(), 0);
    for (const Slave& nd : p.nodes)
      if (nd.was_active && nd.part >= 0) touching_here[static_cast<std::size_t>(nd.part)] = 1;
    if (p.parts > 0)
      Teuchos::reduceAll(*dist_.comm(), Teuchos::REDUCE_MAX, p.parts, touching_here.data(), touching.data());
    std::array<double, kRecord> worst{1.0};
    for (const Slave& nd : p.nodes) {
      if (nd.was_active || !(nd.size > 0.0) || (nd.part >= 0 && touching[static_cast<std::size_t>(nd.part)])) continue;
      double x0[3] = {nd.X[0], nd.X[1], nd.X[2]}, x1[3] = {nd.X[0], nd.X[1], nd.X[2]}, n[3];
      for (int c = 0; c < dim_; ++c) {
        x0[c] += un(nd.lid * dim_ + c, 0);
        x1[c] += up(nd.lid * dim_ + c, 0);
      }
      double g0 = 0.0, g1 = 0.0;
      if (p.master) {
        if (nd.facet < 0) continue;  // nothing within the search radius
        contact::NodeInput in;
        node_input(p, nd, x1, in);
        const auto& fc = p.master->facets()[static_cast<std::size_t>(nd.facet)];
        for (int a = 0; a < fc.nn; ++a)
          for (int c = 0; c < 3; ++c) in.xa[a][c] = xm[3 * static_cast<std::size_t>(fc.node[a]) + static_cast<std::size_t>(c)];
        double rel[3], N[facet::kMaxNodes], a1[3];
        g0 = nd.gap;
        g1 = contact::geometry(in, nullptr, in.xs, in.xa, n, rel, N, a1);
      } else {
        g0 = contact::rigid_gap(now, x0, n);
        g1 = contact::rigid_gap(next, x1, n);
      }
      const double allowed = depth * nd.size;
      if (!(g1 < -allowed)) continue;
      const double from = std::max(g0, 0.0);
      const double f = (from + allowed) / (from - g1);
      if (f < worst[0]) worst = {f, static_cast<double>(nd.gid), static_cast<double>(ip), g0, g1, allowed};
    }
    if (worst[0] < 1.0) mine.push_back(worst);
  }
  const auto best = gather_best<kRecord>(*dist_.comm(), mine, 1, [](const auto& a, const auto& b) { return a[0] < b[0]; });
  Approach out;
  if (best.empty()) return out;
  const auto& b = best.front();
  out.fraction = b[0];
  out.node = static_cast<GId>(b[1]);
  out.pair = static_cast<int>(b[2]);
  out.gap = b[3];
  out.predicted = b[4];
  out.allowed = b[5];
  return out;
}

}  // namespace stentor
