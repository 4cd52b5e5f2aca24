#!/usr/bin/env bash
# A solve that must fail: exit status 3, "cutting dt" then a FAILED line, the
# existing output folder untouched, the partial results kept in <out>.partial.
# No CSV in <out>.partial holds nan or inf, nor any HDF5 dataset there (read with h5py:
# Debian's /usr/bin/python3 with python3-h5py; the scan is skipped, with a note, where no
# python has h5py). Each FRAGMENT must occur in the log.
# A step that failed for good (its cut-backs used up, or below the minimum step) of a deck
# that writes fields leaves its last Newton iterate in <out>.partial/<basename>_failed.xdmf/.h5,
# and the log says so.
# --no-cut: a failure that no cut-back could help (the run stops without "cutting dt").
# usage: newton_failure.sh [--no-cut] STENTOR WORKDIR DECK [FRAGMENT]...
set -u
. "$(dirname "$0")/lib.sh"
need_cut=1
if [ "$1" = --no-cut ]; then
  need_cut=0
  shift
fi
stentor=$1 work=$2 deck=$3
shift 3
rm -rf "$work" && mkdir -p "$work" && cd "$work" || fail "cannot make $work"
out=$work/results
make_results "$out"
snapshot "$out" > snap.before
"$stentor" --output "$out" "$deck" > log.txt 2>&1
rc=$?
cat log.txt
[ "$rc" -eq 3 ] || fail "exit status $rc, expected 3"
[ "$need_cut" -eq 0 ] || grep -q "cutting dt" log.txt || fail "no 'cutting dt' line"
grep -q "^FAILED: " log.txt || fail "no 'FAILED: ' line"
check_results_untouched "$out" snap.before
[ -d "$out.partial" ] || fail "$out.partial was not kept"
ls "$out.partial"/*_history.csv > /dev/null 2>&1 || fail "no history CSV in $out.partial"
for f in "$@"; do
  grep -qF -- "$f" log.txt || fail "the log does not contain '$f'"
done
if grep -q "^FAILED: Newton failed at t = " log.txt && ls "$out.partial"/*.xdmf > /dev/null 2>&1; then
  ls "$out.partial"/*_failed.xdmf "$out.partial"/*_failed.h5 > /dev/null 2>&1 || fail "no <basename>_failed.xdmf/.h5 in $out.partial"
  grep -q "^  the failed step's last iterate (t = .*) is in .*_failed.xdmf" log.txt || fail "the log does not name the failed-state file"
fi
for c in "$out.partial"/*.csv; do
  tail -n +2 "$c" | grep -qi -e nan -e inf && fail "$c holds nan or inf"
done
py=""
for p in /usr/bin/python3 python3; do
  "$p" -c "import h5py, numpy" 2> /dev/null && { py=$p; break; }
done
if ls "$out.partial"/*.h5 > /dev/null 2>&1; then
  if [ -n "$py" ]; then
    "$py" - "$out.partial"/*.h5 <<'PY' || fail "an HDF5 file in $out.partial holds nan or inf"
import sys, h5py, numpy
bad, n = [], 0
def visit(name, obj):
    global n
    if isinstance(obj, h5py.Dataset) and obj.dtype.kind in "fc":
        n += 1
        if not numpy.all(numpy.isfinite(obj[()])):
            bad.append(f"{f.filename}:/{name}")
for path in sys.argv[1:]:
    with h5py.File(path, "r") as f:
        f.visititems(visit)
print(f"HDF5: {n} datasets in {len(sys.argv) - 1} file(s), non-finite in: {bad or 'none'}")
sys.exit(1 if bad else 0)
PY
  else
    echo "NOTE: no python3 with h5py: the HDF5 files were not scanned"
  fi
fi
echo "PASS"
