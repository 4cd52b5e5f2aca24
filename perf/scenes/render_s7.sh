#!/usr/bin/env bash
# The pictures and tables of docs/scenes/s7_summary.md: runs the S7 deck, one strut of the
# S6 ring crimped, expanded into a stenosed layered artery and deflated
# (inputs/s7_ring_artery.xml), twice on one rank: as it is (the wall frictionless) and with
# Coulomb friction mu = 0.1 on the stent-wall pair (`Contact->wall`), each from a copy of
# the deck in the run folder with Output->field list = "displacement, von_mises,
# equivalent_plastic_strain, principal_stress, wall_gap" and fields at t = 0 and the stages' ends
# only (every = 1000), then renders from their HDF5 output with ParaView's pvbatch
# (perf/scenes/render_stent.py, the sector put back together: 16 copies around)
#   docs/scenes/s7_artery_deployment.png  the ring and the artery cut open along the axis,
#                                         crimped in the artery, expanded, deflated: the
#                                         stent's equivalent plastic strain, the wall's
#                                         largest principal stress
#   docs/scenes/s7_artery_end.png         the same seen 40 deg off the axis from the
#                                         proximal end: the stress through the wall
#   docs/scenes/s7_wall_gap.png           the malapposition map: the stent's outer surface
#                                         coloured by its gap to the lumen, expanded and
#                                         deflated
# and with matplotlib (perf/scenes/s7_report.py), from the metrics and history CSVs,
#   docs/scenes/s7_diameters_forces.png   the stent's and the lumen's diameters and the
#                                         contact forces against time, both runs
#   docs/scenes/s7_layer_stresses.png     the layers' largest principal stress (max and
#                                         99th percentile) against time, both runs
# and the tables in <runs>/s7_tables.md (the numbers of docs/scenes/s7_summary.md).
# usage: perf/scenes/render_s7.sh [build-dir]   (default build)
# env: S7_RUNS (where the runs go, default <build-dir>/scenes/s7), S7_SKIP_RUNS=1 (render
#      the runs already there again), S7_OUT (where the PNGs go, default docs/scenes),
#      S7_ARTERY_VMAX (the top of the wall's colour scale, default 20 kPa), S7_GAP_VMAX (the
#      top of the gap's, default 80 µm), S7_RUNS_ONLY=1
#      (the runs only, no pictures)
# Needs ParaView's pvbatch and xvfb-run (Debian: paraview, python3-paraview, xvfb; ci/setup.sh
# installs them) and Debian's python3-matplotlib, python3-h5py, python3-numpy.
set -euo pipefail
ROOT=$(cd "$(dirname "$0")/../.." && pwd)
BUILD=$(cd "${1:-$ROOT/build}" && pwd)
RUNS=${S7_RUNS:-$BUILD/scenes/s7}
OUT=${S7_OUT:-$ROOT/docs/scenes}
mkdir -p "$RUNS" "$OUT"
for tool in pvbatch xvfb-run; do
  command -v $tool > /dev/null || { echo "render_s7.sh: $tool not found (Debian: apt install paraview python3-paraview xvfb)" >&2; exit 2; }
done

DECK=s7_ring_artery
FIELDS='<Parameter name="field list" type="string" value="displacement, von_mises, equivalent_plastic_strain, principal_stress, wall_gap"/>'
FRICTION='<Parameter name="friction" type="double" value="0.1"/>'
run() {  # run folder name, extra sed expression -> $RUNS/<name>/, log $RUNS/<name>.log, wall time printed
  local name=$1 extra=${2:-}
  sed -e '/name="every"/s|value="[^"]*"|value="1000"|' \
      -e "s|<ParameterList name=\"Output\">|<ParameterList name=\"Output\">$FIELDS|" \
      ${extra:+-e "$extra"} "$ROOT/inputs/$DECK.xml" > "$RUNS/$name.xml"
  local t0 ms
  t0=$(date +%s%N)
  "$BUILD/stentor" --overwrite --output "$RUNS/$name" "$RUNS/$name.xml" > "$RUNS/$name.log" 2>&1 \
    || { echo "render_s7.sh: $name failed, see $RUNS/$name.log" >&2; exit 1; }
  ms=$(( ($(date +%s%N) - t0) / 1000000 ))
  printf '%s: %d.%d s wall; %s\n' "$name" $((ms / 1000)) $((ms % 1000 / 100)) "$(grep '^Summary' "$RUNS/$name/$DECK.log")" \
    | tee "$RUNS/$name.wall"
}
if [ "${S7_SKIP_RUNS:-0}" != 1 ]; then
  run frictionless
  run friction_0.1 "s|<ParameterList name=\"wall\">|<ParameterList name=\"wall\">$FRICTION|"
