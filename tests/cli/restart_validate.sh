#!/usr/bin/env bash
# A checkpoint is checked against the deck it restarts (issue 12): a checkpoint of another
# mesh is exit 2 naming the file and both meshes, and the existing output folder stays as
# it was; a checkpoint of the same mesh written by another deck (here: a longer end time
# with the same step) only warns, and the run continues to the new end time.
# DECK_A: the restart_bars deck (end time 0.05, 100 steps).
# usage: restart_validate.sh STENTOR WORKDIR DECK_A DECK_B   (A, B: different meshes; A with checkpoints)
set -u
. "$(dirname "$0")/lib.sh"
stentor=$1 work=$2 deck_a=$3 deck_b=$4
rm -rf "$work" && mkdir -p "$work" && cd "$work" || fail "cannot make $work"
"$stentor" --output a "$deck_a" > a.log 2>&1 || { cat a.log; fail "run of $deck_a failed"; }
ck=$(ls a/*_checkpoint.h5) || fail "no checkpoint in a/"

make_results b
snapshot b > b.snap
"$stentor" --output b --restart "$ck" "$deck_b" > b.log 2>&1
rc=$?
cat b.log
[ "$rc" -eq 2 ] || fail "restart with another mesh: exit status $rc, expected 2"
grep -q "$ck: checkpoint of a mesh with" b.log || fail "the message does not name the checkpoint and its mesh"
check_results_untouched b b.snap
[ -e b.partial ] && fail "b.partial left behind"

# The same mesh, another deck: a longer run (same step) continued from the last checkpoint.
deck_copy "$deck_a" longer.xml -e 's/name="end time" type="double" value="[^"]*"/name="end time" type="double" value="0.06"/' \
  -e 's/name="steps" type="int" value="[^"]*"/name="steps" type="int" value="120"/'
grep -q 'value="0.06"' longer.xml || fail "could not change the end time of $deck_a"
"$stentor" --output c --restart "$ck" longer.xml > c.log 2>&1
rc=$?
[ "$rc" -eq 0 ] || { cat c.log; fail "restart with a longer end time: exit status $rc"; }
grep "warning\|restart " c.log
grep -q "warning: $ck was written by another deck" c.log || fail "no warning about the other deck"
tail -n 1 c/*_history.csv | awk -F, '{ exit !($1 == 120 && $2 > 0.06 - 1e-12 && $2 < 0.06 + 1e-12) }' ||
  fail "the continued run did not reach step 120 at t = 0.06: $(tail -n 1 c/*_history.csv)"
echo "PASS"
