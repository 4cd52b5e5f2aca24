#!/usr/bin/env bash
# Time to solution of the whole 4-step cube stretch (perf/decks/cube_p1.xml, cube_p2.xml:
# uniaxial 20%, Ciarlet-Geymonat rubber, symmetry constraints) and of the dynamic contact
# case (perf/decks/s2_torus_dynamic.xml: S2 through its first impact) with the
# Newton/linear solver variants of issue 14, on any number of ranks. One stentor run per row; prints a
# Markdown table (wall, CPU, peak memory per rank, Newton and GMRES iterations, linear
# set-up and solve time, final reaction of the pulled face) and keeps the logs.
#
#   perf/solve/time_to_solution.sh                              # P1 h=0.05, P2 h=0.1 (~24k DOF)
#   CASES="cube_p2:0.064" RANKS="1 2" perf/solve/time_to_solution.sh   # ~80k DOF P2
#   VARIANTS="base:predictor=none" perf/solve/time_to_solution.sh
#
# Environment: CASES ("deck:h" list), RANKS ("1"), VARIANTS (name:key=value,... with keys
# predictor (Stepping), forcing (Newton), reuse (Linear Solver->preconditioner reuse),
# rebuild (Linear Solver->preconditioner rebuild cost), onchange (Linear Solver->
# preconditioner rebuild on contact change, true|false),
# preconditioner (Linear Solver), smoother (Linear Solver->MueLu->smoother: type), fields
# (Output->fields, true|false)), BUILD (default build), OUT (default /tmp/stentor-tts),
# MPIFLAGS (mpirun options; default: --bind-to core where the ranks fit the cores, as
# docs/deck.md advises and Open MPI does at up to 2 ranks, else --bind-to none; on a
# machine shared with other jobs set MPIFLAGS="--bind-to none"), PY (a python3 with the
# standard library), FEBIO (the FEBio 4 executable; default: febio4 on the PATH).
#
# FEBio, the yardstick: where FEBIO is found, each cube case (cube_p1, cube_p2)
# is also written as an FEBio 4 input from the same gmsh mesh (perf/solve/feb.py: .feb,
# gmsh on the PATH) and run with FEBio on as many OpenMP threads as each row of RANKS has
# ranks (OMP_NUM_THREADS = MKL_NUM_THREADS = r), twice: at FEBio's default convergence
# tests (row "FEBio, tol. default": dtol 0.001, etol 0.01, looser than Stentor's) and at
# Stentor's (row "FEBio, tol. rtol=1e-20": the residual test |R| <= 1e-10 |R0| alone, feb.py
# --tolerances stentor). Rows in the same table, with FEBio's equilibrium iterations as
# Newton, "direct" for its default linear solver (PARDISO), its "time in linear solver" as
# lin. solve, and the sum of Rx over the pulled face's nodes at the last step (10 digits).
# Without FEBio one line says so and only Stentor runs.
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
BUILD=$(cd "${BUILD:-$root/build}" && pwd)
STENTOR=$BUILD/stentor
CASES=${CASES:-"cube_p1:0.05 cube_p2:0.1"}
RANKS=${RANKS:-1}
VARIANTS=${VARIANTS:-"before:predictor=none default:predictor=auto ew:forcing=eisenstat-walker ew+reuse:forcing=eisenstat-walker,reuse=5"}
OUT=${OUT:-/tmp/stentor-tts}
PY=${PY:-/usr/bin/python3}
MPIFLAGS=${MPIFLAGS:-}
FEBIO=${FEBIO:-febio4}
febio=$(command -v "$FEBIO" 2>/dev/null || true)
ncores=$(getconf _NPROCESSORS_ONLN)
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1
[ -x "$STENTOR" ] || { echo "time_to_solution: $STENTOR not found (build first, or set BUILD)" >&2; exit 2; }
mkdir -p "$OUT"
echo "machine: $(getconf _NPROCESSORS_ONLN) cores, load $(cut -d' ' -f1-3 /proc/loadavg), $(git -C "$root" rev-parse --short HEAD 2>/dev/null || echo "no git")"
[ -n "$febio" ] || echo "FEBio: '$FEBIO' not found (set FEBIO to the FEBio 4 executable for its rows): Stentor only"
echo "| case | DOF | ranks | variant | Newton | GMRES | wall [s] | CPU [s] | lin. set-up [s] | lin. solve [s] | peak RSS/rank [MB] | reaction x [N] |"
echo "|---|---|---|---|---|---|---|---|---|---|---|---|"
for c in $CASES; do
  deck=${c%%:*} h=${c#*:}
  for v in $VARIANTS; do
    name=${v%%:*} opts=${v#*:}
    for r in $RANKS; do
      tag=${deck}_h${h}_${name}_np${r}
      xml=$OUT/$tag.xml
      # The deck with Mesh->size, basename and the variant's parameters set (perf/solve/solvelib.py).
      sets=(--set "Mesh/size=double:$h" --set "Output/basename=string:$tag")
      for kv in ${opts//,/ }; do
        k=${kv%%=*} val=${kv#*=}
        case $k in
          predictor) sets+=(--set "Stepping/predictor=string:$val") ;;
          forcing) sets+=(--set "Newton/forcing=string:$val") ;;
          reuse) sets+=(--set "Linear Solver/preconditioner reuse=int:$val") ;;
          rebuild) sets+=(--set "Linear Solver/preconditioner rebuild cost=double:$val") ;;
          onchange) sets+=(--set "Linear Solver/preconditioner rebuild on contact change=bool:$val") ;;
          preconditioner) sets+=(--set "Linear Solver/preconditioner=string:$val") ;;
          smoother) sets+=(--set "Linear Solver/MueLu/smoother: type=string:$val") ;;
          fields) sets+=(--set "Output/fields=bool:$val") ;;
          *) echo "time_to_solution: unknown variant key '$k'" >&2; exit 2 ;;
        esac
      done
      # the default preconditioner (auto) unless a variant sets it
      $PY "$root/perf/solve/solvelib.py" deck "$root/perf/decks/$deck.xml" "$xml" --remove "Linear Solver/preconditioner" "${sets[@]}"
      log=$OUT/$tag.log
      flags=$MPIFLAGS
      if [ -z "$flags" ]; then if [ "$r" -le "$ncores" ]; then flags="--bind-to core"; else flags="--bind-to none"; fi; fi
      (cd "$OUT" && /usr/bin/time -f "TIME %e %U %S %M" mpirun -np "$r" $flags "$STENTOR" "$xml") >"$log" 2>&1 || true
      $PY "$root/perf/solve/solvelib.py" parse "$log" --history "$OUT/results/$tag/${tag}_history.csv" --column reaction_pull_x \
        --label "deck=$deck" --label "h=$h" --label "r=$r" --label "name=$name" \
        --row "| {deck} h={h} | {dofs} | {r} | {name} | {newton} | {linear} | {wall} | {cpu} | {setup} | {solve} | {rss} | {column} |"
    done
  done
  # FEBio on the same mesh and problem (perf/solve/feb.py), r threads for each r of RANKS,
  # once at FEBio's default tolerances and once at Stentor's (feb.py --tolerances).
  if [ -n "$febio" ] && [[ $deck == cube_p* ]]; then
    for ftol in default stentor; do
      ftag=${deck}_h${h}_febio
      [ "$ftol" = stentor ] && ftag=${ftag}_tight
      if $PY "$root/perf/solve/feb.py" write "$root/perf/decks/$deck.xml" "$OUT/$ftag.feb" --size "$h" \
           --tolerances "$ftol" >"$OUT/$ftag.write.log" 2>&1; then
        for r in $RANKS; do
          dir=$OUT/${ftag}_t$r log=$OUT/${ftag}_t$r.log
          rm -rf "$dir" && mkdir -p "$dir" && cp "$OUT/$ftag.feb" "$dir/"
          (cd "$dir" && OMP_NUM_THREADS=$r MKL_NUM_THREADS=$r /usr/bin/time -f "TIME %e %U %S %M" \
            "$febio" -i "$ftag.feb" -o "$ftag.log" -nosplash </dev/null) >"$log" 2>&1 || true
          $PY "$root/perf/solve/feb.py" parse "$dir/$ftag.feb" "$log" --label "deck=$deck" --label "h=$h" --label "r=$r" \
            --row "| {deck} h={h} | {dofs} | {r} | FEBio, tol. {tol} | {newton} | {linear} | {wall} | {cpu} | {setup} | {solve} | {rss} | {column} |"
        done
      else
        echo "| $deck h=$h | ? | - | FEBio ($ftol tol.) | .feb not written: $(tail -n 1 "$OUT/$ftag.write.log") | | | | | | | |"
      fi
    done
  fi
done
