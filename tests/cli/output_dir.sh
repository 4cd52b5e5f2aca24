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
#   manifest     the manifest is verified, not obeyed: a planted one deletes nothing, a
#                copied one replaces no user file, a result changed since is kept, and a
#                deck name with a newline cannot add a line to it
#   concurrent   a run into the folder of a running one (SLOW_DECK): exit 2 naming its pid
#                and host; after that run is killed (SIGKILL), its stale lock is taken over
#   lock_link    a leftover <dir>.partial whose lock file is a symbolic link to a file
#                elsewhere: exit 2 naming the lock file, the link's target untouched; the
#                same with the .partial folder itself a link to a folder elsewhere
#   restart_live --restart from the checkpoint in the .partial of a run still running
#                (SLOW_DECK with a checkpoint every step), into its folder: exit 2 naming
#                the running run, its staging folder neither moved nor changed
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
  # A first run whose results have another basename: all of them are earlier results the
  # second run does not write, and go; the user's file stays.
  python3 - in/deck.xml in/first.xml <<'PY'
import sys
t = open(sys.argv[1]).read()
t = t.replace('<ParameterList name="stentor">', '<ParameterList name="stentor"><ParameterList name="Output"><Parameter name="basename" type="string" value="first"/></ParameterList>', 1) if 'name="Output"' not in t else t.replace('<ParameterList name="Output">', '<ParameterList name="Output"><Parameter name="basename" type="string" value="first"/>', 1)
open(sys.argv[2], "w").write(t)
PY
  run --output r in/first.xml
  [ "$rc" -eq 0 ] || fail "first run: exit status $rc"
  [ -s r/first_history.csv ] || fail "the first run wrote no first_history.csv"
  echo "the user's" > r/MARKER
  run --output r in/deck.xml
  [ "$rc" -eq 0 ] || fail "second run: exit status $rc"
  grep -qF "the results in r will be replaced" log.txt || fail "no notice that the results are replaced"
  [ "$(cat r/MARKER)" = "the user's" ] || fail "the user's unlisted file was touched"
  ls r | grep -q '^first' && fail "a file of the earlier results that this run does not write was kept: $(ls r)"
  grep -q '^stentor-manifest 2$' r/stentor-manifest.txt || fail "no manifest header"
  listed=$(grep -E '^[0-9]+[+]? [0-9a-f]{16} ' r/stentor-manifest.txt | cut -d' ' -f3 | LC_ALL=C sort)
  present=$(ls -A r | grep -v -x -e MARKER -e stentor-manifest.txt | LC_ALL=C sort)
  [ "$listed" = "$present" ] || fail "manifest lists [$listed], folder holds [$present]"
  [ -e r.partial ] && fail "r.partial left behind"
  ;;
