#!/usr/bin/env bash
# Checkpoint and restart (issue 12): a run killed with SIGKILL, restarted from its last
# checkpoint, ends in the same state as the run that was never interrupted.
# usage: restart.sh MODE STENTOR CHECKPOINT_DIFF MPIEXEC NPFLAG WORKDIR DECK BASENAME NP_KILLED NP_RESTART TOL
#   MODE hook:N   the killed run kills itself while writing its N-th checkpoint
#                 (STENTOR_TEST_KILL_CHECKPOINT=N, src/io/Checkpoint.hpp): half a .tmp
#                 file, the one before intact.
#   MODE sigkill: `kill -9` from outside at an arbitrary moment after step 30 (the deck's `checkpoint every` set to 1 here, so that
#                 the kill can land in any part of a step, a checkpoint write included).
#   MODE signal:N[:R]  rank R (default 0) sends itself SIGTERM after step N
#                 (STENTOR_TEST_SIGNAL_AT_STEP, run/StopRequest.hpp): every rank ends that
#                 step, writes the fields and a checkpoint of it and exits 143, saying so.
#   MODE sigterm: `kill -TERM` from outside at an arbitrary moment after step 30: the
#                 step in progress ends, then the same.
# The reference runs uninterrupted on NP_RESTART ranks; the killed run on NP_KILLED; the
# restart (`--restart <out>.partial/<base>_checkpoint.h5`, same --output) on NP_RESTART.
# Checked: the killed run left <out>.partial with a readable checkpoint (sigkill: and its
# XDMF/HDF5 results read by meshio and h5py, xdmf_readers.py --results); the restart
# moved it to <out>.interrupted, exits 0 and writes <out>; its final checkpoint (the whole
# state: u, v, contact history, Gauss points, counters) equals the reference's to TOL
# (checkpoint_diff); its history and energy CSV files (the rows before the checkpoint
# carried over) equal the reference's to TOL per column group (relative to the group's
# largest value) and, on the same rank count, byte for byte.
set -u
. "$(dirname "$0")/lib.sh"
cli_dir=$(cd "$(dirname "$0")" && pwd)
mode=$1 stentor=$2 ckdiff=$3 mpiexec=$4 npflag=$5 work=$6 deck=$7 base=$8 np_killed=$9 np_restart=${10} tol=${11}
rm -rf "$work" && mkdir -p "$work" && cd "$work" || fail "cannot make $work"
flags=$(mpi_flags "$mpiexec")
run() {  # run NP ARGS...: stentor on NP ranks
  local np=$1
  shift
  # shellcheck disable=SC2086
  "$mpiexec" $npflag "$np" $flags "$stentor" "$@"
}
if [ "$mode" = sigkill ]; then  # a checkpoint after every step
  deck_copy "$deck" deck.xml -e 's/name="checkpoint every" type="int" value="[0-9]*"/name="checkpoint every" type="int" value="1"/'
  deck=$work/deck.xml
fi

run "$np_restart" --output ref "$deck" > ref.log 2>&1
rc=$?
[ "$rc" -eq 0 ] || { cat ref.log; fail "reference run: exit status $rc"; }

