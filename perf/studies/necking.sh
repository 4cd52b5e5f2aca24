#!/usr/bin/env bash
# Necking of a circular bar (docs/plasticity.md, "Necking"): runs inputs/necking_bar.xml
# (1/8 model, tet10, Ciarlet-Geymonat plasticity with linear hardening; mm, MPa, N) and
# writes the force-elongation curve of the whole bar with the closed-form reference loads.
#
#   perf/studies/necking.sh [STENTOR]            (default: build/stentor)
#   perf/studies/necking.sh --plot-only          (redraw from docs/studies/necking.csv)
#   WORK=DIR perf/studies/necking.sh --no-run    (remake the CSV and PNG from DIR's history)
#
# Environment: WORK (run folder, default a temp dir; kept), NP (MPI ranks, default 1).
# Writes docs/studies/necking.csv (per step: end displacement u [mm] of the half bar,
# elongation 2u of the whole bar [mm], axial force F of the whole bar [N] = 4 x the
# reaction of the 1/8 model, neck radius r_neck/r_neck0 and end radius r_end/R) and
# docs/studies/necking.png; prints the yield load, the peak load and the Considere
# loads (closed form: tests/system/test_necking.cpp, docs/plasticity.md).
set -uo pipefail
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)
outdir=$root/docs/studies
csv=$outdir/necking.csv
plot_only=0 no_run=0
[ "${1:-}" = "--plot-only" ] && plot_only=1
[ "${1:-}" = "--no-run" ] && no_run=1
bin=$root/build/stentor
[ $plot_only -eq 0 ] && [ $no_run -eq 0 ] && bin=${1:-$bin}
NP=${NP:-1}
WORK=${WORK:-$(mktemp -d "${TMPDIR:-/tmp}/stentor_necking.XXXXXX")}
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1
mkdir -p "$outdir"

# Deck parameters (read from the deck so the closed form follows an edited deck).
deck=$root/inputs/necking_bar.xml
param() { grep -o "name=\"$1\" type=\"double\" value=\"[^\"]*\"" "$deck" | head -n1 | sed 's/.*value="\([^"]*\)"/\1/'; }
C1=$(param C1) C2=$(param C2) D=$(param D) Y=$(param "yield stress") H=$(param hardening)

if [ $plot_only -eq 0 ] && [ $no_run -eq 0 ]; then
  if [ ! -x "$bin" ]; then
    echo "necking.sh: $bin not found; build it first (cmake --build build --target stentor)" >&2
    exit 2
  fi
  python3 "$here/studylib.py" banner "$bin" | sed 's/^/== /'; echo "== $NP rank(s)"
  echo "== run in $WORK"
  start=$(date +%s)
  if [ "$NP" -gt 1 ]; then run=(mpirun -np "$NP" "$bin"); else run=("$bin"); fi
  "${run[@]}" --output "$WORK" --overwrite "$deck" > "$WORK/run.log" 2>&1 || { tail -n 20 "$WORK/run.log"; echo "run failed (log $WORK/run.log)" >&2; exit 1; }
  grep '^Summary' "$WORK/run.log"
  echo "== wall time $(( $(date +%s) - start )) s"
fi
if [ $plot_only -eq 0 ]; then
  python3 - "$WORK/necking_bar_history.csv" "$csv" <<'PY'
import csv, sys
R = 6.413; Rn = 0.982 * R
rows = list(csv.DictReader(open(sys.argv[1])))
with open(sys.argv[2], "w") as f:
    f.write("step,u_mm,elongation_mm,force_N,r_neck_ratio,r_end_ratio,plastic_dissipation_step_mJ\n")
    f.write("0,0,0,0,1,1,0\n")
    for r in rows:
        u = float(r["u_end_z"])
        f.write("%s,%.6f,%.6f,%.3f,%.6f,%.6f,%.6g\n" % (r["step"], u, 2 * u, 4 * float(r["reaction_pull_z"]),
                (Rn + float(r["u_neck_x"])) / Rn, (R + float(r["u_end_x"])) / R, 4 * float(r["plastic_dissipation"])))
PY
fi

