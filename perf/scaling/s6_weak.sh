#!/usr/bin/env bash
# Weak scaling of the S6 stent expansion (inputs/s6_stent.xml: a rigid cylinder expands the
# 6-ring stent and is withdrawn, contact throughout) on its one-strut sector: 1 rank runs
# the proximal half (3 rings, `half length`, held on `symmetry_z`), 2 ranks the whole length
# (6 rings, the same sector, held axially at `anchor`): twice the cells on twice the ranks,
# the same mechanics (the halves are mirror images), so Newton's and the contact's work per
# step are alike and the wall time measures what the ranks add (partition, ghosting, the
# parallel linear solve). A strong-scaling point: the half on 2 ranks. Each run's recoil
# is printed so that the cases can be seen to agree.
#
#   perf/scaling/s6_weak.sh [STENTOR]      # E=5 cells through the strut (about 5k hex8 per rank)
#   E=3 LINEAR=direct perf/scaling/s6_weak.sh
#
# Environment: E (elements through width and thickness, default 5), LINEAR (gmres, the
# default, with MueLu; or direct), FORCING (Newton->forcing: fixed, the default, every
# GMRES solve to 1e-10; eisenstat-walker), OUT (default perf/results/scaling), MPIEXEC (mpirun).
# Writes $OUT/s6_weak.csv. Used for docs/performance.md ("S6 stent: ranks and a 16-rank
# projection").
set -uo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
STENTOR=${1:-$root/build/stentor}
E=${E:-5}
LINEAR=${LINEAR:-gmres}
FORCING=${FORCING:-fixed}
OUT=${OUT:-$root/perf/results/scaling}
MPIEXEC=${MPIEXEC:-mpirun}
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
[ -x "$STENTOR" ] || { echo "s6_weak: $STENTOR not found" >&2; exit 2; }
work=$OUT/s6_weak
rm -rf "$work" && mkdir -p "$work" || exit 2
csv=$OUT/s6_weak.csv
echo "case,ranks,half_length,hex8,dofs,steps,cutbacks,newton_iterations,linear_iterations,wall_s,recoil_stent_percent" > "$csv"

# deck HALF: the S6 stent deck with E cells through the strut, the linear solver, and for
# the whole length the axial hold moved from symmetry_z to the anchor node.
deck() {
  local half=$1
  sed -e "s|\"elements through width\" type=\"int\" value=\"3\"|\"elements through width\" type=\"int\" value=\"$E\"|" \
      -e "s|\"elements through thickness\" type=\"int\" value=\"3\"|\"elements through thickness\" type=\"int\" value=\"$E\"|" \
      -e "s|\"method\" type=\"string\" value=\"direct\"|\"method\" type=\"string\" value=\"$LINEAR\"|" \
      -e "s|\"max iterations\" type=\"int\" value=\"30\"/>|\"max iterations\" type=\"int\" value=\"30\"/><Parameter name=\"forcing\" type=\"string\" value=\"$FORCING\"/>|" \
      -e "s|\"every\" type=\"int\" value=\"5\"|\"every\" type=\"int\" value=\"1000\"|" \
      -e "s|\"half length\" type=\"bool\" value=\"true\"|\"half length\" type=\"bool\" value=\"$half\"|" \
      "$root/inputs/s6_stent.xml" |
    if [ "$half" = false ]; then sed -e 's|"boundary" type="string" value="symmetry_z"|"boundary" type="string" value="anchor"|'; else cat; fi
}

run() {  # run NAME RANKS HALF
  local name=$1 R=$2 half=$3 d=$work/$1.xml
  deck "$half" > "$d"
  local t0 t1
  t0=$(date +%s.%N)
  if [ "$R" -eq 1 ]; then
    "$STENTOR" --output "$work/$name" "$d" > "$work/$name.log" 2>&1
  else
    "$MPIEXEC" --oversubscribe -np "$R" "$STENTOR" --output "$work/$name" "$d" > "$work/$name.log" 2>&1
  fi
  local rc=$?
  t1=$(date +%s.%N)
  [ $rc -eq 0 ] || { echo "s6_weak: $name failed (rc $rc), see $work/$name.log" >&2; tail -5 "$work/$name.log" >&2; return 1; }
  local log=$work/$name.log
  local cells dofs summary recoil
  cells=$(sed -n 's/.*(stent: \([0-9]*\) hex8).*/\1/p' "$log" | head -1)
  dofs=$(awk '$1 == "dofs" { print $2; exit }' "$log")
  summary=$(grep '^Summary:' "$log")
  recoil=$(awk -F'|' '/metrics at the end of .release./ { f = 1 } f && $1 ~ /^ *all *$/ { gsub(/ /, "", $6); print $6; exit }' "$log")
  echo "$summary" | awk -v n="$name" -v R="$R" -v h="$half" -v c="$cells" -v d="$dofs" -v w="$(echo "$t1 - $t0" | bc)" -v r="$recoil" \
    '{ gsub(",", ""); printf "%s,%s,%s,%s,%s,%s,%s,%s,%s,%.1f,%s\n", n, R, h, c, d, $2, $4, $6, $9, w, r }' >> "$csv"
  tail -1 "$csv"
}

echo "S6 weak scaling: $E x $E cells through the strut, $LINEAR, $(getconf _NPROCESSORS_ONLN) cores"
status=0
run half_1rank 1 true || status=1
run whole_2ranks 2 false || status=1
run half_2ranks 2 true || status=1
column -s, -t "$csv"
exit $status
