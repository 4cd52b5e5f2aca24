#!/usr/bin/env bash
# A generated stent's metrics (Output->Stent Metrics, docs/stent.md "Stent metrics") on
# 1 and 2 MPI ranks: inputs/s6_ring_quarter.xml shortened to its first 4 steps (t <= 0.1,
# the cylinder in contact, the crowns yielding) by sed; every column of
# <basename>_metrics.csv agrees to TOL relative to the column's largest magnitude, step and
# stage exactly. Not compared: where the largest plastic strain is (eps_p_max_ring, _crown,
# _x, _y, _z): the quarter's crowns 1 and 3 are mirror images, their strains equal to
# round-off, and which is the larger may change with the partition (its value is compared).
# With SECTOR = period the same ring as its one-strut sector (sector = period, the plane
# x = 0 replaced by the oblique plane theta = 22.5 deg held with components = normal): the
# plane constraints' rows and reactions split between ranks. With SECTOR = s7 the deck
# tests/cli/decks/s7_short.xml as it is (the strut expanded into the layered artery): the
# artery's metrics too (lumen diameters, the layers' stresses and percentiles).
# usage: metrics_mpi.sh STENTOR MPIEXEC NPFLAG WORKDIR TOL [SECTOR]
set -u
. "$(dirname "$0")/lib.sh"
stentor=$1 mpiexec=$2 npflag=$3 work=$4 tol=$5 sector=${6:-quarter}
here=$(cd "$(dirname "$0")" && pwd)
rm -rf "$work" && mkdir -p "$work" && cd "$work" || fail "cannot make $work"
base=s6_ring_quarter
if [ "$sector" = s7 ]; then
  base=s7_short
  cp "$here/decks/s7_short.xml" deck.xml || fail "no deck"
else
  sed -e 's|"end time" type="double" value="1.0"|"end time" type="double" value="0.1"|' \
      -e 's|"steps" type="int" value="40"|"steps" type="int" value="4"|' \
      "$here/../../inputs/s6_ring_quarter.xml" > deck.xml || fail "sed"
  grep -q 'value="0.1"/>' deck.xml || fail "the deck's end time was not edited"
fi
if [ "$sector" = period ]; then
  sed -i -e 's|name="sector" type="string" value="quarter"|name="sector" type="string" value="period"|' \
         -e 's|value="symmetry_x"|value="symmetry_sector"|' \
         -e 's|"components" type="string" value="x"|"components" type="string" value="normal"|' deck.xml || fail "sed"
  grep -q 'value="normal"' deck.xml || fail "the deck's plane was not edited"
fi
flags=$(mpi_flags "$mpiexec")
for np in 1 2; do
  # shellcheck disable=SC2086
  OMP_NUM_THREADS=1 "$mpiexec" $npflag "$np" $flags "$stentor" --output "out$np" deck.xml > "log$np.txt" 2>&1 \
    || { cat "log$np.txt"; fail "$np rank(s): exit status $?"; }
  [ -s "out$np/${base}_metrics.csv" ] || fail "$np rank(s): no metrics CSV"
  grep -q "radial recoil" "log$np.txt" || fail "$np rank(s): no metrics table in the log"
done
awk -F, -v tol="$tol" '
  function abs(x) { return x < 0 ? -x : x }
  FNR == 1 { if (NR == 1) { nc = NF; for (i = 1; i <= NF; ++i) h[i] = $i } else if ($0 != hdr) { print "header differs"; bad = 1 }
             hdr = $0; next }
  NR == FNR { nr = FNR; for (i = 1; i <= NF; ++i) { a[FNR, i] = $i; if (abs($i) > s[i]) s[i] = abs($i) } next }
  { nb = FNR; for (i = 1; i <= NF; ++i) b[FNR, i] = $i }
  END {
    if (nb != nr || nr < 5) { print "rows: " nb " vs " nr; exit 1 }
    worst = 0
    for (r = 2; r <= nr; ++r) for (i = 1; i <= nc; ++i) {
      d = abs(a[r, i] - b[r, i])
      if (h[i] ~ /^eps_p_max_/) continue
      if (h[i] == "step" || h[i] == "stage") { if (d != 0) { print h[i] " row " r ": " a[r, i] " vs " b[r, i]; bad = 1 } continue }
      rel = s[i] > 0 ? d / s[i] : d
      if (rel > worst) { worst = rel; where = h[i] " (row " r ")" }
    }
    printf "2 ranks vs 1: %d rows x %d columns, max relative difference %.3e at %s\n", nr - 1, nc, worst, where
    if (worst > tol) { print "exceeds " tol; bad = 1 }
    exit bad
  }' out1/${base}_metrics.csv out2/${base}_metrics.csv || fail "metrics differ"
echo "PASS"
