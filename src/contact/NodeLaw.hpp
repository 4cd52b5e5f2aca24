// The contact conditions of one slave node p, as a local function of its unknowns, written
// once and templated on the scalar so that Dual numbers give the exact linearisation.
//
// Local unknowns y (in this order): the slave position x_p (dim values), the positions of
// the master facet's nodes x_a (dim each; none for a rigid obstacle), and the slave's bulk
// residual r_p (dim values; the condensed multiplier: the contact force on the slave is
// F = r_p, talk's lambda_nu = -n . r_p <= 0 in compression, lambda_tau = -(I - n n) r_p).
//
// Geometry: a rigid obstacle gives d(x_p) and n = grad d; a master facet gives the closest
// point x_m = sum_a N_a(xi) x_a, its unit outward normal n and d = n . (x_p - x_m). The
// relative displacement over the step at the contact point is
//   rel = (x_p - x_p,n) - sum_a N_a(xi) (x_a - x_a,n)     (rigid: minus the obstacle's translation).
// Normal measure g: "gap" g = d; "persistence" g = n . rel for a master facet (the normal
// relative velocity times dt: the contact force F = -lambda_nu n does work lambda_nu g on the
// pair, so g = 0 makes frictionless contact exactly work-free) and g = d - d_n for a rigid
// obstacle (the same for a plane; d_n is the gap at the start of the step).
//
// Sets (PDAS, from the current values): active iff lambda_nu + c_nu g / dt' <= 0 (dt' = dt for
// persistence, 1 for gap); in the active set, with q = lambda_tau + c_tau (I - n n) rel / dt,
// slip iff |q| + mu lambda_nu >= 0 (direction s = q / |q|), stick otherwise. These are the
// tests with the bulk residual r as multiplier; where the caller has the last linear solve's
// (LawParams::lam), decide_set's tests apply instead. The rows always use r.
// Rows (the slave's dim rows, replaced; the normal condition goes to the component most
// aligned with n):
//   normal                   s_p g
//   stick tangent k          s_p t_k . rel
//   slip / frictionless k    (t_k + mu (s . t_k) n) . r_p
// and the master nodes' rows receive the reaction: r_a += N_a(xi) r_p (all components; on
// a slave with prescribed components the contact force F_c of contact_force() instead).
// s_p is the slave's largest tangent diagonal (a force/length scale). Inactive nodes keep
// their bulk rows (lambda = 0) and send nothing to the master.
// Prescribed components (a slave node on a symmetry plane): their rows stay Dirichlet rows
// and their bulk residual (zeroed by the assembler) is a constant 0 here; the normal
// condition goes to the free component most aligned with n, and the remaining free rows
// take the tangential conditions along the free directions orthogonal to n (3D with one
// prescribed axis e: t = e x n / |e x n|). A node on planes at any angle (LawParams::planes,
// Assembler::plane_normals) is the same with their normals: its fixed rows carry e_i . du
// = 0 and its bulk residual is the projection on the planes, whose fixed components the
// free ones give (complete_on_planes).
#pragma once
#include <Kokkos_Macros.hpp>
#include <cmath>

#include "contact/Dual.hpp"
#include "contact/FacetGeometry.hpp"

