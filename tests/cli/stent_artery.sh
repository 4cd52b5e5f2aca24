#!/usr/bin/env bash
# A crimped ring in the layered artery of `Mesh->Artery`, one generated mesh
# (tests/cli/decks/stent_artery_ring.xml): the stent's period sector (22.5 deg) with the
# artery's cut faces in its symmetry_y / symmetry_sector groups (held along their normals),
# luminal pressure to 16 kPa, the stent inside the lumen, the contact pair stent `outer` ->
# artery `lumen` open.
# Checks: the run ends at t = 1; the written mesh has both bodies' groups (the artery's
# prefixed where the stent has the name); at 16 kPa the lumen's and the outer radius are the
# standalone artery's (docs/artery.md's table, 32 x 6: 2.717329 and 3.241825 mm; the sector
# holds the same cells, so the same discrete answer); the stent's crown does not move; the
# contact pair never closes (no active node, no force; its smallest gap after the first
# step above the 0.4928 mm it starts from, 1.5 cos(pi / 32) - 1).
# With RI RO (6 digits, mm): the lumen's and the outer radius of another artery's table row
# (tests/cli/decks/stent_artery_coronary.xml: the human coronary layers, 1.756304 and
# 2.491764 mm).
# usage: stent_artery.sh STENTOR WORKDIR DECK [RI RO]
set -u
. "$(dirname "$0")/lib.sh"
stentor=$1 work=$2 deck=$3 ri_ref=${4:-2.717329} ro_ref=${5:-3.241825}
rm -rf "$work" && mkdir -p "$work" && cd "$work" || fail "cannot make $work"
"$stentor" --output out "$deck" > log.txt 2>&1 || { tail -30 log.txt; fail "the run failed"; }
grep -q "(stent: [0-9]* hex8, intima: 8 hex8, media: 8 hex8, adventitia: 8 hex8)" log.txt ||
  { grep "mesh " log.txt; fail "not the stent and the artery's three layers"; }
msh=out/stent_artery_mesh.msh
[ -s "$msh" ] || fail "no $msh"
for g in '3 [0-9]* "stent"' '3 [0-9]* "intima"' '3 [0-9]* "media"' '3 [0-9]* "adventitia"' '2 [0-9]* "lumen"' \
         '2 [0-9]* "artery_outer"' '2 [0-9]* "artery_end_proximal"' '2 [0-9]* "artery_end_distal"' '2 [0-9]* "outer"' \
         '2 [0-9]* "end_proximal"' '2 [0-9]* "symmetry_y"' '2 [0-9]* "symmetry_sector"'; do
  grep -q "^$g\$" "$msh" || fail "no group $g in $msh"
done
last() {  # last() CSV COLUMN: the column's value in the last row
  awk -F, -v c="$2" 'NR == 1 { for (i = 1; i <= NF; ++i) if ($i == c) k = i; next } { v = $k } END { print v }' "$1"
}
h=out/stent_artery_history.csv
t=$(last $h time) p=$(last $h pressure_blood)
awk -v t="$t" -v p="$p" 'BEGIN { exit !(t == 1 && p > 0.016 - 1e-15 && p < 0.016 + 1e-15) }' || fail "ended at t = $t, p = $p"
ri=$(awk -v u="$(last $h u_lumen_x)" 'BEGIN { printf "%.7f", 1.5 + u }')
ro=$(awk -v u="$(last $h u_outer_x)" 'BEGIN { printf "%.7f", 2.32 + u }')
echo "lumen radius $ri mm, outer radius $ro mm at 16 kPa"
# (the table's 6 digits, to 1.5e-6 mm)
awk -v r="$ri" -v e="$ri_ref" 'BEGIN { exit !(r > e - 1.5e-6 && r < e + 1.5e-6) }' || fail "lumen radius $ri, not $ri_ref"
awk -v r="$ro" -v e="$ro_ref" 'BEGIN { exit !(r > e - 1.5e-6 && r < e + 1.5e-6) }' || fail "outer radius $ro, not $ro_ref"
for c in x y z; do
  u=$(last $h u_crown_$c)
  awk -v u="$u" 'BEGIN { exit !(u < 1e-12 && u > -1e-12) }' || fail "the stent's crown moved: u_$c = $u"
done
awk -F, 'NR == 1 { for (i = 1; i <= NF; ++i) c[$i] = i; next }
  { if ($c["contact_wall_active"] != 0 || $c["contact_wall_normal_force"] != 0) { print "row " NR ": contact"; bad = 1 }
    if (NR == 2 && !($c["contact_wall_min_gap"] > 0.4928)) { print "row 2: smallest gap " $c["contact_wall_min_gap"]; bad = 1 } }
  END { exit bad }' $h || fail "the stent touched the artery"
# The artery's metrics (Output->Stent Metrics): the lumen uniformly expanded, so every
# station's diameter is the probe's 2 r, and the minimum lumen diameter too; a largest
# principal stress per layer, its 99th percentile not above its maximum.
m=out/stent_artery_metrics.csv
Dm=$(last $m "lumen_D_mean [mm]") Dn=$(last $m "lumen_D_min [mm]")
echo "lumen D mean $Dm, minimum $Dn mm"
for D in "$Dm" "$Dn"; do
  awk -v d="$D" -v r="$ri" 'BEGIN { exit !(d - 2 * r < 3e-6 && 2 * r - d < 3e-6) }' || fail "lumen diameter $D, not 2 x $ri"
done
D0=$(awk -F, 'NR == 1 { for (i = 1; i <= NF; ++i) if ($i == "lumen_D_min [mm]") k = i; next } NR == 2 { print $k }' $m)
awk -v d="$D0" 'BEGIN { exit !(d > 3.0 - 1e-12 && d < 3.0 + 1e-12) }' || fail "lumen diameter $D0 at t = 0, not 3"
for l in intima media adventitia; do
  mx=$(last $m "${l}_sigma1_max [MPa]") p99=$(last $m "${l}_sigma1_p99 [MPa]")
  awk -v a="$mx" -v b="$p99" 'BEGIN { exit !(b > 0 && b <= a) }' || fail "$l: largest principal stress $mx, 99th percentile $p99"
done
D=$(awk -v r="$ri_ref" 'BEGIN { printf "%.4f", 2 * r }')
grep -q "artery (stented segment): lumen D mean 3.0000 -> $D" log.txt || { grep "artery" log.txt; fail "no artery line in the log"; }
echo "PASS"
