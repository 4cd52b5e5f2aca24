#!/usr/bin/env bash
# Hertz line contact between two deformable cylinders (inputs/hertz_cylinders.xml): the
# refinement table of docs/contact.md (Hertz). Runs the ctest case
# ContactBenchmarks.HertzTwoCylinders at more mesh levels, for non-matching (master/slave
# size ratio 1.3, the ctest case) and mirrored (ratio 1) interface meshes, and prints one
# line per run: half-width (edge of the contact set, pressure moment), peak nodal pressure
# and the RMS of the pressure profile against Hertz.
#   usage: perf/scenes/run_hertz.sh [build-dir]              (default build)
#   env:   HERTZ_LEVELS (default "0.008 0.004 0.002"; 0.001 takes ~6 min on 1 core)
#          HERTZ_RATIOS (default "1.3 1")
#          HERTZ_DISCRETIZATION (default node-to-segment; mortar)
set -euo pipefail
ROOT=$(cd "$(dirname "$0")/../.." && pwd)
BUILD=${1:-$ROOT/build}
EXE=$BUILD/test_contact_benchmarks
[ -x "$EXE" ] || { echo "no $EXE: build it first"; exit 1; }
for ratio in ${HERTZ_RATIOS:-1.3 1}; do
  STENTOR_HERTZ_LEVELS="${HERTZ_LEVELS:-0.008 0.004 0.002}" STENTOR_HERTZ_RATIO=$ratio \
    STENTOR_HERTZ_DISCRETIZATION=${HERTZ_DISCRETIZATION:-node-to-segment} \
    "$EXE" --gtest_filter=ContactBenchmarks.HertzTwoCylinders | grep -E '^\[hertz-cyl\]|OK|FAILED|Failure' || true
done