fi
[ "${S7_RUNS_ONLY:-0}" = 1 ] && exit 0

F=$RUNS/frictionless
M=$RUNS/friction_0.1
# Without -screen ...x24 pvbatch's render window fails on Xvfb's default screen ("bad X
# server connection").
PV=(xvfb-run -a -s "-noreset -screen 0 1600x1200x24" pvbatch "$ROOT/perf/scenes/render_stent.py")
render() {  # the arguments of render_stent.py; its output in $RUNS/render_<picture>.log
  local log=$RUNS/render_$(basename "$3" .png).log
  "${PV[@]}" "$@" > "$log" 2>&1 || { echo "render_s7.sh: rendering $3 failed:" >&2; tail -20 "$log" >&2; exit 1; }
  grep -E '^(wrote|artery)' "$log" || true
}
EPS="stent: equivalent plastic strain [-]"
S1="artery: largest principal stress [kPa]"
# the artery: its half y > 0 only (CUT=+y), the stent whole; the wall's stress in kPa,
# its colour scale cut at ARTERY_VMAX (the plaque's largest values lie above it)
ARTERY=(ARTERY_FIELD=principal_stress ARTERY_SCALE=1000 "ARTERY_LABEL=$S1" ARTERY_VMAX=${S7_ARTERY_VMAX:-20} CUT=+y)
(export "${ARTERY[@]}"
TITLE="S7: the ring (16 copies of its strut) in the stenosed artery cut open, frictionless wall" \
  COLS=3 PANEL=700,1000 \
  render "$F" s7_ring_artery "$OUT/s7_artery_deployment.png" equivalent_plastic_strain "$EPS" \
  "1:crimped in the artery" "2.25:expanded (peak)" "2.75:deflated"
TITLE="S7: the ring in the artery cut open, seen 40 deg off the axis, frictionless wall" \
  VIEW=end TILT=40 AZIM=0 \
  render "$F" s7_ring_artery "$OUT/s7_artery_end.png" equivalent_plastic_strain "$EPS" \
  "1:crimped in the artery" "2.25:expanded (peak)" "2.75:deflated")
# The malapposition map: the stent's outer surface coloured by its gap to the lumen
# (the node field wall_gap, averaged per cell over its outer nodes; the other cells and the
# artery, cut open, grey).
GAP="stent: gap to the lumen [µm]"
TITLE="S7: malapposition map, the gap from the stent's outer surface to the lumen, frictionless wall" \
  CUT=+y COLS=2 PANEL=700,1000 SCALE=1000 VMIN=0 VMAX=${S7_GAP_VMAX:-80} CMAP=viridis \
  render "$F" s7_ring_artery "$OUT/s7_wall_gap.png" wall_gap "$GAP" \
  "2.25:expanded (peak)" "2.75:deflated"
/usr/bin/python3 "$ROOT/perf/scenes/s7_report.py" "$OUT/s7_diameters_forces.png" "$OUT/s7_layer_stresses.png" \
  "$F:s7_ring_artery:frictionless" "$M:s7_ring_artery:friction 0.1" > "$RUNS/s7_tables.md"
echo "tables: $RUNS/s7_tables.md"
