#!/usr/bin/env bash
# Output folders (issues 12, 16): a run never deletes or overwrites files it did not
# write, and two runs never write into one folder at once.
# usage: output_dir.sh MODE STENTOR WORKDIR DECK [SLOW_DECK]
#   deck_folder  --output <the deck's own folder>: exit 2 naming the folder, nothing in it
#                changed (today's main deleted the deck and every other file there)
#   foreign      a non-empty folder without a Stentor manifest: exit 2 naming the folder
#                and --overwrite, nothing changed; with --overwrite exit 0, the user's
#                file kept, the results, the deck copy and the log copy written
#   replace      a second run into a Stentor results folder: the files the manifest lists
#                are replaced (a listed file the new run does not write is removed), the
#                user's unlisted file stays; the manifest lists exactly the new files
#   concurrent   a run into the folder of a running one (SLOW_DECK): exit 2 naming its pid
#                and host; after that run is killed (SIGKILL), its stale lock is taken over
set -u
. "$(dirname "$0")/lib.sh"
mode=$1 stentor=$2 work=$3 deck=$4 slow=${5:-}
rm -rf "$work" && mkdir -p "$work" && cd "$work" || fail "cannot make $work"
run() { "$stentor" "$@" > log.txt 2>&1; rc=$?; cat log.txt; }
# A copy of DECK (and its mesh, referenced by absolute path) in folder $1.
copy_deck() {
  mkdir -p "$1"
  sed "s|value=\"\\([^\"]*\\.geo\\)\"|value=\"$(dirname "$deck")/\\1\"|" "$deck" > "$1/deck.xml"
}
case $mode in
deck_folder)
  copy_deck proj
  echo "my notes" > proj/notes.txt
  snapshot proj > snap.before
  run --output proj proj/deck.xml
  [ "$rc" -eq 2 ] || fail "exit status $rc, expected 2"
  grep -qF "the output folder 'proj' holds $work/proj/deck.xml, a file this run reads" log.txt || fail "no message naming the folder and the deck"
  grep -qF -- "--output DIR" log.txt || fail "the message does not say what to do"
  snapshot proj | diff snap.before - || fail "the deck's folder was modified"
  [ -e proj.partial ] && fail "proj.partial was created"
  ;;
foreign)
  copy_deck in
  mkdir other && echo "the user's" > other/user.txt
  snapshot other > snap.before
  run --output other in/deck.xml
  [ "$rc" -eq 2 ] || fail "exit status $rc, expected 2"
  grep -qF "the output folder 'other' is not empty and holds no Stentor results" log.txt || fail "no message naming the folder"
  grep -qF -- "--overwrite" log.txt || fail "the message does not name --overwrite"
  snapshot other | diff snap.before - || fail "the folder was modified"
  run --overwrite --output other in/deck.xml
  [ "$rc" -eq 0 ] || fail "with --overwrite: exit status $rc, expected 0"
  [ "$(cat other/user.txt)" = "the user's" ] || fail "the user's file was changed"
  for f in stentor-manifest.txt stentor_history.csv stentor_deck.xml stentor.log; do
    [ -s "other/$f" ] || fail "other/$f missing"
  done
  cmp -s in/deck.xml other/stentor_deck.xml || fail "the deck copy differs from the deck"
  grep -q "^Summary: " other/stentor.log || fail "the log copy lacks the summary"
  grep -qx "user.txt" other/stentor-manifest.txt && fail "the manifest lists the user's file"
  ;;
replace)
  copy_deck in
  run --output r in/deck.xml
  [ "$rc" -eq 0 ] || fail "first run: exit status $rc"
  echo "the user's" > r/MARKER
  echo "stale" > r/stale_result.csv
  echo stale_result.csv >> r/stentor-manifest.txt  # as if an earlier run had written it
  run --output r in/deck.xml
  [ "$rc" -eq 0 ] || fail "second run: exit status $rc"
  grep -qF "the results in r will be replaced" log.txt || fail "no notice that the results are replaced"
  [ "$(cat r/MARKER)" = "the user's" ] || fail "the user's unlisted file was touched"
  [ -e r/stale_result.csv ] && fail "a file of the earlier results that this run does not write was kept"
  listed=$(grep -v '^#' r/stentor-manifest.txt | LC_ALL=C sort)
  present=$(ls -A r | grep -v -x -e MARKER -e stentor-manifest.txt | LC_ALL=C sort)
  [ "$listed" = "$present" ] || fail "manifest lists [$listed], folder holds [$present]"
  [ -e r.partial ] && fail "r.partial left behind"
  ;;
concurrent)
  copy_deck in
  "$stentor" --output shared "$slow" > slow.txt 2>&1 &
  pid=$!
  for _ in $(seq 1 300); do
    grep -q "^pid $pid" shared.partial/.stentor.lock 2>/dev/null && break
    sleep 0.1
  done
  grep -q "^pid $pid" shared.partial/.stentor.lock || { kill -9 $pid; fail "the slow run wrote no lock"; }
  # Its first staged result row too (under a loaded ctest -j the first step can take
  # seconds), so that "untouched" below has something to check.
  for _ in $(seq 1 300); do
    [ -s shared.partial/stentor_history.csv ] && break
    sleep 0.1
  done
  run --output shared in/deck.xml
  kill -0 $pid 2>/dev/null || fail "the slow run ended too early: make it longer"
  kill -9 $pid; wait $pid 2>/dev/null
  [ "$rc" -eq 2 ] || fail "second run: exit status $rc, expected 2"
  grep -qF "another run is writing into 'shared': pid $pid on host $(hostname)" log.txt || fail "no message naming the running one"
  [ -s shared.partial/stentor_history.csv ] || fail "the running one's staged results were touched"
  run --output shared in/deck.xml
  [ "$rc" -eq 0 ] || fail "after the first run was killed: exit status $rc, expected 0 (stale lock)"
  grep -qF "took over shared.partial from an earlier run that is no longer running (pid $pid" log.txt || fail "no notice of the stale lock"
  [ -e shared.partial ] && fail "shared.partial left behind"
  ;;
*) fail "unknown mode $mode" ;;
esac
echo "PASS"
