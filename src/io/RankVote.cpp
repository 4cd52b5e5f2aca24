#include "io/RankVote.hpp"

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <iostream>
#include <thread>

namespace stentor {

namespace {

[[noreturn]] void abort_vote(int rank, int size, const std::string& local, double timeout_s) {
  std::cerr << "[rank " << rank << "] "
            << (local.empty() ? std::string("waited for ranks that failed inside a collective operation")
                              : local)
            << "\nstentor: the ranks could not agree on this failure within " << timeout_s
            << " s (another rank is stuck in a collective operation); ending all " << size << " ranks (exit status 3)\n"
            << std::flush;
  MPI_Abort(MPI_COMM_WORLD, 3);
  std::abort();
}

}  // namespace

RankVote vote_on_failure(MPI_Comm c, const std::string& local, double timeout_s) {
  int rank = 0, size = 1;
  MPI_Comm_rank(c, &rank);
  MPI_Comm_size(c, &size);
  RankVote a;
  if (size == 1) {
    if (!local.empty()) a = RankVote{0, local};
    return a;
  }
  int mine = local.empty() ? size : rank, lowest = size;
  MPI_Request req;
  MPI_Iallreduce(&mine, &lowest, 1, MPI_INT, MPI_MIN, c, &req);
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
  int done = 0;
  for (auto pause = std::chrono::microseconds(20);; pause = std::min(pause * 2, std::chrono::microseconds(10000))) {
    MPI_Test(&req, &done, MPI_STATUS_IGNORE);
    if (done) break;
    if (std::chrono::steady_clock::now() > deadline) abort_vote(rank, size, local, timeout_s);
    std::this_thread::sleep_for(pause);
  }
  if (lowest == size) return a;
  // Every rank is here: the failing rank's message reaches all of them.
  a.failed_rank = lowest;
  int n = rank == lowest ? static_cast<int>(local.size()) : 0;
  MPI_Bcast(&n, 1, MPI_INT, lowest, c);
  a.failure = rank == lowest ? local : std::string(static_cast<std::size_t>(n), ' ');
  MPI_Bcast(a.failure.data(), n, MPI_CHAR, lowest, c);
  return a;
}

}  // namespace stentor
