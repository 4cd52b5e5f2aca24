#!/usr/bin/env bash
# The same deck on several MPI rank counts gives the same history: every column of
# <basename>_history.csv except the iteration counts agrees with the first run to a
# relative difference below TOL. Reactions are scaled by the largest reaction,
# probe displacements by the largest probe displacement, the energy by its largest
# value, the plastic dissipation by its largest value, a fluid cavity's pressure and
# volume ratio by their largest (so components that are zero up to round-off do not
# count as relative noise; the cavity's pressure K ln(V_fluid / V) magnifies the volume's
# round-off by K). The other columns (a pressure load's value) agree to 1e-12.
# usage: mpi_consistency.sh STENTOR MPIEXEC NPFLAG WORKDIR DECK BASENAME TOL RUN...
# Each RUN is a rank count R or RxT: R MPI ranks with T OpenMP threads each
# (OMP_NUM_THREADS=T; ranks are then not bound to one core, so their threads can spread).
# A run with T > 1 also checks that the log's header reports T threads, so a
# Serial-only build cannot pass a threaded case by accident.
set -u
. "$(dirname "$0")/lib.sh"
stentor=$1 mpiexec=$2 npflag=$3 work=$4 deck=$5 base=$6 tol=$7
shift 7
rm -rf "$work" && mkdir -p "$work" && cd "$work" || fail "cannot make $work"
flags=$(mpi_flags "$mpiexec")
ref=""
status=0
for run in "$@"; do
  np=${run%%x*}
  threads=1
  [ "$run" != "$np" ] && threads=${run#*x}
  tag=$run
  echo "=== $np rank(s) x $threads thread(s)"
  bind=""
  [ "$threads" -gt 1 ] && [ -n "$flags" ] && bind="--bind-to none"
  # shellcheck disable=SC2086
  OMP_NUM_THREADS=$threads OMP_PROC_BIND=false \
    "$mpiexec" $npflag "$np" $flags $bind "$stentor" --output "out$tag" "$deck" > "log$tag.txt" 2>&1
  rc=$?
  grep -E "parallel|dofs|solver|Summary" "log$tag.txt"
  [ "$rc" -eq 0 ] || { cat "log$tag.txt"; fail "$run: exit status $rc"; }
  if [ "$threads" -gt 1 ]; then
    grep -q "x $threads thread(s)" "log$tag.txt" || fail "$run: the log header does not report $threads threads (is this an OpenMP Kokkos build?)"
  fi
  csv="out$tag/${base}_history.csv"
  [ -s "$csv" ] || fail "$csv missing"
  if [ -z "$ref" ]; then
    ref=$csv
    continue
  fi
  awk -F, -v tol="$tol" -v np="$run" '
    function abs(x) { return x < 0 ? -x : x }
    function group(name) {
      if (name ~ /^reaction_/) return "reaction"
      if (name ~ /^u_/) return "probe"
      if (name == "strain_energy") return "energy"
      if (name == "plastic_dissipation") return "plastic"
      if (name == "newton_iterations" || name == "linear_iterations") return ""
      if (name ~ /_force_[xyz]$/ || name ~ /_normal_force$/) return "contact_force"
      if (name ~ /_min_gap$/) return "gap"
      if (name in cavity) return "cavity"
      return "exact"
    }
    FNR == 1 { if (NR == 1) { nc = NF; for (i = 1; i <= NF; ++i) h[i] = $i
                              # a fluid cavity: its pressure and volume are solved for, not the deck'"'"'s
                              for (i = 1; i <= NF; ++i) if ($i ~ /^volume_ratio_/) { n = substr($i, 14); cavity["pressure_" n] = 1; cavity[$i] = 1 } }
               else if ($0 != hdr) { print "header differs"; bad = 1 }
               hdr = $0; next }
    NR == FNR { nr = FNR; for (i = 1; i <= NF; ++i) { a[FNR, i] = $i; g = group(h[i]);
                if (g != "" && abs($i) > scale[g] && !(g == "gap" && abs($i) < 1e-12)) scale[g] = abs($i) } next }
    { nb = FNR; if (NF != nc) { print "row " FNR ": " NF " columns, expected " nc; bad = 1; next }
      for (i = 1; i <= NF; ++i) b[FNR, i] = $i }
    END {
      if (nb != nr) { print "rows: " nb ", expected " nr; exit 1 }
      worst = 0
      for (r = 2; r <= nr; ++r) for (i = 1; i <= nc; ++i) {
        g = group(h[i]); if (g == "") continue
        d = abs(a[r, i] - b[r, i])
        # Gaps of touching nodes are round-off (1e-16 m on these ~1 m models), not a scale.
        if (g == "gap" && abs(a[r, i]) < 1e-12 && abs(b[r, i]) < 1e-12) continue
        if (g == "exact") { if (d > 1e-12 * abs(a[r, i])) { print "row " r " " h[i] ": " a[r, i] " vs " b[r, i]; bad = 1 } continue }
        rel = scale[g] > 0 ? d / scale[g] : d
        if (rel > worst) { worst = rel; where = h[i] " (row " r ")" }
        if (rel > maxg[g]) maxg[g] = rel
      }
      printf "%s vs reference: max relative difference %.3e at %s", np, worst, where
      for (g in maxg) printf "; %s %.3e", g, maxg[g]
      printf "\n"
      if (worst > tol) { print "exceeds " tol; bad = 1 }
      exit bad
    }' "$ref" "$csv" || status=1
  # Newton iteration counts should match too; report, do not fail (a residual right
  # at the tolerance may take one more iteration on another partition).
  cut -d, -f4 "$ref" | cmp -s - <(cut -d, -f4 "$csv") || echo "note: Newton iteration counts differ between 1st run and $run"
done
[ "$status" -eq 0 ] || fail "histories differ"
echo "PASS"
