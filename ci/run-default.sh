#!/usr/bin/env bash
# Set-up (packages, configure, build) then the default deck: an arterial ring
# inflated by internal pressure. Prints where the results are.
set -euo pipefail
cd "$(dirname "$0")/.."
bash ci/setup.sh
./build/stentor --output results/artery_ring inputs/artery_ring.xml
