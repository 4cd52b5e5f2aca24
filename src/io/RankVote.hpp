// The ranks' vote on a failure, with a deadline, on a raw MPI communicator.
//
// Each rank passes its own failure ("" if none); every rank receives the lowest failing
// rank and its message. A rank that failed inside a collective operation may leave the
// others waiting inside it, never reaching the vote: after `timeout_s` seconds the vote
// prints this rank's failure (or that it waited) on stderr and ends every rank with
// MPI_Abort, exit status 3, instead of hanging. parallel/Agreement.hpp is the same vote
// on a Teuchos communicator; io/Checkpoint.cpp votes with it before a file is closed.
#pragma once
#include <mpi.h>

#include <string>

namespace stentor {

struct RankVote {
  int failed_rank = -1;  // the lowest rank that failed, -1 if none
  std::string failure;   // that rank's message ("" if none failed)
};

// Collective over `comm` (every rank, in the same order). One rank: `local`.
RankVote vote_on_failure(MPI_Comm comm, const std::string& local, double timeout_s);

}  // namespace stentor
