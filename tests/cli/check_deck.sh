#!/usr/bin/env bash
# `stentor --check DECK` exits 0, says the deck is valid and writes nothing.
# usage: check_deck.sh STENTOR WORKDIR DECK
set -u
. "$(dirname "$0")/lib.sh"
stentor=$1 work=$2 deck=$3
log=$work.log
rm -rf "$work" && mkdir -p "$work" && cd "$work" || fail "cannot make $work"
"$stentor" --check "$deck" > "$log" 2>&1
rc=$?
cat "$log"
[ "$rc" -eq 0 ] || fail "stentor --check $deck: exit status $rc"
grep -q "deck and mesh are valid" "$log" || fail "no 'deck and mesh are valid' line"
[ -z "$(ls -A)" ] || fail "--check wrote files: $(ls -A)"
echo "PASS"
