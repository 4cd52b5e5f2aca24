#!/usr/bin/env bash
# 3D Hertz contact, Stentor against FEBio 4 on the same gmsh mesh: a quarter of the lower half
# of an elastic sphere (R = 1, E = 1, nu = 0.3, Ciarlet-Geymonat) pressed onto a rigid plane by
# moving its equator down by delta (perf/contact/hertz3d.py says what is written and measured).
# For each mesh size hc (element size at the contact, graded to Mesh->size 0.15 away from it)
# and each core count: Stentor (rigid plane obstacle, exact active-set constraint, static,
# gap condition) on r MPI ranks, and FEBio (sliding-elastic against a block whose nodes are
# all fixed, augmented Lagrangian) on r OpenMP/MKL threads. Prints one Markdown table: total
# force against Hertz at the prescribed delta, contact radius and peak pressure against Hertz
# at the run's own force, Newton iterations, wall time.
#
#   perf/contact/hertz3d.sh                                  # hc 0.02 0.01 0.005, 1 and 2 cores
#   perf/contact/hertz3d.sh -s "0.02 0.01" -r 1 -f /tmp/febio-build/bin/febio4 -o /tmp/hz3
#
# Options: -s "HC ..." mesh sizes at the contact (default "0.02 0.01 0.005");
#          -r "R ..."  cores: Stentor's MPI ranks, FEBio's threads (default "1 2");
#          -f FEBIO    the FEBio 4 executable (default /tmp/febio-build/bin/febio4; built by
#                      /work/shared/tools/febio/build.sh); without it Stentor runs alone and
#                      the script says so;
#          -o DIR      work folder (default /tmp/hertz3d), emptied per case;
#          -d DELTA    the equator's displacement (default 5e-3: Hertz a = 0.071 R).
# Environment: STENTOR (default build/stentor of this checkout), PY (default /usr/bin/python3,
# with h5py), NICE (default "nice -n 5": leave priority to others on a shared machine),
# MPIFLAGS (default "--bind-to none"), SOLVER (Stentor's Linear Solver->method: gmres, the
# default, with MueLu; or direct), FEBIO_PENALTY (auto_penalty factor, default 100), FEBIO_ATOL (augmentation tolerance
# on the multipliers, default 1e-2), FEBIO_GAPTOL (default 0: off), FEBIO_MAXAUG (default 50),
# FEBIO_SYMM (symmetric | non-symmetric, default non-symmetric, as FEBio advises for sliding-elastic), STEPS (load steps, default 2).
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
SIZES="0.02 0.01 0.005" RANKS="1 2" FEBIO=/tmp/febio-build/bin/febio4 OUT=/tmp/hertz3d DELTA=5e-3
while getopts "s:r:f:o:d:h" opt; do
  case $opt in
    s) SIZES=$OPTARG ;; r) RANKS=$OPTARG ;; f) FEBIO=$OPTARG ;; o) OUT=$OPTARG ;; d) DELTA=$OPTARG ;;
    *) sed -n '2,/^set -euo/p' "$0" | sed '$d'; exit 2 ;;
  esac