namespace stentor::contact {

constexpr int kMaxLocal = 3 * (1 + facet::kMaxNodes) + 3;
using AD = Dual<kMaxLocal>;

enum State : int { NotSlave = -1, Free = 0, Inactive = 1, Stick = 2, Slip = 3 };

// A rigid analytic obstacle at the end of the step (translation and radius applied).
struct Obstacle {
  int kind = 0;  // 0 plane, 1 circle / sphere, 2 cylinder, 3 capsule
  double point[3] = {0, 0, 0}, normal[3] = {0, 0, 0}, axis[3] = {0, 0, 0};
  double radius = 0.0;
  double length = 0.0;    // capsule: the axis segment runs from point to point + length axis
  bool inside = false;    // body inside the curved obstacle
  double dw[3] = {0, 0, 0};  // translation over the step
};

template <class T>
KOKKOS_INLINE_FUNCTION T rigid_gap(const Obstacle& o, const T x[3], T n[3]) {
  using std::sqrt;
  T r[3];
  for (int k = 0; k < 3; ++k) r[k] = x[k] - o.point[k];
  if (o.kind == 0) {
    for (int k = 0; k < 3; ++k) n[k] = T(o.normal[k]);
    return n[0] * r[0] + n[1] * r[1] + n[2] * r[2];
  }
  if (o.kind == 2 || o.kind == 3) {
    // Cylinder: distance from the axis line. Capsule: from the closest point of the axis
    // segment (clamped to its ends, whose neighbourhoods are spherical / circular caps).
    T a = r[0] * o.axis[0] + r[1] * o.axis[1] + r[2] * o.axis[2];
    if (o.kind == 3) {
      if (value(a) < 0.0) a = T(0.0);
      if (value(a) > o.length) a = T(o.length);
    }
    for (int k = 0; k < 3; ++k) r[k] = r[k] - a * o.axis[k];
  }
  const T rho = sqrt(r[0] * r[0] + r[1] * r[1] + r[2] * r[2]);
  if (value(rho) > 0.0) {
    for (int k = 0; k < 3; ++k) n[k] = r[k] / rho;
  } else {
    n[0] = T(1.0), n[1] = T(0.0), n[2] = T(0.0);
  }
  if (o.inside) {
    for (int k = 0; k < 3; ++k) n[k] = -n[k];
    return o.radius - rho;
  }
  return rho - o.radius;
}

// Everything one evaluation needs about a slave node (host-side record, double).
struct NodeInput {
  int dim = 2;
  int nm = 0;                         // master facet nodes (0: rigid obstacle)
  CellType facet = CellType::Invalid;
  double orient = 1.0;
  double xi[2] = {0, 0};              // closest-point parameters (master facet)
  bool xi_inside = true;              // projection inside the facet (else clamped to its edge or vertex)
  double xi_free[2] = {0, 0};         // clamped: the parameters before clamping (facet::project)
  double xs[3] = {0, 0, 0}, xs_n[3] = {0, 0, 0};
  double xa[facet::kMaxNodes][3] = {}, xa_n[facet::kMaxNodes][3] = {};
  double r[3] = {0, 0, 0};
  double d_n = 0.0;
  bool fixed[3] = {false, false, false};  // prescribed components (their rows are not contact rows)
};

struct LawParams {
  bool persistence = true;
  double dt = 1.0, cn = 1.0, ct = 1.0, mu = 0.0, sp = 1.0;
  double release = 0.0;  // an active node is released when lambda_nu + c_nu g > release (>= 0)
  // The multiplier that decides the sets (values only; the rows keep the bulk residual r):
  // with `has_lam`, the contact force of the last linear solve at this iterate (Contact::
  // linearised_step: 0 for a node inactive in that solve), else r itself.
  bool has_lam = false;
  double lam[3] = {0, 0, 0};
  int base = Free;  // with has_lam: the node's set in that solve (decide_set)
  // Cycle control (Contact::linearised_step): a node whose set flipped back and forth in this
  // step is held active (force_active) and/or in one tangential state (force_tangent: Stick
  // or Slip; 0 none) until the step ends; its conditions are checked at convergence
  // (Contact::verify_held).
  bool force_active = false;
  bool force_inactive = false;  // held out of contact (Contact::verify_held's revision of a held active node)
  int force_tangent = 0;
  // A node held slipping slides with a fixed friction direction (world frame, projected on
  // the current tangent plane): the held equations are then smooth, and their solution is
  // checked at convergence (Contact::verify_held). Unset: the direction of q.
  bool has_slip_dir = false;
  double slip_dir[3] = {0, 0, 0};
  // The node slides on planes (`normal` Dirichlet sets): orthonormal directions e_i, whose
  // constraint rows are the components pj_i (Assembler::plane_normals).
  int planes = 0;
  double e[3][3] = {};
  int pj[3] = {0, 0, 0};
};

// A vector v on the node's planes (e_i . v = 0) from its free components: the components
// pj_i, which carry the constraint rows, solve sum_l e_i(pj_l) v_pj_l = -sum_{k free} e_i(k)
// v_k (Cramer; prescribed Cartesian components are 0 in v and in e_i).
template <class T>
KOKKOS_INLINE_FUNCTION void complete_on_planes(const LawParams& p, T v[3]) {
  const int m = p.planes;
  if (m == 0) return;
  bool row[3] = {false, false, false};
  for (int i = 0; i < m; ++i) row[p.pj[i]] = true;
  T b[3] = {T(0.0), T(0.0), T(0.0)};
  for (int i = 0; i < m; ++i)
    for (int c = 0; c < 3; ++c)
      if (!row[c]) b[i] -= p.e[i][c] * v[c];
  if (m == 1) {
    v[p.pj[0]] = b[0] / p.e[0][p.pj[0]];
  } else if (m == 2) {
    const double a00 = p.e[0][p.pj[0]], a01 = p.e[0][p.pj[1]], a10 = p.e[1][p.pj[0]], a11 = p.e[1][p.pj[1]];
    const double det = a00 * a11 - a01 * a10;
    v[p.pj[0]] = (a11 * b[0] - a01 * b[1]) / det;
    v[p.pj[1]] = (a00 * b[1] - a10 * b[0]) / det;
  } else {
    for (int i = 0; i < 3; ++i) v[p.pj[i]] = T(0.0);
  }
}

// Results of one evaluation (double): values and derivatives with respect to y.
struct NodeOutput {
  int state = Free;
  int nvar = 0;                       // dim (2 + nm) unknowns
  double gap = 0.0, normal[3] = {0, 0, 0}, rel[3] = {0, 0, 0};
  double res[3] = {0, 0, 0};          // replaced slave rows
  double dres[3][kMaxLocal] = {};
  double add[facet::kMaxNodes][3] = {};  // additions to the master rows
  double dadd[facet::kMaxNodes][3][kMaxLocal] = {};
};

// Orthonormal tangents: from the facet's first covariant tangent (master facets, smooth
// in the unknowns) or from the least aligned axis (rigid obstacles).
template <class T>
KOKKOS_INLINE_FUNCTION void tangents(int dim, const T n[3], const T* a1, T t[2][3]) {
  using std::sqrt;
  if (dim == 2) {
    t[0][0] = -n[1], t[0][1] = n[0], t[0][2] = T(0.0);
    return;
  }
  T e[3];
  if (a1) {
    // t1 = (a1 - (a1.n) n) / |.|
    const T an = a1[0] * n[0] + a1[1] * n[1] + a1[2] * n[2];
    for (int c = 0; c < 3; ++c) e[c] = a1[c] - an * n[c];
    const T len = sqrt(e[0] * e[0] + e[1] * e[1] + e[2] * e[2]);
    for (int c = 0; c < 3; ++c) t[0][c] = e[c] / len;
  } else {
    int k = 0;
    for (int c = 1; c < 3; ++c)
      if (std::abs(value(n[c])) < std::abs(value(n[k]))) k = c;
    for (int c = 0; c < 3; ++c) e[c] = T(c == k ? 1.0 : 0.0);
    T a[3] = {n[1] * e[2] - n[2] * e[1], n[2] * e[0] - n[0] * e[2], n[0] * e[1] - n[1] * e[0]};
    const T len = sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
    for (int c = 0; c < 3; ++c) t[0][c] = a[c] / len;
  }
  t[1][0] = n[1] * t[0][2] - n[2] * t[0][1];
  t[1][1] = n[2] * t[0][0] - n[0] * t[0][2];
  t[1][2] = n[0] * t[0][1] - n[1] * t[0][0];
}

// Exact d g_k / d xi_l of the projection equations g_k = a_k . (x_s - x_m) at xi0 (double).
KOKKOS_INLINE_FUNCTION void projection_jacobian(const NodeInput& in, const double xi0[2], double J[2][2]) {
  using D2 = Dual<2>;
  D2 xi[2] = {D2::seed(xi0[0], 0), D2::seed(xi0[1], 1)};
  D2 x[facet::kMaxNodes][3];
  for (int a = 0; a < in.nm; ++a)
    for (int c = 0; c < 3; ++c) x[a][c] = D2(in.xa[a][c]);
  facet::Frame<D2> f;
  facet::frame(in.facet, in.nm, in.dim, 1.0, x, xi, f);
  for (int k = 0; k < in.dim - 1; ++k) {
    D2 g(0.0);
    for (int c = 0; c < 3; ++c) g += f.a[k][c] * (in.xs[c] - f.xm[c]);
    for (int l = 0; l < 2; ++l) J[k][l] = g.d[l];
  }
}

// The closest-point parameters as functions of the unknowns: xi* - J^-1 g(xi*, y) (exact
// first derivatives, since g(xi*) = 0 and J = dg/dxi at xi*). A projection past the facet's
// edge is facet::project's clamp of the root on the extended facet, xi_free: the same
// expression at xi_free, then clamped (facet::clamp_t), so the parameter along an edge
// keeps its derivative (3D) and only the clamped ones are constants (2D: an end point).
template <class T>
KOKKOS_INLINE_FUNCTION void projection_parameters(const NodeInput& in, const T xs[3], const T (*xa)[3], T xi[2]) {
  const double* xi0 = in.xi_inside ? in.xi : in.xi_free;
  xi[0] = T(xi0[0]);
  xi[1] = T(xi0[1]);
  double J[2][2] = {{1.0, 0.0}, {0.0, 1.0}};
  projection_jacobian(in, xi0, J);
  facet::Frame<T> f;
  facet::frame(in.facet, in.nm, in.dim, 1.0, xa, xi, f);
  T g[2] = {T(0.0), T(0.0)};
  for (int k = 0; k < in.dim - 1; ++k)
    for (int c = 0; c < 3; ++c) g[k] += f.a[k][c] * (xs[c] - f.xm[c]);
  if (in.dim == 2) {
    xi[0] = xi[0] - g[0] / J[0][0];
  } else {
    const double det = J[0][0] * J[1][1] - J[0][1] * J[1][0];
    const T d0 = (J[1][1] * g[0] - J[0][1] * g[1]) / det, d1 = (J[0][0] * g[1] - J[1][0] * g[0]) / det;
    xi[0] = xi[0] - d0;
    xi[1] = xi[1] - d1;
  }
  if (!in.xi_inside) facet::clamp_t(in.facet, xi);
}

// Gap, normal, relative displacement and (facets) the shape-function values at the
// contact point.
template <class T>
KOKKOS_INLINE_FUNCTION T geometry(const NodeInput& in, const Obstacle* ob, const T xs[3], const T (*xa)[3], T n[3], T rel[3], T* N,
                                  T a1[3]) {
  if (in.nm == 0) {
    const T d = rigid_gap(*ob, xs, n);
    for (int c = 0; c < 3; ++c) rel[c] = xs[c] - in.xs_n[c] - ob->dw[c];
    return d;
  }
  T xi[2];
  projection_parameters(in, xs, xa, xi);
  facet::Frame<T> f;
  facet::frame(in.facet, in.nm, in.dim, in.orient, xa, xi, f);
  for (int c = 0; c < 3; ++c) {
    n[c] = f.n[c];
    a1[c] = f.a[0][c];
    rel[c] = xs[c] - in.xs_n[c];
    for (int a = 0; a < in.nm; ++a) rel[c] = rel[c] - f.N[a] * (xa[a][c] - in.xa_n[a][c]);
  }
  for (int a = 0; a < in.nm; ++a) N[a] = f.N[a];
  return n[0] * (xs[0] - f.xm[0]) + n[1] * (xs[1] - f.xm[1]) + n[2] * (xs[2] - f.xm[2]);
}

template <class T>
KOKKOS_INLINE_FUNCTION T dot3(const T* a, const T* b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

// The node's set at this iterate, from values: 0 inactive, 1 stick (or frictionless), 2
// slip. f is the deciding multiplier (the bulk residual r, or the last solve's, LawParams::
// lam), lam_n = -n . f, g the normal measure over dt' (dt with persistence, else 1), rel_t
// the tangential relative displacement over dt, q = lambda_tau + c_tau rel_t.
//   Without the last solve's multipliers (`set update` = residual): active iff
//   lambda_nu + c_nu g <= release; slip iff |q| >= mu |lambda_nu|.
//   With them (primal-dual active set; Hueber-Stadler-Wohlmuth 2008), each node is decided
//   by what its own set in that solve left free: a node active in it (whose linearised gap
//   is zero) stays active iff it presses, lambda_nu <= release; a node inactive in it
//   (lambda = 0) enters iff it penetrates, c_nu g <= release, and enters sticking iff its
//   slip is below the augmented bound, c_tau |rel_t| < mu c_nu (-g) (Alart-Curnier); a
//   sticking node (zero linearised slip) stays sticking iff |lambda_tau| <= mu |lambda_nu|;
//   a slipping node (lambda_tau on the cone) keeps slipping iff it slides along
//   lambda_tau, rel_t . lambda_tau >= 0. No decision then weighs a multiplier against
//   c times the nonlinear remainder of a constraint the solve met, so the sets do not
//   depend on c_nu, c_tau (only the entering nodes' stick/slip on their ratio).
// Held nodes (cycle control) keep the held set.
struct SetInput {
  double lam_n, g, lam_t[3], rel_t[3], q[3];
};

KOKKOS_INLINE_FUNCTION int decide_set(const LawParams& p, const SetInput& in) {
  const double lam_aug = in.lam_n + p.cn * in.g;
  const bool from_solve = p.has_lam && p.base >= Stick;
  bool active = from_solve ? in.lam_n <= p.release : (p.has_lam ? p.cn * in.g : lam_aug) <= p.release;
  if (p.force_active) active = true;
  if (p.force_inactive) active = false;
  if (!active) return 0;
  if (!(p.mu > 0.0)) return 1;
  if (p.force_tangent != 0) return p.force_tangent == Stick ? 1 : 2;
  const double lt = std::sqrt(dot3(in.lam_t, in.lam_t)), qn = std::sqrt(dot3(in.q, in.q));
  if (!p.has_lam) return qn >= -p.mu * in.lam_n ? 2 : 1;
  if (p.base == Stick) return lt > -p.mu * std::min(in.lam_n, 0.0) ? 2 : 1;
  if (p.base == Slip) return dot3(in.rel_t, in.lam_t) >= 0.0 ? 2 : 1;
  return qn >= -p.mu * std::min(lam_aug, 0.0) ? 2 : 1;
}

// A 3D slave node on one plane (one prescribed component, or one `normal` plane): the
// plane's unit normal e (the prescribed axis, or the plane's e_0) and a = e x n, whose
// direction is the node's one free tangential direction t1. False (e, a untouched) unless
// dim = 3 with exactly one prescribed component. Shared by law(), contact_force() and the
// cycle control's checks (ContactHolds.cpp).
template <class T>
KOKKOS_INLINE_FUNCTION bool plane_cross(int dim, const bool fixed[3], int planes, const double (&pe)[3][3], const T n[3], double e[3],
                                        T a[3]) {
  int nfixed = 0, axis = 0;
  for (int c = 0; c < dim; ++c)
    if (fixed[c]) ++nfixed, axis = c;
  if (dim != 3 || nfixed != 1) return false;
  for (int c = 0; c < 3; ++c) e[c] = planes == 1 ? pe[0][c] : (c == axis ? 1.0 : 0.0);
  a[0] = e[1] * n[2] - e[2] * n[1], a[1] = e[2] * n[0] - e[0] * n[2], a[2] = e[0] * n[1] - e[1] * n[0];
  return true;
}

// The law of one active or candidate slave node in scalar T, from its geometry: the
// normal measure d (gap) and, with persistence, g = n . rel (master surfaces) or d - d_n
// (rigid), the normal n, the relative displacement rel, the tangent direction a1 (null:
// from the least aligned axis) and the bulk residual r. res: the slave's rows. Returns the
// state. Branches use the values only. Shared by node-to-segment and mortar (Mortar.hpp).
template <class T>
KOKKOS_INLINE_FUNCTION int law(int dim, const bool fixed[3], const LawParams& p, const T& g, const T n[3], const T rel[3], const T* a1,
                               const T r[3], T res[3], const double normal[3]) {
  using std::sqrt;
  const T rn = dot3(n, r);
  T t[2][3];
  tangents(dim, n, a1, t);
  // 3D on one plane: the one free tangential direction t1 = e x n / |e x n|. The node can
  // slide only along it, and its friction force acts along it (the mirror image across the
  // plane cancels the rest), so the sets and the slip direction are decided from the
  // components along t1 alone: the tangential projections of r and rel off the plane (from
  // the tilt of n against it) are not friction.
  double e[3];
  T a[3];
  const bool one_tangent = plane_cross(dim, fixed, p.planes, p.e, n, e, a);
  if (one_tangent) {
    const T len = sqrt(dot3(a, a));
    for (int c = 0; c < 3; ++c) t[0][c] = a[c] / len;
  }
  const T reln = dot3(n, rel);
  T q[3];
  // The decision's values: the deciding multiplier f (r unless p.has_lam).
  SetInput si;
  double f[3], nv[3];
  for (int c = 0; c < 3; ++c) f[c] = p.has_lam ? p.lam[c] : value(r[c]), nv[c] = value(n[c]);
  const double fn = dot3(f, nv);
  si.lam_n = -fn;
  si.g = value(g) / (p.persistence ? p.dt : 1.0);
  for (int c = 0; c < 3; ++c) {
    const T relt = (rel[c] - reln * n[c]) / p.dt;
    q[c] = -(r[c] - rn * n[c]) + p.ct * relt;
    si.lam_t[c] = -(f[c] - fn * nv[c]);
    si.rel_t[c] = value(relt);
  }
  if (one_tangent) {
    const T qt = dot3(q, t[0]);
    double t1[3], lt = 0.0, st = 0.0;
    for (int c = 0; c < 3; ++c) t1[c] = value(t[0][c]), lt += si.lam_t[c] * t1[c], st += si.rel_t[c] * t1[c];
    for (int c = 0; c < 3; ++c) q[c] = qt * t[0][c], si.lam_t[c] = lt * t1[c], si.rel_t[c] = st * t1[c];
  }
  for (int c = 0; c < 3; ++c) si.q[c] = si.lam_t[c] + p.ct * si.rel_t[c];
  const int set = decide_set(p, si);
  if (set == 0) return Inactive;
  bool stick = false;
  T s[3] = {T(0.0), T(0.0), T(0.0)};
  if (p.mu > 0.0) {
    const T qn = sqrt(dot3(q, q));
    T dt_[3];  // the held direction on the tangent plane
    if (set == 2 && p.has_slip_dir) {
      const T dn = p.slip_dir[0] * n[0] + p.slip_dir[1] * n[1] + p.slip_dir[2] * n[2];
      for (int c = 0; c < 3; ++c) dt_[c] = p.slip_dir[c] - dn * n[c];
    }
    const T dl = set == 2 && p.has_slip_dir ? sqrt(dot3(dt_, dt_)) : T(0.0);
    if (set == 2 && value(dl) > 1e-3) {
      for (int c = 0; c < 3; ++c) s[c] = dt_[c] / dl;
    } else if (set == 2 && value(qn) > 0.0) {
      for (int c = 0; c < 3; ++c) s[c] = q[c] / qn;
    } else {
      stick = true;
    }
  }
  int slot_n = -1;
  for (int c = 0; c < dim; ++c)
    if (!fixed[c] && (slot_n < 0 || std::abs(normal[c]) > std::abs(normal[slot_n]))) slot_n = c;
  int slot_t[2] = {0, 0}, nt = 0;
  for (int c = 0; c < dim; ++c)
    if (c != slot_n && !fixed[c]) slot_t[nt++] = c;
  // 3D, two tangents: each goes to the free component it is most aligned with, so the row's
  // diagonal entry is its leading term. In component order, a plane z = 0 (t1 = e_y, t2 =
  // -e_x) put t1 . r_p on the x row: a zero diagonal on stick rows and an off-diagonal
  // stiffness on slip rows, which Gauss-Seidel (MueLu's smoother) cannot relax (GMRES
  // stalled, docs/solvers.md "Contact rows and Gauss-Seidel").
  if (nt == 2 && std::abs(value(t[0][slot_t[1]])) > std::abs(value(t[0][slot_t[0]]))) {
    const int s0 = slot_t[0];
    slot_t[0] = slot_t[1];
    slot_t[1] = s0;
  }
  res[slot_n] = p.sp * g;
  for (int k = 0; k < nt; ++k) {
    if (stick) {
      res[slot_t[k]] = p.sp * dot3(t[k], rel);
    } else {
      const T st = p.mu * dot3(s, t[k]);
      T comb[3];
      for (int c = 0; c < 3; ++c) comb[c] = t[k][c] + st * n[c];
      res[slot_t[k]] = dot3(comb, r);
    }
  }
  return stick ? Stick : Slip;
}

// The contact force F_c on a slave node with prescribed components (on symmetry planes):
// the force that acts between the slave and the master, in the directions the contact
// conditions act in (n and the free tangents), whose part along the node's free
// directions V is its bulk residual r (r is in V: prescribed components zeroed, `normal`
// planes completed). The rest of F_c, across V, is taken by the planes' reaction at the
// slave, which does no work; the master receives -F_c. (Sending it -r instead sends it
// the plane's reaction too, which works on the master's motion off the plane: with
// persistence the pair's work was then not zero, and a dynamic run's energy identity
// closed only to that work.) Without prescribed components F_c = r.
//   3D, one plane e (one free tangent t1 = e x n): F_c = (r . n) / (1 - (n . e)^2) n + (r . t1) t1;
//   one free direction v (2D with one prescribed component, 3D with two): F_c = (r . v) / (n . v) n.
template <class T>
KOKKOS_INLINE_FUNCTION void contact_force(int dim, const bool fixed[3], const LawParams& p, const T n[3], const T r[3], T F[3]) {
  using std::sqrt;
  int nfixed = 0, free_axis = 0;
  for (int c = 0; c < dim; ++c) {
    if (fixed[c]) ++nfixed;
    else free_axis = c;
  }
  for (int c = 0; c < 3; ++c) F[c] = r[c];
  if (nfixed == 0 || nfixed >= dim) return;
  double e[3];
  T t[3];
  if (plane_cross(dim, fixed, p.planes, p.e, n, e, t)) {
    const T ne = n[0] * e[0] + n[1] * e[1] + n[2] * e[2];
    const T tl = sqrt(dot3(t, t));
    if (!(value(tl) > 1e-6)) return;  // n along the plane's normal: no tangent, leave r
    for (int c = 0; c < 3; ++c) t[c] = t[c] / tl;
    const T a = dot3(r, n) / (1.0 - ne * ne), b = dot3(r, t);
    for (int c = 0; c < 3; ++c) F[c] = a * n[c] + b * t[c];
    return;
  }
  T v[3] = {T(0.0), T(0.0), T(0.0)};
  if (p.planes == 0) {
    v[free_axis] = T(1.0);
  } else {
    const T rl = sqrt(dot3(r, r));
    if (!(value(rl) > 0.0)) return;
    for (int c = 0; c < 3; ++c) v[c] = r[c] / rl;
  }
  const T nv = dot3(n, v);
  if (!(std::abs(value(nv)) > 1e-6)) return;
  const T a = dot3(r, v) / nv;
  for (int c = 0; c < 3; ++c) F[c] = a * n[c];
}

// The conditions of one node in scalar T. res: the slave's rows; add: master rows' additions.
// Returns the state. Branches use the values only.
template <class T>
KOKKOS_INLINE_FUNCTION int conditions(const NodeInput& in, const LawParams& p, const Obstacle* ob, const T xs[3], const T (*xa)[3],
                                      const T r[3], T res[3], T (*add)[3], double* gap, double* normal, double* relv) {
  T n[3], rel[3], N[facet::kMaxNodes], a1[3];
  const T d = geometry(in, ob, xs, xa, n, rel, N, a1);
  *gap = value(d);
  for (int c = 0; c < 3; ++c) normal[c] = value(n[c]), relv[c] = value(rel[c]);
  T g = d;
  if (p.persistence) g = in.nm == 0 ? d - in.d_n : dot3(n, rel);
  const int state = law(in.dim, in.fixed, p, g, n, rel, in.nm ? a1 : static_cast<const T*>(nullptr), r, res, normal);
  if (state == Inactive) return state;
  T F[3];
  contact_force(in.dim, in.fixed, p, n, r, F);
  for (int a = 0; a < in.nm; ++a)
    for (int c = 0; c < in.dim; ++c) add[a][c] = N[a] * F[c];
  return state;
}

// Evaluates the conditions with Dual numbers seeded on y and unpacks values and
// derivatives into out.
KOKKOS_INLINE_FUNCTION void evaluate(const NodeInput& in, const LawParams& p, const Obstacle* ob, NodeOutput& out) {
  const int dim = in.dim;
  int v = 0;
  AD xs[3], xa[facet::kMaxNodes][3], r[3];
  for (int c = 0; c < 3; ++c) xs[c] = c < dim ? AD::seed(in.xs[c], v++) : AD(in.xs[c]);
  for (int a = 0; a < in.nm; ++a)
    for (int c = 0; c < 3; ++c) xa[a][c] = c < dim ? AD::seed(in.xa[a][c], v++) : AD(in.xa[a][c]);
  // A prescribed component's bulk residual is zeroed by the assembler: a constant here.
  for (int c = 0; c < 3; ++c) {
    r[c] = AD(0.0);
    if (c >= dim) continue;
    if (!in.fixed[c]) r[c] = AD::seed(in.r[c], v);
    ++v;  // the layout keeps a slot per component
  }
  complete_on_planes(p, r);
  out.nvar = v;
  AD res[3], add[facet::kMaxNodes][3];
  out.state = conditions(in, p, ob, xs, xa, r, res, add, &out.gap, out.normal, out.rel);
  if (out.state == Inactive) return;
  for (int k = 0; k < dim; ++k) {
    if (in.fixed[k]) continue;
    out.res[k] = res[k].v;
    for (int j = 0; j < v && j < kMaxLocal; ++j) out.dres[k][j] = res[k].d[j];
  }
  for (int a = 0; a < in.nm; ++a)
    for (int c = 0; c < dim; ++c) {
      out.add[a][c] = add[a][c].v;
      for (int j = 0; j < v && j < kMaxLocal; ++j) out.dadd[a][c][j] = add[a][c].d[j];
    }
}

}  // namespace stentor::contact
