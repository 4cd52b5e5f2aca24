#!/usr/bin/env bash
# docs/deck.md's dynamic contact example is the shipped deck it says it is, and stentor
# accepts it: the ```xml block after "## A complete dynamic contact example" equals
# inputs/s1_ring.xml byte for byte, and `stentor --check` on the extracted copy (next to a
# copy of its mesh) exits 0.
# usage: docs_example.sh STENTOR WORKDIR SOURCE_DIR
set -u
. "$(dirname "$0")/lib.sh"
stentor=$1 work=$2 src=$3
rm -rf "$work" && mkdir -p "$work" && cd "$work" || fail "cannot make $work"
awk '/^## A complete dynamic contact example$/ { sec = 1; next }
     sec && /^```xml$/ { on = 1; next }
     on && /^```$/ { exit }
     on { print }' "$src/docs/deck.md" > example.xml
[ -s example.xml ] || fail "no \`\`\`xml block under '## A complete dynamic contact example' in docs/deck.md"
cmp example.xml "$src/inputs/s1_ring.xml" || fail "the example in docs/deck.md differs from inputs/s1_ring.xml"
cp "$src/inputs/ring.geo" . || fail "cannot copy inputs/ring.geo"
"$stentor" --check example.xml > check.log 2>&1 || { cat check.log; fail "stentor --check rejects the example"; }
grep -q 'dynamic' example.xml && grep -q '<ParameterList name="Contact">' example.xml || fail "the example is not a dynamic contact deck"
echo "PASS"
