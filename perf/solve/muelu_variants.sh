#!/usr/bin/env bash
# MueLu variants on one deck (issue 14): for each variant, a copy of DECK with
# `Linear Solver` set to GMRES + preconditioner muelu and the variant's parameters, one
# stentor run (nice, 1 thread), and a row of Newton iterations, GMRES iterations (total and
# per Newton iteration), preconditioner builds, linear set-up and solve time, wall time,
# cut-backs, linear-solver fallbacks and whether the run completed. Writes
# OUT/variants.csv (appends) and prints a Markdown table; keeps decks and logs in OUT.
#
#   perf/solve/muelu_variants.sh [-n "RANKS"] [-v "VARIANTS"] [-x NAME=SPEC]... [-s EDIT]...
#                                [-o OUT] [-l LIMIT_S] [-p] DECK [SIZE]
#
#   perf/solve/muelu_variants.sh perf/decks/cube_p1.xml 0.05
#   perf/solve/muelu_variants.sh -v "default pg gs1 pg+gs1" -s "Stepping/end time=double:0.08" \
#       -s "Stepping/steps=int:40" inputs/s2_torus.xml
#   perf/solve/muelu_variants.sh -x 'damp=MueLu/sa: damping factor=double:1.0' -v "default damp" DECK
#
# DECK: any deck (Mesh->file made absolute); SIZE: Mesh->size. -n: ranks (env RANKS,
# default 1; 1 runs without mpirun). -v: variant names (env VARIANTS; default: the whole
# catalogue below); "a+b" applies a's and then b's settings. -x NAME=SPEC adds a variant: SPEC
# is ';'-separated PATH=TYPE:VALUE, PATH relative to `Linear Solver`. -s EDIT: PATH=TYPE:VALUE
# relative to the deck's top list, applied to every run (shorten a run, set friction).
# -o: output folder (env OUT, default /tmp/stentor-muelu-variants/<deck>[_h<SIZE>]);
# -l: time limit per run in seconds (default 600; "timeout" in the table). -p: no runs, the
# table again from the logs already in OUT (same options otherwise; the CSV is rewritten).
# Env: STENTOR (default build/stentor), NICE (default 10).
# The default variant is Stentor's own MueLu set-up (src/solver/MueLuPreconditioner.cpp);
# every run starts from an empty `Linear Solver->MueLu` list, keeps the deck's other
# `Linear Solver` parameters (tolerance, restart...) and writes no fields.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)
PY=/usr/bin/python3
lib=$here/solvelib.py

# name -> SPEC (PATH=TYPE:VALUE;..., PATH relative to `Linear Solver`)
declare -A CAT=(
  [default]=""
  [sa-nonsym]="MueLu/problem: symmetric=bool:false"
  [pg]="MueLu/multigrid algorithm=string:pg;MueLu/problem: symmetric=bool:false"
  [unsmoothed]="MueLu/multigrid algorithm=string:unsmoothed"
  [emin]="MueLu/multigrid algorithm=string:emin"
  [cheb2]="MueLu/smoother: type=string:CHEBYSHEV;MueLu/smoother: params/chebyshev: degree=int:2"
  [cheb3]="MueLu/smoother: type=string:CHEBYSHEV;MueLu/smoother: params/chebyshev: degree=int:3"
  [gs1]="MueLu/smoother: type=string:RELAXATION;MueLu/smoother: params/relaxation: type=string:Gauss-Seidel;MueLu/smoother: params/relaxation: sweeps=int:1"
  [gs2]="MueLu/smoother: type=string:RELAXATION;MueLu/smoother: params/relaxation: type=string:Gauss-Seidel;MueLu/smoother: params/relaxation: sweeps=int:2"
  [sgs2]="MueLu/smoother: type=string:RELAXATION;MueLu/smoother: params/relaxation: type=string:Symmetric Gauss-Seidel;MueLu/smoother: params/relaxation: sweeps=int:2"
  [reuse-none]="MueLu/reuse: type=string:none"
  [reuse-RP]="MueLu/reuse: type=string:RP"
  [prec-reuse0]="preconditioner reuse=int:0"
  [prec-reuse5]="preconditioner reuse=int:5"
  [prec-reuse100]="preconditioner reuse=int:100"
  [schwarz]="preconditioner=string:schwarz"
  [direct]="method=string:direct"
)
ORDER="default sa-nonsym pg unsmoothed cheb2 cheb3 gs1 sgs2 reuse-none reuse-RP prec-reuse0 prec-reuse5 prec-reuse100"

