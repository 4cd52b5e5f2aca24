#!/usr/bin/env bash
# Thread speed-up of the assembly kernels and atomic vs coloured sums: bench_assembly
# without the Newton solve, 1 rank x T threads, each variant ROUNDS times interleaved (the
# fastest of REPEAT calls per round, then the fastest round: a shared VM is noisy).
# Writes perf/results/scaling/threads.csv and threads.png (see docs/performance.md).
#
#   perf/scaling/threads.sh                       # THREADS="1 2", P1 h=0.04 and P2 h=0.1
#   CASES="cube_p2:0.1 cube_p2_plastic:0.1" ASSEMBLIES=atomic perf/scaling/threads.sh
#                                                 # elastic vs plastic (every point flowing)
#   THREADS="1 2 4 8 16" perf/scaling/threads.sh  # on a bigger machine
#   perf/scaling/threads.sh --plot-only           # redraw the PNG from the CSV
#
# Environment: THREADS, CASES ("deck:h" list), ASSEMBLIES ("atomic coloring"), ROUNDS (3),
# REPEAT (5), OUT, BUILD.
. "$(dirname "$0")/lib.sh"
THREADS=${THREADS:-"1 2"}
CASES=${CASES:-"cube_p1:0.04 cube_p2:0.1"}
ASSEMBLIES=${ASSEMBLIES:-"atomic coloring"}
ROUNDS=${ROUNDS:-3}
OUT=${OUT:-$root/perf/results/scaling}
mkdir -p "$OUT/logs"
csv=$OUT/threads.csv
plot_only=0
[ "${1:-}" = "--plot-only" ] && plot_only=1   # redraw threads.png from threads.csv
if [ $plot_only -eq 0 ]; then
raw=$(mktemp)
echo "threads: $BENCH on $CORES cores, $(uname -n)"
for round in $(seq 1 "$ROUNDS"); do
  for c in $CASES; do
    deck=${c%%:*} h=${c#*:}
    for asm in $ASSEMBLIES; do
      for T in $THREADS; do
        log=$OUT/logs/threads_${deck}_${asm}_t${T}_round${round}.log
        launch 1 "$T" "$BENCH" "$root/perf/decks/$deck.xml" --size "$h" --repeat "$REPEAT" --no-newton \
          --assembly "$asm" --csv "$raw" --tag "$deck $asm T=$T" > "$log" 2>&1 || { echo "FAILED: $log"; exit 1; }
        awk -F, -v d="$deck" -v a="$asm" -v T="$T" 'NR > 1 && $1 ~ ("\\[" d " " a " T=" T "\\]") && $7 ~ /\[min\]/ {
          printf "   round %d %s %s T=%s %-24s %.4f s\n", '"$round"', d, a, T, $7, $8 }' "$raw" | tail -n 2
      done
    done
  done
done
# Fastest round per (deck, assembly, threads, kernel); speed-up against 1 thread atomic.
echo "deck,dofs,gauss_points,assembly,threads,kernel,seconds,speedup_vs_1thread_same_assembly,speedup_vs_1thread_atomic" > "$csv"
awk -F, 'NR > 1 && $7 ~ /\[min\]$/ {
    match($1, /\[[^]]*\]$/); split(substr($1, RSTART + 1, RLENGTH - 2), q, " "); deck = q[1]; asm = q[2]; T = substr(q[3], 3)
    k = $7; sub(/\[min\]$/, "", k)
    key = deck SUBSEP asm SUBSEP T SUBSEP k
    if (!(key in best) || $8 < best[key]) best[key] = $8
    dofs[deck] = $4; gp[deck] = $6; keys[key] = 1
  }
  END {
    for (key in keys) {
      split(key, f, SUBSEP)
      one = best[f[1] SUBSEP f[2] SUBSEP 1 SUBSEP f[4]]; ref = best[f[1] SUBSEP "atomic" SUBSEP 1 SUBSEP f[4]]
      printf "%s,%d,%d,%s,%d,%s,%.5f,%.3f,%.3f\n", f[1], dofs[f[1]], gp[f[1]], f[2], f[3], f[4], best[key], one / best[key], ref / best[key]
    }
  }' "$raw" | sort -t, -k1,1 -k6,6 -k4,4 -k5,5n >> "$csv"
rm -f "$raw"
fi
column -s, -t "$csv"
if command -v gnuplot > /dev/null; then
  gnuplot <<GP
set terminal pngcairo size 1100,600 font ",10" noenhanced
set bmargin 11
set output "$OUT/threads.png"
set datafile separator ","
set title "Assembly kernels, 1 rank x T threads ($CORES-core $(uname -n)): speed-up against 1 thread, atomic sums"
set style data histograms
set style histogram clustered
set style fill solid 0.8 border -1
set ylabel "speed-up"
set yrange [0:*]
set key top left
set xtics rotate by -30
plot "$csv" every ::1 using 9:xtic(sprintf("%s %s %s T=%d", stringcolumn(1), stringcolumn(6), stringcolumn(4), column(5))) title "speed-up"
GP
  echo "wrote $OUT/threads.png"
fi
