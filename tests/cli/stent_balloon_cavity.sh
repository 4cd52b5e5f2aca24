#!/usr/bin/env bash
# One strut's sector of the S6 ring on the deformable balloon, inflated by volume
# (tests/cli/decks/stent_balloon_cavity.xml: `type` = fluid cavity on `balloon_inner`,
# volume ratio 1.12, bulk modulus 2200 MPa). Checks: the run ends; at every step the
# cavity's volume is the fluid's at the reported pressure, V/V0 = (1 + 0.12 t/T) exp(-p/K);
# the pressure rises once the balloon presses on the strut; the balloon is in contact; the
# pressure-diameter plot is drawn from the cavity's pressure.
# usage: stent_balloon_cavity.sh STENTOR WORKDIR DECK
set -u
. "$(dirname "$0")/lib.sh"
stentor=$1 work=$2 deck=$3
rm -rf "$work" && mkdir -p "$work" && cd "$work" || fail "cannot make $work"
"$stentor" --output out "$deck" > log.txt 2>&1 || { tail -30 log.txt; fail "the run failed"; }
grep -q "^Summary:" log.txt || fail "no summary"
h=out/balloon_cavity_history.csv
awk -F, 'NR == 1 { for (i = 1; i <= NF; ++i) { if ($i == "time") t = i; if ($i == "pressure_inflation") p = i;
                   if ($i == "volume_ratio_inflation") v = i }
                   if (!t || !p || !v) { print "missing columns"; exit 1 }; next }
         { want = (1 + 0.12 * $t / 0.25) * exp(-$p / 2200); d = $v - want; if (d < 0) d = -d
           if (d > 1e-12) { printf "step %d: V/V0 %.15g, expected %.15g\n", NR - 1, $v, want; exit 1 }
           last = $p }
         END { if (!(last > 0.01)) { printf "pressure at the end %g MPa: the balloon does not press on the strut\n", last; exit 1 } }' "$h" \
  || fail "the cavity's volume does not follow its fluid"
n=$(awk -F, -v c=contact_balloon_active 'NR == 1 { for (i = 1; i <= NF; ++i) if ($i == c) k = i; next } { v = $k } END { print v }' "$h")
[ "${n:-0}" -ge 30 ] || fail "only ${n:-0} balloon nodes in contact at the end"
[ -s out/balloon_cavity_pressure_diameter_inflation.png ] || fail "no pressure-diameter plot"
echo "PASS"
