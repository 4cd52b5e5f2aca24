#!/usr/bin/env bash
# Runs bench_assembly on the ~200k-DOF benchmark decks (P1 and P2 tets) with 1 and 2 MPI
# ranks and appends the results to perf/results/bench_assembly.csv. See docs/performance.md.
#
#   perf/run_bench.sh [BUILD_DIR]          (default BUILD_DIR: build-perf)
#
# Environment (all optional):
#   RANKS="1 2"            MPI rank counts
#   DECKS="cube_p1 cube_p2" decks in perf/decks/
#   REPEAT=5               assembly calls timed per measurement
#   SIZE=                  override Mesh->size (e.g. SIZE=0.2 for a quick check)
#   NEWTON_ITERATIONS_P1=2 cap on the Newton iterations of the P1 / P2 solve (0: no cap, the
#   NEWTON_ITERATIONS_P2=1 deck's limit of 25). With the default Schwarz/ILU(1) preconditioner a
#                          Newton iteration at 200k DOF takes 5-15 minutes on 2 cores and the
#                          uncapped solve does not converge (docs/performance.md); the capped run
#                          measures the cost per iteration.
#   CSV=perf/results/bench_assembly.csv
#   EXTRA=                 more bench_assembly options (e.g. "--fill-level 0")
set -uo pipefail
here=$(cd "$(dirname "$0")" && pwd)
root=$(dirname "$here")
build=${1:-$root/build-perf}
bin=$build/perf/bench_assembly
RANKS=${RANKS:-"1 2"}
DECKS=${DECKS:-"cube_p1 cube_p2"}
REPEAT=${REPEAT:-5}
SIZE=${SIZE:-}
NEWTON_ITERATIONS_P1=${NEWTON_ITERATIONS_P1:-2}
NEWTON_ITERATIONS_P2=${NEWTON_ITERATIONS_P2:-1}
CSV=${CSV:-$here/results/bench_assembly.csv}
EXTRA=${EXTRA:-}

if [ ! -x "$bin" ]; then
  echo "run_bench.sh: $bin not found; build it first:" >&2
  echo "  cmake -S . -B build-perf -G Ninja -DCMAKE_BUILD_TYPE=Release && ninja -C build-perf bench_assembly" >&2
  exit 2
fi
mkdir -p "$(dirname "$CSV")"

echo "== machine"
echo "date      $(date -u +%Y-%m-%dT%H:%M:%SZ)"
echo "host      $(uname -n) $(uname -sr)"
echo "nproc     $(nproc)"
echo "cpu       $(lscpu | sed -n 's/^Model name:[[:space:]]*//p' | head -1)"
echo "memory    $(free -g | awk '/^Mem:/{print $2 " GiB"}')"
echo "loadavg   $(cat /proc/loadavg)"
echo "mpirun    $(mpirun --version 2>/dev/null | head -1)"
echo "git       $(git -C "$root" rev-parse --short HEAD 2>/dev/null)$(git -C "$root" diff --quiet HEAD -- src 2>/dev/null || echo ' (+ uncommitted changes in src/)')"
echo "csv       $CSV"

export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
status=0
for deck in $DECKS; do
  for np in $RANKS; do
    args=(--repeat "$REPEAT" --csv "$CSV")
    [ -n "$SIZE" ] && args+=(--size "$SIZE")
    case $deck in *p2*) cap=$NEWTON_ITERATIONS_P2 ;; *) cap=$NEWTON_ITERATIONS_P1 ;; esac
    [ "$cap" != 0 ] && args+=(--newton-iterations "$cap")
    # shellcheck disable=SC2206
    args+=($EXTRA)
    echo
    echo "== $deck, $np rank(s): mpirun -np $np --oversubscribe --bind-to none $bin $here/decks/$deck.xml ${args[*]}"
    mpirun -np "$np" --oversubscribe --bind-to none "$bin" "$here/decks/$deck.xml" "${args[@]}"
    rc=$?
    # 3: the (uncapped) Newton solve did not converge: reported, not an error of the benchmark.
    if [ $rc -ne 0 ] && [ $rc -ne 3 ]; then
      echo "run_bench.sh: $deck on $np rank(s) failed (exit $rc)" >&2
      status=1
    fi
  done
done
echo
echo "loadavg at end: $(cat /proc/loadavg)"
exit $status
