#!/usr/bin/env bash
# A rank stuck inside a collective never votes: the rank that votes must end the whole
# job with exit status 3 and its message within the vote's time limit, not hang.
# usage: agreement_stuck.sh MPIEXEC TEST_AGREEMENT WORKDIR
set -u
. "$(dirname "$0")/lib.sh"
mpiexec=$1 exe=$2 work=$3
rm -rf "$work" && mkdir -p "$work" && cd "$work" || fail "cannot make $work"
start=$(date +%s)
STENTOR_TEST_AGREEMENT_STUCK=1 timeout 60 "$mpiexec" -np 2 $(mpi_flags "$mpiexec") -x STENTOR_TEST_AGREEMENT_STUCK \
  "$exe" --gtest_filter=Agreement.StuckRankEndsTheJob > log.txt 2>&1
rc=$?
took=$(( $(date +%s) - start ))
cat log.txt
echo "--- exit $rc after $took s"
[ "$rc" -eq 124 ] && fail "the job hung (killed by timeout after 60 s)"
[ "$rc" -eq 3 ] || fail "exit status $rc, expected 3"
grep -qF "preconditioner set-up threw on rank 1" log.txt || fail "the failing rank's message is missing"
grep -qF "could not agree on this failure within 1 s" log.txt || fail "no explanation of the abort"
[ "$took" -lt 30 ] || fail "took $took s (the limit was 1 s)"
echo "PASS"
