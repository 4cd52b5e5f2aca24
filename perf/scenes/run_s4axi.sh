#!/usr/bin/env bash
# Scene S4-axi: the stent-artery procedure in axisymmetry (inputs/s4_axi.xml: inflation,
# deflation, withdrawal of a rigid balloon under an 8-turn 316L coil stent in a coronary
# artery). Runs the deck once on one rank, times it (wall and CPU: /usr/bin/time, the
# whole process with meshing and plots), and writes into docs/scenes/: s4axi_metrics.csv
# (the metrics after every step), s4axi_stages.csv (per stage) and s4axi_metrics.png
# (radii [mm] and the artery's largest hoop and von Mises stress [MPa] over the procedure).
#   usage: perf/scenes/run_s4axi.sh [build-dir]     (default build; needs gnuplot)
#   env:   S4AXI_RUNS (raw output dir, default <build>/scenes/s4axi); S4AXI_SKIP_RUN=1 (plot
#          the last run again)
set -euo pipefail
ROOT=$(cd "$(dirname "$0")/../.." && pwd)
BUILD=${1:-$ROOT/build}
EXE=$BUILD/stentor
RUNS=${S4AXI_RUNS:-$BUILD/scenes/s4axi}
DOCS=$ROOT/docs/scenes
[ -x "$EXE" ] || { echo "no $EXE: build it first"; exit 1; }
mkdir -p "$RUNS" "$DOCS"
if [ "${S4AXI_SKIP_RUN:-0}" != 1 ]; then
  rm -rf "$RUNS/out" "$RUNS/out.partial"
  /usr/bin/time -f "%e %U %S" -o "$RUNS/time" "$EXE" --output "$RUNS/out" "$ROOT/inputs/s4_axi.xml" > "$RUNS/log" 2>&1 ||
    { echo "S4-axi FAILED (see $RUNS/log)"; exit 1; }
fi
read -r wall user sys < "$RUNS/time"
grep -E "^Summary|^  (mesh|newton|contact|assembly) " "$RUNS/log"
echo "S4-axi: wall $wall s, CPU $(echo "$user + $sys" | bc) s (user $user, sys $sys), load average $(cut -d' ' -f1 /proc/loadavg)"
cp "$RUNS/out/s4_axi_metrics.csv" "$DOCS/s4axi_metrics.csv"
cp "$RUNS/out/s4_axi_stages.csv" "$DOCS/s4axi_stages.csv"
gnuplot <<GP
set terminal pngcairo size 960,720 noenhanced
set datafile separator ","
set output "$DOCS/s4axi_metrics.png"
set multiplot layout 2,1 title "S4-axi: 316L coil stent (8 turns) in a coronary artery, axisymmetric (inflation 0-1 s, deflation 1-2 s, withdrawal 2-3 s)"
set xlabel "time [s]"; set ylabel "radius [mm]"; set key inside right bottom
set yrange [1.3:1.75]
plot "$DOCS/s4axi_metrics.csv" using 2:4 with linespoints pt 7 ps 0.4 lw 2 title "lumen radius (mean over the stent span)", \
     "" using 2:5 with lines title "lumen radius (min)", "" using 2:6 with linespoints pt 7 ps 0.4 lw 2 title "stent inner radius (mean)", \
     "" using 2:8 with lines dt 2 title "stent inner radius (end turns)"
set autoscale y; set ylabel "stress [MPa]"
plot "$DOCS/s4axi_metrics.csv" using 2:13 with linespoints pt 7 ps 0.4 lw 2 title "artery: largest hoop stress sigma_thth", \
     "" using 2:12 with lines title "artery: largest von Mises stress"
unset multiplot
GP
echo "wrote $DOCS/s4axi_metrics.csv, s4axi_stages.csv, s4axi_metrics.png"
