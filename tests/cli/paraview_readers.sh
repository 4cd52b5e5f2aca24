#!/usr/bin/env bash
# cli.paraview.*: runs DECK (at ORDER) and opens the result with ParaView's three XDMF
# readers under pvbatch (paraview_readers.py). Skipped (exit 77) where ParaView's Python
# modules (Debian paraview + python3-paraview) or Xvfb are not installed.
set -u
here=$(cd "$(dirname "$0")" && pwd)
. "$here/lib.sh"
stentor=$1 work=$2 deck=$3 order=$4 vtk_type=$5
command -v pvbatch >/dev/null && command -v Xvfb >/dev/null && [ -d /usr/lib/python3/dist-packages/paraview ] || {
  echo "skipped: pvbatch, Xvfb or python3-paraview not installed"; exit 77; }
rm -rf "$work" && mkdir -p "$work" && cd "$work" || fail "cannot make $work"
sed -e "s|value=\"\\([^\"]*\\.geo\\)\"|value=\"$(dirname "$deck")/\\1\"|" \
    -e "s|<Parameter name=\"fields\" type=\"bool\" value=\"false\"/>|<Parameter name=\"fields\" type=\"bool\" value=\"true\"/>|" "$deck" > deck.xml
grep -q '<Parameter name="order"' deck.xml || sed -i "s|<ParameterList name=\"Mesh\">|<ParameterList name=\"Mesh\"><Parameter name=\"order\" type=\"int\" value=\"$order\"/>|" deck.xml
sed -i "s|<Parameter name=\"order\" type=\"int\" value=\"[0-9]\"/>|<Parameter name=\"order\" type=\"int\" value=\"$order\"/>|" deck.xml
"$stentor" --output results deck.xml > log.txt 2>&1 || { cat log.txt; fail "the run failed"; }
xdmf=$(ls results/*.xdmf)
start_xvfb "$PWD"
PYTHONPATH=/usr/lib/python3/dist-packages timeout 120 pvbatch "$here/paraview_readers.py" "$PWD/$xdmf" "$vtk_type" 2>&1 |
  grep -v "^$" | tee pv.txt
[ "${PIPESTATUS[0]}" -eq 0 ] || fail "ParaView could not read $xdmf as expected"
echo "PASS"
