#!/usr/bin/env bash
# A run that must succeed: exit 0 and "Results in" in its log.
# usage: run_ok.sh WORKDIR -- COMMAND...   (@OUT@ in COMMAND: WORKDIR/results)
set -u
. "$(dirname "$0")/lib.sh"
work=$1
shift 2
rm -rf "$work" && mkdir -p "$work" && cd "$work" || fail "cannot make $work"
args=()
for a in "$@"; do args+=("${a//@OUT@/$work/results}"); done
"${args[@]}" > log.txt 2>&1
rc=$?
cat log.txt
[ "$rc" -eq 0 ] || fail "exit status $rc, expected 0"
grep -q "^Results in " log.txt || fail "no 'Results in' line"
echo "PASS"
