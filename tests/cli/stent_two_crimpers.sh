#!/usr/bin/env bash
# Two contact pairs sharing the slave group `outer` in different stages
# (tests/cli/decks/stent_two_crimpers.xml): a first crimper in 'crimp' and 'release', a
# second one in 'crimp again'.
# Checks: the run ends at t = 2.25; the first crimper holds nodes in its stage 'crimp' and
# none in 'crimp again', the second none before 'crimp again' and some at its end; at the
# first crimp's end the outer diameter is the crimper's 2 x 1.30 mm and at the end the
# second's 2 x 1.25 mm (every outer node inside it, the outermost on it: 1e-6 mm).
# usage: stent_two_crimpers.sh STENTOR WORKDIR DECK
set -u
. "$(dirname "$0")/lib.sh"
stentor=$1 work=$2 deck=$3
rm -rf "$work" && mkdir -p "$work" && cd "$work" || fail "cannot make $work"
"$stentor" --output out "$deck" > log.txt 2>&1 || { tail -30 log.txt; fail "the run failed"; }
h=out/two_crimpers_history.csv m=out/two_crimpers_metrics.csv
awk -F, 'NR == 1 { for (i = 1; i <= NF; ++i) c[$i] = i; next }
  { s = $c["stage"]; a = $c["contact_first_active"]; b = $c["contact_second_active"]; t = $c["time"]
    if (s == 1 && t == 1 && a == 0) { print "t = 1: the first crimper holds no node"; bad = 1 }
    if (s == 3 && a != 0) { print "t = " t ": the first crimper active in crimp again"; bad = 1 }
    if (s < 3 && b != 0) { print "t = " t ": the second crimper active before its stage"; bad = 1 }
    last_b = b; last_t = t }
  END { if (last_t != 2.25 || last_b == 0) { print "end t = " last_t ", second crimper " last_b " nodes"; bad = 1 }; exit bad }' $h ||
  fail "the pairs are not active in their own stages only"
awk -F, 'NR == 1 { for (i = 1; i <= NF; ++i) if ($i == "D_max [mm]") k = i; next }
  $2 == 1 { d1 = $k } { d = $k }
  END { printf "outer diameter %.9f at t = 1, %.9f at the end\n", d1, d
        exit !(d1 > 2.6 - 1e-6 && d1 < 2.6 + 1e-6 && d > 2.5 - 1e-6 && d < 2.5 + 1e-6) }' $m ||
  fail "the outer diameter is not the crimpers' 2.6 and 2.5 mm"
echo "PASS"
