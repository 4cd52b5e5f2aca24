# Shared by perf/scaling/strong.sh and weak.sh (sourced). Runs perf/bench_assembly on
# R MPI ranks x T OpenMP threads and turns its rows into one line of the scaling CSV.
#
# Environment: BUILD (build folder with perf/bench_assembly; default build-openmp if it
# exists, else build), DECK (default perf/decks/cube_p1.xml), NEWTON (Newton iterations
# timed per case, default 3), STEPS (load steps of the deck; the timed Newton solve is the
# first, so 50 steps make it a mild 0.4% stretch whose tangents are alike on every mesh,
# where the deck's 4 steps distort the boundary layer of fine meshes and Newton needs line
# search), REPEAT (assembly calls timed, default 3), MPIEXEC (mpirun).
set -uo pipefail
scaling_dir=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
root=$(cd "$scaling_dir/../.." && pwd)
if [ -z "${BUILD:-}" ]; then
  BUILD=$root/build
  [ -x "$root/build-openmp/perf/bench_assembly" ] && BUILD=$root/build-openmp
fi
BENCH=$BUILD/perf/bench_assembly
DECK=${DECK:-$root/perf/decks/cube_p1.xml}
NEWTON=${NEWTON:-3}
STEPS=${STEPS:-50}
REPEAT=${REPEAT:-3}
MPIEXEC=${MPIEXEC:-mpirun}
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
[ -x "$BENCH" ] || { echo "scaling: $BENCH not found (build the project first)" >&2; exit 2; }

# Cores of this machine (not `nproc`: it follows OMP_NUM_THREADS, which launch() sets).
CORES=$(getconf _NPROCESSORS_ONLN)
CSV_HEADER="study,ranks,threads,h,dofs,preconditioner,assembly,backend,assembly_call_s,newton_iterations,gmres_iterations,gmres_per_newton,assembly_per_newton_s,setup_per_newton_s,solve_per_newton_s,newton_step_s,converged"

# launch R T CMD...: R ranks with T threads each. Where R*T fits the cores, each rank gets
# T cores of its own (--map-by slot:PE=T) and its threads are pinned inside them
# (OMP_PROC_BIND=spread, OMP_PLACES=threads); where it does not (an oversubscribed small
# machine), nothing is bound (--bind-to none), as binding would stack threads on one core.
launch() {
  local R=$1 T=$2
  shift 2
  local bind
  if [ $((R * T)) -gt "$CORES" ]; then
    # Threads that find no work sleep (passive) instead of spinning on a core another
    # process needs.
    bind="--oversubscribe --bind-to none"
    export OMP_PROC_BIND=false OMP_WAIT_POLICY=passive
    unset OMP_PLACES
  else
    # Each thread owns its core: spinning between kernels (active) is what makes short
    # kernels (SpMV, vector updates) pay off.
    bind="--map-by slot:PE=$T --bind-to core"
    export OMP_PROC_BIND=spread OMP_PLACES=threads OMP_WAIT_POLICY=active
  fi
  export OMP_NUM_THREADS=$T
  # shellcheck disable=SC2086
  "$MPIEXEC" -np "$R" $bind -x OMP_NUM_THREADS -x OMP_PROC_BIND -x OMP_WAIT_POLICY \
    ${OMP_PLACES:+-x OMP_PLACES} "$@"
}

# run_case STUDY R T H PRECONDITIONER ASSEMBLY OUTCSV LOGDIR
run_case() {
  local study=$1 R=$2 T=$3 h=$4 prec=$5 asm=$6 out=$7 logs=$8
  local tmp log
  tmp=$(mktemp)
  log=$logs/${study}_r${R}_t${T}_h${h}_${prec}_${asm}.log
  mkdir -p "$logs"
  echo "== $study: $R rank(s) x $T thread(s), h = $h, $prec, $asm assembly"
  launch "$R" "$T" "$BENCH" "$DECK" --size "$h" --repeat "$REPEAT" --newton-iterations "$NEWTON" --steps "$STEPS" \
    --preconditioner "$prec" --assembly "$asm" --csv "$tmp" > "$log" 2>&1
  local rc=$?
  grep -E "mesh|parallel|newton +[0-9]|residual\+tangent " "$log" | sed 's/^/   /'
  if [ $rc -ne 0 ]; then
    echo "   FAILED (exit $rc), see $log"
    rm -f "$tmp"
    return 1
  fi
  local backend
  backend=$(sed -n 's/.*MPI rank(s) x [0-9]* \([A-Za-z]*\) thread(s).*/\1/p' "$log" | head -n1)
  awk -F, -v study="$study" -v R="$R" -v T="$T" -v h="$h" -v prec="$prec" -v asm="$asm" -v backend="$backend" '
    NR > 1 { dofs = $4; sec[$7] = $8; cnt[$7] = $10 }
    END {
      its = 0; conv = 0
      for (k in sec) if (k ~ /^newton_total/) { its = cnt[k]; conv = (k == "newton_total" || k == "newton_total(capped)") }
      n = its > 0 ? its : 1
      a = sec["newton_assembly"] / n; s = sec["newton_prec_setup"] / n; l = sec["newton_linear_solve"] / n
      printf "%s,%d,%d,%s,%d,%s,%s,%s,%.6g,%d,%d,%.4g,%.6g,%.6g,%.6g,%.6g,%d\n", study, R, T, h, dofs, prec, asm, backend,
             sec["residual+tangent"], its, cnt["newton_linear_solve"], cnt["newton_linear_solve"] / n, a, s, l, a + s + l, conv
    }' "$tmp" >> "$out"
  tail -n1 "$out" | sed 's/^/   -> /'
  rm -f "$tmp"
}

# plot CSV PNG TITLE XLABEL XEXPR: time per Newton step (stacked: assembly, preconditioner
# setup, solve) and GMRES iterations per Newton step, one bar group per CSV row.
plot() {
  local csv=$1 png=$2 title=$3
  command -v gnuplot > /dev/null || { echo "gnuplot not found: $png not drawn"; return 0; }
  gnuplot <<GP
set terminal pngcairo size 1200,600 font ",10" noenhanced
set bmargin 10
set output "$png"
set datafile separator ","
set multiplot layout 1,2 title "$title"
set style data histograms
set style histogram rowstacked
set style fill solid 0.8 border -1
set boxwidth 0.7
set xtics rotate by -35
set key above
set ylabel "seconds per Newton iteration"
set title "time per Newton iteration"
plot "$csv" every ::1 using 13:xtic(sprintf("%s %s %dx%d %s", stringcolumn(6), stringcolumn(7), column(2), column(3), stringcolumn(5))) title "assembly", \
     "" every ::1 using 14 title "preconditioner setup", \
     "" every ::1 using 15 title "linear solve"
set style histogram clustered
set yrange [0:*]
set ylabel "GMRES iterations per Newton iteration"
set title "iterations"
set key above
plot "$csv" every ::1 using 12:xtic(sprintf("%s %s %dx%d %s", stringcolumn(6), stringcolumn(7), column(2), column(3), stringcolumn(5))) title "GMRES / Newton"
unset multiplot
GP
  echo "wrote $png"
}
