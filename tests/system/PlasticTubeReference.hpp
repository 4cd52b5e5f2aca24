// Radial reference for a thick-walled tube a <= R <= b in plane strain (u_z = 0), J2
// (von Mises) plasticity with linear hardening, loaded by a prescribed bore displacement
// (a frictionless rigid mandrel) and released (bore traction-free). docs/verification.md,
// "Plastic tube expanded by a rigid mandrel".
//
// The deformation is radial, x = (R + u(R)) e_r, so F = diag(F_r, F_t, 1) in (r, theta, z)
// with F_r = 1 + u', F_t = 1 + u/R, and for an isotropic law the stresses are diagonal too.
// Radial equilibrium in the reference configuration (first Piola-Kirchhoff P_r, P_t):
//
//   d(R P_r)/dR = P_t,   a <= R <= b,   P_r(b) = 0,
//   and either u(a) = u_a (the mandrel; the contact pressure is p = -sigma_r(a) = -P_r(a)/F_t(a))
//   or P_r(a) = -p F_t(a) (a follower pressure p on the current bore; p = 0: released);
//   at small strain P = sigma, F_t(a) = 1 in these conditions.
//
// Its weak form, per radian: sum over the radial elements of the integral of
// (P_r dN_i/dR + P_t N_i/R) R dR = f_ext,i, with f_ext,0 = p (a + u(a)) (the pressure times
// the current bore radius). Solved here by linear elements in R with one Gauss point (the
// element midpoint: one volume constraint per element, so a nearly incompressible wall
// does not lock), backward-Euler increments in the load, Newton with a forward-difference
// tridiagonal tangent, that of the elastic law in the first iteration of a release (the
// tangent only steers the iteration; convergence is asserted on the residual). Two point
// laws, with the same interface:
//  - SmallStrainJ2: linear isotropic elasticity (E, nu), von Mises yield Y + H alpha,
//    radial return (exact for this law: one step, Delta gamma = f_trial / (3G + H));
//  - FiniteStrain<Law>: Stentor's multiplicative law itself (neo-Hookean plasticity, the
//    exponential return map of src/material/Plasticity.hpp) at F = diag(F_r, F_t, 1): the
//    finite-strain radial problem the 2D runs solve, without their discretisation.
#pragma once
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

#include "material/ElasticConstants.hpp"
#include "material/NeoHookean.hpp"
#include "material/Plasticity.hpp"

