#!/usr/bin/env bash
# Balloon angioplasty of a stenosed coronary artery, axisymmetric (inputs/axi_angioplasty.xml:
# a deformable balloon inflated to 0.6 MPa in a 60 % area stenosis, deflated, withdrawn). Runs
# the deck once on one rank, times it (wall and CPU: /usr/bin/time, the whole process with
# meshing), then perf/scenes/axi_angioplasty_report.py writes into docs/scenes/:
# axi_angioplasty_stages.csv (lumen radius, gain, recoil, balloon radius, largest hoop stress
# per layer at each state) and axi_angioplasty.png (profiles and hoop stresses).
#   usage: perf/scenes/run_axi_angioplasty.sh [build-dir]   (needs python3-h5py, -numpy, -matplotlib)
#   env:   AXA_RUNS (raw output dir, default <build>/scenes/axi_angioplasty); AXA_SKIP_RUN=1
#          (report on the last run again)
set -euo pipefail
ROOT=$(cd "$(dirname "$0")/../.." && pwd)
BUILD=${1:-$ROOT/build}
EXE=$BUILD/stentor
RUNS=${AXA_RUNS:-$BUILD/scenes/axi_angioplasty}
DOCS=$ROOT/docs/scenes
[ -x "$EXE" ] || { echo "no $EXE: build it first"; exit 1; }
mkdir -p "$RUNS" "$DOCS"
if [ "${AXA_SKIP_RUN:-0}" != 1 ]; then
  rm -rf "$RUNS/out" "$RUNS/out.partial"
  /usr/bin/time -f "%e %U %S" -o "$RUNS/time" "$EXE" --output "$RUNS/out" "$ROOT/inputs/axi_angioplasty.xml" > "$RUNS/log" 2>&1 ||
    { echo "axi_angioplasty FAILED (see $RUNS/log)"; exit 1; }
fi
read -r wall user sys < "$RUNS/time"
grep -E "^Summary|^  (mesh|newton|contact|assembly) " "$RUNS/log"
echo "axi_angioplasty: wall $wall s, CPU $(echo "$user + $sys" | bc) s (user $user, sys $sys), load average $(cut -d' ' -f1 /proc/loadavg)"
/usr/bin/python3 "$ROOT/perf/scenes/axi_angioplasty_report.py" "$RUNS/out" "$DOCS/axi_angioplasty_stages.csv" "$DOCS/axi_angioplasty.png"
