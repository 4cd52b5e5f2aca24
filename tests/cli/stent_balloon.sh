#!/usr/bin/env bash
# One strut's sector of the S6 ring on the deformable balloon of `Mesh->Balloon`
# (tests/cli/decks/stent_balloon_ring.xml): the balloon's inflation pressure (0 -> 0.14 MPa)
# unfolds it onto the strut (node-to-segment contact of its outer surface on the stent's
# inner and side faces, `inner_and_sides`, friction 0.2) and starts to open the ring.
# Checks: the run ends without a cut-back; the history's pressure column follows the load;
# the balloon is in contact; the ring opens to the measured 3.0982 mm (D_mean, from 3.0);
# the stent metrics count the metal only (the ring's 0.1758 mm^3, as without the balloon);
# the pressure-diameter plot is drawn.
# usage: stent_balloon.sh STENTOR WORKDIR DECK
set -u
. "$(dirname "$0")/lib.sh"
stentor=$1 work=$2 deck=$3
rm -rf "$work" && mkdir -p "$work" && cd "$work" || fail "cannot make $work"
"$stentor" --output out "$deck" > log.txt 2>&1 || { tail -30 log.txt; fail "the run failed"; }
grep -q "^Summary: 10 steps, 0 cut-backs" log.txt || { grep -E "cutting|Summary" log.txt; fail "cut-backs"; }
last() {  # last() CSV COLUMN: the column's value in the last row
  awk -F, -v c="$2" 'NR == 1 { for (i = 1; i <= NF; ++i) if ($i == c) k = i; next } { v = $k } END { print v }' "$1"
}
p=$(last out/balloon_ring_history.csv pressure_inflation)
awk -v p="$p" 'BEGIN { exit !(p > 0.14 - 1e-12 && p < 0.14 + 1e-12) }' || fail "pressure at the end: $p, not 0.14"
n=$(last out/balloon_ring_history.csv contact_balloon_active)
[ "${n:-0}" -ge 40 ] || fail "only ${n:-0} balloon nodes in contact at the end"
d=$(last out/balloon_ring_metrics.csv "D_mean [mm]")
awk -v d="$d" 'BEGIN { exit !(d > 3.0981 && d < 3.0983) }' || fail "ring diameter at the end: $d mm, not 3.0982"
grep -q "metal volume 1.7581e-01 mm^3" log.txt || { grep "metal volume" log.txt; fail "the metal volume counts the balloon"; }
[ -s out/balloon_ring_pressure_diameter_inflation.png ] || fail "no pressure-diameter plot"
echo "PASS"
