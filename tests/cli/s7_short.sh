#!/usr/bin/env bash
# S7's procedure, short (tests/cli/decks/s7_short.xml): one strut of the S6 ring expanded
# by a rigid balloon into the layered artery (the pair `lumen` -> stent `outer`) and
# deflated; and the same deck with the wall's pair left out of the stages (the stent
# expanded freely, the artery untouched).
# Checks: both runs end at t = 1.5; the stent against the wall (gap, malapposition per area
# and per strut, prolapse, the wall_gap field: below); the lumen's nodes never penetrate the stent (smallest
# gap >= -1e-9 mm) and rest on it after deflation; the lumen opened (minimum lumen diameter
# from 3.1 to more than 3.4 mm) but not beyond the stent (mean lumen diameter <= the
# stent's outer D_max); the wall pushes the stent back: its recoil exceeds the free
# stent's; without the pair the lumen stays at 3.1 mm (1e-9) and the wall unstressed; the
# summary advises MUMPS (KLU2's factorizations are about half of the run).
# usage: s7_short.sh STENTOR WORKDIR DECK
set -u
. "$(dirname "$0")/lib.sh"
stentor=$1 work=$2 deck=$3
rm -rf "$work" && mkdir -p "$work" && cd "$work" || fail "cannot make $work"
# The run with the malapposition map written (its last frame is checked below).
sed 's|<Parameter name="fields" type="bool" value="false"/>|<Parameter name="field list" type="string" value="displacement wall_gap"/><Parameter name="every" type="int" value="1000"/>|' \
  "$deck" > map.xml
"$stentor" --output out map.xml > log.txt 2>&1 || { tail -30 log.txt; fail "the run failed"; }
sed 's|value="balloon, wall"|value="balloon"|' "$deck" > free.xml
"$stentor" --output free free.xml > free.txt 2>&1 || { tail -30 free.txt; fail "the free run failed"; }
last() {  # last() CSV COLUMN
  awk -F, -v c="$2" 'NR == 1 { for (i = 1; i <= NF; ++i) if ($i == c) k = i; next } { v = $k } END { print v }' "$1"
}
h=out/s7_short_history.csv m=out/s7_short_metrics.csv fm=free/s7_short_metrics.csv
for f in $h free/s7_short_history.csv; do
  t=$(last $f time)
  awk -v t="$t" 'BEGIN { exit !(t > 1.5 - 1e-12 && t < 1.5 + 1e-12) }' || fail "$f ends at t = $t"
done
awk -F, 'NR == 1 { for (i = 1; i <= NF; ++i) c[$i] = i; next }
  $c["contact_wall_min_gap"] != "nan" && $c["contact_wall_min_gap"] < -1e-9 { print "t = " $c["time"] ": gap " $c["contact_wall_min_gap"]; bad = 1 }
  { a = $c["contact_wall_active"] } END { if (a == 0) { print "no lumen node on the stent at the end"; bad = 1 }; exit bad }' $h ||
  fail "the lumen penetrates or leaves the stent"
Dmin=$(last $m "lumen_D_min [mm]") Dl=$(last $m "lumen_D_mean [mm]") Ds=$(last $m "D_max [mm]")
rw=$(last $m "radial_recoil [-]") rf=$(last $fm "radial_recoil [-]")
echo "minimum lumen diameter $Dmin mm, mean $Dl mm, stent D_max $Ds mm; recoil $rw (free $rf)"
awk -v d="$Dmin" -v l="$Dl" -v s="$Ds" 'BEGIN { exit !(d > 3.4 && l <= s + 1e-9) }' || fail "the lumen: MLD $Dmin, mean $Dl, stent $Ds"
awk -v a="$rw" -v b="$rf" 'BEGIN { exit !(a > b + 1e-6 && b > 0) }' || fail "recoil $rw with the wall, $rf free"
for c in "lumen_D_min [mm]" "lumen_D_mean [mm]"; do
  v=$(last $fm "$c")
  awk -v v="$v" 'BEGIN { exit !(v > 3.1 - 1e-9 && v < 3.1 + 1e-9) }' || fail "free run: $c = $v, not 3.1"
