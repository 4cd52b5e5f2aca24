#!/usr/bin/env bash
# A solve that must fail: exit status 3, "cutting dt" then a FAILED line, the
# existing output folder untouched, the partial results kept in <out>.partial.
# usage: newton_failure.sh STENTOR WORKDIR DECK
set -u
. "$(dirname "$0")/lib.sh"
stentor=$1 work=$2 deck=$3
rm -rf "$work" && mkdir -p "$work" && cd "$work" || fail "cannot make $work"
out=$work/results
make_results "$out"
snapshot "$out" > snap.before
"$stentor" --output "$out" "$deck" > log.txt 2>&1
rc=$?
cat log.txt
[ "$rc" -eq 3 ] || fail "exit status $rc, expected 3"
grep -q "cutting dt" log.txt || fail "no 'cutting dt' line"
grep -q "^FAILED: " log.txt || fail "no 'FAILED: ' line"
check_results_untouched "$out" snap.before
[ -d "$out.partial" ] || fail "$out.partial was not kept"
ls "$out.partial"/*_history.csv > /dev/null 2>&1 || fail "no history CSV in $out.partial"
echo "PASS"
