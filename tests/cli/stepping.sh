#!/usr/bin/env bash
# Step-size control and the log (issue 12).
# usage: stepping.sh MODE STENTOR WORKDIR DECK
#   growth     exit 0; the first step is cut back, then each accepted step grows by
#              Stepping->growth (1.5) up to the deck's step; the history has one row per
#              accepted step (rejected steps write nothing) and the XDMF one time per
#              accepted step plus t = 0
#   max_steps  exit 3 naming Stepping->max steps; 3 rows in the partial history; the
#              existing output folder untouched
#   flush      stdout redirected to a file, the run killed with SIGKILL after 3 history
#              rows: the log already holds those steps' progress lines (line-buffered)
set -u
. "$(dirname "$0")/lib.sh"
mode=$1 stentor=$2 work=$3 deck=$4
rm -rf "$work" && mkdir -p "$work" && cd "$work" || fail "cannot make $work"
out=$work/results
rows() { tail -n +2 "$1" | wc -l; }
case $mode in
growth)
  "$stentor" --output "$out" "$deck" > log.txt 2>&1
  rc=$?
  cat log.txt
  [ "$rc" -eq 0 ] || fail "exit status $rc, expected 0"
  grep -q "cutting dt" log.txt || fail "no cut-back: the deck no longer tests the growth"
  steps=$(sed -nE 's/^Summary: ([0-9]+) steps.*/\1/p' log.txt)
  csv=$(ls "$out"/*_history.csv)
  [ "$(rows "$csv")" -eq "$steps" ] || fail "history has $(rows "$csv") rows for $steps accepted steps"
  ntimes=$(grep -c '<Time ' "$out"/*.xdmf)
  [ "$ntimes" -eq $((steps + 1)) ] || fail "XDMF has $ntimes times for $steps accepted steps (+ t = 0)"
  # Column 3 is dt. After the first accepted step every dt is min(target, 1.5 x previous)
  # until the target is reached (or the end of the interval shortens the last step).
  awk -F, -v target=0.25 'NR == 2 { prev = $3; t = $2; if (prev >= target) { print "first step not cut back"; exit 1 } next }
       NR > 2 { want = 1.5 * prev; if (want > target) want = target;
                if (($3 < want * (1 - 1e-9) || $3 > want * (1 + 1e-9)) && $2 < 1 - 1e-9) { printf "row %d: dt %g, expected %g\n", NR - 1, $3, want; exit 1 }
                if ($2 > t + $3 * (1 + 1e-9) || $2 <= t) { printf "row %d: time %g after %g with dt %g\n", NR - 1, $2, t, $3; exit 1 }
                prev = $3; t = $2 }' "$csv" \
    || fail "dt did not grow back by 1.5 per step to the deck's step"
  awk -F, 'NR > 1 && $3 > m { m = $3 } END { if (m < 0.25 * (1 - 1e-9)) exit 1 }' "$csv" || fail "dt never reached the deck's step 0.25"
  ;;
max_steps)
  make_results "$out"
  snapshot "$out" > snap.before
  "$stentor" --output "$out" "$deck" > log.txt 2>&1
  rc=$?
  cat log.txt
  [ "$rc" -eq 3 ] || fail "exit status $rc, expected 3"
  grep -q "^FAILED: reached Stepping->max steps = 3 (3 accepted, 0 rejected)" log.txt || fail "no FAILED line naming Stepping->max steps"
  check_results_untouched "$out" snap.before
  [ "$(rows "$out".partial/*_history.csv)" -eq 3 ] || fail "the partial history does not have 3 rows"
  ;;
flush)
  "$stentor" --output "$out" "$deck" > log.txt 2>&1 &
  pid=$!
  csv=$out.partial/stentor_history.csv
  for _ in $(seq 1 600); do
    [ -f "$csv" ] && [ "$(rows "$csv")" -ge 3 ] && break
    kill -0 $pid 2>/dev/null || break
    sleep 0.1
  done
  kill -9 $pid 2>/dev/null
  wait $pid 2>/dev/null
  cat log.txt
  [ -f "$csv" ] && [ "$(rows "$csv")" -ge 3 ] || fail "the run wrote no 3 history rows"
  grep -q "^Summary" log.txt && fail "the run ended before it was killed: make the deck longer"
  n=$(grep -c '^  step ' log.txt)
  [ "$n" -ge 3 ] || fail "the killed run's log holds $n progress lines, expected >= 3 (stdout not flushed per step)"
  grep -q '^  step .*\[[0-9.]* s, ~[0-9.]* s left\]$' log.txt || fail "progress lines lack '[elapsed, ~left]'"
  ;;
*) fail "unknown mode $mode" ;;
esac
echo "PASS"