manifest)
  copy_deck in
  # (a) A planted manifest (plain names, as an older or a hand-made one) lists the user's
  # files: a run into the folder deletes none of them and says so.
  mkdir p && echo "mine" > p/a.txt && echo "mine too" > p/b.txt
  printf '# Stentor results folder\na.txt\nb.txt\n' > p/stentor-manifest.txt
  run --output p in/deck.xml
  [ "$rc" -eq 0 ] || fail "planted manifest: exit status $rc"
  grep -qF "2 files that p/stentor-manifest.txt lists are not as the run that wrote them left them" log.txt || fail "no report of the unverified entries"
  [ "$(cat p/a.txt)" = "mine" ] && [ "$(cat p/b.txt)" = "mine too" ] || fail "a file a planted manifest lists was changed"
  # (b) A real manifest copied into another folder, beside a user file with a result's
  # name: that file does not match, so the run refuses to replace it.
  mkdir q && cp p/stentor-manifest.txt q/ && echo "user data" > q/stentor_history.csv
  run --output q in/deck.xml
  [ "$rc" -eq 2 ] || fail "copied manifest: exit status $rc, expected 2"
  grep -qF "holds files that its Stentor results do not list but that this run would write: stentor_history.csv" log.txt ||
    fail "no message naming the user's file"
  [ "$(cat q/stentor_history.csv)" = "user data" ] || fail "the user's file was replaced"
  # (c) A listed result changed by the user since: kept, and not replaced without --overwrite.
  echo "my edit" >> p/stentor_history.csv
  run --output p in/deck.xml
  [ "$rc" -eq 2 ] || fail "changed result: exit status $rc, expected 2"
  tail -n 1 p/stentor_history.csv | grep -qx "my edit" || fail "the changed result was replaced"
  # (d) A deck whose file name holds a newline and a name of the user's: the manifest
  # stays one line per file, and that user file survives the next run.
  nl=$'x\nnotes.txt\ny.xml'
  cp in/deck.xml "in/$nl"
  run --output n "in/$nl"
  [ "$rc" -eq 0 ] || fail "deck name with a newline: exit status $rc"
  grep -qx "notes.txt" n/stentor-manifest.txt && fail "the deck name broke a manifest line"
  echo "keep me" > n/notes.txt
  run --output n "in/$nl"
  [ "$rc" -eq 0 ] || fail "second run of the newline deck: exit status $rc"
  [ "$(cat n/notes.txt)" = "keep me" ] || fail "the user's notes.txt was deleted or changed"
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
lock_link)
  copy_deck in
  mkdir elsewhere && echo "precious" > elsewhere/target.txt
  snapshot elsewhere > snap.before
  mkdir l.partial && ln -s "$work/elsewhere/target.txt" l.partial/.stentor.lock
  run --output l in/deck.xml
  [ "$rc" -eq 2 ] || fail "lock file a link: exit status $rc, expected 2"
  grep -qF "the lock file l.partial/.stentor.lock is a symbolic link" log.txt || fail "no message naming the lock file link"
  snapshot elsewhere | diff snap.before - || fail "the link's target was written"
  [ -L l.partial/.stentor.lock ] || fail "the link was removed"
  ln -s "$work/elsewhere" m.partial
  run --output m in/deck.xml
  [ "$rc" -eq 2 ] || fail "staging folder a link: exit status $rc, expected 2"
  grep -qF "'m.partial' exists and is not a Stentor staging folder" log.txt || fail "no message naming m.partial"
  snapshot elsewhere | diff snap.before - || fail "the folder the link points to was changed"
  ;;
restart_live)
  deck_copy "$slow" live.xml -e 's#<Parameter name="fields" type="bool" value="false"/>#&<Parameter name="checkpoint every" type="int" value="1"/>#'
  grep -q "checkpoint every" live.xml || fail "could not add checkpoints to $slow"
  "$stentor" --output live live.xml > live.txt 2>&1 &
  pid=$!
  for _ in $(seq 1 300); do
    [ -s live.partial/stentor_checkpoint.h5 ] && break
    sleep 0.1
  done
  [ -s live.partial/stentor_checkpoint.h5 ] || { kill -9 $pid; fail "the slow run wrote no checkpoint"; }
  run --output live --restart live.partial/stentor_checkpoint.h5 live.xml
  alive=0; kill -0 $pid 2>/dev/null && alive=1
  kill -9 $pid; wait $pid 2>/dev/null
  [ $alive -eq 1 ] || fail "the slow run ended too early: make it longer"
  [ "$rc" -eq 2 ] || fail "restart into a running run's folder: exit status $rc, expected 2"
  grep -qF "cannot restart into 'live': another run is writing into it: pid $pid on host $(hostname)" log.txt ||
    fail "no message naming the running one"
  [ -e live.interrupted ] && fail "the running run's staging folder was moved"
  [ -s live.partial/stentor_checkpoint.h5 ] || fail "the running run's checkpoint is gone"
  ;;
*) fail "unknown mode $mode" ;;
esac
echo "PASS"
