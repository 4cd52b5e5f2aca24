#!/usr/bin/env bash
# A GoogleTest executable on 2 ranks, or MPI_GTEST_NP (Open MPI as root and
# oversubscribed: lib.sh).
# usage: [MPI_GTEST_NP=N] mpi_gtest.sh MPIEXEC EXECUTABLE [GTEST_ARGS...]
set -u
. "$(dirname "$0")/lib.sh"
mpiexec=$1 exe=$2
shift 2
exec "$mpiexec" -np "${MPI_GTEST_NP:-2}" $(mpi_flags "$mpiexec") "$exe" "$@"
