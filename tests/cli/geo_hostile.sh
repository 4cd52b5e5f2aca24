#!/usr/bin/env bash
# Hostile .geo corpus (corpus/geo_hostile/*.geo, docs/robustness.md "Mesh scripts"):
# statements that write, delete, run or end, with computed file names (StrCat, Sprintf,
# GetEnv, DirName, variables), inside loops, If blocks, macros, included, merged and
# .opt files. Each case is run as a user would (`stentor --output out deck.xml`, HOME
# a stand-in home folder holding a .bashrc, @WATCH@ in the case replaced by a watched
# folder holding a file): it must exit 2 with the refusal its first line names
# ("// expect: <text>"), and the watched folder, the stand-in home and the case's
# folder must be as before (no out, no out.partial).
# usage: geo_hostile.sh STENTOR CORPUS_DIR DECK WORKDIR
set -u
. "$(dirname "$0")/lib.sh"
stentor=$1 corpus=$2 deck=$3 work=$4
rm -rf "$work" && mkdir -p "$work" || fail "cannot make $work"
n=0
for geo in "$corpus"/*.geo; do
  name=$(basename "$geo" .geo)
  case_dir=$work/$name
  mkdir -p "$case_dir/watch" "$case_dir/home" && cd "$case_dir" || fail "cannot make $case_dir"
  echo "keep me" > watch/keep.txt
  echo "# the user's shell start-up file" > home/.bashrc
  for f in "$geo" "$geo.opt" "$corpus"/*.txt; do
    [ -f "$f" ] && sed "s#@WATCH@#$case_dir/watch#g" "$f" > "$(basename "$f")"
  done
  sed "s#value=\"geo_systemcall.geo\"#value=\"$name.geo\"#" "$deck" > deck.xml
  expect=$(sed -n '1s#^// expect: ##p' "$name.geo")
  before=$(snapshot "$case_dir")
  HOME=$case_dir/home PWN_TARGET=$case_dir/watch/env.txt "$stentor" --output out deck.xml > ../"$name".out 2> ../"$name".err
  rc=$?
  after=$(snapshot "$case_dir")
  echo "$name: exit $rc: $(head -c 200 ../"$name".err)"
  [ "$rc" -eq 2 ] || { cat ../"$name".out ../"$name".err; fail "$name: exit status $rc, expected 2"; }
  grep -qF -- "$expect" ../"$name".err || fail "$name: stderr does not name '$expect'"
  grep -qF -- ".geo" ../"$name".err || grep -qF -- ".txt" ../"$name".err || fail "$name: stderr names no file"
  [ "$before" = "$after" ] || { diff <(echo "$before") <(echo "$after"); fail "$name: files changed (watched folder, home or case folder)"; }
  n=$((n + 1))
done
[ "$n" -ge 40 ] || fail "only $n cases in $corpus"
echo "PASS: $n hostile .geo cases refused (exit 2), nothing written"
