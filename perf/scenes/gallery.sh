#!/usr/bin/env bash
# The pictures of docs/gallery.md that are not made by the scene scripts: runs
# inputs/artery_ring.xml (the default run, about 4 s) with Output->field list =
# "default, principal_stress, log_strain" and renders, with perf/scenes/render_section.py,
#   docs/gallery/artery_ring_sigma1.png      largest principal Cauchy stress at 50 and 100 kPa
#   docs/gallery/artery_ring_log_strain.png  log strain xx at 100 kPa
# and runs the scenes S1 (inputs/s1_ring.xml) and S3 (inputs/s3_ring_foundation.xml) with
# fields every 5 steps to 0.2 s (about 15 s and 30 s), rendering von Mises snapshots of the
# first impact:
#   docs/gallery/s1_impact.png, docs/gallery/s3_impact.png
# usage: perf/scenes/gallery.sh [build-dir]   (default build; needs Debian's
#        python3-matplotlib, python3-h5py, python3-numpy)
# The S4/S5 pictures the gallery also shows come from perf/scenes/run_s5.sh.
set -euo pipefail
ROOT=$(cd "$(dirname "$0")/../.." && pwd)
BUILD=${1:-$ROOT/build}
RUNS=$BUILD/scenes/gallery
OUT=$ROOT/docs/gallery
R=$ROOT/perf/scenes/render_section.py
mkdir -p "$RUNS" "$OUT"
sed -e "s|value=\"artery_ring\(_pins\)\{0,1\}.geo\"|value=\"$ROOT/inputs/artery_ring_pins.geo\"|" \
    -e 's|<ParameterList name="Output">|<ParameterList name="Output"><Parameter name="field list" type="string" value="default, principal_stress, log_strain"/>|' \
    "$ROOT/inputs/artery_ring.xml" > "$RUNS/artery_ring.xml"
"$BUILD/stentor" --overwrite --output "$RUNS/out" "$RUNS/artery_ring.xml" > "$RUNS/log.txt"
SCALE=1e-3 /usr/bin/python3 "$R" "$RUNS/out" artery_ring "$OUT/artery_ring_sigma1.png" "principal_stress[0]" \
  "largest principal Cauchy stress [kPa]" "0.5:50 kPa" "1:100 kPa"
SCALE=100 /usr/bin/python3 "$R" "$RUNS/out" artery_ring "$OUT/artery_ring_log_strain.png" "log_strain[0]" \
  "log strain xx [%]" "1:100 kPa"

# S1 and S3: the first impact (the scene decks run to 0.2 s with fields every 5 steps).
for scene in s1_ring s3_ring_foundation; do
  sed -e "s|value=\"ring.geo\"|value=\"$ROOT/inputs/ring.geo\"|" \
      -e "s|value=\"s3_ring_foundation.geo\"|value=\"$ROOT/inputs/s3_ring_foundation.geo\"|" \
      -e '/name="end time"/s|value="[^"]*"|value="0.2"|' \
      -e '/name="steps"/s|value="[^"]*"|value="200"|' \
      -e '/name="fields"/s|value="[^"]*"|value="true"|' -e '/name="every"/d' \
      -e 's|<ParameterList name="Output">|<ParameterList name="Output"><Parameter name="every" type="int" value="5"/>|' \
      "$ROOT/inputs/$scene.xml" > "$RUNS/$scene.xml"
  "$BUILD/stentor" --overwrite --output "$RUNS/$scene" "$RUNS/$scene.xml" > "$RUNS/$scene.log"
done
OBSTACLE_LABEL="rigid plane" SCALE=1e-6 /usr/bin/python3 "$R" "$RUNS/s1_ring" s1_ring "$OUT/s1_impact.png" von_mises \
  "von Mises stress [MPa]" "0.03:first contact" "0.06:compressed" "0.1:flattened" "0.15:springing back"
SCALE=1e-6 /usr/bin/python3 "$R" "$RUNS/s3_ring_foundation" s3_ring_foundation "$OUT/s3_impact.png" von_mises \
  "von Mises stress [MPa]" "0.03:first contact" "0.06:compressed" "0.1:flattened" "0.15:springing back"
