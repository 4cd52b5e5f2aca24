#!/usr/bin/env bash
# Scene S2 in dynamics, Stentor against FEBio 4 on the same gmsh mesh: the hyperelastic torus of
# inputs/s2_torus.xml (inputs/torus.geo) thrown at v0 = (1, 0, -4) m/s at the rigid plane z = 0,
# frictionless, tet4, Ciarlet-Geymonat (the same W in both codes), N equal steps to T
# (default 40 steps of 2 ms: the first impact, 12-54 ms, and the flight after it);
# perf/contact/s2_torus.py says what is written and measured.
# For each mesh size h and core count: Stentor (Gonzalez energy-consistent midpoint, the
# persistence condition against the analytic plane, exact active-set constraint; direct
# solver) on r MPI ranks, and FEBio (DYNAMIC, Newmark beta = 1/4, gamma = 1/2; a rigid-body
# slab as the floor, sliding-node-on-facet by default, augmented Lagrangian) on r
# OpenMP/MKL threads. Prints one Markdown table against Stentor on 1 core (per h): peak
# contact force and its time, contact interval (lift-off), centre-of-mass velocity and
# height after, the largest differences of the force history and of the centre of mass,
# penetration, energy drift, Newton iterations, wall time; then the force and energy
# histories of the 1-core runs of the first h.
#
#   perf/contact/s2_torus.sh                          # h 0.12, 1 and 2 cores
#   perf/contact/s2_torus.sh -s "0.12 0.08" -r 1 -o /tmp/s2b
#
# Options: -s "H ..."  Mesh->size (default 0.12: 1100 nodes, 3767 tet4);
#          -r "R ..."  cores: Stentor's MPI ranks, FEBio's threads (default "1 2");
#          -c "C ..."  FEBio contact types (default sliding-node-on-facet; also
#                      sliding-elastic, sliding-facet-on-facet);
#          -f FEBIO    the FEBio 4 executable (default /tmp/febio-build/bin/febio4); without it
#                      Stentor runs alone and the script says so;
#          -o DIR      work folder (default /tmp/s2_torus), emptied per h;
#          -n STEPS    steps (default 40); -T END end time (default 0.08 s).
# Environment: STENTOR (default build/stentor of this checkout), PY (default /usr/bin/python3,
# with h5py and numpy), NICE (default "nice -n 5"), MPIFLAGS (default "--bind-to none"),
# SOLVER (Stentor's Linear Solver->method, default direct), FORMULATION (Stentor's contact
# condition: persistence, the default, or gap), FEBIO_PENALTY (auto_penalty factor, default
# 100), FEBIO_ATOL (augmentation tolerance, default 1e-2), FEBIO_MAXAUG (default 50),
# FEBIO_SYMM (default non-symmetric), FEBIO_NEWTON (strict: |R| <= 1e-10 |R0| alone, the
# default; default: FEBio's dtol 0.001, etol 0.01, no residual test), FEBIO_RULE (TET4G4,
# the default: consistent mass as Stentor's; tet4: FEBio's default 1-point rule, whose mass
# matrix is not the consistent one), EVERY (rows of the history table: every K-th step of the contact, 1).
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
SIZES="0.12" RANKS="1 2" CONTACTS="sliding-node-on-facet" FEBIO=/tmp/febio-build/bin/febio4 OUT=/tmp/s2_torus STEPS=40 END=0.08
while getopts "s:r:c:f:o:n:T:h" opt; do
  case $opt in
    s) SIZES=$OPTARG ;; r) RANKS=$OPTARG ;; c) CONTACTS=$OPTARG ;; f) FEBIO=$OPTARG ;; o) OUT=$OPTARG ;;
    n) STEPS=$OPTARG ;; T) END=$OPTARG ;;
    *) sed -n '2,/^set -euo/p' "$0" | sed '$d'; exit 2 ;;
  esac
