// The linear solve inside each Newton iteration: Belos GMRES preconditioned by MueLu
// (smoothed aggregation; the default where Trilinos has it) or Ifpack2 additive Schwarz
// (ILU subdomain solves), or a direct solve (Amesos2 KLU2, or MUMPS across the ranks:
// solver/MumpsSolver.hpp). The matrix graph never changes, so symbolic work (Schwarz
// overlap, ILU pattern, KLU symbolic factorization, MUMPS analysis) is done once; numeric
// work once per Newton iteration.
//
// Fallback: when the preconditioner set-up or a solve throws on any rank (e.g. MueLu's
// "damping factor needs to be finite" on a matrix with zero diagonal entries, an ILU
// breakdown, Belos's "residual norms is NaN"), or a GMRES solve ends with a non-finite
// residual or solution, or gains less than one digit (relative residual > 0.1) in its first
// cycle with a preconditioner built for this very matrix, the solver moves one step down the chain
// muelu -> schwarz (RILUK) -> direct (`direct solver`) for the rest of the run, solves the same
// system again, and prints one warning line on rank 0. On several ranks the ranks vote
// after every set-up and solve (parallel/Agreement.hpp), so all of them take the same
// branch, whichever rank threw; a rank stuck inside a collective of the package ends the
// job with exit status 3 after the vote's time limit, never a hang. Only a failure of the
// last link reaches Newton: LinearSolverFailure, thrown on every rank alike (a failed
// iteration: cut-back).
//
// A preconditioner is kept across Newton iterations and steps while the matrix graph stays
// the same (Linear Solver->preconditioner reuse), and rebuilt when solver/ReusePolicy.hpp
// says the GMRES iterations it loses outweigh a build, or after tangent_changed() (Newton:
// a changed contact active set) or rebuild_preconditioner() (a checkpoint). A kept one with
// which GMRES gains less than one digit in its first cycle is rebuilt for the current matrix
// and the system solved again; only a freshly built one that stalls moves down the chain.
#pragma once
#include <memory>
#include <string>
#include <vector>

#include "deck/Config.hpp"
#include "parallel/LinearAlgebra.hpp"
#include "solver/SolverFailure.hpp"

namespace stentor {

struct Agreement;

class LinearSolver {
 public:
  LinearSolver(const LinearSolverConfig& cfg, const la::RCP<const la::Comm>& comm);
  ~LinearSolver();

  // Reference coordinates of the owned nodes (3 per node, in the order of the owned
  // dof map's nodes; dof = node*dim + c). Multigrid builds the rigid-body modes of
  // elasticity from them; other preconditioners ignore them. Call before setup().
  void set_node_coordinates(int dim, const std::vector<double>& owned_xyz);

  // New matrix values (same graph as the previous call, if any).
  void setup(const la::RCP<la::CrsMatrix>& A);

  struct Result {
    bool converged = false;
    int iterations = 0;
    double residual = 0.0;  // achieved relative residual (0 for direct)
  };
  // tolerance > 0: this solve's relative residual tolerance instead of the configured one
  // (inexact Newton's forcing term); the direct method ignores it.
  Result solve(const la::Vector& b, la::Vector& x, double tolerance = 0.0);

  // The next setup() builds the preconditioner afresh, however recent it is. Called at
  // every checkpoint: a run restarted there builds one at its first setup, so with the
  // uninterrupted run doing the same both stay bitwise equal (preconditioner reuse).
  void rebuild_preconditioner() { force_rebuild_ = true; }

  // The next tangent's discrete part changed (a contact active set or a stick/slip state,
  // NewtonSystem::settled() false): its preconditioner is built afresh, unless
  // Linear Solver->preconditioner rebuild on contact change is false.
  void tangent_changed() {
    if (rebuild_on_change_) force_rebuild_ = true;
  }

  // The configured relative residual tolerance (Belos pass-through included); 0 for direct.
  double tolerance() const;

  std::string description() const;

  // Wall time spent in setup() (preconditioner or factorization) and solve() so far;
  // builds: setups that built or recomputed the preconditioner (the others reused it).
  struct Times {
    double setup = 0.0, solve = 0.0;
    long setups = 0, solves = 0, builds = 0;
    long stale_rebuilds = 0;  // reused preconditioners rebuilt because GMRES stalled with them
    int fallbacks = 0;  // steps taken down the fallback chain
  };
  const Times& times() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  void setup_once(const la::RCP<la::CrsMatrix>& A);
  void setup_or_fall_back(const la::RCP<la::CrsMatrix>& A);
  Result solve_once(const la::Vector& b, la::Vector& x, double tolerance);
  bool fall_back(const std::string& why);
  Agreement agree(const std::string& why) const;
  bool force_rebuild_ = false;
  bool rebuild_on_change_ = true;
};

}  // namespace stentor
