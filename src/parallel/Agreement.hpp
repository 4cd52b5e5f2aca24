// Agreeing on a failure across MPI ranks without hanging.
//
// A third-party package (MueLu, Belos, Ifpack2, Amesos2) may throw on some ranks only,
// or on all of them. To recover (the linear solver's fallback chain, a cut-back) every
// rank must take the same branch, so after each guarded call all ranks vote: each passes
// its own failure ("" if none) and all receive the failure of the lowest failing rank.
// A rank that threw in the middle of a collective leaves the others waiting inside that
// collective, never reaching the vote: the vote then waits at most `timeout_s` seconds and
// ends the job (MPI_Abort with exit status 3, the failure printed) instead of hanging.
#pragma once
#include <string>

#include <Teuchos_Comm.hpp>

namespace stentor {

struct Agreement {
  int failed_rank = -1;  // the lowest rank that failed, -1 if none
  std::string failure;   // that rank's message ("" if none failed)
  bool failed() const { return failed_rank >= 0; }
};

// The vote. Collective: every rank calls it, in the same order. On one rank: `local`.
// When the others do not all arrive within timeout_s, prints this rank's failure (or that
// it waited) on stderr and ends every rank with MPI_Abort, exit status 3.
Agreement agree_on_failure(const Teuchos::Comm<int>& comm, const std::string& local, double timeout_s = 60.0);

}  // namespace stentor
