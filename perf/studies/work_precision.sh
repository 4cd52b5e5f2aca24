#!/usr/bin/env bash
# Work-precision study of the dynamic time schemes (see docs/studies/README.md).
#
# A free 2D square block (plane strain, P2 triangles), spinning about its centre and
# translating, no loads and no supports, is integrated to the final time T with each scheme
# at dt = T/N. The error is the distance between the probe displacement at T (corner (1,1))
# and that of a reference run (same mesh, gonzalez at N = NREF). The cost is the wall time
# of the run (the "Summary: ... s" line). Also recorded: the relative energy drift
# |E_N - E_0| / E_0 at T and its maximum over the run.
#
#   perf/studies/work_precision.sh [STENTOR]     (default: build-study/stentor)
#
# Environment (all optional):
#   SCHEMES="gonzalez midpoint newmark hht"   schemes (hht runs with hht alpha = HHT_ALPHA)
#   NS="10 20 40 80 160 320"   steps per run;   NREF=1280   steps of the reference (gonzalez)
#   T=1  OMEGA=4  VX=1  SIZE=0.2  ORDER=2  HHT_ALPHA=-0.1
#   WORK=<tmp dir>         where the runs write their results (kept: logs, CSVs)
#
# Writes docs/studies/work_precision.csv, work_precision.png (error vs wall time),
# work_precision_order.png (error vs dt), work_precision_energy.png (energy drift vs dt);
# the generated decks go to perf/studies/decks/work_precision/.
set -uo pipefail
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)
bin=${1:-$root/build-study/stentor}
SCHEMES=${SCHEMES:-"gonzalez midpoint newmark hht"}
NS=${NS:-"10 20 40 80 160 320"}
NREF=${NREF:-1280}
T=${T:-1}
OMEGA=${OMEGA:-4}
VX=${VX:-1}
SIZE=${SIZE:-0.2}
ORDER=${ORDER:-2}
HHT_ALPHA=${HHT_ALPHA:--0.1}
WORK=${WORK:-$(mktemp -d "${TMPDIR:-/tmp}/stentor_wp.XXXXXX")}
decks=$here/decks/work_precision
outdir=$root/docs/studies
csv=$outdir/work_precision.csv

if [ ! -x "$bin" ]; then
  echo "work_precision.sh: $bin not found; build it first:" >&2
  echo "  cmake -S . -B build-study -G Ninja -DCMAKE_BUILD_TYPE=Release && ninja -C build-study stentor" >&2
  exit 2