namespace stentor::testing::tube {

// One point update: first Piola-Kirchhoff P_r, P_t, Cauchy sigma_t, the Hill (von Mises)
// norm of the stress and the yield stress after the update, the equivalent plastic strain.
struct PointOut {
  double Pr, Pt, st, q, sy, alpha;  // st: Cauchy hoop stress
};

struct SmallStrainJ2 {
  double E, nu, Y, H;
  struct State {
    double ep[3] = {0.0, 0.0, 0.0};  // plastic strain (r, theta, z)
    double alpha = 0.0;
  };
  static State initial() { return {}; }
  static constexpr bool kFinite = false;  // loads on the reference bore
  SmallStrainJ2 elastic() const { return {E, nu, 1e300, 0.0}; }
  PointOut update(double Fr, double Ft, const State& s0, State& s1) const {
    const Lame l = lame_from_young(E, nu);
    const double e[3] = {Fr - 1.0 - s0.ep[0], Ft - 1.0 - s0.ep[1], -s0.ep[2]};
    const double tr = e[0] + e[1] + e[2];
    double sig[3], s[3];
    for (int i = 0; i < 3; ++i) sig[i] = l.lambda * tr + 2.0 * l.mu * e[i];
    const double mean = (sig[0] + sig[1] + sig[2]) / 3.0;
    for (int i = 0; i < 3; ++i) s[i] = sig[i] - mean;
    double q = std::sqrt(1.5 * (s[0] * s[0] + s[1] * s[1] + s[2] * s[2]));
    s1 = s0;
    const double sy0 = Y + H * s0.alpha;
    if (q > sy0) {
      const double dg = (q - sy0) / (3.0 * l.mu + H);
      for (int i = 0; i < 3; ++i) {
        const double n = 1.5 * s[i] / q;
        s1.ep[i] += dg * n;
        sig[i] -= 2.0 * l.mu * dg * n;
      }
      s1.alpha += dg;
      q -= 3.0 * l.mu * dg;
    }
    return {sig[0], sig[1], sig[1], q, Y + H * s1.alpha, s1.alpha};
  }
};

template <class Law>
struct FiniteStrain {
  Law law;
  using State = PlasticState;
  static State initial() { return {Mat3::identity(), 0.0}; }
  static constexpr bool kFinite = true;  // loads on the current bore
  FiniteStrain elastic() const {
    FiniteStrain f = *this;
    f.law.Y = 1e300;
    return f;
  }
  PointOut update(double Fr, double Ft, const State& s0, State& s1) const {
    Mat3 C = Mat3::zero();
    C(0, 0) = Fr * Fr;
    C(1, 1) = Ft * Ft;
    C(2, 2) = 1.0;
    typename Law::Step st;
    const PointResponse r = law.template update_state<false>(C, s0, st);
    if (!r.converged) throw std::runtime_error("tube reference: return map failed");
    s1 = st.state;
    return {Fr * r.S(0, 0), Ft * r.S(1, 1), Ft * r.S(1, 1) / Fr, st.mandel_hill, law.yield_stress(s1.alpha),
            s1.alpha};
  }
};

template <class Law>
class RadialTube {
 public:
  using State = typename Law::State;
  RadialTube(Law law, double a, double b, int n)
      : law_(law), a_(a), b_(b), n_(n), u_(n + 1, 0.0), state_(n, Law::initial()), trial_(n, Law::initial()),
        out_(n) {}

  // The mandrel: u(a) = ua; returns the contact pressure on the current bore.
  double move_bore(double ua) {
    // Predictor: the increment spread as u ~ 1/R (the incompressible shape), so that no
    // element starts from the jump of the bore node alone.
    const double du = ua - u_[0];
    for (int i = 0; i <= n_; ++i) u_[i] += du * a_ / (a_ + i * (b_ - a_) / n_);
    solve(true, 0.0);
    return pressure();
  }
  // A follower pressure p on the current bore (0: released); returns u(a).
  double press_bore(double p) {
    solve(false, p);
    return u_[0];
  }
  // -sigma_r at the bore: the reaction per radian over the current bore radius.
  double pressure() const { return reaction_ / bore(); }
  double ua() const { return u_[0]; }
  double ub() const { return u_[n_]; }
  int elements() const { return n_; }
  double midpoint(int e) const { return a_ + (e + 0.5) * (b_ - a_) / n_; }
  const PointOut& point(int e) const { return out_[e]; }
  // Cauchy hoop stress at the bore, extrapolated linearly from the first two points.
  double bore_hoop_stress() const {
    return 1.5 * out_[0].st - 0.5 * out_[1].st;
  }
  // Reference radius of the elastic-plastic boundary: the outer edge of the outermost
  // element that has flowed (alpha > 0); a if none, b if all. Resolution (b - a) / n.
  double plastic_radius() const {
    int last = -1;
    for (int e = 0; e < n_; ++e)
      if (out_[e].alpha > 0.0) last = e;
    return a_ + (last + 1) * (b_ - a_) / n_;
  }
  int newton_iterations() const { return iterations_; }

 private:
  // Element midpoint response at the element's displacements (u1, u2): the residual
  // contributions (per radian) to its two nodes.
  void element(const Law& law, int e, double u1, double u2, State& s1, PointOut& o, double r[2]) const {
    const double L = (b_ - a_) / n_, Rm = midpoint(e);
    o = law.update(1.0 + (u2 - u1) / L, 1.0 + 0.5 * (u1 + u2) / Rm, state_[e], s1);
    r[0] = (-o.Pr / L + 0.5 * o.Pt / Rm) * L * Rm;
    r[1] = (o.Pr / L + 0.5 * o.Pt / Rm) * L * Rm;
  }

