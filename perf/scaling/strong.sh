#!/usr/bin/env bash
# Strong scaling: one problem size, ranks x threads varied. Writes
# perf/results/scaling/strong.csv and strong.png (see docs/performance.md).
#
#   perf/scaling/strong.sh                    # H=0.04 (41k dofs, P1), CONFIGS="1x1 1x2 2x1"
#   H=0.023 CONFIGS="1x1 1x2 2x1 1x4 4x1 2x2 4x4 16x1 1x16" PRECS="muelu schwarz" perf/scaling/strong.sh
#
# Environment: H (Mesh->size), CONFIGS (RxT list), PRECS (preconditioners), ASSEMBLY
# (list of atomic|coloring), OUT (folder), NAME (CSV/PNG stem, default strong), plus those
# of lib.sh (BUILD, DECK, NEWTON, STEPS, REPEAT).
. "$(dirname "$0")/lib.sh"
H=${H:-0.04}
CONFIGS=${CONFIGS:-"1x1 1x2 2x1"}
PRECS=${PRECS:-"schwarz"}
ASSEMBLY=${ASSEMBLY:-atomic}
OUT=${OUT:-$root/perf/results/scaling}
mkdir -p "$OUT"
NAME=${NAME:-strong}
csv=$OUT/$NAME.csv
echo "$CSV_HEADER" > "$csv"
echo "strong scaling: $BENCH on $CORES cores, $(uname -n), deck $DECK, h = $H"
status=0
for asm in $ASSEMBLY; do
  for prec in $PRECS; do
    for c in $CONFIGS; do
      run_case "$NAME" "${c%x*}" "${c#*x}" "$H" "$prec" "$asm" "$csv" "$OUT/logs" || status=1
    done
  done
done
plot "$csv" "$OUT/$NAME.png" "Strong scaling, $(basename "$DECK" .xml), h = $H, $CORES-core $(uname -n)"
exit $status
