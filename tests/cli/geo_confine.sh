#!/usr/bin/env bash
# The kernel's confinement of gmsh's process alone (mesh/Confine.hpp) stops a .geo from
# writing: with the .geo screen turned off (STENTOR_TEST_NO_GEO_SCREEN=1, a test hook),
# a mesh script that appends to the stand-in home's .bashrc by a computed name, writes
# into a watched folder and runs `touch` there meshes (exit 0 or 2) and changes nothing.
# The control run, also without the confinement (STENTOR_TEST_NO_LANDLOCK=1), shows the
# same script does write, and that the log then says gmsh's process is unconfined.
# Exit 77 (skipped) where the kernel has no Landlock.
# usage: geo_confine.sh STENTOR GEO DECK WORKDIR
set -u
. "$(dirname "$0")/lib.sh"
stentor=$1 geo=$2 deck=$3 work=$4
rm -rf "$work" && mkdir -p "$work/watch" "$work/home" && cd "$work" || fail "cannot make $work"
echo "keep me" > watch/keep.txt
echo "# the user's shell start-up file" > home/.bashrc
{
  echo "Printf(\"touch /tmp/x\") >> StrCat(\"$work/home/\", \".bashrc\");"
  echo "Printf(\"pwned\") > Sprintf(\"$work/watch/printf%g.txt\", 1);"
  echo "SystemCall StrCat(\"touch \", \"$work/watch/systemcall.txt\");"
  cat "$geo"
} > hostile.geo
sed "s#value=\"geo_systemcall.geo\"#value=\"$work/hostile.geo\"#" "$deck" > deck.xml
before=$(snapshot "$work/watch"; snapshot "$work/home")
STENTOR_TEST_NO_GEO_SCREEN=1 HOME=$work/home "$stentor" --check deck.xml > confined.log 2>&1
rc=$?
cat confined.log
if grep -q "this kernel has no Landlock" confined.log; then
  echo "SKIP: this kernel has no Landlock"
  exit 77
fi
case $rc in 0 | 2) ;; *) fail "confined run: exit status $rc, expected 0 or 2" ;; esac
grep -q "without Landlock" confined.log && fail "the confined run says it ran unconfined"
after=$(snapshot "$work/watch"; snapshot "$work/home")
[ "$before" = "$after" ] || { diff <(echo "$before") <(echo "$after"); fail "the confined gmsh process wrote"; }
echo "confined: exit $rc, the watched folder and the stand-in home unchanged"

STENTOR_TEST_NO_GEO_SCREEN=1 STENTOR_TEST_NO_LANDLOCK=1 HOME=$work/home "$stentor" --check deck.xml > control.log 2>&1
rc=$?
cat control.log
grep -q "runs without Landlock confinement (turned off by STENTOR_TEST_NO_LANDLOCK=1)" control.log ||
  fail "the unconfined run does not say so in its log"
[ -f watch/printf1.txt ] && [ -f watch/systemcall.txt ] && grep -q "touch /tmp/x" home/.bashrc ||
  fail "control: the unconfined, unscreened script did not write (exit $rc): the test shows nothing"
echo "PASS: confinement alone stopped the writes the unconfined control made"
