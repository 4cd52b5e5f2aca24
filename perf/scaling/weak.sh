#!/usr/bin/env bash
# Weak scaling: about the same number of dofs per rank, ranks doubled (the mesh size
# shrinks by 2^(1/3) per doubling), for each preconditioner: iteration growth of
# one-level Schwarz (Ifpack2) against multigrid (MueLu). Writes
# perf/results/scaling/weak.csv and weak.png (see docs/performance.md).
#
#   perf/scaling/weak.sh                          # H1=0.08 (~8k dofs per rank), RANKS="1 2 4 8"
#   H1=0.05 RANKS="1 2 4 8 16" THREADS=1 perf/scaling/weak.sh
#
# Environment: H1 (Mesh->size on one rank), RANKS, THREADS (per rank), PRECS, ASSEMBLY,
# OUT, plus those of lib.sh. On a machine with fewer cores than ranks the runs are
# oversubscribed: the iteration counts are still exact, the times are not scaling data.
. "$(dirname "$0")/lib.sh"
H1=${H1:-0.08}
RANKS=${RANKS:-"1 2 4 8"}
THREADS=${THREADS:-1}
PRECS=${PRECS:-"schwarz muelu"}
ASSEMBLY=${ASSEMBLY:-atomic}
OUT=${OUT:-$root/perf/results/scaling}
mkdir -p "$OUT"
csv=$OUT/weak.csv
echo "$CSV_HEADER" > "$csv"
echo "weak scaling: $BENCH on $CORES cores, $(uname -n), deck $DECK, h(1 rank) = $H1"
status=0
for prec in $PRECS; do
  for R in $RANKS; do
    h=$(awk -v h="$H1" -v r="$R" 'BEGIN { printf "%.4g", h / r^(1/3) }')
    run_case weak "$R" "$THREADS" "$h" "$prec" "$ASSEMBLY" "$csv" "$OUT/logs" || status=1
  done
done
plot "$csv" "$OUT/weak.png" "Weak scaling, $(basename "$DECK" .xml), ~dofs/rank fixed, $CORES-core $(uname -n)"
exit $status
