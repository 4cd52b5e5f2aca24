// Cycle control of the contact sets (Contact.hpp, "Cycle control"): the nodes whose set in
// the solves went back and forth are held for the rest of the step (count_flips), and their
// conditions are checked, and revised, at convergence (verify_held).
#include <Teuchos_CommHelpers.hpp>

#include <algorithm>
#include <cmath>
#include <sstream>

#include "contact/Contact.hpp"

namespace stentor {

using contact::dot3;

namespace {
// The part of v orthogonal to the unit normal n, and its length.
double tangential(const double* v, const double* n, double* vt) {
  const double vn = dot3(v, n);
  for (int c = 0; c < 3; ++c) vt[c] = v[c] - vn * n[c];
  return std::sqrt(dot3(vt, vt));
}
}  // namespace

// A 3D slave node on one plane (one prescribed component, or one `normal` plane e) slides
// only along t1 = e x n / |e x n|, and its friction acts along t1 (NodeLaw.hpp, law()):
// its tangential force and slip are their components along t1. Elsewhere the whole
// tangential part. Returns the length.
double Contact::friction_part(const Slave& nd, const double* v, double* vt) const {
  const double len = tangential(v, nd.normal, vt);
  double e[3], t[3];
  if (!contact::plane_cross(dim_, nd.fixed, nd.planes, nd.e, nd.normal, e, t)) return len;
  const double tl = std::sqrt(dot3(t, t));
  if (!(tl > 0.0)) return len;
  const double a = dot3(v, t) / (tl * tl);
  for (int c = 0; c < 3; ++c) vt[c] = a * t[c];
  return std::abs(a) * tl;
}

// The set of this solve (nd.state) against the last one's (nd.base_state): a node that
// entered or left contact kFreezeAfter times in the step is held active from now on, one
// that changed between stick and slip that often is held slipping, with its friction
// direction fixed to that of q = lambda_tau + c_tau v at this iterate (the direction the
// slip law would take; verify_held may revise it). Node-to-segment: a node whose facet (or
// whether its projection fell inside it) changed kFacetFreezeAfter times is held on its
// facet (hold_facet_projection).
void Contact::count_flips(const Pair& p, Slave& nd) const {
  const bool was = nd.base_state >= contact::Stick, is = nd.state >= contact::Stick;
  if (was != is) ++nd.normal_flips;
  else if (was && nd.state != nd.base_state) ++nd.tangent_flips;
  if (nd.normal_flips >= kFreezeAfter && is && !nd.hold_inactive) nd.hold_active = true;
  if (p.master && !p.mortar && nd.facet >= 0 && nd.solve_facet >= 0 && (nd.facet != nd.solve_facet || nd.inside != nd.solve_inside))
    ++nd.facet_flips;
  nd.solve_facet = nd.facet, nd.solve_inside = nd.inside;
  if (nd.facet_flips >= kFacetFreezeAfter && nd.hold_facet < 0 && is && nd.facet >= 0) nd.hold_facet = nd.facet;
  if (nd.tangent_flips >= kFreezeAfter && nd.hold_tangent == 0) {
    nd.hold_tangent = contact::Slip;
    const double ct = tangent_penalty(p, nd, dt_);
    double ft[3], vt[3], q[3];
    friction_part(nd, nd.f, ft);
    friction_part(nd, nd.rel, vt);
    for (int c = 0; c < 3; ++c) q[c] = -ft[c] + ct * vt[c] / dt_;
    const double qn = std::sqrt(dot3(q, q));
    for (int c = 0; c < 3; ++c) nd.hold_dir[c] = qn > 0.0 ? q[c] / qn : 0.0;
  }
}

namespace {
// The worst failed condition among the held nodes of one rank (kind 1: tension on a held
// active node, 2: a held sticking node outside the Coulomb cone, 3: a held slipping node
// slipping against or across its friction force, 4: a released node penetrating, 5: a node
// held on a facet ending off it). Kind 1 is always revised (the node is released), so
// only 2-5 end a step.
struct HeldFailure {
  double excess = 0.0, value = 0.0, bound = 0.0;
  long long gid = -1;
  int pair = -1, kind = 0;
};

std::string held_message(const HeldFailure& w, const std::string& pair) {
  std::ostringstream os;
  os.precision(4);
  os << "contact node " << w.gid << " of 'Contact->" << pair << "' ";
  if (w.kind == 2) os << "cycled between stick and slip; sticking it ends outside the Coulomb cone, |lambda_tau| = " << w.value
                      << " > mu |lambda_nu| = " << w.bound;
  if (w.kind == 3) os << "cycled between stick and slip; slipping it slides " << w.value << " against or across its friction force";
  if (w.kind == 4) os << "entered and left contact repeatedly; held active it ends in tension, released it penetrates, normal gap measure "
                      << w.value;
  if (w.kind == 5) {
    os << "changed master facets repeatedly; held on a facet, then on its closest one, it ends off the facet by more than "
       << Contact::kHoldBand << " in the facet's parameters";
    return os.str();
  }
  os << " (tolerance " << Contact::kKktTolerance << " x the pair's largest nodal force or slip, or x the node's size)";
  return os.str();
}
}  // namespace

int Contact::verify_held(std::string& why) {
  HeldFailure w;
  long revised = 0;
  for (std::size_t ip = 0; ip < pairs_.size(); ++ip) {
    Pair& p = pairs_[ip];
    // The largest nodal force, tangential slip and relative displacement of the active nodes.
    double loc[3] = {0.0, 0.0, 0.0}, glob[3] = {0.0, 0.0, 0.0};
    for (const auto& nd : p.nodes)
      if (nd.state >= contact::Stick) {
        double st[3];
        loc[0] = std::max(loc[0], std::sqrt(dot3(nd.f, nd.f)));
        loc[1] = std::max(loc[1], friction_part(nd, nd.rel, st));
        loc[2] = std::max(loc[2], std::sqrt(dot3(nd.rel, nd.rel)));
      }
    Teuchos::reduceAll(*dist_.comm(), Teuchos::REDUCE_MAX, 3, loc, glob);
    const double ftol = kKktTolerance * glob[0], stol = kKktTolerance * glob[1], gtol = kKktTolerance * glob[2];
    for (auto& nd : p.nodes) {
      // Lengths (gap, slip) are also allowed kKktTolerance of the node's own size: the
      // pair's largest slip shrinks with the step, and with it a tolerance on it alone
      // (measured: a slip of 5e-7 against the friction force, on cells of 0.01, failed a
      // step cut to 1e-4 of its length).
      const double gtol_n = std::max(gtol, kKktTolerance * nd.size), stol_n = std::max(stol, kKktTolerance * nd.size);
      if (nd.hold_inactive && nd.state != contact::Free) {
        // Released after it ended in tension: it must not penetrate (the law's normal measure).
        const double g = p.persistence ? nd.gap - nd.d_n : nd.gap;
        if (nd.state < contact::Stick && g < -gtol_n) {
          HeldFailure f{(-g - gtol_n) / std::max(gtol_n, 1e-300), g, 0.0, static_cast<long long>(nd.gid), static_cast<int>(ip), 4};
          if (f.excess > w.excess) w = f;
        }
        continue;
      }
      if (nd.hold_facet >= 0 && nd.state >= contact::Stick && !nd.hold_in_band) {
        // Held on a facet past its end: held on its closest facet instead, once; then a failure.
        if (nd.hold_revisions < 2) {
          nd.hold_facet = -2;
          ++nd.hold_revisions;
          ++revised;
          continue;
        }
        HeldFailure f{1.0, 0.0, 0.0, static_cast<long long>(nd.gid), static_cast<int>(ip), 5};
        if (f.excess > w.excess) w = f;
        continue;
      }
      if (!(nd.hold_active || nd.hold_tangent) || nd.state < contact::Stick) continue;
      const double lam_n = -dot3(nd.f, nd.normal);
      double ft[3], st[3];  // the tangential force (lambda_tau = -ft) and slip
      const double lam_t = friction_part(nd, nd.f, ft), slip = friction_part(nd, nd.rel, st);
      const double bound = p.cfg.friction * std::max(-lam_n, 0.0), along = -dot3(ft, st);  // lambda_tau . slip
      // The slip off the friction direction: against it, or (3D) across it.
      const double across = lam_t > 0.0 ? std::sqrt(std::max(slip * slip - along * along / (lam_t * lam_t), 0.0)) : 0.0;
      const double off = std::max(along < 0.0 ? slip : 0.0, across);
      HeldFailure f;
      if (nd.hold_active && lam_n > ftol) f = {lam_n - ftol, lam_n, 0.0, 0, 0, 1};
      else if (nd.hold_tangent == contact::Stick && lam_t - bound > ftol) f = {(lam_t - bound - ftol) / std::max(ftol, 1e-300), lam_t, bound, 0, 0, 2};
      else if (nd.hold_tangent == contact::Slip && off > stol_n) f = {(off - stol_n) / std::max(stol_n, 1e-300), off, 0.0, 0, 0, 3};
      if (f.kind == 0) continue;
      // Revisions: a held slip off its friction direction is held sticking; a held stick
      // outside the cone slips along the force that held it (the direction the load
      // drives it), so the three states of a 2D node are each tried at most once.
      if (f.kind == 1) {  // released: held out of contact, checked for penetration
        nd.hold_active = false;
        nd.hold_inactive = true;
        nd.hold_tangent = 0;
      } else if (f.kind == 3 && nd.hold_revisions == 0) {
        nd.hold_tangent = contact::Stick;
      } else if (f.kind == 2 && nd.hold_revisions < 2 && lam_t > 0.0) {
        nd.hold_tangent = contact::Slip;
        for (int c = 0; c < 3; ++c) nd.hold_dir[c] = -ft[c] / lam_t;
      } else {
        f.kind = -f.kind;
      }
      if (f.kind > 0) {
        ++nd.hold_revisions;
        ++revised;
        continue;
      }
      f.kind = -f.kind;
      f.gid = static_cast<long long>(nd.gid), f.pair = static_cast<int>(ip);
      if (f.excess > w.excess) w = f;
    }
  }
  long grev = 0;
  Teuchos::reduceAll(*dist_.comm(), Teuchos::REDUCE_SUM, 1, &revised, &grev);
  if (grev > 0) return 1;
  double ex = w.excess, gex = 0.0;
  Teuchos::reduceAll(*dist_.comm(), Teuchos::REDUCE_MAX, 1, &ex, &gex);
  if (!(gex > 0.0)) return 0;
  // The highest rank holding the worst excess sends its record.
  const int me = dist_.comm()->getRank();
  int from = w.excess == gex ? me : -1, gfrom = -1;
  Teuchos::reduceAll(*dist_.comm(), Teuchos::REDUCE_MAX, 1, &from, &gfrom);
  double rec[5] = {-1, -1, -1, -1, -1}, grec[5];
  if (me == gfrom) rec[0] = static_cast<double>(w.gid), rec[1] = w.pair, rec[2] = w.kind, rec[3] = w.value, rec[4] = w.bound;
  Teuchos::reduceAll(*dist_.comm(), Teuchos::REDUCE_MAX, 5, rec, grec);
  HeldFailure g;
  g.gid = static_cast<long long>(grec[0]), g.kind = static_cast<int>(grec[2]), g.value = grec[3], g.bound = grec[4];
  why = held_message(g, pairs_[static_cast<std::size_t>(grec[1])].cfg.name);
  return 2;
}

}  // namespace stentor
