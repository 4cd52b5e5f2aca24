#!/usr/bin/env bash
# The S6 stent (inputs/s6_stent.xml: one strut's sector of the half length, 3 rings) expanded
# by a rigid cylinder and released by shrinking it at the rate the stent recoils: at the
# reversal the crown nodes end in contact with nearly zero force, a few hundred of them
# cycle and are held, and the held nodes in tension are released round after round (5
# rounds, docs/contact.md "Held nodes"). The run must have no cut-back and give the free
# spring-back's recoil (the stent ends clear of the cylinder): end ring 1.131 %, stent
# 1.183 % (docs/stent.md, "The whole stent").
# usage: stent_reversal.sh STENTOR WORKDIR DECK
set -u
. "$(dirname "$0")/lib.sh"
stentor=$1 work=$2 deck=$3
rm -rf "$work" && mkdir -p "$work" && cd "$work" || fail "cannot make $work"
"$stentor" --output out "$deck" > log.txt 2>&1 || { tail -30 log.txt; fail "the run failed"; }
grep -q "^Summary: 40 steps, 0 cut-backs" log.txt || { grep -E "cutting|Summary" log.txt; fail "cut-backs at the reversal"; }
table=$(awk '/metrics at the end of .release./{f=1} f' log.txt)
echo "$table" | grep -Eq '^  0 +\|.*\| +1\.131 \|' || { echo "$table"; fail "end ring recoil"; }
echo "$table" | grep -Eq '^  all +\|.*\| +1\.183 \|' || { echo "$table"; fail "stent recoil"; }
echo "PASS"
