#!/usr/bin/env bash
# Input size limits (docs/robustness.md, "Input size limits"): a deck or .geo larger than
# --max-input-size (default 64 MiB) and a .msh larger than --max-mesh-size are refused
# unread, exit 2 naming the file, its size and the limit, within seconds (the files here
# are sparse); running out of memory ends with exit 4 naming the phase.
# usage: size_limits.sh STENTOR GEO_DECK MSH_DECK WORKDIR
set -u
. "$(dirname "$0")/lib.sh"
stentor=$1 geo_deck=$2 msh_deck=$3 work=$4
rm -rf "$work" && mkdir -p "$work" && cd "$work" || fail "cannot make $work"
expect() {  # expect STATUS FRAGMENT... -- ARGS...: stentor ARGS exits STATUS within 20 s, stderr holds each FRAGMENT
  local want=$1 frags=() start rc
  shift
  while [ "$1" != "--" ]; do frags+=("$1"); shift; done
  shift
  start=$(date +%s)
  timeout 20 "$stentor" "$@" > out.txt 2> err.txt
  rc=$?
  echo "stentor $* -> exit $rc in $(($(date +%s) - start)) s: $(cat err.txt)"
  [ "$rc" -eq "$want" ] || fail "exit status $rc, expected $want"
  for f in "${frags[@]}"; do grep -qF -- "$f" err.txt || fail "stderr does not name '$f'"; done
}
truncate -s 65M big_deck.xml
expect 2 "big_deck.xml: deck of 68157440 bytes (65 MiB), larger than the limit of 64 MiB" "--max-input-size" -- --check big_deck.xml
expect 2 "big_deck.xml: deck of 68157440 bytes" "limit of 10 MiB" -- --max-input-size 10M --check big_deck.xml
truncate -s 65M big.geo
sed "s#value=\"geo_systemcall.geo\"#value=\"$work/big.geo\"#" "$geo_deck" > geo_deck.xml
expect 2 "big.geo: mesh script (.geo) of 68157440 bytes (65 MiB), larger than the limit of 64 MiB" -- --output o geo_deck.xml
[ -e o ] || [ -e o.partial ] && fail "a refused input made an output folder"
deck_copy "$msh_deck" msh_deck.xml
expect 2 ".msh file of" "larger than the limit of 100 B" "--max-mesh-size" -- --max-mesh-size 100 --check msh_deck.xml
expect 2 "--max-input-size needs a size > 0" -- --max-input-size 12X --check msh_deck.xml
STENTOR_TEST_FAIL_RANK=0:alloc expect 4 "out of memory on rank 0 while setting up the run" -- --check msh_deck.xml
echo "PASS"