done
STENTOR=${STENTOR:-$root/build/stentor}
PY=${PY:-/usr/bin/python3}
NICE=${NICE:-nice -n 5}
MPIFLAGS=${MPIFLAGS:---bind-to none}
SOLVER=${SOLVER:-direct}
FORM=${FORMULATION:-persistence}
FP=${FEBIO_PENALTY:-100} FA=${FEBIO_ATOL:-1e-2} FM=${FEBIO_MAXAUG:-50} FS=${FEBIO_SYMM:-non-symmetric}
FN=${FEBIO_NEWTON:-strict} FR=${FEBIO_RULE:-TET4G4} EVERY=${EVERY:-1}
H="$PY $root/perf/contact/s2_torus.py"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
[ -x "$STENTOR" ] || { echo "s2_torus: $STENTOR not found (build first, or set STENTOR)" >&2; exit 2; }
febio=""
if [ -x "$FEBIO" ]; then febio=$FEBIO; fi
mkdir -p "$OUT"
echo "machine: $(getconf _NPROCESSORS_ONLN) cores, load $(cut -d' ' -f1-3 /proc/loadavg) at start; $(git -C "$root" rev-parse --short HEAD 2>/dev/null || echo "no git"); $STEPS steps to t = $END s"
[ -n "$febio" ] || echo "FEBio: '$FEBIO' not found (-f): Stentor only"
echo
echo "Stentor: Gonzalez, plane obstacle, exact (active set), $FORM; Newton defaults (dynamic: |r| <= 1e-12 ref); $SOLVER"
if [ "$FN" = strict ]; then fnewton="rtol 1e-20 (|R| <= 1e-10 |R0|), dtol = etol = 0"; else fnewton="FEBio's default tests (dtol 0.001, etol 0.01, rtol 0)"; fi
[ -z "$febio" ] || echo "FEBio:   DYNAMIC, Newmark beta 0.25, gamma 0.5 (rhoi -2, alpha 1); rigid-body slab; AUGLAG, auto_penalty x $FP, tolerance $FA, maxaug $FM, $FS; full Newton, $fnewton; $FR"
hist=() hlabels=()
for h in $SIZES; do
  case_dir=$OUT/h$h
  rm -rf "$case_dir" && mkdir -p "$case_dir"
  cp "$root/inputs/torus.geo" "$case_dir/"
  $H deck "$case_dir/s2.xml" --geo torus.geo --size "$h" --steps "$STEPS" --end "$END" --solver "$SOLVER" --formulation "$FORM"
  $H feb "$case_dir/s2.feb" --geo "$case_dir/torus.geo" --size "$h" --steps "$STEPS" --end "$END" > "$case_dir/feb.log"
  runs=() labels=()
  for r in $RANKS; do
    res=$case_dir/stentor_np$r log=$case_dir/stentor_np$r.log
    if [ "$r" = 1 ]; then run=("$STENTOR"); else run=(mpirun --allow-run-as-root --oversubscribe -np "$r" $MPIFLAGS "$STENTOR"); fi
    (cd "$case_dir" && /usr/bin/time -f "TIME %e %U %S %M" $NICE "${run[@]}" --output "$res" s2.xml) >"$log" 2>&1 || true
    $H stentor "$res" "$log" "$res.json" --geo "$case_dir/s2.json" || true
    runs+=("$res.json") labels+=("--label" "$h | Stentor | $r | plane obstacle (exact), $FORM")
  done
  h5=$(ls "$case_dir"/stentor_np*/s2.h5 2>/dev/null | head -1 || true)
  mesh_check=$([ -n "$h5" ] && $H same-mesh "$h5" "$case_dir/s2.json" || echo "not checked")
  if [ -n "$febio" ]; then
    for c in $CONTACTS; do
      cdir=$case_dir/$c
      mkdir -p "$cdir"
      $H feb "$cdir/s2.feb" --geo "$case_dir/torus.geo" --size "$h" --steps "$STEPS" --end "$END" --contact "$c" \
        --penalty "$FP" --atol "$FA" --maxaug "$FM" --symmetric "$FS" --tolerances "$FN" --rule "$FR" > "$cdir/feb.log"
      for r in $RANKS; do
        dir=$cdir/febio_t$r log=$cdir/febio_t$r.screen
        mkdir -p "$dir" && cp "$cdir/s2.feb" "$cdir/s2.json" "$dir/"
        (cd "$dir" && OMP_NUM_THREADS=$r MKL_NUM_THREADS=$r /usr/bin/time -f "TIME %e %U %S %M" \
          $NICE "$febio" -i s2.feb -o s2.log -silent </dev/null) >"$log" 2>&1 || true
        $H febio "$dir" "$log" "$dir.json" --geo "$cdir/s2.json" || true
        runs+=("$dir.json") labels+=("--label" "$h | FEBio | $r | $c")
      done
    done
  fi
  nodes=$(sed -n 's/.*: \([0-9]*\) nodes, \([0-9]*\) tet4.*/\1 nodes, \2 tet4/p' "$case_dir/feb.log")
  echo
  echo "h = $h: $nodes; Stentor's mesh (HDF5) against the .feb's: $mesh_check"
  echo
  echo "| h | code | cores | contact | Newton (aug.) | wall [s] | F own [kN] | F step [kN] | F 2-step [kN] | t peak [ms] | contact [ms] | v_c,z after [m/s] | z_c(T) [m] | dF / F peak | dz_c [m] | penetration [m] | E drift | E(T)/E0 - 1 |"
  echo "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"
  $H table "$case_dir/stentor_np1.json" "${runs[@]}" "${labels[@]}" \
    --row "| {label} | {naug} | {wall} | {Fown} | {Fpeak} | {F2peak} | {tpeak} | {on} | {vz} | {zc} | {dF} | {dz} | {gap} | {Ed} | {Ee} |"
  if [ ${#hist[@]} = 0 ]; then
    hist=("$case_dir/stentor_np1.json") hlabels=(--label "Stentor")
    for c in $CONTACTS; do [ -z "$febio" ] || { hist+=("$case_dir/$c/febio_t1.json"); hlabels+=(--label "FEBio $c"); }; done
  fi
done
echo
echo "F step: the step's contact force from the momentum change, (p_z,n+1 - p_z,n) / dt; F 2-step: its mean over two"
echo "consecutive steps; F own: the code's own force (Stentor: contact_floor_force_z; FEBio: the floor's Fz at the step end);"
echo "dF, dz_c: against Stentor on 1 core; E: K + W from the nodal fields, same formula for both codes."
echo
echo "Histories (first h, 1 core): F step (kN) at the step's mid-time, E/E0 - 1 at its end:"
echo
$H curves "${hist[@]}" "${hlabels[@]}" --every "$EVERY" || true
