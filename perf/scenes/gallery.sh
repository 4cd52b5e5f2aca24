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
# the 3D scene S2 (inputs/s2_torus.xml, the whole 0.3 s, 150 steps, about 40 s) with fields
# at every step (field list "displacement, von_mises, contact_pressure"), rendered in 3D by
# perf/scenes/render_3d.py (the torus' boundary surface, von Mises of the cell that owns
# each face, the rigid plane):
#   docs/gallery/s2_torus_impact.png
# and the axial S4 (inputs/s4_stent_artery.xml as it is, about 35 s of CPU) with fields at
# t = 0 and the stage ends only (every = 1000; "displacement, von_mises"):
#   docs/scenes/s4_stages.png (the picture docs/scenes/README.md, S4, shows)
# usage: perf/scenes/gallery.sh [build-dir]   (default build; needs Debian's
#        python3-matplotlib, python3-h5py, python3-numpy)
# env: GALLERY_ONLY (a list of artery, s1, s3, s2, s4: only those; default all),
#      GALLERY_RUNS (where the runs go, default <build-dir>/scenes/gallery)
# The S4 cross-section and S5 pictures the gallery also shows come from perf/scenes/run_s5.sh.
set -euo pipefail
ROOT=$(cd "$(dirname "$0")/../.." && pwd)
BUILD=${1:-$ROOT/build}
RUNS=${GALLERY_RUNS:-$BUILD/scenes/gallery}
ONLY=${GALLERY_ONLY:-artery s1 s3 s2 s4}
want() { case " $ONLY " in *" $1 "*) return 0 ;; *) return 1 ;; esac; }
OUT=$ROOT/docs/gallery
R=$ROOT/perf/scenes/render_section.py
mkdir -p "$RUNS" "$OUT"
if want artery; then
sed -e "s|value=\"artery_ring\(_pins\)\{0,1\}.geo\"|value=\"$ROOT/inputs/artery_ring_pins.geo\"|" \
    -e 's|<ParameterList name="Output">|<ParameterList name="Output"><Parameter name="field list" type="string" value="default, principal_stress, log_strain"/>|' \
    "$ROOT/inputs/artery_ring.xml" > "$RUNS/artery_ring.xml"
"$BUILD/stentor" --overwrite --output "$RUNS/out" "$RUNS/artery_ring.xml" > "$RUNS/log.txt"
SCALE=1e-3 /usr/bin/python3 "$R" "$RUNS/out" artery_ring "$OUT/artery_ring_sigma1.png" "principal_stress[0]" \
  "largest principal Cauchy stress [kPa]" "0.5:50 kPa" "1:100 kPa"
SCALE=100 /usr/bin/python3 "$R" "$RUNS/out" artery_ring "$OUT/artery_ring_log_strain.png" "log_strain[0]" \
  "log strain xx [%]" "1:100 kPa"
fi

# S1 and S3: the first impact (the scene decks run to 0.2 s with fields every 5 steps).
for scene in s1_ring s3_ring_foundation; do
  case $scene in s1_ring) want s1 || continue ;; *) want s3 || continue ;; esac
  sed -e "s|value=\"ring.geo\"|value=\"$ROOT/inputs/ring.geo\"|" \
      -e "s|value=\"s3_ring_foundation.geo\"|value=\"$ROOT/inputs/s3_ring_foundation.geo\"|" \
      -e '/name="end time"/s|value="[^"]*"|value="0.2"|' \
      -e '/name="steps"/s|value="[^"]*"|value="200"|' \
      -e '/name="fields"/s|value="[^"]*"|value="true"|' -e '/name="every"/d' \
      -e 's|<ParameterList name="Output">|<ParameterList name="Output"><Parameter name="every" type="int" value="5"/>|' \
      "$ROOT/inputs/$scene.xml" > "$RUNS/$scene.xml"
  "$BUILD/stentor" --overwrite --output "$RUNS/$scene" "$RUNS/$scene.xml" > "$RUNS/$scene.log"
done
want s1 && OBSTACLE_LABEL="rigid plane" SCALE=1e-6 /usr/bin/python3 "$R" "$RUNS/s1_ring" s1_ring "$OUT/s1_impact.png" von_mises \
  "von Mises stress [MPa]" "0.03:first contact" "0.06:compressed" "0.1:flattened" "0.15:springing back"
want s3 && SCALE=1e-6 /usr/bin/python3 "$R" "$RUNS/s3_ring_foundation" s3_ring_foundation "$OUT/s3_impact.png" von_mises \
  "von Mises stress [MPa]" "0.03:first contact" "0.06:compressed" "0.1:flattened" "0.15:springing back"

# S2 (3D): the whole run with fields at every step, only the fields the picture needs.
if want s2; then
  sed -e "s|value=\"torus.geo\"|value=\"$ROOT/inputs/torus.geo\"|" -e '/name="fields"/d' \
      -e 's|<ParameterList name="Output">|<ParameterList name="Output"><Parameter name="every" type="int" value="1"/><Parameter name="field list" type="string" value="displacement, von_mises, contact_pressure"/>|' \
      "$ROOT/inputs/s2_torus.xml" > "$RUNS/s2_torus.xml"
  "$BUILD/stentor" --overwrite --output "$RUNS/s2_torus" "$RUNS/s2_torus.xml" > "$RUNS/s2_torus.log"
  VIEW=20,-25 VMAX=0.6 SCALE=1e-6 /usr/bin/python3 "$ROOT/perf/scenes/render_3d.py" "$RUNS/s2_torus" s2_torus \
    "$OUT/s2_torus_impact.png" von_mises "von Mises stress [MPa]" \
    "0:before impact" "0.034:first impact" "0.234:maximum compression" "0.3:rebound"
fi

# S4, axial section: the deck as it is, fields at t = 0 and the stage ends.
if want s4; then
  sed -e "s|value=\"s4_stent_artery.geo\"|value=\"$ROOT/inputs/s4_stent_artery.geo\"|" \
      -e '/name="every"/s|value="[^"]*"|value="1000"|' \
      -e 's|<ParameterList name="Output">|<ParameterList name="Output"><Parameter name="field list" type="string" value="displacement, von_mises"/>|' \
      "$ROOT/inputs/s4_stent_artery.xml" > "$RUNS/s4_stent_artery.xml"
  "$BUILD/stentor" --overwrite --output "$RUNS/s4_stent_artery" "$RUNS/s4_stent_artery.xml" > "$RUNS/s4_stent_artery.log"
  XLIM=-0.2,8.2 YLIM=-1.7,1.7 SCALE=1e-3 VMAX=120 /usr/bin/python3 "$R" "$RUNS/s4_stent_artery" s4_stent_artery \
    "$ROOT/docs/scenes/s4_stages.png" von_mises "von Mises stress [kPa]" \
    "0:start" "1:after insertion" "2:inflated" "3:after extraction"
fi
