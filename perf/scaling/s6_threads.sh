#!/usr/bin/env bash
# Ranks x threads on the S6 stent expansion (inputs/s6_stent.xml on its one-strut sector of
# the proximal half: a rigid cylinder expands the 3 rings and is withdrawn, contact
# throughout): the same deck as 1 rank x 1 thread, 1 x 2 and 2 x 1, with GMRES and the
# additive Schwarz preconditioner (the OpenMP build of ci/build-trilinos-openmp.sh has no
# MueLu). On a 2-core machine these are the points of the ranks x threads curve; each
# run's recoil is printed so that the cases can be seen to agree.
#
#   perf/scaling/s6_threads.sh [STENTOR]      # default build-openmp/stentor
#   E=3 perf/scaling/s6_threads.sh
#
# Environment: E (elements through width and thickness, default 5), LINEAR (gmres, the
# default, or direct: KLU2, which threads nothing and gathers the matrix on one rank),
# PREC (schwarz, the default; or none), OUT (default perf/results/scaling), MPIEXEC
# (mpirun). Writes
# $OUT/s6_threads.csv. Used for docs/performance.md ("S6 stent: ranks x threads").
set -uo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
STENTOR=${1:-$root/build-openmp/stentor}
E=${E:-5}
PREC=${PREC:-schwarz}
LINEAR=${LINEAR:-gmres}
OUT=${OUT:-$root/perf/results/scaling}
MPIEXEC=${MPIEXEC:-mpirun}
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMP_WAIT_POLICY=passive
[ -x "$STENTOR" ] || { echo "s6_threads: $STENTOR not found" >&2; exit 2; }
work=$OUT/s6_threads
rm -rf "$work" && mkdir -p "$work" || exit 2
csv=$OUT/s6_threads.csv
echo "case,ranks,threads,hex8,dofs,steps,cutbacks,newton_iterations,linear_iterations,wall_s,assembly_s,linear_setup_s,linear_solve_s,recoil_stent_percent" > "$csv"

deck=$work/s6_stent.xml
sed -e "s|\"elements through width\" type=\"int\" value=\"3\"|\"elements through width\" type=\"int\" value=\"$E\"|" \
    -e "s|\"elements through thickness\" type=\"int\" value=\"3\"|\"elements through thickness\" type=\"int\" value=\"$E\"|" \
    -e "$([ "$LINEAR" = direct ] && echo 's|x|x|' || echo "s|\"method\" type=\"string\" value=\"direct\"|\"method\" type=\"string\" value=\"gmres\"/><Parameter name=\"preconditioner\" type=\"string\" value=\"$PREC\"|")" \
    -e "s|\"max iterations\" type=\"int\" value=\"30\"/>|\"max iterations\" type=\"int\" value=\"30\"/><Parameter name=\"forcing\" type=\"string\" value=\"fixed\"/>|" \
    -e "s|\"every\" type=\"int\" value=\"5\"|\"every\" type=\"int\" value=\"1000\"|" \
    "$root/inputs/s6_stent.xml" > "$deck"

run() {  # run NAME RANKS THREADS
  local name=$1 R=$2 T=$3 log=$work/$1.log
  local t0 t1
  t0=$(date +%s.%N)
  if [ "$R" -eq 1 ]; then
    OMP_NUM_THREADS=$T OMP_PROC_BIND=false "$STENTOR" --output "$work/$name" "$deck" > "$log" 2>&1
  else
    "$MPIEXEC" --oversubscribe --bind-to none -x OMP_NUM_THREADS="$T" -np "$R" "$STENTOR" --output "$work/$name" "$deck" > "$log" 2>&1
  fi
  local rc=$?
  t1=$(date +%s.%N)
  [ $rc -eq 0 ] || { echo "s6_threads: $name failed (rc $rc), see $log" >&2; tail -5 "$log" >&2; return 1; }
  grep -q "Kokkos OpenMP x $T thread" "$log" || grep -q "x $T thread" "$log" || { echo "s6_threads: $name did not run $T thread(s)" >&2; grep "parallel" "$log" >&2; return 1; }
  local cells dofs summary recoil asm setup solve
  cells=$(sed -n 's/.*(stent: \([0-9]*\) hex8).*/\1/p' "$log" | head -1)
  dofs=$(awk '$1 == "dofs" { print $2; exit }' "$log")
  summary=$(grep '^Summary:' "$log")
  asm=$(awk '$1 == "assembly" { print $2; exit }' "$log")
  setup=$(sed -n 's/.*linear set-up \([0-9.]*\) s.*/\1/p' "$log" | head -1)
  solve=$(sed -n 's/.*linear solve \([0-9.]*\) s.*/\1/p' "$log" | head -1)
  recoil=$(awk -F'|' '/metrics at the end of .release./ { f = 1 } f && $1 ~ /^ *all *$/ { gsub(/ /, "", $6); print $6; exit }' "$log")
  echo "$summary" | awk -v n="$name" -v R="$R" -v T="$T" -v c="$cells" -v d="$dofs" -v w="$(echo "$t1 - $t0" | bc)" -v r="$recoil" \
    -v a="$asm" -v su="$setup" -v so="$solve" \
    '{ gsub(",", ""); printf "%s,%s,%s,%s,%s,%s,%s,%s,%s,%.1f,%s,%s,%s,%s\n", n, R, T, c, d, $2, $4, $6, $9, w, a, su, so, r }' >> "$csv"
  tail -1 "$csv"
}

echo "S6 ranks x threads: $E x $E cells through the strut, $LINEAR$([ "$LINEAR" = direct ] || echo " + $PREC"), $(getconf _NPROCESSORS_ONLN) cores"
status=0
run r1_t1 1 1 || status=1
run r1_t2 1 2 || status=1
run r2_t1 2 1 || status=1
column -s, -t "$csv"
exit $status
