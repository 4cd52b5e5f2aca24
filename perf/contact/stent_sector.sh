#!/usr/bin/env bash
# The S6 stent sector expanded by a cylinder, Stentor against FEBio 4 on the same hex8 mesh:
# the one-strut sector of inputs/s6_ring_sector.xml, ELASTIC (neo-Hookean, E = 196000 MPa,
# nu = 0.3: the same strain energy in both codes), standard hex8, expanded as cut (no crimp)
# by a cylinder against `inner` whose radius grows from R0 to R0 + DR in N static steps,
# frictionless (perf/contact/stent_sector.py says what is written and measured).
# Stentor (analytic cylinder obstacle, exact active-set constraint; direct solver) runs first
# on 1 rank and writes the generated mesh (Mesh->write mesh); the .feb is built from that
# .msh (same nodes, same numbering, same hex8); FEBio (a tube of hex8 whose nodes are all
# prescribed to grow radially; contact node-on-facet by default, augmented Lagrangian) on
# r OpenMP/MKL threads. Prints one Markdown table against Stentor on 1 rank: radial contact
# force of the sector at the final radius and the largest difference over the steps, outer
# diameter at the end, largest nodal displacement difference, Newton iterations, wall time.
#
#   perf/contact/stent_sector.sh                         # 1 and 2 cores, node-on-facet
#   perf/contact/stent_sector.sh -r 1 -c "sliding-node-on-facet sliding-elastic" -o /tmp/ss2
#
# Options: -r "R ..."  cores: Stentor's MPI ranks, FEBio's threads (default "1 2");
#          -c "C ..."  FEBio contact types (default sliding-node-on-facet; also
#                      sliding-facet-on-facet, sliding-elastic);
#          -f FEBIO    the FEBio 4 executable (default /tmp/febio-build/bin/febio4); without
#                      it Stentor runs alone and the script says so;
#          -o DIR      work folder (default /tmp/stent_sector), emptied;
#          -n STEPS    load steps (default 21: 0.02 mm of radius per step).
# Environment: STENTOR (default build/stentor of this checkout), PY (default /usr/bin/python3,
# with h5py), NICE (default "nice -n 5"), MPIFLAGS (default "--bind-to none"), SOLVER
# (Stentor's Linear Solver->method, default direct), R0, DR (the cylinder's radius and its
# growth, default 1.38 and 0.42 mm: the stent's inner radius is 1.4 mm), FEBIO_PENALTY
# (auto_penalty factor, default 100), FEBIO_ATOL (augmentation tolerance, default 1e-3),
# FEBIO_MAXAUG (default 50), FEBIO_SYMM (default non-symmetric), FEBIO_NEWTON (strict: the
# residual test alone, |R| <= 1e-10 |R0|, the default; default: FEBio's own dtol 0.001, etol
# 0.01, no residual test), NBALLOON (the tube's cells around, default 256).
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
RANKS="1 2" CONTACTS="sliding-node-on-facet" FEBIO=/tmp/febio-build/bin/febio4 OUT=/tmp/stent_sector STEPS=21
while getopts "r:c:f:o:n:h" opt; do
  case $opt in
    r) RANKS=$OPTARG ;; c) CONTACTS=$OPTARG ;; f) FEBIO=$OPTARG ;; o) OUT=$OPTARG ;; n) STEPS=$OPTARG ;;
    *) sed -n '2,/^set -euo/p' "$0" | sed '$d'; exit 2 ;;
  esac
