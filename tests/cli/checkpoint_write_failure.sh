#!/usr/bin/env bash
# A checkpoint write that fails on one rank only (a full disk on that rank's node): the
# ranks agree on the failure before the file is closed, so the job ends on every rank with
# exit status 3 and the failing rank's message, instead of one rank leaving the parallel
# write while another still writes (which hung the job until it was killed).
# Test hook: STENTOR_TEST_FAIL_CHECKPOINT_RANK=R (src/io/Checkpoint.cpp).
# usage: checkpoint_write_failure.sh STENTOR MPIEXEC NPFLAG WORKDIR DECK NP RANK
set -u
. "$(dirname "$0")/lib.sh"
stentor=$1 mpiexec=$2 npflag=$3 work=$4 deck=$5 np=$6 rank=$7
rm -rf "$work" && mkdir -p "$work" && cd "$work" || fail "cannot make $work"
flags=$(mpi_flags "$mpiexec")
start=$(date +%s)
# shellcheck disable=SC2086
STENTOR_TEST_FAIL_CHECKPOINT_RANK=$rank timeout 100 "$mpiexec" $npflag "$np" $flags "$stentor" --output out "$deck" > log.txt 2>&1
rc=$?
cat log.txt
[ "$rc" -ne 124 ] || fail "the job hung (killed after 100 s)"
[ "$rc" -eq 3 ] || fail "exit status $rc, expected 3"
grep -qF "writing the checkpoint at step 10 failed" log.txt || fail "no message naming the checkpoint"
grep -qF "No space left on device" log.txt || fail "no reason given"
[ "$rank" -eq 0 ] || grep -qF "(on rank $rank)" log.txt || fail "the failing rank is not named"
grep -q "^  step   11 " log.txt && fail "the run went on after the failed checkpoint"
[ -e out ] && fail "the results folder was created"
echo "PASS in $(( $(date +%s) - start )) s"
