#!/usr/bin/env bash
# Stability map of the dynamic time schemes (see docs/studies/README.md).
#
# A free 2D square block (plane strain, P2 triangles) spinning about its centre at OMEGA
# rad/s, no loads and no supports, is integrated to T with dt = T/N, for stiffness factors F
# (C1, C2 and D all multiplied by F; same density) and each scheme. Steps are never cut back
# (Stepping->max cutbacks = 0), so every run uses the dt it names, and a Newton failure ends
# it with exit status 3. A run is classified
#   blow-up      total energy grew by more than 10% (whether or not Newton then failed)
#   newton-fail  exit status 3 (Newton failed within Newton->max iterations = NEWTON_MAX)
#                before the energy grew by 10%
#   drift        ran to T, max |E - E_0| / E_0 > 1% (growth or loss)
#   stable       ran to T, max |E - E_0| / E_0 <= 1%
# (blow-up and newton-fail together are the "blow-up: exit 3 or energy growth > 10%" set.)
#
#   perf/studies/stability_map.sh [STENTOR]     (default: build-study/stentor)
#
# Environment (all optional):
#   SCHEMES="gonzalez midpoint newmark hht"   FACTORS="1 10 100 1000"   NS="10 20 40 80 160"
#   T=2  OMEGA=6  SIZE=0.2  ORDER=2  HHT_ALPHA=-0.1  NEWTON_MAX=25 (the deck default)
#   WORK=<tmp dir>      where the runs write their results (kept: logs, CSVs)
#   CSV=docs/studies/stability_map.csv  PNG=docs/studies/stability_map.png
#   DECKS=perf/studies/decks/stability_map   (a folder directly under perf/studies/decks/)
#   PLOT_ONLY=1         skip the runs, redraw the PNG from docs/studies/stability_map.csv
#
# Writes docs/studies/stability_map.csv and docs/studies/stability_map.png; the generated
# decks go to perf/studies/decks/stability_map/.
set -uo pipefail
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)
bin=${1:-$root/build-study/stentor}
SCHEMES=${SCHEMES:-"gonzalez midpoint newmark hht"}
FACTORS=${FACTORS:-"1 10 100 1000"}
NS=${NS:-"10 20 40 80 160"}
T=${T:-2}
OMEGA=${OMEGA:-6}
SIZE=${SIZE:-0.2}
ORDER=${ORDER:-2}
HHT_ALPHA=${HHT_ALPHA:--0.1}
NEWTON_MAX=${NEWTON_MAX:-25}
WORK=${WORK:-$(mktemp -d "${TMPDIR:-/tmp}/stentor_sm.XXXXXX")}
decks=${DECKS:-$here/decks/stability_map}
outdir=$root/docs/studies
csv=${CSV:-$outdir/stability_map.csv}
png=${PNG:-$outdir/stability_map.png}
case $csv in /*) ;; *) csv=$PWD/$csv ;; esac
case $png in /*) ;; *) png=$PWD/$png ;; esac

if [ ! -x "$bin" ]; then
  echo "stability_map.sh: $bin not found; build it first:" >&2
  echo "  cmake -S . -B build-study -G Ninja -DCMAKE_BUILD_TYPE=Release && ninja -C build-study stentor" >&2
  exit 2
fi
mkdir -p "$decks" "$outdir" "$WORK"

python3 "$here/studylib.py" banner "$bin" | sed 's/^/== /'  # the machine banner shared by the studies
echo "== runs in $WORK"

# Deck template: @SCHEME@, @N@, @C1@, @C2@, @D@ are replaced per run (base: C1 = 1e4,
# C2 = 1e3, D = 1e4 Pa, density 1000). Mesh path relative to perf/studies/decks/stability_map/.
template() {
  cat <<EOF
<ParameterList name="stentor">
  <ParameterList name="Problem">
    <Parameter name="title" type="string" value="stability map: spinning free block (@SCHEME@, N = @N@, C1 = @C1@)"/>
    <Parameter name="analysis" type="string" value="dynamic"/>
  </ParameterList>
  <ParameterList name="Mesh">
    <Parameter name="file" type="string" value="../../../../inputs/block2d.geo"/>
    <Parameter name="size" type="double" value="$SIZE"/>
    <Parameter name="order" type="int" value="$ORDER"/>
  </ParameterList>
  <ParameterList name="Materials">
    <ParameterList name="rubber">
      <Parameter name="C1" type="double" value="@C1@"/>
      <Parameter name="C2" type="double" value="@C2@"/>
      <Parameter name="D" type="double" value="@D@"/>
      <Parameter name="density" type="double" value="1000"/>
    </ParameterList>
  </ParameterList>
  <ParameterList name="Bodies">
    <ParameterList name="block">
      <Parameter name="material" type="string" value="rubber"/>
    </ParameterList>
  </ParameterList>
  <ParameterList name="Initial Conditions">
    <Parameter name="angular velocity" type="Array(double)" value="{$OMEGA}"/>
    <Parameter name="center" type="Array(double)" value="{0.5, 0.5}"/>
  </ParameterList>
  <ParameterList name="Time Integration">
    <Parameter name="scheme" type="string" value="@SCHEME@"/>
    <Parameter name="hht alpha" type="double" value="$HHT_ALPHA"/>
  </ParameterList>
  <ParameterList name="Stepping">
    <Parameter name="end time" type="double" value="$T"/>
    <Parameter name="steps" type="int" value="@N@"/>
    <Parameter name="max cutbacks" type="int" value="0"/>
  </ParameterList>
  <ParameterList name="Newton">
    <Parameter name="max iterations" type="int" value="$NEWTON_MAX"/>
  </ParameterList>
  <ParameterList name="Linear Solver">
    <Parameter name="method" type="string" value="direct"/>
  </ParameterList>
  <ParameterList name="Output">
    <Parameter name="basename" type="string" value="run"/>
    <Parameter name="fields" type="bool" value="false"/>
  </ParameterList>
</ParameterList>
EOF
}

if [ "${PLOT_ONLY:-0}" != 1 ]; then
rm -f "$decks"/*.xml
hdr="scheme,factor,N,dt,omega_dt,rc,steps,t_reached,newton_iterations,newton_mean,newton_max,energy_growth_max,energy_loss_max,energy_drift_max,wall_s,status"
echo "$hdr" >"$csv"
printf '  %-9s %5s %5s %4s %6s %8s %9s %10s %10s  %s\n' scheme F N rc steps newton/st max_it growth loss status
for s in $SCHEMES; do
  for f in $FACTORS; do
    for n in $NS; do
      name="${s}_F${f}_N${n}"
      deck=$decks/$name.xml
      out=$WORK/$name
      c1=$(awk -v f="$f" 'BEGIN{printf "%g", 1e4 * f}')
      c2=$(awk -v f="$f" 'BEGIN{printf "%g", 1e3 * f}')
      template | sed -e "s/@SCHEME@/$s/g" -e "s/@N@/$n/g" -e "s/@C1@/$c1/g" -e "s/@C2@/$c2/g" -e "s/@D@/$c1/g" >"$deck"
      rm -rf "$out" "$out.partial"
      "$bin" "$deck" --output "$out" >"$WORK/$name.log" 2>&1
      rc=$?
      dir=$out
      [ -d "$dir" ] || dir=$out.partial
      summary=$(grep '^Summary:' "$WORK/$name.log")
      steps=$(echo "$summary" | sed -E 's/^Summary: ([0-9]+) steps.*/\1/')
      newton=$(echo "$summary" | sed -E 's/.* ([0-9]+) Newton iterations.*/\1/')
      wall=$(echo "$summary" | sed -E 's/.* ([0-9.]+) s$/\1/')
      # Energy: max growth / loss relative to E_0; time reached; Newton iterations per step.
      en=$(awk -F, 'NR==2{e0=$5} NR>1{d=($5-e0)/e0; if(d>g)g=d; if(-d>l)l=-d; t=$2} END{m=(g>l)?g:l; printf "%.6g,%.6e,%.6e,%.6e", t+0, g+0, l+0, m+0}' "$dir/run_energy.csv")
      nmax=$(awk -F, 'NR==1{for(i=1;i<=NF;i++) if($i=="newton_iterations") c=i} NR>1 && $c>m{m=$c} END{print m+0}' "$dir/run_history.csv")
      # A failed step's iterations count in the Summary total but not in the history.
      [ "$rc" -ne 0 ] && nmax=$(grep -oE 'no convergence in [0-9]+' "$WORK/$name.log" | grep -oE '[0-9]+$' | head -1 || echo "$nmax")
      IFS=, read -r treach growth loss drift <<<"$en"
      status=$(awk -v rc="$rc" -v g="$growth" -v m="$drift" 'BEGIN{ if (g > 0.10) print "blow-up"; else if (rc != 0) print "newton-fail"; else if (m > 0.01) print "drift"; else print "stable"}')
      dt=$(awk -v t="$T" -v n="$n" 'BEGIN{printf "%.6g", t / n}')
      wdt=$(awk -v t="$T" -v n="$n" -v w="$OMEGA" 'BEGIN{printf "%.4g", w * t / n}')
      nmean=$(awk -v a="$newton" -v b="$steps" 'BEGIN{printf "%.2f", (b > 0) ? a / b : a}')
      echo "$s,$f,$n,$dt,$wdt,$rc,$steps,$treach,$newton,$nmean,$nmax,$growth,$loss,$drift,$wall,$status" >>"$csv"
      printf '  %-9s %5s %5s %4s %6s %8s %9s %10.2e %10.2e  %s\n' "$s" "$f" "$n" "$rc" "$steps" "$nmean" "$nmax" "$growth" "$loss" "$status"
    done
  done
