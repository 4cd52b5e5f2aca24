#include "parallel/RawComm.hpp"

#include <Teuchos_DefaultMpiComm.hpp>

namespace stentor {

MPI_Comm raw_mpi_comm(const Teuchos::Comm<int>& comm) {
  const auto* mpi = dynamic_cast<const Teuchos::MpiComm<int>*>(&comm);
  return mpi ? (*mpi->getRawMpiComm())() : MPI_COMM_SELF;
}

}  // namespace stentor
