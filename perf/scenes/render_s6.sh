#!/usr/bin/env bash
# The pictures and tables of docs/scenes/s6_summary.md: runs the S6 procedure on the whole
# stent (inputs/s6_stent_procedure.xml, about 60-75 s on one rank) and on its ring alone
# (inputs/s6_ring_sector.xml, about 20 s), one after the other, each from a copy of the deck
# in the run folder with Output->field list = "displacement, von_mises,
# equivalent_plastic_strain" and fields at t = 0 and the stages' ends only (every = 1000),
# then renders from their HDF5 output with ParaView's pvbatch (perf/scenes/render_stent.py,
# the one-strut sector of the half length put back together into the whole stent: 32 copies)
#   docs/scenes/s6_stent_plastic_strain.png  the stent as cut, crimped, at the peak of the
#                                            expansion and recoiled: equivalent plastic strain
#   docs/scenes/s6_crown_plastic_strain.png  the crown with the largest plastic strain, close
#                                            up, crimped, at the peak and recoiled
#   docs/scenes/s6_stent_von_mises.png       von Mises stress at the peak and recoiled
#   docs/scenes/s6_ring_plastic_strain.png   the ring alone (16 copies of its sector)
# and with matplotlib (perf/scenes/s6_report.py), from the metrics and history CSVs,
#   docs/scenes/s6_diameters_forces.png      diameters against time, the tools' force against
#                                            their diameter
# and the tables in <runs>/s6_tables.md (the numbers of docs/scenes/s6_summary.md).
# usage: perf/scenes/render_s6.sh [build-dir]   (default build)
# env: S6_RUNS (where the runs go, default <build-dir>/scenes/s6), S6_SKIP_RUNS=1 (render
#      the runs already there again), S6_OUT (where the PNGs go, default docs/scenes)
# Needs ParaView's pvbatch and xvfb-run (Debian: paraview, python3-paraview, xvfb; ci/setup.sh
# installs them) and Debian's python3-matplotlib, python3-h5py, python3-numpy.
set -euo pipefail
ROOT=$(cd "$(dirname "$0")/../.." && pwd)
BUILD=$(cd "${1:-$ROOT/build}" && pwd)
RUNS=${S6_RUNS:-$BUILD/scenes/s6}
OUT=${S6_OUT:-$ROOT/docs/scenes}
mkdir -p "$RUNS" "$OUT"
for tool in pvbatch xvfb-run; do
  command -v $tool > /dev/null || { echo "render_s6.sh: $tool not found (Debian: apt install paraview python3-paraview xvfb)" >&2; exit 2; }
done

FIELDS='<Parameter name="field list" type="string" value="displacement, von_mises, equivalent_plastic_strain"/>'
run() {  # deck name -> run folder $RUNS/<name>, log $RUNS/<name>.log, wall time printed
  local name=$1
  sed -e '/name="every"/s|value="[^"]*"|value="1000"|' \
      -e "s|<ParameterList name=\"Output\">|<ParameterList name=\"Output\">$FIELDS|" \
      "$ROOT/inputs/$name.xml" > "$RUNS/$name.xml"
  local t0 ms
  t0=$(date +%s%N)
  "$BUILD/stentor" --overwrite --output "$RUNS/$name" "$RUNS/$name.xml" > "$RUNS/$name.log" 2>&1 \
    || { echo "render_s6.sh: $name failed, see $RUNS/$name.log" >&2; exit 1; }
  ms=$(( ($(date +%s%N) - t0) / 1000000 ))
  printf '%s: %d.%d s wall; %s\n' "$name" $((ms / 1000)) $((ms % 1000 / 100)) "$(grep '^Summary' "$RUNS/$name/$name.log")"
}
if [ "${S6_SKIP_RUNS:-0}" != 1 ]; then
  run s6_stent_procedure
  run s6_ring_sector
fi

S=$RUNS/s6_stent_procedure
G=$RUNS/s6_ring_sector
# Without -screen ...x24 pvbatch's render window fails on Xvfb's default screen ("bad X
# server connection").
PV=(xvfb-run -a -s "-noreset -screen 0 1600x1200x24" pvbatch "$ROOT/perf/scenes/render_stent.py")
render() {  # the arguments of render_stent.py; its output in $RUNS/render_<picture>.log
  local log=$RUNS/render_$(basename "$3" .png).log
  "${PV[@]}" "$@" > "$log" 2>&1 || { echo "render_s6.sh: rendering $3 failed:" >&2; tail -20 "$log" >&2; exit 1; }
  grep -E '^(wrote|crown)' "$log" || true
}
EPS="equivalent plastic strain [-]"
TITLE="S6 stent (316L, 6 rings, rebuilt from its one-strut sector of the half length)" \
  render "$S" s6_stent_procedure "$OUT/s6_stent_plastic_strain.png" equivalent_plastic_strain "$EPS" \
  "0:as cut" "1:crimped" "2.25:expanded (peak)" "2.75:recoiled"
TITLE="S6 stent: the crown with the largest plastic strain (end ring), seen from outside" VIEW=crown \
  render "$S" s6_stent_procedure "$OUT/s6_crown_plastic_strain.png" equivalent_plastic_strain "$EPS" \
  "1:crimped" "2.25:expanded (peak)" "2.75:recoiled"
TITLE="S6 stent: von Mises stress at the peak and the residual stress after recoil" \
  render "$S" s6_stent_procedure "$OUT/s6_stent_von_mises.png" von_mises "von Mises stress [MPa]" \
  "2.25:expanded (peak)" "2.75:recoiled"
TITLE="S6 ring alone (rebuilt from its one-strut sector), seen 30 deg off its axis" VIEW=end TILT=30 AZIM=11.25 \
  render "$G" s6_ring_sector "$OUT/s6_ring_plastic_strain.png" equivalent_plastic_strain "$EPS" \
  "0:as cut" "1:crimped" "2.25:expanded (peak)" "2.75:recoiled"
/usr/bin/python3 "$ROOT/perf/scenes/s6_report.py" "$OUT/s6_diameters_forces.png" \
  "$S:s6_stent_procedure:stent" "$G:s6_ring_sector:ring alone" > "$RUNS/s6_tables.md"
echo "tables: $RUNS/s6_tables.md"
