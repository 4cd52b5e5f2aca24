#!/usr/bin/env bash
# AddressSanitizer + UndefinedBehaviorSanitizer: builds stentor and a few test programs
# with -fsanitize=address,undefined in their own folder (build-asan, Release + -g1), then runs a
# small meaningful subset: the cli.corpus subset (hostile decks and meshes), some
# bad-input cases, the hostile checkpoints (restart_hostile.sh), unit tests (deck, io,
# checkpoint, material), one contact and one plastic system test. Exit 1 on any sanitizer report (or failed test).
#   STENTOR_ASAN_BUILD_DIR  build folder (default build-asan)
#   STENTOR_JOBS            parallel compile jobs (default 2)
# Cold time on the 2-core development machine: see docs/robustness.md.
set -uo pipefail
cd "$(dirname "$0")/.."
src=$(pwd)
B=${STENTOR_ASAN_BUILD_DIR:-build-asan}
san="-fsanitize=address,undefined -fno-omit-frame-pointer -fno-sanitize-recover=undefined"
t0=$(date +%s)
if [ ! -f "$B/build.ninja" ]; then
  mkdir -p "$B"
  cmake -S . -B "$B" -G Ninja -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_FLAGS="-g1 $san" \
        -DCMAKE_EXE_LINKER_FLAGS="-fsanitize=address,undefined" > "$B/configure.log" 2>&1 \
    || { cat "$B/configure.log"; exit 1; }
fi
tests="test_deck test_io test_checkpoint test_ciarlet_geymonat test_plasticity test_contact test_plasticity_fe test_mortar checkpoint_edit"
# gtest_discover_tests runs each test program after linking (--gtest_list_tests): without
# this, LeakSanitizer reports Open MPI's allocations there and fails the build.
export ASAN_OPTIONS=detect_leaks=0
cmake --build "$B" -j "${STENTOR_JOBS:-2}" --target stentor $tests || exit 1
t1=$(date +%s)
echo "[asan] build: $((t1 - t0)) s"

export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1
# Open MPI's own allocations are reported as leaks: leak checking off. Any error ends the
# process with status 86 (UBSan: -fno-sanitize-recover), found below in the logs too.
export ASAN_OPTIONS=detect_leaks=0:halt_on_error=1:exitcode=86:allocator_may_return_null=1
export UBSAN_OPTIONS=halt_on_error=1:print_stacktrace=1:exitcode=86
export OMP_NUM_THREADS=1 OMP_PROC_BIND=false
log=$(cd "$B" && pwd)/asan-logs  # absolute: the runs below happen inside $B
rm -rf "$log" && mkdir -p "$log"
fails=()
run() {  # run NAME COMMAND...: its output in $log/NAME.txt
  local name=$1; shift
  local s=$(date +%s)
  if ! "$@" > "$log/$name.txt" 2>&1; then fails+=("$name"); fi
  echo "[asan] $name: $(( $(date +%s) - s )) s"
}
cd "$B"
run test_deck ./test_deck
run test_io ./test_io
run test_checkpoint ./test_checkpoint
run test_material ./test_ciarlet_geymonat
run test_plasticity ./test_plasticity
run test_contact ./test_contact --gtest_filter="${STENTOR_ASAN_CONTACT:-Contact.StaticBlockOnPlane:Contact.ImpactPersistenceConservesEnergy:Contact.CoulombSlipAboveLimit:Contact.FirstStepLeapfrogUsesTheInitialVelocity}"
run test_mortar ./test_mortar
run test_plasticity_fe ./test_plasticity_fe --gtest_filter="${STENTOR_ASAN_PLASTIC:-*}"
# The corpus subset, without the address-space limit (ASan reserves terabytes of it)
# and with more time (ASan runs 2-5x slower). Left out: the .geo cases that only an
# address-space limit stops quickly (a list of 1e9 numbers, sizes and counts without
# bound: under ASan gmsh's process runs without one, so they run until 'Mesh->time
# limit'; geo_huge_list went past 90 s), which the Release build's corpus covers.
asan_skip='^(?!geo_(huge_list|mesh_size_factor|mesh_size_field|mesh_size_min_max|mesh_transfinite|mesh_layers|mesh_min_curve_points|mesh_threads|mesh_smoothing)$)'
run cli_corpus bash "$src/tests/cli/corpus/corpus.sh" ./stentor "$src/inputs" "$PWD/asan-corpus" \
    --subset 24 --jobs 2 --mem-mb 0 --timeout 90 --match "$asan_skip"
# Hostile checkpoints (hand-edited, bit-flipped, truncated, reshaped): read by the
# sanitized stentor, each must end in exit 2 naming the dataset, no report.
run cli_restart_hostile bash "$src/tests/cli/restart_hostile.sh" "$PWD/stentor" "$PWD/tests/cli/checkpoint_edit" \
    "$(command -v mpirun)" -np "$PWD/asan-hostile" "$src/tests/cli/decks/restart_bars.xml" 1
# Bad inputs, run as a user would (some, like a non-finite initial energy, are only
# found when the run starts): exit 2 expected.
rm -rf asan-out && mkdir -p asan-out
for c in bad_wrong_type bad_contact_group bad_geo_systemcall bad_node_count bad_nonfinite_velocity; do
  run "cli_$c" bash -c "cd '$src/tests/cli/decks' && '$PWD/stentor' --output '$PWD/asan-out/$c' $c.xml; test \$? -eq 2"
done
cd "$src"
# A report anywhere (also in a corpus case's stderr) fails the script.
reports=$(grep -rlE "ERROR: AddressSanitizer|runtime error:|ERROR: LeakSanitizer" "$log" "$B/asan-corpus" "$B/asan-hostile" 2>/dev/null)
[ -n "$reports" ] && fails+=("sanitizer reports in: $reports")
echo "[asan] total: $(( $(date +%s) - t0 )) s"
if [ ${#fails[@]} -gt 0 ]; then
  for f in "${fails[@]}"; do echo "[asan] FAILED: $f"; done
  for f in "${fails[@]}"; do [ -f "$log/$f.txt" ] && tail -40 "$log/$f.txt"; done
  exit 1
fi
echo "[asan] clean"
