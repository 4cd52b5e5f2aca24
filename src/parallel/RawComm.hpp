// The MPI communicator under a Teuchos one, for the MPI calls Stentor makes itself
// (broadcasts, all-to-all exchanges, the failure vote).
#pragma once
#include <mpi.h>

#include <Teuchos_Comm.hpp>

namespace stentor {

// The raw communicator of `comm`; MPI_COMM_SELF when it is not a Teuchos::MpiComm (a
// serial communicator: one process).
MPI_Comm raw_mpi_comm(const Teuchos::Comm<int>& comm);

}  // namespace stentor
