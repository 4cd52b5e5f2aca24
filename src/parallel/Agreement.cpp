#include "parallel/Agreement.hpp"

#include "io/RankVote.hpp"
#include "parallel/RawComm.hpp"

namespace stentor {

Agreement agree_on_failure(const Teuchos::Comm<int>& comm, const std::string& local, double timeout_s) {
  if (comm.getSize() == 1) return local.empty() ? Agreement{} : Agreement{0, local};
  const RankVote v = vote_on_failure(raw_mpi_comm(comm), local, timeout_s);
  return Agreement{v.failed_rank, v.failure};
}

}  // namespace stentor