done
STENTOR=${STENTOR:-$root/build/stentor}
PY=${PY:-/usr/bin/python3}
NICE=${NICE:-nice -n 5}
MPIFLAGS=${MPIFLAGS:---bind-to none}
SOLVER=${SOLVER:-direct}
R0=${R0:-1.38} DR=${DR:-0.42}
FP=${FEBIO_PENALTY:-100} FA=${FEBIO_ATOL:-1e-3} FM=${FEBIO_MAXAUG:-50} FS=${FEBIO_SYMM:-non-symmetric} FN=${FEBIO_NEWTON:-strict}
NB=${NBALLOON:-256}
H="$PY $root/perf/contact/stent_sector.py"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
[ -x "$STENTOR" ] || { echo "stent_sector: $STENTOR not found (build first, or set STENTOR)" >&2; exit 2; }
febio=""
if [ -x "$FEBIO" ]; then febio=$FEBIO; fi
rm -rf "$OUT" && mkdir -p "$OUT"
echo "machine: $(getconf _NPROCESSORS_ONLN) cores, load $(cut -d' ' -f1-3 /proc/loadavg) at start; $(git -C "$root" rev-parse --short HEAD 2>/dev/null || echo "no git"); cylinder radius $R0 -> $(awk -v a="$R0" -v b="$DR" 'BEGIN { print a + b }') mm in $STEPS steps"
[ -n "$febio" ] || echo "FEBio: '$FEBIO' not found (-f): Stentor only"
echo
echo "Stentor: cylinder obstacle, exact (active set); Newton defaults (static: |r| <= 1e-10 ref); $SOLVER"
if [ "$FN" = strict ]; then fnewton="rtol 1e-20 (|R| <= 1e-10 |R0|), dtol = etol = 0"; else fnewton="FEBio's default tests (dtol 0.001, etol 0.01, rtol 0)"; fi
[ -z "$febio" ] || echo "FEBio:   AUGLAG, auto_penalty x $FP, tolerance $FA, maxaug $FM, $FS; full Newton, $fnewton; tube of $NB hex8 around"
$H deck "$OUT/sector.xml" --r0 "$R0" --dr "$DR" --steps "$STEPS" --solver "$SOLVER"
runs=() labels=()
for r in $RANKS; do
  res=$OUT/stentor_np$r log=$OUT/stentor_np$r.log
  if [ "$r" = 1 ]; then run=("$STENTOR"); else run=(mpirun --allow-run-as-root --oversubscribe -np "$r" $MPIFLAGS "$STENTOR"); fi
  (cd "$OUT" && /usr/bin/time -f "TIME %e %U %S %M" $NICE "${run[@]}" --output "$res" sector.xml) >"$log" 2>&1 || true
  runs+=("$OUT/stentor_np$r.json") labels+=("--label" "Stentor | $r | cylinder obstacle (exact)")
done
msh=$OUT/stentor_np1/sector_mesh.msh
[ -f "$msh" ] || msh=$(ls "$OUT"/stentor_np*/sector_mesh.msh 2>/dev/null | head -1 || true)
[ -n "$msh" ] || { echo "stent_sector: Stentor wrote no mesh (see $OUT/stentor_np*.log)" >&2; exit 3; }
# the .feb's nodes and sets (sector.json) from Stentor's mesh; the measurements read them
$H feb "$OUT/sector.feb" --msh "$msh" --r0 "$R0" --dr "$DR" --steps "$STEPS" >/dev/null
for r in $RANKS; do
  $H stentor "$OUT/stentor_np$r" "$OUT/stentor_np$r.log" "$OUT/stentor_np$r.json" --geo "$OUT/sector.json" || true
done
mesh_check=$($H same-mesh "$OUT/stentor_np1/sector.h5" "$OUT/sector.json" 2>/dev/null || echo "not checked")
if [ -n "$febio" ]; then
  for c in $CONTACTS; do
    case_dir=$OUT/$c
    mkdir -p "$case_dir"
    $H feb "$case_dir/sector.feb" --msh "$msh" --r0 "$R0" --dr "$DR" --steps "$STEPS" --contact "$c" \
      --penalty "$FP" --atol "$FA" --maxaug "$FM" --symmetric "$FS" --nballoon "$NB" --tolerances "$FN" > "$case_dir/feb.log"
    for r in $RANKS; do
      dir=$case_dir/febio_t$r log=$case_dir/febio_t$r.screen
      mkdir -p "$dir" && cp "$case_dir/sector.feb" "$case_dir/sector.json" "$dir/"
      (cd "$dir" && OMP_NUM_THREADS=$r MKL_NUM_THREADS=$r /usr/bin/time -f "TIME %e %U %S %M" \
        $NICE "$febio" -i sector.feb -o sector.log -silent </dev/null) >"$log" 2>&1 || true
      $H febio "$dir" "$log" "$dir.json" --geo "$case_dir/sector.json" || true
      runs+=("$dir.json") labels+=("--label" "FEBio | $r | $c")
    done
  done
fi
echo
echo "| code | cores | contact | Newton (aug.) | wall [s] | F(R0+DR) [N] | F/F_ref - 1 | max over steps | D_out mean [mm] | D_out max [mm] | max abs(u - u_ref) [mm] | FEBio's last gap [mm] |"
echo "|---|---|---|---|---|---|---|---|---|---|---|---|"
$H table "$OUT/stentor_np1.json" "${runs[@]}" "${labels[@]}" \
  --row "| {label} | {naug} | {wall} | {F} | {dF} | {dFmax} | {D} | {Dmax} | {du} | {gap} |"
echo
echo "F: the sector's radial contact force (1/16 of the ring's); ref: Stentor on 1 rank; 'max over steps': the largest"
echo "relative difference of F against ref over the steps with F > 1 % of ref's final F; D_out: 2 r over the sector's"
echo "outer nodes at the end (plain mean and largest); Stentor's mesh (HDF5) against the .feb's: $mesh_check"
