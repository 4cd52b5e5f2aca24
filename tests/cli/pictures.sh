#!/usr/bin/env bash
# cli.pictures.*: tools/stentor_pictures.py under pvbatch on a run of DECK. The pictures
# it promises exist (one per output with --time all), are PNGs of the size asked for with
# the bodies drawn in many colours (pictures_check.py reads them back with VTK); a
# missing field or body and an existing picture are refused with exit 2 and nothing
# overwritten. Skipped (77) where ParaView's Python modules or Xvfb are missing.
# usage: pictures.sh STENTOR WORKDIR DECK SOURCE_DIR FIELD [BODY]
set -u
here=$(cd "$(dirname "$0")" && pwd)
. "$here/lib.sh"
stentor=$1 work=$2 deck=$3 src=$4 field=$5 body=${6:-}
command -v pvbatch >/dev/null && command -v Xvfb >/dev/null && [ -d /usr/lib/python3/dist-packages/paraview ] || {
  echo "skipped: pvbatch, Xvfb or python3-paraview not installed"; exit 77; }
rm -rf "$work" && mkdir -p "$work" && cd "$work" || fail "cannot make $work"
sed -e "s|value=\"\\([^\"]*\\.geo\\)\"|value=\"$(dirname "$deck")/\\1\"|" \
    -e "s|<Parameter name=\"fields\" type=\"bool\" value=\"false\"/>|<Parameter name=\"fields\" type=\"bool\" value=\"true\"/>|" \
    -e "s|<Parameter name=\"every\" type=\"int\" value=\"[0-9]*\"/>|<Parameter name=\"every\" type=\"int\" value=\"8\"/>|" "$deck" > deck.xml
"$stentor" --output results deck.xml > log.txt 2>&1 || { cat log.txt; fail "the run failed"; }
xdmf=$(ls results/*.xdmf | grep -v _obstacles)
base=$(basename "$xdmf" .xdmf)
nout=$(grep -c '<Grid Name="step' "$xdmf" || true)
[ "$nout" -ge 3 ] || fail "$xdmf has $nout outputs, expected 3 or more"
export PYTHONPATH=/usr/lib/python3/dist-packages
start_xvfb "$PWD"
pictures() { timeout 120 pvbatch "$src/tools/stentor_pictures.py" "$@" 2>&1 | grep -v '^$'; return "${PIPESTATUS[0]}"; }
bodyarg=(); [ -n "$body" ] && bodyarg=(--body "$body")
pictures "$xdmf" --list | tee list.txt || fail "--list failed"
grep -q "^fields: .*$field" list.txt || fail "--list does not name $field"
pictures "$xdmf" --field "$field" --size 800x600 | tee one.txt || fail "one picture: exit $?"
pictures "$xdmf" --field "$field" --time all --size 640x480 "${bodyarg[@]}" | tee all.txt || fail "--time all: exit $?"
dir=results_pictures
[ -s "$dir/${base}_$field.png" ] || fail "no $dir/${base}_$field.png"
n=$(ls "$dir/${base}_${field}_"*.png | wc -l)
[ "$n" -eq "$nout" ] || fail "--time all wrote $n pictures for $nout outputs"
timeout 60 pvpython "$here/pictures_check.py" 800 600 30 "$dir/${base}_$field.png" || fail "the picture"
timeout 60 pvpython "$here/pictures_check.py" 640 480 1 "$dir/${base}_${field}_"*.png || fail "the frames"
# Refusals: exit 2, a message naming what is wrong, nothing overwritten.
before=$(snapshot "$dir")
pictures "$xdmf" --field no_such_field > bad_field.txt; rc=$?
[ "$rc" -eq 2 ] && grep -q "has no such field; it has .*$field" bad_field.txt || { cat bad_field.txt; fail "an unknown field: exit $rc"; }
pictures "$xdmf" --body no_such_body > bad_body.txt; rc=$?
[ "$rc" -eq 2 ] && grep -q "has no such body" bad_body.txt || { cat bad_body.txt; fail "an unknown body: exit $rc"; }
pictures "$xdmf" --field "$field" --size 800x600 > exists.txt; rc=$?
[ "$rc" -eq 2 ] && grep -q "exists (give --overwrite" exists.txt || { cat exists.txt; fail "an existing picture: exit $rc"; }
[ "$before" = "$(snapshot "$dir")" ] || fail "a refused call changed $dir"
pictures "$xdmf" --field "$field" --size 800x600 --overwrite > /dev/null || fail "--overwrite: exit $?"
echo "PASS"
