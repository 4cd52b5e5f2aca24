#!/usr/bin/env bash
# Set-up (packages, configure, build) then the whole test suite.
set -euo pipefail
cd "$(dirname "$0")/.."
bash ci/setup.sh
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1
cd "${STENTOR_BUILD_DIR:-build}"
ctest --output-on-failure -j "${STENTOR_TEST_JOBS:-2}" "$@"
