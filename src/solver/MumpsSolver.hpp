// A sparse direct solve on every rank together: MUMPS (Amestoy, Duff, L'Excellent, Koster
// 2001; Debian's libmumps-dev, the MPI build), the parallel direct path of `Linear
// Solver->direct solver` = mumps. The matrix goes in distributed (each rank its own rows as
// triplets, MUMPS' ICNTL(18) = 3), renumbered contiguously; MUMPS orders it (its automatic
// choice: METIS or SCOTCH/PORD), factors it across the ranks, and solves with the
// right-hand side gathered on rank 0 and the solution scattered back (vectors only: the
// factors stay distributed). The analysis (ordering, symbolic factorization) is done once per
// nonzero pattern, the numeric factorization at every setup. On several ranks MUMPS sums the
// fronts' contributions in the order they arrive, so its results vary at round-off from run
// to run (one rank: repeatable); hence it is asked for, not the default.
//
// Failures (a singular matrix, MUMPS out of its workspace after one retry with four times
// the relaxation) throw std::runtime_error with MUMPS' INFOG(1) and INFOG(2) named, on every
// rank alike (MUMPS reports them globally), for LinearSolver's fallback and Newton's cut-back.
#pragma once
#include <memory>

#include "parallel/LinearAlgebra.hpp"

namespace stentor {

class MumpsSolver {
 public:
  explicit MumpsSolver(const la::RCP<const la::Comm>& comm);
  ~MumpsSolver();
  MumpsSolver(const MumpsSolver&) = delete;
  MumpsSolver& operator=(const MumpsSolver&) = delete;

  // Factors A (collective); the analysis is redone when A's nonzero pattern differs from
  // the last call's on any rank (the entries are compared, not the matrix object).
  void factor(const la::CrsMatrix& A);
  // x = A^-1 b for the last factored A (collective).
  void solve(const la::Vector& b, la::Vector& x);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace stentor
