#!/usr/bin/env bash
# The default run (inputs/artery_ring.xml): exit 0, all result files (a static run: no
# energy plot), a lumen that
# opens (positive radial displacement at both probes) and one history row per step.
# usage: default_run.sh STENTOR WORKDIR DECK
set -u
. "$(dirname "$0")/lib.sh"
stentor=$1 work=$2 deck=$3
rm -rf "$work" && mkdir -p "$work" && cd "$work" || fail "cannot make $work"
base=$(sed -n 's/.*name="basename" type="string" value="\([^"]*\)".*/\1/p' "$deck")
steps=$(sed -n 's/.*name="steps" type="int" value="\([0-9]*\)".*/\1/p' "$deck")
[ -n "$base" ] && [ -n "$steps" ] || fail "cannot read Output->basename / Stepping->steps from $deck"
"$stentor" --output results "$deck" > log.txt 2>&1
rc=$?
cat log.txt
[ "$rc" -eq 0 ] || fail "exit status $rc"
grep -q "^Results in " log.txt || fail "no 'Results in' line"
for f in "$base.xdmf" "$base.h5" "${base}_history.csv" "${base}_reactions.png" "${base}_probes.png"; do
  [ -s "results/$f" ] || fail "results/$f missing or empty"
done
[ -e "results/${base}_energy.png" ] && fail "a static run wrote ${base}_energy.png"
for f in results/*.png; do
  [ "$(head -c 4 "$f" | tail -c 3)" = "PNG" ] || fail "$f is not a PNG"
done
[ "$(head -c 4 "results/$base.h5" | tail -c 3)" = "HDF" ] || fail "$base.h5 is not HDF5"
grep -q "<Xdmf" "results/$base.xdmf" || fail "$base.xdmf is not XDMF"
[ -e results.partial ] && fail "results.partial left behind after a successful run"
csv="results/${base}_history.csv"
awk -F, -v steps="$steps" '
  NR == 1 { for (i = 1; i <= NF; ++i) c[$i] = i
            if (!("u_lumen_x_x" in c) || !("u_lumen_y_y" in c)) { print "no u_lumen_x_x / u_lumen_y_y column"; exit 1 }
            next }
  { rows++; ux = $c["u_lumen_x_x"]; uy = $c["u_lumen_y_y"]; t = $c["time"]; cuts = $c["cutbacks"]
    if (ux + 0 <= prevx || uy + 0 <= prevy) { print "row " NR ": lumen radius did not grow (" ux ", " uy ")"; bad = 1 }
    prevx = ux + 0; prevy = uy + 0 }
  END {
    if (bad) exit 1
    if (rows != steps) { print rows " history rows, expected " steps; exit 1 }
    if (cuts != 0) { print cuts " cut-backs, expected none"; exit 1 }
    if (t < 1 - 1e-12 || t > 1 + 1e-12) { print "last time " t ", expected 1"; exit 1 }
    if (ux <= 0 || uy <= 0) { print "radial displacement at the lumen not positive: " ux ", " uy; exit 1 }
    printf "lumen radial displacement %.4e m (x probe), %.4e m (y probe) after %d steps\n", ux, uy, rows
  }' "$csv" || fail "history check failed ($csv)"
echo "PASS"