done

fi

# Plot: one panel per scheme, dt on x, stiffness factor on y, marker by status, labelled
# with the max energy drift (or the time reached, for a run that stopped).
cd "$WORK" || exit 1
for s in $SCHEMES; do
  for st in stable drift blow-up newton-fail; do
    awk -F, -v s="$s" -v st="$st" 'NR>1 && $1==s && $16==st{print $4, $2}' "$csv" >"map_${s}_${st}.dat"
  done
  awk -F, -v s="$s" 'NR>1 && $1==s{ lab = sprintf("%.1e", $14); if ($6 != 0) lab = ($7 > 0) ? lab sprintf(", t=%.2g", $8) : "t=0"; printf "%s %s \"%s\"\n", $4, $2, lab }' "$csv" >"map_${s}_labels.dat"
done
ns=$(echo "$SCHEMES" | wc -w)
rows=$(((ns + 1) / 2))
{
  echo "set terminal pngcairo size 1100,$((430 * rows)) font ',10'"
  echo "set output '$png'"
  echo "set multiplot layout $rows,2 title 'Spinning free block (omega = $OMEGA rad/s, T = $T s, P2): Newton <= $NEWTON_MAX it.; label = max |E - E_0|/E_0 (t = time reached if Newton failed)'"
  echo "set logscale xy; set format x '%g'; set xrange [0.008:0.32]; set ytics (1, 10, 100, 1000); set yrange [0.4:2500]; set offsets graph 0.08, graph 0.08, 0, 0"
  echo "set xlabel 'dt [s]'; set ylabel 'stiffness factor (C1, C2, D)'; set grid; set key outside bottom center horizontal"
  for s in $SCHEMES; do
    lbl=$s
    [ "$s" = hht ] && lbl="hht (alpha $HHT_ALPHA)"
    echo "set title '$lbl'"
    echo "plot 'map_${s}_stable.dat' u 1:2 w p pt 7 ps 2.2 lc rgb '#2ca02c' t 'stable (<1%)', \
'map_${s}_drift.dat' u 1:2 w p pt 5 ps 2.2 lc rgb '#ff9f1a' t 'drift (>1%)', \
'map_${s}_blow-up.dat' u 1:2 w p pt 2 ps 2.4 lw 3 lc rgb '#d62728' t 'energy blow-up (>10%)', \
'map_${s}_newton-fail.dat' u 1:2 w p pt 9 ps 2.4 lc rgb '#7f7f7f' t 'Newton failure (exit 3)', \
'map_${s}_labels.dat' u 1:2:3 w labels offset 0,1.5 font ',8' notitle"
  done
  echo "unset multiplot"
} | gnuplot 2>&1 | grep -v 'empty\|Skipping data file' || true
echo "== wrote $csv and $png"
