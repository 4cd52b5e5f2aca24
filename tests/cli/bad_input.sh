#!/usr/bin/env bash
# Bad input: stentor must exit with status 2, explain on stderr, and leave an
# existing output folder alone (no <out>.partial either).
# usage: bad_input.sh STENTOR WORKDIR [-e FRAGMENT]... -- STENTOR_ARGS...
# Each FRAGMENT must occur (fixed string) in stderr. "@OUT@" in STENTOR_ARGS is
# replaced by the output folder.
set -u
. "$(dirname "$0")/lib.sh"
stentor=$1 work=$2
shift 2
frags=()
while [ $# -gt 0 ] && [ "$1" != "--" ]; do
  [ "$1" = "-e" ] || fail "expected -e FRAGMENT or --, got '$1'"
  frags+=("$2")
  shift 2
done
shift  # --
rm -rf "$work" && mkdir -p "$work" && cd "$work" || fail "cannot make $work"
out=$work/results
make_results "$out"
snapshot "$out" > snap.before
args=()
for a in "$@"; do args+=("${a//@OUT@/$out}"); done

"$stentor" "${args[@]}" > stdout.txt 2> stderr.txt
rc=$?
echo "--- stentor ${args[*]} (exit $rc)"
echo "--- stderr:"; cat stderr.txt
[ "$rc" -eq 2 ] || { echo "--- stdout:"; cat stdout.txt; fail "exit status $rc, expected 2"; }
[ -s stderr.txt ] || fail "nothing on stderr"
for f in "${frags[@]}"; do
  grep -qF -- "$f" stderr.txt || fail "stderr does not contain '$f'"
done
check_results_untouched "$out" snap.before
[ -e "$out.partial" ] && fail "$out.partial was created for an input error"
# Nothing else appeared in the working folder (e.g. a default 'results').
extra=$(ls -A | grep -v -x -e results -e snap.before -e stdout.txt -e stderr.txt)
[ -z "$extra" ] || fail "unexpected files in the working folder: $extra"
echo "PASS"
