#!/usr/bin/env bash
# The threaded path: builds (or reuses) the OpenMP Trilinos and Stentor against it
# (ci/build-trilinos-openmp.sh), then runs the tests that exercise threads there:
#   Threads.*              element kernels on 2 OpenMP threads, atomic vs coloured sums
#   hybrid.consistency.*   the same decks on 1x1, 1x2, 2x1, 2x2 ranks x threads (1e-10)
#   mpi.consistency.*      rank-count consistency on this build as well
#   system tests: dynamics and contact verification on threads (1 thread per test process
#                 as ctest runs two at once; Threads.* and hybrid.* use 2)
# Only the targets those tests need are built, to keep CI within its time limit.
set -euo pipefail
cd "$(dirname "$0")/.."
BUILD_DIR=${STENTOR_OMP_BUILD_DIR:-build-openmp}
export STENTOR_OMP_TARGETS="stentor test_threads_assembly test_dynamics test_contact bench_assembly"
bash ci/build-trilinos-openmp.sh
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1
export OMP_WAIT_POLICY=passive
cd "$BUILD_DIR"
ctest --output-on-failure -j "${STENTOR_TEST_JOBS:-2}" \
  -R '^(Threads\.|hybrid\.|mpi\.consistency\.|Dynamics|Contact)' "$@"