done
STENTOR=${STENTOR:-$root/build/stentor}
PY=${PY:-/usr/bin/python3}
NICE=${NICE:-nice -n 5}
MPIFLAGS=${MPIFLAGS:---bind-to none}
SOLVER=${SOLVER:-gmres}
STEPS=${STEPS:-2}
FP=${FEBIO_PENALTY:-100} FA=${FEBIO_ATOL:-1e-2} FG=${FEBIO_GAPTOL:-0} FM=${FEBIO_MAXAUG:-50} FS=${FEBIO_SYMM:-non-symmetric}
H="$PY $root/perf/contact/hertz3d.py"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
[ -x "$STENTOR" ] || { echo "hertz3d: $STENTOR not found (build first, or set STENTOR)" >&2; exit 2; }
febio=""
if [ -x "$FEBIO" ]; then febio=$FEBIO; fi
mkdir -p "$OUT"
echo "machine: $(getconf _NPROCESSORS_ONLN) cores, load $(cut -d' ' -f1-3 /proc/loadavg) at start; $(git -C "$root" rev-parse --short HEAD 2>/dev/null || echo "no git"); delta = $DELTA, R = 1, E = 1, nu = 0.3, $STEPS load steps"
[ -n "$febio" ] || echo "FEBio: '$FEBIO' not found (-f): Stentor only"
S_SET="plane obstacle, exact (active set), gap; Newton rtol 1e-10 (default); $SOLVER"
F_SET="sliding-elastic vs fixed block, AUGLAG, auto_penalty x $FP, tolerance $FA, gaptol $FG, maxaug $FM, $FS; full Newton, rtol 1e-20 (|R| <= 1e-10 |R0|), dtol = etol = 0"
echo
echo "Stentor: $S_SET"
[ -z "$febio" ] || echo "FEBio:   $F_SET"
echo
echo "| hc | nodes / tet4 | code | cores | Newton (aug.) | wall [s] | F | F/F_H(delta) - 1 | a | a/a_H(F) - 1 | p0 | p0/p0_H(F) - 1 | active |"
echo "|---|---|---|---|---|---|---|---|---|---|---|---|---|"
ROW="| {hc} | {nodes} / {cells} | {code} | {r} | {newton} | {wall} | {F} | {eF} | {a} | {ea} | {p0} | {ep} | {active} |"
FROW="| {hc} | {nodes} / {cells} | {code} | {r} | {newton} ({aug}) | {wall} | {F} | {eF} | {a} | {ea} | {p0} | {ep} | {active} |"
mesh_check=""
for hc in $SIZES; do
  case_dir=$OUT/hc$hc
  rm -rf "$case_dir" && mkdir -p "$case_dir"
  $H geo "$case_dir/hertz3d.geo" --hc "$hc" --delta "$DELTA"
  $H deck "$case_dir/hertz3d.xml" --geo hertz3d.geo --delta "$DELTA" --steps "$STEPS" --solver "$SOLVER"
  for r in $RANKS; do
    res=$case_dir/stentor_np$r log=$case_dir/stentor_np$r.log
    if [ "$r" = 1 ]; then run=("$STENTOR"); else run=(mpirun --allow-run-as-root --oversubscribe -np "$r" $MPIFLAGS "$STENTOR"); fi
    (cd "$case_dir" && /usr/bin/time -f "TIME %e %U %S %M" $NICE "${run[@]}" --output "$res" hertz3d.xml) >"$log" 2>&1 || true
    $H stentor "$res" "$log" --label "hc=$hc" --label "r=$r" --label "code=Stentor" --row "$ROW" || true
  done
  if [ -n "$febio" ]; then
    $H feb "$case_dir/hertz3d.feb" --geo "$case_dir/hertz3d.geo" --delta "$DELTA" --steps "$STEPS" \
      --penalty "$FP" --atol "$FA" --gaptol "$FG" --maxaug "$FM" --symmetric "$FS" > "$case_dir/feb.log"
    h5=$(ls "$case_dir"/stentor_np*/hertz3d.h5 2>/dev/null | head -1 || true)
    [ -z "$h5" ] || mesh_check="$mesh_check hc $hc: $($H same-mesh "$h5" "$case_dir/hertz3d.facets.json");"
    for r in $RANKS; do
      dir=$case_dir/febio_t$r log=$case_dir/febio_t$r.screen
      mkdir -p "$dir" && cp "$case_dir/hertz3d.feb" "$case_dir/hertz3d.facets.json" "$dir/"
      (cd "$dir" && OMP_NUM_THREADS=$r MKL_NUM_THREADS=$r /usr/bin/time -f "TIME %e %U %S %M" \
        $NICE "$febio" -i hertz3d.feb -o hertz3d.log -silent </dev/null) >"$log" 2>&1 || true
      $H febio "$dir" "$log" --label "hc=$hc" --label "r=$r" --label "code=FEBio" --row "$FROW" || true
    done
  fi
done
[ -z "$mesh_check" ] || { echo; echo "Stentor's mesh (HDF5) against the .feb's:$mesh_check"; }