  // Residual f_int - f_ext and the tridiagonal tangent (sub l, diagonal d, super up).
  // elastic_tangent: the differences of the law with plastic flow switched off (the
  // state frozen), the tangent of an elastic unloading step.
  double assemble(bool dirichlet, double p, bool elastic_tangent, std::vector<double>& res, std::vector<double>& l,
                  std::vector<double>& d, std::vector<double>& up) {
    const Law tangent_law = elastic_tangent ? law_.elastic() : law_;
    const int m = n_ + 1;
    res.assign(m, 0.0);
    l.assign(m, 0.0);
    d.assign(m, 0.0);
    up.assign(m, 0.0);
    const double h = 1e-9 * (b_ - a_);
    for (int e = 0; e < n_; ++e) {
      double r[2], rp[2], r0[2];
      State tmp0;
      PointOut o0;
      // The unperturbed residual of the law the differences use (the elastic one: another).
      if (elastic_tangent) element(tangent_law, e, u_[e], u_[e + 1], tmp0, o0, r0);
      element(law_, e, u_[e], u_[e + 1], trial_[e], out_[e], r);
      State tmp;
      PointOut o;
      res[e] += r[0];
      res[e + 1] += r[1];
      scale_ = std::max(scale_, std::max(std::abs(r[0]), std::abs(r[1])));
      element(tangent_law, e, u_[e] + h, u_[e + 1], tmp, o, rp);
      const double* base = elastic_tangent ? r0 : r;
      d[e] += (rp[0] - base[0]) / h;
      l[e + 1] += (rp[1] - base[1]) / h;
      element(tangent_law, e, u_[e], u_[e + 1] + h, tmp, o, rp);
      up[e] += (rp[0] - base[0]) / h;
      d[e + 1] += (rp[1] - base[1]) / h;
    }
    reaction_ = res[0];
    scale_ = std::max(scale_, std::abs(p) * bore());
    if (dirichlet) {
      res[0] = 0.0;
      d[0] = 1.0;
      up[0] = 0.0;
    } else {
      res[0] -= p * bore();
      if (Law::kFinite) d[0] -= p;
    }
    double worst = 0.0;
    for (double v : res) worst = std::max(worst, std::abs(v));
    return worst;
  }

  void solve(bool dirichlet, double p) {
    std::vector<double> res, l, d, up;
    double last = 0.0;
    for (int it = 0; it < 40; ++it) {
      scale_ = 0.0;  // the largest element force at this iterate
      // The first iteration of a release takes the elastic tangent: from a wall at its limit
      // load the elastic-plastic one is near singular under a prescribed pressure.
      const double r = assemble(dirichlet, p, !dirichlet && it == 0, res, l, d, up);
      // Converged: 1e-11 of the element forces, or stalled at round-off below 1e-7 of them
      // (the round-off of the stresses grows with lambda/E: 1e-8 at nu = 0.49995).
      if (r <= 1e-11 * scale_ || (it >= 2 && r <= 1e-7 * scale_ && r > 0.5 * last)) {
        state_ = trial_;
        return;
      }
      last = r;
      ++iterations_;
      // Thomas algorithm on K du = -res.
      const int m = n_ + 1;
      for (int i = 1; i < m; ++i) {
        const double w = l[i] / d[i - 1];
        d[i] -= w * up[i - 1];
        res[i] -= w * res[i - 1];
      }
      std::vector<double> du(m);
      du[m - 1] = -res[m - 1] / d[m - 1];
      for (int i = m - 2; i >= 0; --i) du[i] = (-res[i] - up[i] * du[i + 1]) / d[i];
      for (int i = 0; i < m; ++i) u_[i] += du[i];
    }
    throw std::runtime_error("tube reference: Newton did not converge");
  }
  // The bore radius the pressure acts on (current at finite strain, reference at small strain).
  double bore() const { return Law::kFinite ? a_ + u_[0] : a_; }