# Closed forms (uniaxial stress; the derivation is in docs/plasticity.md, "Necking"):
# yield P_y = tau(l_y)/l_y with |M|_H = tau(l_y) = Y; Considere tau(le) = (1/H + 1/E_t(le))^-1.
read -r Fy Fc_uni Fc_min Pc lc <<< "$(python3 - "$C1" "$C2" "$D" "$Y" "$H" <<'PY'
import math, sys
C1, C2, D, Y, H = map(float, sys.argv[1:6]); K = C1 + 2 * C2 + D
def tau(le):
    l2 = le * le; a = C2 + D * l2; b = C1 + C2 * l2
    m = 2 * K / (b + math.sqrt(b * b + 4 * a * K))
    return 2 * (C1 * l2 + 2 * C2 * l2 * m + D * l2 * m * m - K)
Et = lambda le, h=1e-5: (tau(le * math.exp(h)) - tau(le * math.exp(-h))) / (2 * h)
def bisect(g, lo, hi):
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if g(mid) < 0 else (lo, mid)
    return 0.5 * (lo + hi)
ly = bisect(lambda l: tau(l) - Y, 1.0, 2.0)
le = bisect(lambda l: tau(l) - 1 / (1 / H + 1 / Et(l)), ly, 2.0)
tc = tau(le); lc = le * math.exp((tc - Y) / H); Pc = tc / lc
R = 6.413; A0 = math.pi * R * R; Amin = math.pi * (0.982 * R) ** 2
print("%.2f %.2f %.2f %.4f %.5f" % (Y / ly * Amin, Pc * A0, Pc * Amin, Pc, lc))
PY
)"
python3 - "$csv" "$Fy" "$Fc_uni" "$Fc_min" "$Pc" "$lc" <<'PY'
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
Fy, Fcu, Fcm, Pc, lc = map(float, sys.argv[2:7])
F = [float(r["force_N"]) for r in rows]
i = max(range(len(F)), key=lambda k: F[k])
first = next(k for k, r in enumerate(rows) if float(r["plastic_dissipation_step_mJ"]) > 0)
last = rows[-1]
print("closed form: P_c = %.3f MPa at stretch %.4f; F_y (weakest section) = %.0f N; Considere F_c: uniform bar %.0f N, weakest section %.0f N" % (Pc, lc, Fy, Fcu, Fcm))
print("first plastic step %s: F = %.0f N (previous step %.0f N)" % (rows[first]["step"], F[first], F[first - 1]))
print("peak: F = %.0f N at elongation %.3f mm (step %s): %+.2f%% vs the uniform bar, %+.2f%% vs the weakest section"
      % (F[i], float(rows[i]["elongation_mm"]), rows[i]["step"], 100 * (F[i] / Fcu - 1), 100 * (F[i] / Fcm - 1)))
print("at the peak: r_neck/r0 = %.4f, r_end/R = %.4f; at the end (elongation %.2f mm, F = %.0f N): r_neck/r0 = %.4f, r_end/R = %.4f"
      % (float(rows[i]["r_neck_ratio"]), float(rows[i]["r_end_ratio"]), float(last["elongation_mm"]), F[-1],
         float(last["r_neck_ratio"]), float(last["r_end_ratio"])))
PY

if command -v gnuplot > /dev/null; then
  gnuplot <<GP
set terminal pngcairo size 1000,620 font ",10" noenhanced
set output "$outdir/necking.png"
set datafile separator ","
set title "Necking of a circular bar (R = 6.413 mm, L = 53.334 mm, 1.8% imperfection; tet10 1/8 model): Y = $Y MPa, H = $H MPa"
set xlabel "elongation of the bar 2u [mm]"
set ylabel "axial force F [kN]"
set y2label "radius / initial radius"
set y2tics
set ytics nomirror
set yrange [0:*]
set y2range [0:1.05]
set key bottom left
set grid
plot "$csv" every ::1 using 3:(\$4/1000) with linespoints pt 7 ps 0.4 lw 2 title "F (FE)", \
     $Fc_uni/1000 with lines dt 2 lw 1.5 title sprintf("Considere load, uniform bar: %.1f kN", $Fc_uni/1000), \
     $Fc_min/1000 with lines dt 3 lw 1.5 title sprintf("Considere load, weakest section: %.1f kN", $Fc_min/1000), \
     "$csv" every ::1 using 3:5 axes x1y2 with lines lw 1.5 title "r_neck / r_neck0 (mid-length)", \
     "$csv" every ::1 using 3:6 axes x1y2 with lines lw 1.5 title "r_end / R (pulled end)"
GP
  echo "wrote $csv and $outdir/necking.png"
fi
