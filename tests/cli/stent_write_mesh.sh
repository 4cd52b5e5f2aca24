#!/usr/bin/env bash
# Mesh->write mesh: inputs/s6_ring_quarter.xml cut to one step, with `write mesh` = true,
# writes <basename>_mesh.msh into the output folder: gmsh 2.2 ASCII with the quarter ring's
# 2192 nodes, its 1224 hexes and the physical groups by name, listed in the manifest.
# usage: stent_write_mesh.sh STENTOR WORKDIR
set -u
. "$(dirname "$0")/lib.sh"
here=$(cd "$(dirname "$0")" && pwd)
stentor=$1 work=$2
rm -rf "$work" && mkdir -p "$work" && cd "$work" || fail "cannot make $work"
sed -e 's|<Parameter name="generator" type="string" value="stent"/>|&<Parameter name="write mesh" type="bool" value="true"/>|' \
    -e 's|"end time" type="double" value="0.5"|"end time" type="double" value="0.025"|' \
    -e 's|"steps" type="int" value="20"|"steps" type="int" value="1"|' \
    "$here/../../inputs/s6_ring_quarter.xml" > deck.xml || fail "sed"
"$stentor" --output "$work/results" deck.xml > log.txt 2>&1 || { cat log.txt; fail "the run failed"; }
msh=results/s6_ring_quarter_mesh.msh
[ -f "$msh" ] || fail "no $msh"
head -3 "$msh" | grep -qx "2.2 0 8" || fail "not gmsh 2.2 ASCII"
nodes=$(awk '/^\$Nodes/{getline; print; exit}' "$msh")
[ "$nodes" = 2192 ] || fail "$nodes nodes, expected 2192"
hexes=$(awk '/^\$Elements/{on=1; next} /^\$EndElements/{on=0} on && $2 == 5' "$msh" | wc -l)
[ "$hexes" = 1224 ] || fail "$hexes hexes, expected 1224"
for g in stent inner outer end_proximal end_distal symmetry_x symmetry_y ring_0 anchor; do
  grep -q "\"$g\"" "$msh" || fail "no physical group '$g'"
done
grep -q " s6_ring_quarter_mesh.msh$" results/stentor-manifest.txt || fail "the mesh file is not in the manifest"
echo "PASS"
