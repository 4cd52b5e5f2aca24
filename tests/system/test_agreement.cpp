// The ranks' vote on a failure (parallel/Agreement.hpp). On one rank (ctest's default)
// the vote is the rank's own failure; tests/cli runs this file on 2 ranks as well
// (mpi.agreement.np2) and checks that a rank left waiting ends the job (mpi.agreement.stuck).
#include <gtest/gtest.h>

#include <chrono>
#include <cstdlib>
#include <string>
#include <thread>

#include <Tpetra_Core.hpp>

#include "parallel/Agreement.hpp"

using stentor::agree_on_failure;

TEST(Agreement, NoFailureNoVote) {
  const auto comm = Tpetra::getDefaultComm();
  const stentor::Agreement a = agree_on_failure(*comm, "");
  EXPECT_FALSE(a.failed());
  EXPECT_EQ(a.failed_rank, -1);
  EXPECT_EQ(a.failure, "");
}

// Only the last rank fails: every rank learns its rank and message.
TEST(Agreement, OneRanksFailureReachesEveryRank) {
  const auto comm = Tpetra::getDefaultComm();
  const int last = comm->getSize() - 1;
  const std::string mine = comm->getRank() == last ? "set-up failed on the last rank (" + std::to_string(last) + ")" : "";
  const stentor::Agreement a = agree_on_failure(*comm, mine);
  EXPECT_TRUE(a.failed());
  EXPECT_EQ(a.failed_rank, last);
  EXPECT_EQ(a.failure, "set-up failed on the last rank (" + std::to_string(last) + ")");
}

// Every rank fails with its own message: the lowest rank's wins, on every rank.
TEST(Agreement, LowestFailingRankWins) {
  const auto comm = Tpetra::getDefaultComm();
  const stentor::Agreement a = agree_on_failure(*comm, "failure of rank " + std::to_string(comm->getRank()));
  EXPECT_EQ(a.failed_rank, 0);
  EXPECT_EQ(a.failure, "failure of rank 0");
}

// A rank late by less than the time limit (a slow local factorization) is waited for.
TEST(Agreement, ALateRankIsWaitedFor) {
  const auto comm = Tpetra::getDefaultComm();
  if (comm->getRank() == 0) std::this_thread::sleep_for(std::chrono::milliseconds(300));
  const stentor::Agreement a = agree_on_failure(*comm, comm->getRank() == 0 ? "late" : "", 5.0);
  EXPECT_EQ(a.failed_rank, 0);
  EXPECT_EQ(a.failure, "late");
}

// Run only by mpi.agreement.stuck (STENTOR_TEST_AGREEMENT_STUCK=1, 2 ranks): rank 0 never
// votes (as if stuck in a collective of a package), rank 1 votes with a 1 s limit and must
// end the whole job with exit status 3 instead of waiting forever.
TEST(Agreement, StuckRankEndsTheJob) {
  const char* v = std::getenv("STENTOR_TEST_AGREEMENT_STUCK");
  const auto comm = Tpetra::getDefaultComm();
  if (!v || comm->getSize() < 2) GTEST_SKIP() << "run by mpi.agreement.stuck on 2 ranks";
  if (comm->getRank() == 0) {
    std::this_thread::sleep_for(std::chrono::seconds(60));
    FAIL() << "rank 0 was not ended by rank 1's abort";
  }
  agree_on_failure(*comm, "preconditioner set-up threw on rank 1", 1.0);
  FAIL() << "the vote returned although rank 0 never voted";
}
