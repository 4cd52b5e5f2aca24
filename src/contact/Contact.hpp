// Node-to-rigid-obstacle frictional contact, solved by the primal-dual active set
// (semi-smooth Newton) method inside the global Newton loop (docs/contact.md).
//
// The multipliers are condensed: at a Newton iterate u the contact force on a slave node
// is what balances the bulk residual there, f_c = r_bulk,p, so (talk's signs, lambda_nu <= 0
// in compression, residual R = r_bulk + lambda_nu n + lambda_tau = 0)
//   lambda_nu = -n . r_bulk,p,   lambda_tau = -(I - n n) r_bulk,p.
// Each evaluation decides, from (lambda^k, u^k), the sets
//   A_nu  = {lambda_nu + c_nu g <= 0} (g = delta d_nu = (d(x) - d_n)/dt for "persistence",
//                                       g = d(x) for "gap"), inactive otherwise (lambda = 0);
//   slip  = {|lambda_tau + c_tau delta d_tau| + mu lambda_nu >= 0} in A_nu, stick otherwise;
// and rewrites the node's rows of the owned residual and tangent in its (n, t[, t2]) basis:
//   active normal row   s_p (d(x) - target) with row s_p n^T  (target d_n or 0),
//   stick tangent rows  s_p t_i . (x - x_n - dw)   with rows s_p t_i^T,
//   slip / frictionless (t_i + mu (s . t_i) n)^T r_bulk with rows (t_i + mu (s . t_i) n)^T K,
// s_p being the node's largest tangent diagonal (a force/length scale). The derivatives of
// n, t and of the slip direction s are neglected (exact for a plane and in 2D slip).
// For "persistence" only nodes whose leapfrog gap d_n + (dt/2dt_last)(d_n - d_{n-1}) <= 0
// are candidates, and so are the nodes that ended the last step active (persistence keeps
// them in contact until lambda_nu + c_nu delta d_nu > 0 releases them); the others are free.
#pragma once
#include <array>
#include <memory>
#include <string>
#include <vector>

#include "assembly/Assembler.hpp"
#include "deck/Config.hpp"
#include "mesh/Mesh.hpp"
#include "parallel/Distribution.hpp"

namespace stentor {

class Contact {
 public:
  // nullptr when the deck has no "Contact" sublist: a run without contact pays nothing.
  static std::unique_ptr<Contact> create(const Config& cfg, const Mesh& mesh, const Distribution& dist, const Assembler& assembler);
  Contact(const Config& cfg, const Mesh& mesh, const Distribution& dist, const Assembler& assembler);

  // Gap history at t = 0 from u_0 (d_{-1} = d_0).
  void initialize(const la::Vector& u0, double end_time);
  // The step t_n -> t_n + dt from the converged u_n.
  void begin_step(double t_n, double dt, const la::Vector& u_n);
  // After Assembler::assemble(): active sets from u, then the slave nodes' rows of r
  // (owned) and, when K is given, of the tangent. Purely local.
  void apply(const la::Vector& u, la::Vector& r, la::CrsMatrix* K);

  struct PairStats {
    long active = 0, stick = 0, slip = 0;
    std::array<double, 3> force{};  // total contact force on the body (sum over active nodes)
    double min_gap = 0.0;
  };
  struct StepStats {
    std::vector<PairStats> pairs;
    double work = 0.0;                 // normal work (+ tangential work of a moving obstacle) on the body over the step
    double friction_dissipation = 0.0; // -f_tau . (du - dw)_tau >= 0 over the step
  };
  // Global set sizes of the last apply() (collective), e.g. "contact 3 active (1 stick, 2 slip)".
  std::string iteration_summary() const;
  // After a converged step at u_{n+1} (the last apply() was at u_{n+1}): forces, energy
  // terms, set sizes (collective); then d_{n-1} <- d_n <- d(x_{n+1}, t_{n+1}).
  StepStats accept(const la::Vector& u_np1);

  // Per owned slave node, for the HDF5 output: global node id and 6 values
  // (state: 0 free, 1 inactive, 2 stick, 3 slip; gap d(x, t); lambda_nu; lambda_tau x, y, z),
  // from the last apply() at u.
  struct NodalFields {
    std::vector<long long> nodes;
    std::vector<double> values;  // 6 per node
  };
  NodalFields nodal_fields(const la::Vector& u) const;

  std::vector<std::string> history_columns() const;
  std::vector<double> history_values(const StepStats& s) const;
  std::string progress(const StepStats& s) const;
  std::string description() const;

 private:
  struct Node {
    la::LO lid = 0;                  // owned node index
    std::array<la::LO, 3> col{};     // local column index (tangent's column map) of the node's dofs
    double X[3] = {0, 0, 0};
    double x_n[3] = {0, 0, 0};
    double d_n = 0.0, d_prev = 0.0;
    double scale = 1.0;              // s_p
    bool was_active = false;         // active at the end of the last accepted step
    int state = 0;                   // 0 free (not a candidate), 1 inactive, 2 stick, 3 slip (2, 3: active)
    double f[3] = {0, 0, 0};         // r_bulk at the node at the last apply()
  };
  struct Pair {
    ContactPairConfig cfg;
    bool persistence = true;
    std::vector<Node> nodes;
    long excluded = 0;               // slave nodes with a prescribed component (left out), global
  };
  // Signed gap and its gradient (unit normal, 3 components) at x, time t.
  double gap(const Pair& p, const double* x, double t, double* n) const;
  std::array<double, 3> translation(const Pair& p, double t) const;

  int dim_;
  double end_time_ = 1.0, t0_ = 0.0, t1_ = 0.0, dt_ = 1.0, dt_last_ = 0.0, gap_tol_ = 0.0;
  const Distribution& dist_;
  std::vector<Pair> pairs_;
};

}  // namespace stentor
