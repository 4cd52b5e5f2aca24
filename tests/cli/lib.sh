# Helpers shared by the tests/cli scripts (sourced; bash, coreutils, awk only).

fail() {
  echo "FAIL: $*" >&2
  exit 1
}

# snapshot DIR: one line per entry under DIR (the folder itself included): path, type,
# size, mtime and, for files, a checksum. Two equal snapshots: nothing was created,
# removed or modified.
snapshot() {
  (cd "$1" && find . -printf '%p %y %s %T@\n' | LC_ALL=C sort && find . -type f -print0 | LC_ALL=C sort -z | xargs -0 -r md5sum)
}

# make_results DIR: a results folder from an earlier run (its manifest listing a fake
# CSV) holding a file of the user's (MARKER, not listed).
make_results() {
  rm -rf "$1" "$1.partial" "$1.old"
  mkdir -p "$1"
  echo "earlier results: must survive" > "$1/MARKER"
  printf 'step,time\n1,1\n' > "$1/old_history.csv"
  printf '# Stentor results folder (made by tests/cli/lib.sh)\nold_history.csv\n' > "$1/stentor-manifest.txt"
  touch -d '2020-01-01 00:00:00' "$1/MARKER" "$1/old_history.csv" "$1/stentor-manifest.txt" "$1"
}

# check_results_untouched DIR SNAPSHOT_FILE
check_results_untouched() {
  [ -f "$1/MARKER" ] || fail "the marker file in $1 is gone"
  snapshot "$1" | diff "$2" - >&2 || fail "the existing output folder $1 was modified"
  [ -e "$1.old" ] && fail "$1.old was left behind"
  return 0
}

# The MPI launcher: Open MPI refuses root without these and more ranks than cores
# without --oversubscribe.
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
export OMPI_MCA_rmaps_base_oversubscribe=1
mpi_flags() {
  if "$1" --version 2>&1 | grep -q "Open MPI\|OpenRTE"; then echo "--oversubscribe"; fi
}

# deck_copy DECK OUT [SED_ARGS...]: a copy of DECK at OUT, edited by sed, whose relative
# mesh path still resolves (made absolute against DECK's folder).
deck_copy() {
  local deck=$1 out=$2 dir
  shift 2
  dir=$(cd "$(dirname "$deck")" && pwd)
  sed -e "s#\(name=\"file\" type=\"string\" value=\"\)\([^/\"][^\"]*\)\"#\1$dir/\2\"#" "$@" "$deck" > "$out"
}

# start_xvfb DIR: an X server of this script's own for ParaView's pvbatch, DISPLAY
# exported, ended when the script exits. Xvfb picks a free display itself (-displayfd),
# so parallel tests do not race for one as with `xvfb-run -a`, and -noreset keeps it
# accepting connections: by default an X server resets when its last client leaves, and
# pvbatch (which probes OpenGL in one connection, then draws in another) then met a
# resetting server under load and aborted with "bad X server connection".
start_xvfb() {
  rm -f "$1/xvfb.display"
  Xvfb -displayfd 9 -screen 0 1280x1024x24 -nolisten tcp -noreset 9>"$1/xvfb.display" 2>"$1/xvfb.log" &
  _xvfb_pid=$!
  trap 'kill "$_xvfb_pid" 2>/dev/null' EXIT
  local i
  for i in $(seq 200); do
    [ -s "$1/xvfb.display" ] && break
    sleep 0.1
  done
  [ -s "$1/xvfb.display" ] || fail "Xvfb did not start (its log: $1/xvfb.log)"
  export DISPLAY=":$(head -n 1 "$1/xvfb.display")"
}
