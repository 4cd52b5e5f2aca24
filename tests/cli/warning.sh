#!/usr/bin/env bash
# A questionable deck that runs, with a warning naming the culprit on the log (stdout).
# usage: warning.sh STENTOR WORKDIR MODE DECK [-e FRAGMENT | -n FRAGMENT]...
#   MODE: check (`stentor --check`, exit 0), run (a run into WORKDIR/out, exit 0 or 3),
#         ok (a run that must end with exit 0) or ok_np2 (the same on 2 ranks, with the
#         launcher in $STENTOR_MPIEXEC)
#   -e: the log must contain FRAGMENT; -n: it must not
set -u
. "$(dirname "$0")/lib.sh"
stentor=$1 work=$2 mode=$3 deck=$4
shift 4
rm -rf "$work" && mkdir -p "$work" && cd "$work" || fail "cannot make $work"
if [ "$mode" = check ]; then
  "$stentor" --check "$deck" > stdout.txt 2> stderr.txt
  rc=$?
  [ "$rc" -eq 0 ] || { cat stdout.txt stderr.txt; fail "--check: exit status $rc, expected 0"; }
elif [ "$mode" = run ]; then
  "$stentor" --output out "$deck" > stdout.txt 2> stderr.txt
  rc=$?
  [ "$rc" -eq 0 ] || [ "$rc" -eq 3 ] || { cat stdout.txt stderr.txt; fail "exit status $rc, expected 0 or 3"; }
else
  launch=()
  [ "$mode" = ok_np2 ] && launch=("$STENTOR_MPIEXEC" -np 2 $(mpi_flags "$STENTOR_MPIEXEC"))
  timeout 120 "${launch[@]}" "$stentor" --output out "$deck" > stdout.txt 2> stderr.txt
  rc=$?
  [ "$rc" -eq 0 ] || { cat stdout.txt stderr.txt; fail "exit status $rc, expected 0"; }
fi
cat stdout.txt
while [ $# -gt 0 ]; do
  case $1 in
    -e) grep -qF -- "$2" stdout.txt || fail "the log does not contain '$2'" ;;
    -n) ! grep -qF -- "$2" stdout.txt || fail "the log contains '$2'" ;;
    *) fail "expected -e FRAGMENT or -n FRAGMENT, got '$1'" ;;
  esac
  shift 2
done
echo "PASS"
