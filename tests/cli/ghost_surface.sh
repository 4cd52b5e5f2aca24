#!/usr/bin/env bash
# Contact surface ghosting (issue 9): on NP ranks every rank imports only the surface nodes
# near its own slave nodes, fewer than the whole surface, and the run succeeds.
# usage: ghost_surface.sh STENTOR MPIEXEC NPFLAG WORKDIR DECK NP
set -u
. "$(dirname "$0")/lib.sh"
stentor=$1 mpiexec=$2 npflag=$3 work=$4 deck=$5 np=$6
rm -rf "$work" && mkdir -p "$work" && cd "$work" || fail "cannot make $work"
flags=""
"$mpiexec" --version 2>/dev/null | grep -q "Open MPI" && flags="--oversubscribe"
"$mpiexec" $npflag "$np" $flags "$stentor" --output out "$deck" > log.txt 2>&1 || { cat log.txt; fail "exit status $?"; }
line=$(grep -E "surface: [0-9]+ nodes; each rank imports" log.txt) || { cat log.txt; fail "no surface ghosting line"; }
echo "$line"
read -r total lo hi < <(echo "$line" | sed -E 's/.*surface: ([0-9]+) nodes;.*: ([0-9]+) to ([0-9]+).*/\1 \2 \3/')
[ "$hi" -lt "$total" ] || fail "a rank imports $hi of the $total surface nodes: the whole surface"
grep -q "^Results in " log.txt || fail "no 'Results in' line"
echo "PASS"