done
v=$(last $fm "intima_sigma1_max [MPa]")
awk -v v="$v" 'BEGIN { exit !(v < 1e-12 && v > -1e-12) }' || fail "free run: intima stressed ($v MPa)"
# The lumen's area in contact: some after deflation (the stent rests on the wall), none in
# the free run; below the lumen's own area over the stent's span, pi 3.1 mm x 1 mm.
a=$(last $m "lumen_contact_area [mm^2]") af=$(last $fm "lumen_contact_area [mm^2]")
echo "lumen area in contact $a mm^2 (free $af)"
awk -v a="$a" -v f="$af" 'BEGIN { exit !(a > 0 && a < 3.14159265 * 3.1 && f == 0) }' || fail "contact area $a, free $f"
# The stent against the wall. As cut (the first row) the stent's outer surface (r = 1.5 mm)
# lies 0.05 mm inside the lumen (r = 1.55 mm at its nodes, flat facets between them): the
# largest gap is 0.05 cos(half a facet's angle), all of the surface malapposed, no prolapse.
# At the end the stent rests on the wall (gap < a tenth of the strut, 0.01 mm) and the lumen
# bulges between the struts by less than the strut's thickness. The free run leaves the lumen
# at r = 1.55 mm inside the stent: the prolapse is the stent contour's radius less 1.55 mm,
# between the ring's smallest and largest outer radius less 1.55 mm.
first() {  # first() CSV COLUMN
  awk -F, -v c="$2" 'NR == 1 { for (i = 1; i <= NF; ++i) if ($i == c) k = i; next } NR == 2 { print $k }' "$1"
}
g0=$(first $m "stent_wall_gap_max [mm]") a0=$(first $m "malapposed_area [%]") p0=$(first $m "prolapse_max [mm]")
g=$(last $m "stent_wall_gap_max [mm]") ma=$(last $m "malapposed_area [%]") p=$(last $m "prolapse_max [mm]")
pf=$(last $fm "prolapse_max [mm]") Dfmin=$(last $fm "D_min [mm]") Dfmax=$(last $fm "D_max [mm]")
echo "stent against the wall: as cut gap $g0 mm, malapposed $a0 %, prolapse $p0 mm; at the end $g mm, $ma %, $p mm; free run prolapse $pf mm (D $Dfmin .. $Dfmax mm)"
awk -v g="$g0" -v a="$a0" -v p="$p0" 'BEGIN { exit !(g > 0.0499 && g <= 0.05 + 1e-12 && a == 100 && p == 0) }' ||
  fail "as cut: gap $g0, malapposed $a0 %, prolapse $p0"
awk -v g="$g" -v a="$ma" -v p="$p" 'BEGIN { exit !(g >= 0 && g < 0.01 && a < 50 && p > 0 && p < 0.1) }' ||
  fail "at the end: gap $g, malapposed $ma %, prolapse $p"
awk -v p="$pf" -v lo="$Dfmin" -v hi="$Dfmax" 'BEGIN { exit !(p >= lo / 2 - 1.55 - 1e-9 && p <= hi / 2 - 1.55 + 1e-9 && p > 0.1) }' ||
  fail "free run: prolapse $pf, not within the stent's radii less 1.55 mm ($Dfmin .. $Dfmax)"
# Per strut (one strut in the one-strut sector): its outer surface's mean distance. As cut
# all of it lies inside the lumen, between 1.55 cos(pi / 64) - 1.5 = 0.04813 mm (at a
# facet's middle; 64 cells around) and the largest node gap: malapposed; at the end it rests on the wall, its mean distance within the largest node
# gap: apposed.
s0=$(first $m "malapposed_struts [%]") d0=$(first $m "strut_gap_max [mm]")
s=$(last $m "malapposed_struts [%]") d=$(last $m "strut_gap_max [mm]")
echo "struts: as cut $s0 % malapposed, distance $d0 mm; at the end $s %, $d mm"
awk -v s="$s0" -v d="$d0" -v g="$g0" 'BEGIN { exit !(s == 100 && d > 1.55 * cos(3.14159265358979 / 64) - 1.5 && d <= g + 1e-12) }' ||
  fail "as cut: struts $s0 % malapposed, distance $d0 (largest node gap $g0)"
awk -v s="$s" -v d="$d" -v g="$g" 'BEGIN { exit !(s == 0 && d <= g && d < 0.01) }' ||
  fail "at the end: struts $s % malapposed, distance $d (largest node gap $g)"
grep -q "struts (1 in the model; a strut's distance: its outer surface's mean distance to the lumen): 0.00 % malapposed" log.txt ||
  fail "no struts line in the log"
grep -q "artery (stented segment): lumen D mean 3.1000 -> " log.txt || fail "no artery paragraph in the log"
grep -q "stent against the wall: largest gap " log.txt || fail "no apposition line in the log"
# KLU2's factorizations are about half of this 3D run: a build with MUMPS advises it.
if ldd "$stentor" | grep -q dmumps; then
  grep -q "^note: KLU2's factorizations took .* s of the run's .* s; on 3D meshes 'Linear Solver->direct solver' = mumps" log.txt ||
    fail "no advice to use MUMPS after a run spent mostly in KLU2"
fi
# The map: the last frame's wall_gap is defined on the stent's outer nodes only (NaN
# elsewhere) and its largest value is the metric's.
/usr/bin/python3 - out/s7_short.h5 "$g" <<'PY' || fail "the wall_gap field"
import sys, h5py, numpy as np
f = h5py.File(sys.argv[1], "r")
last = max((k for k in f if k.startswith("step_")), key=lambda k: int(k[5:]))
w = f[last + "/wall_gap"][:]
n = int(np.sum(~np.isnan(w)))
print("wall_gap: %d outer nodes of %d, largest %.17g (metric %s)" % (n, len(w), np.nanmax(w), sys.argv[2]))
sys.exit(0 if 0 < n < len(w) and abs(np.nanmax(w) - float(sys.argv[2])) <= 1e-12 else 1)
PY
echo "PASS"