if [ "${mode%%:*}" = hook ]; then
  STENTOR_TEST_KILL_CHECKPOINT=${mode#hook:} run "$np_killed" --output out "$deck" > killed.log 2>&1
  rc=$?
elif [ "${mode%%:*}" = signal ]; then
  STENTOR_TEST_SIGNAL_AT_STEP=${mode#signal:} run "$np_killed" --output out "$deck" > killed.log 2>&1
  rc=$?
else
  # The stentor process itself (one rank, no launcher): a SIGKILLed mpirun would leave
  # its ranks running.
  [ "$np_killed" -eq 1 ] || fail "$mode mode runs the killed run on 1 rank"
  "$stentor" --output out "$deck" > killed.log 2>&1 &
  pid=$!
  for _ in $(seq 1 1500); do  # a checkpoint, and 30 steps done (contact starts at step 21 in restart_bars)
    [ -f "out.partial/${base}_checkpoint.h5" ] && [ "$(cat out.partial/"${base}"_history.csv 2> /dev/null | wc -l)" -gt 30 ] && break
    sleep 0.02
  done
  sleep "0.0$((RANDOM % 10))"
  if [ "$mode" = sigterm ]; then kill -TERM "$pid" 2> /dev/null; else kill -9 "$pid" 2> /dev/null; fi
  wait "$pid"
  rc=$?
fi
echo "killed run: exit status $rc; $(grep -c '^  step' killed.log) steps logged"
[ "$rc" -ne 0 ] || fail "the run ended before it was killed (exit 0): nothing tested"
ck=out.partial/${base}_checkpoint.h5
stopped_at=
if [ "${mode%%:*}" = signal ] || [ "$mode" = sigterm ]; then
  tail -n 12 killed.log
  [ "$rc" -eq 143 ] || fail "stopped by SIGTERM: exit status $rc, expected 143"
  line=$(grep "^STOPPED: SIGTERM received: the run stopped after step " killed.log) || fail "no STOPPED line in the log"
  echo "$line" | grep -q "continue with: stentor --restart $ck " || fail "the STOPPED line does not give the restart command"
  grep -q "^Partial results kept in out.partial" killed.log || fail "the log does not say where the partial results are"
  stopped_at=$(echo "$line" | sed 's/.*after step \([0-9]*\).*/\1/')
  [ "${mode%%:*}" = signal ] && { n=${mode#signal:}; [ "$stopped_at" = "${n%%:*}" ] || fail "stopped after step $stopped_at, not ${n%%:*}"; }
fi
[ -f "$ck" ] || { ls -la out.partial; fail "no checkpoint $ck after the kill"; }
ls out.partial
if [ "$mode" = sigkill ]; then
  # The results written so far stay readable after kill -9 at any moment (issue 12):
  # meshio and h5py read every step the XDMF lists, alike, each at a history row's time.
  /usr/bin/python3 "$cli_dir/xdmf_readers.py" --results out.partial "$base" > partial_readers.log 2>&1
  rc=$?
  cat partial_readers.log
  if [ "$rc" -eq 77 ]; then
    echo "NOTE: the .partial XDMF/HDF5 not read (no python3-meshio/h5py)"
  else
    [ "$rc" -eq 0 ] || fail "the killed run's XDMF/HDF5 in out.partial is not readable"
  fi
fi

run "$np_restart" --output out --restart "$ck" "$deck" > restart.log 2>&1
rc=$?
[ "$rc" -eq 0 ] || { cat restart.log; fail "restart: exit status $rc"; }
grep "restart " restart.log
grep -q "restart  from $ck: step" restart.log || fail "the log does not say where it restarted from"
if [ -n "$stopped_at" ]; then  # the checkpoint is of the step the run stopped after
  grep -q "restart  from $ck: step $stopped_at," restart.log || fail "the restart is not from step $stopped_at"
fi
[ -d out.interrupted ] || fail "out.interrupted (the killed run's results) missing"
[ -f "out/${base}_checkpoint.h5" ] || fail "no final checkpoint in out/"

echo "final state vs the uninterrupted run:"
"$ckdiff" "ref/${base}_checkpoint.h5" "out/${base}_checkpoint.h5" "$tol" || fail "final checkpoints differ"

for f in history energy; do
  a=ref/${base}_$f.csv b=out/${base}_$f.csv
  [ -f "$a" ] || continue
  [ "$(wc -l < "$a")" -eq "$(wc -l < "$b")" ] || fail "$b: $(wc -l < "$b") lines, the reference has $(wc -l < "$a")"
  awk -F, -v tol="$tol" -v file="$b" '
    function abs(x) { return x < 0 ? -x : x }
    function group(n) {  # the name without _x/_y/_z; energy terms share one scale
      if (n ~ /^(kinetic|strain|total|external_work|support_work|dissipation|balance_residual|contact_work|friction_dissipation|plastic_dissipation|strain_energy)$/) return "energy"
      sub(/_[xyz]$/, "", n)
      return n
    }
    FNR == 1 { if (NR == 1) for (i = 1; i <= NF; ++i) g[i] = group(h[i] = $i); else if ($0 != hdr) { print file ": header differs"; exit 1 }
               hdr = $0; next }
    NR == FNR { for (i = 1; i <= NF; ++i) { a[FNR, i] = $i; if (abs($i) > s[g[i]]) s[g[i]] = abs($i) } next }
    { for (i = 1; i <= NF; ++i) { if (h[i] ~ /iterations$/) continue
        d = abs($i - a[FNR, i]); r = s[g[i]] > 0 ? d / s[g[i]] : d
        if (r > w) { w = r; where = h[i] " (line " FNR ")" } } }
    END { printf "%s: max relative difference %.3e at %s\n", file, w, w > 0 ? where : "-"; exit w > tol }' "$a" "$b" ||
    fail "$b differs from the uninterrupted run"
  if [ "$np_killed" = "$np_restart" ]; then cmp "$a" "$b" || fail "$b: not byte for byte the uninterrupted run's"; fi
done

# Stent metrics: the restarted run's rows start at the checkpoint, so its last metrics and
# stage rows (the recoil from the peak before the checkpoint, the foreshortening from the
# as-cut length, the stage's start) must equal the uninterrupted run's.
for f in metrics stages; do
  a=ref/${base}_$f.csv b=out/${base}_$f.csv
  [ -f "$a" ] || continue
  [ -f "$b" ] || fail "$b missing"
  { head -1 "$a"; tail -1 "$a"; tail -1 "$b"; } | awk -F, -v tol="$tol" -v file="$b" '
    function abs(x) { return x < 0 ? -x : x }
    NR == 1 { for (i = 1; i <= NF; ++i) h[i] = $i; next }
    NR == 2 { for (i = 1; i <= NF; ++i) a[i] = $i; n = NF; next }
    { if (NF != n) { print file ": " NF " columns, the reference has " n; exit 1 }
      for (i = 1; i <= NF; ++i) {
        if ($i == a[i]) continue
        if (abs($i - a[i]) > tol * (abs(a[i]) > 1 ? abs(a[i]) : 1)) { print file ": last row, " h[i] " = " $i ", the uninterrupted run: " a[i]; exit 1 } } }
    END { if (NR == 3) print file ": the last row equals the uninterrupted run'"'"'s" }' ||
    fail "$b: the last row differs from the uninterrupted run"
done
echo "PASS"
