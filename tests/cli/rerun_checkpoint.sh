#!/usr/bin/env bash
# A re-run never empties a killed run's checkpoint (docs/robustness.md): a run killed
# with SIGKILL after its first checkpoint; the same command again exits 2 naming the
# checkpoint, its time and step, --restart and --overwrite, and leaves <out>.partial
# byte for byte as it was; `--restart <checkpoint>` then finishes the run (exit 0).
# usage: rerun_checkpoint.sh STENTOR DECK BASENAME WORKDIR
set -u
. "$(dirname "$0")/lib.sh"
stentor=$1 deck=$2 base=$3 work=$4
rm -rf "$work" && mkdir -p "$work" && cd "$work" || fail "cannot make $work"
ck=out.partial/${base}_checkpoint.h5
"$stentor" --output out "$deck" > killed.log 2>&1 &
pid=$!
for _ in $(seq 1 1500); do
  [ -f "$ck" ] && break
  sleep 0.02
done
kill -9 "$pid" 2> /dev/null
wait "$pid"
rc=$?
[ "$rc" -ne 0 ] || fail "the run ended before it was killed (exit 0): nothing tested"
[ -f "$ck" ] || { cat killed.log; fail "no checkpoint $ck after the kill"; }
echo "killed run: exit status $rc, $(grep -c '^  step' killed.log) steps logged"
before=$(snapshot out.partial)
sum=$(md5sum < "$ck")

"$stentor" --output out "$deck" > rerun.out 2> rerun.err
rc=$?
cat rerun.err
[ "$rc" -eq 2 ] || { cat rerun.out; fail "plain re-run: exit status $rc, expected 2"; }
for f in "holds the checkpoint $ck (t = " ", step " "--restart $ck" "--overwrite"; do
  grep -qF -- "$f" rerun.err || fail "the re-run's message does not name '$f'"
done
[ "$(md5sum < "$ck")" = "$sum" ] || fail "the checkpoint changed"
[ "$(snapshot out.partial)" = "$before" ] || fail "out.partial changed"
[ -e out ] && fail "the refused re-run made the output folder"

"$stentor" --output out --restart "$ck" "$deck" > restart.log 2>&1
rc=$?
[ "$rc" -eq 0 ] || { cat restart.log; fail "--restart: exit status $rc"; }
grep "restart " restart.log
[ -s "out/${base}_history.csv" ] || fail "the restarted run wrote no out/${base}_history.csv"
echo "PASS: the plain re-run kept the checkpoint; --restart finished the run"