fi
mkdir -p "$decks" "$outdir" "$WORK"
rm -f "$decks"/*.xml

python3 "$here/studylib.py" banner "$bin" | sed 's/^/== /'  # the machine banner shared by the studies
echo "== runs in $WORK"

# Deck template: @SCHEME@ and @N@ are replaced per run. The mesh path is relative to the
# generated deck's folder (perf/studies/decks/work_precision/).
template() {
  cat <<EOF
<ParameterList name="stentor">
  <ParameterList name="Problem">
    <Parameter name="title" type="string" value="work-precision: spinning and translating free block (@SCHEME@, N = @N@)"/>
    <Parameter name="analysis" type="string" value="dynamic"/>
  </ParameterList>
  <ParameterList name="Mesh">
    <Parameter name="file" type="string" value="../../../../inputs/block2d.geo"/>
    <Parameter name="size" type="double" value="$SIZE"/>
    <Parameter name="order" type="int" value="$ORDER"/>
  </ParameterList>
  <ParameterList name="Materials">
    <ParameterList name="rubber">
      <Parameter name="C1" type="double" value="1e4"/>
      <Parameter name="C2" type="double" value="1e3"/>
      <Parameter name="D" type="double" value="1e4"/>
      <Parameter name="density" type="double" value="1000"/>
    </ParameterList>
  </ParameterList>
  <ParameterList name="Bodies">
    <ParameterList name="block">
      <Parameter name="material" type="string" value="rubber"/>
    </ParameterList>
  </ParameterList>
  <ParameterList name="Initial Conditions">
    <Parameter name="velocity" type="Array(double)" value="{$VX, 0}"/>
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
  <ParameterList name="Linear Solver">
    <Parameter name="method" type="string" value="direct"/>
  </ParameterList>
  <ParameterList name="Output">
    <Parameter name="basename" type="string" value="run"/>
    <Parameter name="fields" type="bool" value="false"/>
    <ParameterList name="Probes">
      <ParameterList name="corner">
        <Parameter name="point" type="Array(double)" value="{1, 1}"/>
      </ParameterList>
    </ParameterList>
  </ParameterList>
</ParameterList>
EOF
}

# run SCHEME N -> appends "scheme,N,dt,rc,steps,newton,wall,ux,uy,drift_T,drift_max,balance_max" to $WORK/raw.csv
run() {
  local s=$1 n=$2 name="${1}_N${2}"
  local deck=$decks/$name.xml out=$WORK/$name
  template | sed -e "s/@SCHEME@/$s/g" -e "s/@N@/$n/g" >"$deck"
  rm -rf "$out" "$out.partial"
  "$bin" "$deck" --output "$out" >"$WORK/$name.log" 2>&1
  local rc=$?
  local dir=$out
  [ -d "$dir" ] || dir=$out.partial
  local summary steps newton wall balance
  summary=$(grep '^Summary:' "$WORK/$name.log")
  steps=$(echo "$summary" | sed -E 's/^Summary: ([0-9]+) steps.*/\1/')
  newton=$(echo "$summary" | sed -E 's/.* ([0-9]+) Newton iterations.*/\1/')
  wall=$(echo "$summary" | sed -E 's/.* ([0-9.]+) s$/\1/')
  balance=$(grep '^Energy balance' "$WORK/$name.log" | sed -E 's/.*= //')
  local probe drift
  probe=$(awk -F, 'NR==1{for(i=1;i<=NF;i++){if($i=="u_corner_x")cx=i; if($i=="u_corner_y")cy=i}} NR>1{x=$cx; y=$cy} END{print x "," y}' "$dir/run_history.csv")
  drift=$(awk -F, 'NR==2{e0=$5} NR>1{d=($5-e0)/e0; if(d<0)d=-d; if(d>m)m=d; last=d} END{printf "%.6e,%.6e", last, m}' "$dir/run_energy.csv")
  echo "$s,$n,$(awk -v t="$T" -v n="$n" 'BEGIN{printf "%.6e", t/n}'),$rc,$steps,$newton,$wall,$probe,$drift,$balance" >>"$WORK/raw.csv"
  printf '  %-9s N=%-5s rc=%s steps=%-5s newton=%-6s wall=%6s s  u=(%s)  drift=%s\n' "$s" "$n" "$rc" "$steps" "$newton" "$wall" "$probe" "${drift%%,*}"
}

: >"$WORK/raw.csv"
echo "== reference: gonzalez, N = $NREF and N = $((NREF / 2)) (Richardson check)"
run gonzalez "$NREF"
run gonzalez "$((NREF / 2))"
echo "== sweep"
for s in $SCHEMES; do
  for n in $NS; do run "$s" "$n"; done
done

