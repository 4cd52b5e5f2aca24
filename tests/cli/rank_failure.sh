#!/usr/bin/env bash
# An error on one MPI rank only must end every rank (MPI_Abort with the documented exit
# status), never hang the job. Uses the test hook STENTOR_TEST_FAIL_RANK=R[:input]
# (src/app/main.cpp): rank R alone throws right after reading the deck, while the other
# ranks go on into the mesh broadcast and would wait for it forever.
# usage: rank_failure.sh MPIEXEC STENTOR WORKDIR DECK HOOK EXPECTED_STATUS [FRAGMENT]...
set -u
. "$(dirname "$0")/lib.sh"
mpiexec=$1 stentor=$2 work=$3 deck=$4 hook=$5 want=$6
shift 6
rm -rf "$work" && mkdir -p "$work" && cd "$work" || fail "cannot make $work"
out=$work/results
make_results "$out"
snapshot "$out" > snap.before
start=$(date +%s)
# HOOK: the value of STENTOR_TEST_FAIL_RANK, or VAR=VALUE for another test hook
# (STENTOR_TEST_FAIL_WRITE=...), or "none" for a run that fails by itself.
case $hook in
none) var=STENTOR_TEST_NOTHING hook=STENTOR_TEST_NOTHING= ;;
*=*) var=${hook%%=*} ;;
*) var=STENTOR_TEST_FAIL_RANK hook=STENTOR_TEST_FAIL_RANK=$hook ;;
esac
env "$hook" timeout 90 "$mpiexec" -np 2 $(mpi_flags "$mpiexec") -x "$var" \
  "$stentor" --output "$out" "$deck" > log.txt 2>&1
rc=$?
cat log.txt
echo "--- exit $rc after $(( $(date +%s) - start )) s"
[ "$rc" -eq 124 ] && fail "the job hung (killed by timeout after 90 s)"
[ "$rc" -eq "$want" ] || fail "exit status $rc, expected $want"
for f in "$@"; do
  grep -qF -- "$f" log.txt || fail "the output does not contain '$f'"
done
check_results_untouched "$out" snap.before
echo "PASS"
