#!/usr/bin/env bash
# A solve that must fail: exit status 3, "cutting dt" then a FAILED line, the
# existing output folder untouched, the partial results kept in <out>.partial.
# No CSV in <out>.partial holds nan or inf. Each FRAGMENT must occur in the log.
# --no-cut: a failure that no cut-back could help (the run stops without "cutting dt").
# usage: newton_failure.sh [--no-cut] STENTOR WORKDIR DECK [FRAGMENT]...
set -u
. "$(dirname "$0")/lib.sh"
need_cut=1
if [ "$1" = --no-cut ]; then
  need_cut=0
  shift
fi
stentor=$1 work=$2 deck=$3
shift 3
rm -rf "$work" && mkdir -p "$work" && cd "$work" || fail "cannot make $work"
out=$work/results
make_results "$out"
snapshot "$out" > snap.before
"$stentor" --output "$out" "$deck" > log.txt 2>&1
rc=$?
cat log.txt
[ "$rc" -eq 3 ] || fail "exit status $rc, expected 3"
[ "$need_cut" -eq 0 ] || grep -q "cutting dt" log.txt || fail "no 'cutting dt' line"
grep -q "^FAILED: " log.txt || fail "no 'FAILED: ' line"
check_results_untouched "$out" snap.before
[ -d "$out.partial" ] || fail "$out.partial was not kept"
ls "$out.partial"/*_history.csv > /dev/null 2>&1 || fail "no history CSV in $out.partial"
for f in "$@"; do
  grep -qF -- "$f" log.txt || fail "the log does not contain '$f'"
done
for c in "$out.partial"/*.csv; do
  tail -n +2 "$c" | grep -qi -e nan -e inf && fail "$c holds nan or inf"
done
echo "PASS"
