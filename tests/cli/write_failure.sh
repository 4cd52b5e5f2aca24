#!/usr/bin/env bash
# A result file that cannot be written stops the run at once: exit 3, one line on stderr
# naming the file and the reason, the earlier results untouched, the results written so
# far kept in <out>.partial.
# usage: write_failure.sh STENTOR WORKDIR DECK hook NAME[:N] FRAGMENT [MAXROWS]
#          the test hook STENTOR_TEST_FAIL_WRITE=NAME[:N] (src/io/WriteError.hpp) fails
#          the N-th and later writes of NAME with ENOSPC (a disk filling up); FRAGMENT
#          must be in stderr; the partial history has at most MAXROWS rows (the run
#          stopped there; the hook fails a write after it was made) when given
#        write_failure.sh STENTOR WORKDIR SLOW_DECK fsize
#          a real failure: a file size limit (prlimit) set on the running process, a
#          little above its .h5's size, makes HDF5's writes fail with EFBIG ("File too
#          large"); skipped (77) without prlimit
#        write_failure.sh STENTOR WORKDIR DECK tmpfs KB FRAGMENT
#          a real full disk: the output folder on a tmpfs of KB kilobytes (in a mount
#          namespace of its own: unshare -m; skipped (77) where mounting is not allowed)
set -u
. "$(dirname "$0")/lib.sh"
stentor=$1 work=$2 deck=$3 mode=$4
if [ "$mode" = tmpfs ] && [ -z "${STENTOR_TEST_IN_NS:-}" ]; then
  rm -rf "$work" && mkdir -p "$work/disk" || fail "cannot make $work"
  if ! unshare -m true 2> /dev/null || ! unshare -m mount -t tmpfs -o size=4k tmpfs "$work/disk" 2> /dev/null; then
    echo "SKIP: cannot mount a tmpfs here (unshare -m / mount not permitted)"
    exit 77
  fi
  STENTOR_TEST_IN_NS=1 exec unshare -m bash "$0" "$@"
fi
if [ "$mode" = tmpfs ]; then
  mount -t tmpfs -o size="$5k" tmpfs "$work/disk" || fail "mount failed"
  cd "$work" || fail "cannot enter $work"
  out=$work/disk/results
else
  rm -rf "$work" && mkdir -p "$work" && cd "$work" || fail "cannot make $work"
  out=$work/results
fi
make_results "$out"
snapshot "$out" > snap.before
rows() { tail -n +2 "$1" | wc -l; }
case $mode in
hook)
  spec=$5 frag=$6 maxrows=${7:-}
  STENTOR_TEST_FAIL_WRITE=$spec "$stentor" --output "$out" "$deck" > stdout.txt 2> stderr.txt
  rc=$?
  ;;
fsize)
  command -v prlimit > /dev/null || { echo "SKIP: no prlimit"; exit 77; }
  frag="stentor.h5 failed: File too large" maxrows=""
  sed "s|value=\"\\([^\"]*\\.geo\\)\"|value=\"$(dirname "$deck")/\\1\"|; s|name=\"fields\" type=\"bool\" value=\"false\"|name=\"fields\" type=\"bool\" value=\"true\"|" \
    "$deck" > slow_fields.xml
  "$stentor" --output "$out" slow_fields.xml > stdout.txt 2> stderr.txt &
  pid=$!
  for _ in $(seq 1 300); do
    [ -f "$out.partial/stentor_history.csv" ] && [ "$(rows "$out.partial/stentor_history.csv")" -ge 3 ] && break
    sleep 0.1
  done
  size=$(stat -c %s "$out.partial/stentor.h5") || { kill -9 $pid; fail "no .h5 written"; }
  prlimit --pid $pid --fsize=$((size + 40000)) || { kill -9 $pid; fail "prlimit failed"; }
  wait $pid
  rc=$?
  ;;
tmpfs)
  frag=$6 maxrows=""
  "$stentor" --output "$out" "$deck" > stdout.txt 2> stderr.txt
  rc=$?
  ;;
*) fail "unknown mode $mode" ;;
esac
echo "--- exit $rc; stderr:"; cat stderr.txt
[ "$rc" -eq 3 ] || { echo "--- stdout:"; tail -5 stdout.txt; fail "exit status $rc, expected 3"; }
[ "$(grep -c . stderr.txt)" -eq 1 ] || fail "stderr is not one line"
grep -qF -- "$frag" stderr.txt || fail "stderr does not contain '$frag'"
grep -qF -- "$out" stderr.txt || fail "stderr does not name the file in $out(.partial)"
grep -q "^Results in " stdout.txt && fail "the run reported results"
check_results_untouched "$out" snap.before
[ "$mode" = tmpfs ] || [ -f "$out.partial/stentor_history.csv" ] || fail "the partial results were not kept"
if [ -n "$maxrows" ]; then
  n=$(rows "$out.partial/stentor_history.csv")
  [ "$n" -le "$maxrows" ] || fail "the run went on after the failed write: $n history rows, expected <= $maxrows"
fi
echo "PASS"