RANKS=${RANKS:-1}
VARIANTS=${VARIANTS:-$ORDER}
OUT=${OUT:-}
LIMIT=600
EDITS=()
PARSE_ONLY=0
usage() { sed -n '2,/^set -euo/p' "$0" | sed '$d; s/^# \{0,1\}//' >&2; exit 2; }
while getopts "n:v:x:s:o:l:ph" opt; do
  case $opt in
    n) RANKS=$OPTARG ;;
    v) VARIANTS=$OPTARG ;;
    x) CAT[${OPTARG%%=*}]=${OPTARG#*=} ;;
    s) EDITS+=(--set "$OPTARG") ;;
    o) OUT=$OPTARG ;;
    l) LIMIT=$OPTARG ;;
    p) PARSE_ONLY=1 ;;
    *) usage ;;
  esac
done
shift $((OPTIND - 1))
if [ $# -lt 1 ] || [ $# -gt 2 ]; then usage; fi
DECK=$(cd "$(dirname "$1")" && pwd)/$(basename "$1")
SIZE=${2:-}
name=$(basename "$DECK" .xml)
OUT=${OUT:-/tmp/stentor-muelu-variants/$name${SIZE:+_h$SIZE}}
STENTOR=${STENTOR:-$root/build/stentor}
[ -x "$STENTOR" ] || { echo "muelu_variants: $STENTOR not found (build first, or set STENTOR)" >&2; exit 2; }
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1
export OMP_NUM_THREADS=1
mkdir -p "$OUT"
[ "$PARSE_ONLY" = 1 ] && rm -f "$OUT/variants.csv"
for v in $VARIANTS; do  # every name known before the first run
  for part in ${v//+/ }; do [ -n "${CAT[$part]+x}" ] || { echo "muelu_variants: unknown variant '$part' (known: ${!CAT[*]})" >&2; exit 2; }; done
done

$PY "$root/perf/studies/studylib.py" banner "$STENTOR"
echo "deck: $DECK${SIZE:+, Mesh->size $SIZE}${EDITS:+, edits:$(printf ' %s' "${EDITS[@]}" | sed 's/ --set / /g')}"
echo "csv: $OUT/variants.csv"
echo
echo "| variant | ranks | dofs | Newton | GMRES | GMRES/Newton | builds | set-up [s] | solve [s] | wall [s] | cut-backs | completed |"
echo "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|"
for v in $VARIANTS; do
  sets=(--set "Linear Solver/method=string:gmres" --set "Linear Solver/preconditioner=string:muelu")
  for part in ${v//+/ }; do
    IFS=';' read -r -a items <<<"${CAT[$part]}"
    for it in ${items[@]+"${items[@]}"}; do sets+=(--set "Linear Solver/$it"); done
  done
  for r in $RANKS; do
    tag=${v}_np$r
    xml=$OUT/$tag.xml log=$OUT/$tag.log
    $PY "$lib" deck "$DECK" "$xml" --remove "Linear Solver/MueLu" ${SIZE:+--set "Mesh/size=double:$SIZE"} \
      --set "Output/fields=bool:false" --set "Output/basename=string:$tag" ${EDITS[@]+"${EDITS[@]}"} "${sets[@]}"
    if [ "$PARSE_ONLY" = 0 ]; then
      launch=("$STENTOR")
      [ "$r" -gt 1 ] && launch=(mpirun -np "$r" --bind-to none "$STENTOR")
      rc=0
      (cd "$OUT" && /usr/bin/time -f "TIME %e %U %S %M" timeout "$LIMIT" nice -n "${NICE:-10}" \
         "${launch[@]}" --overwrite --output "$OUT/$tag" "$xml") >"$log" 2>&1 || rc=$?
      echo "EXIT $rc" >>"$log"
    fi
    $PY "$lib" parse "$log" --csv "$OUT/variants.csv" \
      --label "deck=$name" --label "size=${SIZE:-deck}" --label "ranks=$r" --label "variant=$v" \
      --row "| {variant} | {ranks} | {dofs} | {newton} | {linear} | {per_newton} | {builds} | {setup} | {solve} | {wall} | {cutbacks} | {completed} |"
  done
done
