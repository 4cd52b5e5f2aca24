#!/usr/bin/env bash
# Strong scaling: one problem size, ranks x threads varied. Writes
# perf/results/scaling/strong.csv and strong.png (see docs/performance.md).
#
#   perf/scaling/strong.sh                    # H=0.04 (~65k dofs, P1), CONFIGS="1x1 1x2 2x1"
#   H=0.023 CONFIGS="1x1 1x2 2x1 1x4 4x1 2x2 4x4 16x1 1x16" PRECS="muelu schwarz" perf/scaling/strong.sh
#
# Environment: H (Mesh->size), CONFIGS (RxT list), PRECS (preconditioners), ASSEMBLY
# (atomic|coloring), OUT (folder), plus those of lib.sh (BUILD, DECK, NEWTON, REPEAT).
. "$(dirname "$0")/lib.sh"
H=${H:-0.04}
CONFIGS=${CONFIGS:-"1x1 1x2 2x1"}
PRECS=${PRECS:-"schwarz"}
ASSEMBLY=${ASSEMBLY:-atomic}
OUT=${OUT:-$root/perf/results/scaling}
mkdir -p "$OUT"
csv=$OUT/strong.csv
echo "$CSV_HEADER" > "$csv"
echo "strong scaling: $BENCH on $(nproc) cores, $(uname -n), deck $DECK, h = $H"
status=0
for prec in $PRECS; do
  for c in $CONFIGS; do
    run_case strong "${c%x*}" "${c#*x}" "$H" "$prec" "$ASSEMBLY" "$csv" "$OUT/logs" || status=1
  done
done
plot "$csv" "$OUT/strong.png" "Strong scaling, $(basename "$DECK" .xml), h = $H, $(nproc)-core $(uname -n)"
exit $status
