#!/usr/bin/env bash
# Bad stent parameters (Mesh->Stent, docs/stent.md): inputs/s6_ring_quarter.xml edited by
# a sed script, then bad_input.sh (exit 2, the message, nothing written). BAD_DECK names
# another deck of inputs/ to edit (the artery's: inputs/artery_layers.xml).
# usage: stent_bad.sh STENTOR WORKDIR SED_SCRIPT [-e FRAGMENT]...
# The edited deck is WORKDIR.xml (beside WORKDIR, which bad_input.sh empties).
set -u
here=$(cd "$(dirname "$0")" && pwd)
stentor=$1 work=$2 script=$3
shift 3
mkdir -p "$(dirname "$work")"
deck="$here/../../inputs/${BAD_DECK:-s6_ring_quarter.xml}"
sed -e "$script" "$deck" > "$work.xml" || exit 1
cmp -s "$deck" "$work.xml" && { echo "FAIL: the sed script changed nothing"; exit 1; }
exec bash "$here/bad_input.sh" "$stentor" "$work" "$@" -- --output @OUT@ "$work.xml"