  Law law_;
  double a_, b_;
  int n_;
  std::vector<double> u_;
  std::vector<State> state_, trial_;
  std::vector<PointOut> out_;
  double reaction_ = 0.0, scale_ = 0.0;
  int iterations_ = 0;
};

// The loading history of the mandrel test: the bore moved to ua_max in `load_steps` equal
// increments, then released by the pressure falling to 0 in `release_steps` (while the
// mandrel touches the bore it carries the bore's pressure, whatever its own path).
struct Expansion {
  std::vector<double> ua, p;  // loading path: bore displacement and contact pressure
  double p_max = 0.0;         // at ua_max
  double c = 0.0;             // plastic radius at ua_max (reference configuration)
  double ub_max = 0.0;        // outer displacement at ua_max
  double ua_residual = 0.0;   // bore displacement after release
  double hoop_residual = 0.0; // Cauchy hoop stress at the bore after release
  double hoop_loaded = 0.0;   // at ua_max
  std::vector<double> R, q_max, alpha_max;  // profiles at ua_max (element midpoints)
  std::vector<double> hoop_res;             // Cauchy hoop stress after release (element midpoints)
};

template <class Law>
Expansion expand_and_release(const Law& law, double a, double b, int n, double ua_max, int load_steps,
                             int release_steps) {
  RadialTube<Law> t(law, a, b, n);
  Expansion x;
  for (int k = 1; k <= load_steps; ++k) {
    x.ua.push_back(ua_max * k / load_steps);
    x.p.push_back(t.move_bore(x.ua.back()));
  }
  x.p_max = x.p.back();
  x.c = t.plastic_radius();
  x.ub_max = t.ub();
  x.hoop_loaded = t.bore_hoop_stress();
  for (int e = 0; e < n; ++e) {
    x.R.push_back(t.midpoint(e));
    x.q_max.push_back(t.point(e).q);
    x.alpha_max.push_back(t.point(e).alpha);
  }
  for (int k = 1; k <= release_steps; ++k) t.press_bore(x.p_max * (1.0 - double(k) / release_steps));
  x.ua_residual = t.ua();
  x.hoop_residual = t.bore_hoop_stress();
  for (int e = 0; e < n; ++e) x.hoop_res.push_back(t.point(e).st);
  return x;
}

// A profile given at the element midpoints R (uniform), linearly interpolated at r (held
// constant beyond the first and last midpoints).
inline double interpolate(const std::vector<double>& R, const std::vector<double>& v, double r) {
  if (r <= R.front()) return v.front();
  if (r >= R.back()) return v.back();
  const double h = R[1] - R[0];
  const std::size_t i = std::min(R.size() - 2, static_cast<std::size_t>((r - R.front()) / h));
  const double w = (r - R[i]) / h;
  return (1.0 - w) * v[i] + w * v[i + 1];
}

// The plastic radius read off the elastic zone: there the stresses have Lame's form
// (sigma_r, sigma_t = A -+ B/R^2, sigma_z = 2 nu A at small strain), so q^2 = q0^2 + q1 / R^4
// exactly; a least-squares line through the elastic points (R, q) and q(c) = sigma_y give c.
inline double plastic_radius_from_elastic_zone(const std::vector<double>& R, const std::vector<double>& q, double sy) {
  double s1 = 0, sx = 0, sxx = 0, sy2 = 0, sxy = 0;
  for (std::size_t i = 0; i < R.size(); ++i) {
    const double x = std::pow(R[i], -4.0), y = q[i] * q[i];
    s1 += 1;
    sx += x;
    sxx += x * x;
    sy2 += y;
    sxy += x * y;
  }
  const double q1 = (s1 * sxy - sx * sy2) / (s1 * sxx - sx * sx), q0 = (sy2 - q1 * sx) / s1;
  return std::pow(q1 / (sy * sy - q0), 0.25);
}

}  // namespace stentor::testing::tube