# Errors against the reference, observed orders; CSV for the plots.
python3 - "$WORK/raw.csv" "$csv" "$NREF" "$WORK" <<'PY'
import csv, math, sys
raw, out, nref, work = sys.argv[1], sys.argv[2], int(sys.argv[3]), sys.argv[4]
rows = [r for r in csv.reader(open(raw))]
ref = next(r for r in rows if r[0] == "gonzalez" and int(r[1]) == nref)
half = next(r for r in rows if r[0] == "gonzalez" and int(r[1]) == nref // 2)
rx, ry = float(ref[7]), float(ref[8])
def dist(r):
    return math.hypot(float(r[7]) - rx, float(r[8]) - ry)
ref_err = dist(half) / 3.0  # Richardson: e(N) ~ (e(N/2) - e(N)) / 3 for a 2nd-order scheme
hdr = ["scheme", "N", "dt", "rc", "steps", "newton_iterations", "wall_s", "u_x", "u_y", "error",
       "energy_drift_T", "energy_drift_max", "balance_max"]
with open(out, "w") as f:
    w = csv.writer(f, lineterminator="\n")
    w.writerow(hdr)
    for r in rows:
        is_ref = r[0] == "gonzalez" and int(r[1]) in (nref, nref // 2)
        err = "" if (int(r[3]) != 0 or is_ref) else "%.6e" % dist(r)
        w.writerow([r[0] + ("(ref)" if is_ref else "")] + r[1:9] + [err] + r[9:])
print("reference (gonzalez N=%d): u_corner = (%s, %s); Richardson estimate of its error %.2e" % (nref, ref[7], ref[8], ref_err))
# per-scheme data files for gnuplot, and observed orders
schemes = []
for r in rows:
    if r[0] not in schemes and not (r[0] == "gonzalez" and int(r[1]) in (nref, nref // 2)):
        schemes.append(r[0])
for s in schemes:
    pts = [r for r in rows if r[0] == s and int(r[1]) not in (nref, nref // 2) and int(r[3]) == 0]
    pts.sort(key=lambda r: int(r[1]))
    with open("%s/%s.dat" % (work, s), "w") as f:
        for r in pts:
            f.write("%s %s %.6e %s %s\n" % (r[2], r[6], dist(r), max(float(r[9]), 1e-16), max(float(r[10]), 1e-16)))
    orders = []
    for a, b in zip(pts, pts[1:]):
        ea, eb = dist(a), dist(b)
        orders.append("%.2f" % (math.log(ea / eb) / math.log(float(a[2]) / float(b[2]))) if ea > 0 and eb > 0 else "-")
    failed = [r[1] for r in rows if r[0] == s and int(r[3]) != 0]
    print("%-9s errors %s" % (s, " ".join("%.2e" % dist(r) for r in pts)))
    print("%-9s observed orders %s%s" % (s, " ".join(orders), ("; failed at N = " + ",".join(failed)) if failed else ""))
    print("%-9s energy drift at T %s" % (s, " ".join("%.1e" % float(r[9]) for r in pts)))
PY

cd "$WORK" || exit 1
plots=""
for s in $SCHEMES; do
  [ -s "$s.dat" ] || continue
  lbl=$s
  [ "$s" = hht ] && lbl="hht (alpha $HHT_ALPHA)"
  plots="$plots${plots:+, }'$s.dat' using COLX:COLY with linespoints lw 2 pt 7 title '$lbl'"
done
if [ -n "$plots" ]; then
  gnuplot <<EOF
set terminal pngcairo size 800,600 font ',11'
set logscale xy
set format y '10^{%L}'
set grid
set key top right
set output '$outdir/work_precision.png'
set title 'Work-precision: spinning free block, P2, T = $T (reference: gonzalez N = $NREF)'
set xlabel 'wall time of the run [s]'
set ylabel 'error of the probe displacement at T [m]'
plot $(echo "$plots" | sed 's/COLX/2/g; s/COLY/3/g')
set output '$outdir/work_precision_order.png'
set title 'Convergence: probe error at T vs time step'
set xlabel 'dt [s]'
set key bottom right
plot $(echo "$plots" | sed 's/COLX/1/g; s/COLY/3/g'), 20*x**2 with lines dt 2 lc 'gray' title 'slope 2'
set output '$outdir/work_precision_energy.png'
set title 'Energy drift |E_N - E_0| / E_0 at T (values < 1e-16 shown as 1e-16)'
set ylabel 'relative energy drift'
set key bottom right
plot $(echo "$plots" | sed 's/COLX/1/g; s/COLY/4/g')
EOF
fi
echo "== wrote $csv and $outdir/work_precision{,_order,_energy}.png"
