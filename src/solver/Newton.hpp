// Newton's method with backtracking line search, for any residual the caller defines.
//
// Convergence (all norms global 2-norms over owned dofs):
//   ||r|| <= max(rtol * ref, atol)                          (residual test), or
//   ||du|| <= inc_tol * ||u||  and  ||r|| <= sqrt(rtol) * ref  (increment test, for
//   steps whose residual is limited by round-off).
// Line search: Armijo backtracking on ||r||, with a watchdog for contact active sets
// (NewtonConfig::line_search_watchdog, explained in line_search()). The full step is
// evaluated with the tangent (it is usually accepted); halved trials are residual-only
// unless the system's residual needs the tangent, and the tangent at an accepted halved
// step is assembled only if Newton goes on.
// Linear tolerance: fixed, or Eisenstat-Walker's forcing term (NewtonConfig::forcing).
// Step-length control (NewtonConfig::max_increment): an update whose largest component
// exceeds the limit is scaled down to it before the line search.
// A trial state the residual cannot be evaluated at (an inverted element) counts as a
// failed line-search trial; if even the smallest step is inadmissible, or the iteration
// limit is reached, the solve fails and the caller cuts the time/load step.
#pragma once
#include <ostream>
#include <string>
#include <vector>

#include "deck/Config.hpp"
#include "parallel/LinearAlgebra.hpp"
#include "solver/LinearSolver.hpp"

namespace stentor {

class NewtonSystem {
 public:
  virtual ~NewtonSystem() = default;
  // r(u) (and the tangent, available through matrix(), when `tangent`). Returns false when
  // u is inadmissible (e.g. det F <= 0 somewhere); r is then undefined.
  virtual bool evaluate(const la::Vector& u, la::Vector& r, bool tangent) = 0;
  virtual la::RCP<la::CrsMatrix> matrix() = 0;
  // Size of the forces in play at the last evaluate() (e.g. |f_ext| and the reactions),
  // the reference of the relative residual test: an initial guess that is already
  // nearly exact makes |r_0| alone a useless (round-off sized) reference.
  virtual double force_scale() const { return 0.0; }
  // False while a discrete part of the residual (e.g. a contact active set) still changed
  // at the last evaluate(): Newton does not stop then, however small the residual.
  virtual bool settled() const { return true; }
  // True if evaluate(u, r, false) can differ from the residual of evaluate(u, r, true)
  // (e.g. contact rows scaled by the tangent's diagonal): line-search trials then
  // assemble the tangent too.
  virtual bool residual_needs_tangent() const { return false; }
  // 2-norm over the dofs of the reference coordinates X (0: unknown). A Newton correction
  // below the round-off of the current coordinates X + u (8 eps (|X| + |u|)) cannot
  // improve the state: Newton stops there (converged to machine precision) however large
  // the residual's own round-off (at strains of 1e-9 and below, C - I loses most digits
  // and the residual floor sat above every target: a 1e-3 Pa traction on a 0.5 MPa block
  // failed after 6 cut-backs).
  virtual double coordinate_scale() const { return 0.0; }
  // After each linear solve, Newton's correction du (limited, before the line search) from
  // the tangent of the last evaluate(); then, before each trial evaluate(u + alpha du),
  // alpha. A system whose discrete part is decided by the multipliers of the linearised
  // problem (contact's primal-dual active set) keeps them as state here.
  virtual void linearised_step(const la::Vector& du) { (void)du; }
  virtual void step_length(double alpha) { (void)alpha; }
  // At convergence, whether the solution meets every condition the iteration held fixed
  // (contact nodes held after cycling): 0 yes; 1 no, and the holds were revised (Newton
  // iterates on); 2 no, `why` says where (Newton fails and the step is cut back).
  virtual int verify_held(std::string& why) {
    (void)why;
    return 0;
  }
  // Rank-one terms of the tangent that matrix() leaves out: dr/du = matrix() + sum_i c_i
  // left_i right_i^T, at the last evaluate() with the tangent (a fluid cavity's pressure-
  // volume coupling, which couples every dof of its wall: a dense block). The linear solve
  // takes them by Sherman-Morrison-Woodbury (linear_solve below).
  struct RankOne {
    const la::Vector* left;
    const la::Vector* right;
    double c;
  };
  virtual std::vector<RankOne> rank_one() const { return {}; }
};

struct NewtonResult {
  bool converged = false;
  int iterations = 0;
  int linear_iterations = 0;
  double residual = 0.0, residual0 = 0.0;
  double first_ratio = 0.0;  // |r_1| / |r_0| of the first iteration (0: none done)
  std::string failure;  // why it failed, for the log
  bool inadmissible = false;  // it failed because an evaluate() found the state inadmissible
};

// One linear solve of a Newton-like iteration (setup for K, then K x = b at relative
// tolerance `tol`, 0: the configured one). When the whole fallback chain fails (on any
// rank: the ranks vote, LinearSolver.hpp), returns false on every rank with `failure`
// set, so the caller cuts the step back; InputError propagates.
bool linear_solve(LinearSolver& lin, const la::RCP<la::CrsMatrix>& K, const la::Vector& b, la::Vector& x, double tol,
                  LinearSolver::Result& res, std::string& failure);
// The same with the system's rank-one terms: (K + sum_i c_i l_i r_i^T) x = b, from K x0 = b and
// K y_i = l_i (one set-up, 1 + m solves): x = x0 - Y (C^-1 + R^T Y)^-1 R^T x0.
bool linear_solve(LinearSolver& lin, NewtonSystem& sys, const la::Vector& b, la::Vector& x, double tol,
                  LinearSolver::Result& res, std::string& failure);

// Rounds of revisions of held contact nodes in one solve (NewtonSystem::verify_held) before
// the step fails. Each round revises at least one node, and a node only a few times (it is
// released once; a held slip becomes a stick once, a held stick a slip at most twice), so
// the rounds end; the bound caps their cost. The S6 stent released by a shrinking cylinder needs 5 rounds
// (137 nodes held at the reversal, where they end in contact with nearly zero force).
constexpr int kMaxHeldRevisions = 16;

// first_ratio_hint > 0: the first iteration's |r_1| / |r_0| in a previous, similar solve (the
// last step's NewtonResult::first_ratio); Eisenstat-Walker forcing then starts from
// 0.9 hint^2 instead of `forcing max` (a step that one tight solve nearly converges, as in
// dynamics, is not solved loosely first).
NewtonResult newton_solve(NewtonSystem& sys, la::Vector& u, LinearSolver& lin, const NewtonConfig& cfg, std::ostream* log,
                          double first_ratio_hint = 0.0);

}  // namespace stentor
