#!/usr/bin/env bash
# Scene S4 (talk): stent in an arterial tissue, three stages (insertion, inflation,
# extraction of a rigid capsule balloon). Runs inputs/s4_stent_artery.xml for the talk's
# friction sweep mu = 0, 0.1, 0.2, 0.3, 0.4 on the stent-artery pair (eta = 1 Pa s), and
# mu = 0.2 with eta = 1 MPa s; then writes into docs/scenes/: s4_denergy.png (E_{n+1} - E_n
# per step, one curve per mu, as in the talk), s4_energy.png (energy terms of mu = 0.2
# over the procedure), s4_metrics.png (lumen and stent radii over time), s4_denergy.csv
# and s4_summary.md (per run: completion, steps, cut-backs, Newton iterations, energy
# balance, wall time, and the stent metrics at the end of each stage).
#   usage: perf/scenes/run_s4.sh [build-dir]     (default build; needs gnuplot, python3)
#   env:   S4_RUNS (raw output dir, default <build>/scenes/s4); S4_SKIP_RUNS=1 (tables only);
#          S4_JOBS (runs at a time, default 1: the timings are then for one core each)
set -euo pipefail
ROOT=$(cd "$(dirname "$0")/../.." && pwd)
BUILD=${1:-$ROOT/build}
EXE=$BUILD/stentor
RUNS=${S4_RUNS:-$BUILD/scenes/s4}
DOCS=$ROOT/docs/scenes
mkdir -p "$RUNS" "$DOCS"
[ -x "$EXE" ] || { echo "no $EXE: build it first"; exit 1; }

base=$ROOT/inputs/s4_stent_artery.xml
geo="s|value=\"s4_stent_artery.geo\"|value=\"$ROOT/inputs/s4_stent_artery.geo\"|"
variant() {  # name mu eta
  sed -e "$geo" -e "/name=\"friction\"/s|value=\"[^\"]*\"|value=\"$2\"|" \
      -e "/name=\"viscosity\"/s|value=\"[^\"]*\"|value=\"$3\"|" \
      -e "/name=\"basename\"/s|value=\"[^\"]*\"|value=\"$1\"|" "$base" > "$RUNS/$1.xml"
}
NAMES=""
for mu in 0 0.1 0.2 0.3 0.4; do variant "s4_mu$mu" "$mu" 1; NAMES="$NAMES s4_mu$mu"; done
variant s4_mu0.2_eta1e6 0.2 1e6; NAMES="$NAMES s4_mu0.2_eta1e6"

run() {  # name
  /usr/bin/time -f "%e %U" -o "$RUNS/$1.time" "$EXE" --output "$RUNS/$1" "$RUNS/$1.xml" > "$RUNS/$1.log" 2>&1 &&
    echo "== $1: done in $(cat "$RUNS/$1.time") s" || echo "== $1: FAILED (see $RUNS/$1.log)"
}
if [ "${S4_SKIP_RUNS:-0}" != 1 ]; then
  export -f run; export EXE RUNS
  printf '%s\n' $NAMES | xargs -P "${S4_JOBS:-1}" -I{} bash -c 'run {}'
fi

python3 - "$RUNS" "$DOCS" $NAMES <<'PY'
import csv, os, re, statistics, sys
runs, docs, names = sys.argv[1], sys.argv[2], sys.argv[3:]
def read(path):
    if not os.path.exists(path):
        return None
    with open(path) as f:
        rows = list(csv.DictReader(f))
    return {k: [float(x[k]) for x in rows] for k in rows[0]} if rows else None
def out(n):  # results folder, or the partial one of a failed run
    d = os.path.join(runs, n)
    return d if os.path.isdir(d) and os.path.exists(os.path.join(d, n + "_energy.csv")) else d + ".partial"
lines = ["| run | completed | steps | cut-backs | Newton iterations | Newton median / max | max \\|balance\\| per step [J/m] | wall [s] | CPU [s] |",
         "|---|---|---|---|---|---|---|---|---|"]
stage_lines = ["| run | stage | lumen radius [m] | lumen gain | stent radius [m] | radial recoil | dogboning | foreshortening | max contact pressure [Pa] | max wall von Mises [Pa] | max wall hoop [Pa] | dE [J/m] | W_contact [J/m] | D_visc [J/m] | D_fric [J/m] |",
               "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"]
series = {}
for n in names:
    d = out(n)
    e, h, s = (read(os.path.join(d, n + suf)) for suf in ("_energy.csv", "_history.csv", "_stages.csv"))
    log = open(os.path.join(runs, n + ".log")).read() if os.path.exists(os.path.join(runs, n + ".log")) else ""
    done = "Results in" in log
    tw = open(os.path.join(runs, n + ".time")).read().split()[-2:] if os.path.exists(os.path.join(runs, n + ".time")) else ["-", "-"]
    t = " | ".join(tw if len(tw) == 2 else tw + ["-"])  # wall and user CPU seconds (the machine may be shared)
    if e is None or h is None:
        lines.append("| %s | no output | | | | | | %s |" % (n, t)); continue
    series[n] = (e["time"][1:], [e["total"][i + 1] - e["total"][i] for i in range(len(e["total"]) - 1)], e)
    nw = h["newton_iterations"]
    m = re.search(r"Summary: (\d+) steps, (\d+) cut-backs", log)
    cuts = int(m.group(2)) if m else int(h["cutbacks"][-1])
    m = re.search(r"Summary: \d+ steps, \d+ cut-backs, (\d+) Newton iterations", log)
    its = m.group(1) if m else "-"  # failed attempts included
    lines.append("| %s | %s | %d | %d | %s | %g / %d | %.2e | %s |" % (n, "yes" if done else "no (stopped at t = %.4g)" % h["time"][-1], len(nw),
                 cuts, its, statistics.median(nw), max(nw), max(abs(x) for x in e["balance_residual"]), t))
    for i in range(len(s["stage"]) if s else 0):
        g = lambda k: s[k][i]
        stage_lines.append("| %s | %d | %.4f | %.2f %% | %.4f | %.2f %% | %.2f %% | %.2f %% | %.3g | %.3g | %.3g | %.4g | %.4g | %.3g | %.3g |" % (
            n, g("stage"), g("lumen_radius_mean"), 100 * g("lumen_gain"), g("stent_radius_mean"), 100 * g("radial_recoil"),
            100 * g("dogboning"), 100 * g("foreshortening"), g("stage_contact_pressure_max"), g("stage_artery_von_mises_max"),
            g("stage_artery_hoop_stress_max"), g("stage_delta_energy"), g("stage_contact_work"), g("stage_dissipation"),
            g("stage_friction_dissipation")))
with open(os.path.join(docs, "s4_denergy.csv"), "w") as f:
    w = csv.writer(f)
    for n, (t, de, _) in series.items():
        w.writerow(["# " + n]); w.writerow(["time", "dE"])
        for a, b in zip(t, de): w.writerow([a, b])
        w.writerow([]); w.writerow([])
text = "\n".join(lines) + "\n\nStent metrics at the end of each stage (stage 1 insertion, 2 inflation, 3 extraction; " \
       "energy terms of the stage):\n\n" + "\n".join(stage_lines) + "\n"
open(os.path.join(docs, "s4_summary.md"), "w").write(text)
print(text)
PY
plots=""; i=0
for n in $NAMES; do
  case $n in *eta1e6) continue;; esac
  plots="$plots${plots:+, }\"$DOCS/s4_denergy.csv\" index $i using 1:2 with linespoints pt 7 ps 0.4 title \"${n#s4_}\""
  i=$((i + 1))
done
m2=$(ls -d "$RUNS"/s4_mu0.2 "$RUNS"/s4_mu0.2.partial 2>/dev/null | head -1 || true)
gnuplot <<GP
set terminal pngcairo size 960,560 noenhanced
set datafile separator ","
set output "$DOCS/s4_denergy.png"
set title "S4: E_{n+1} - E_n per step (Gonzalez + persistence, eta = 1 Pa s), one curve per friction coefficient"
set xlabel "time [s] (0-1 insertion, 1-2 inflation, 2-3 extraction)"; set ylabel "E_{n+1} - E_n [J/m]"
set key outside bottom horizontal
plot $plots
set output "$DOCS/s4_energy.png"
set title "S4, mu = 0.2: energy terms over the procedure"
set ylabel "energy [J/m]"; set key autotitle columnhead outside bottom horizontal
plot "$m2/s4_mu0.2_energy.csv" using 2:5 with lines lw 2 title "E = kinetic + strain", \
     "" using 2:3 with lines title "kinetic", "" using 2:16 with lines title "contact work (balloon)", \
     "" using 2:17 with lines title "friction dissipation", "" using 2:8 with lines title "viscous dissipation"
set output "$DOCS/s4_metrics.png"
set title "S4, mu = 0.2: lumen and stent radii"
set ylabel "radius [m]"
plot "$m2/s4_mu0.2_metrics.csv" using 2:4 with lines lw 2 title "lumen radius (mean over the stented span)", \
     "" using 2:5 with lines title "lumen radius (min)", "" using 2:6 with lines lw 2 title "stent radius (mean)", \
     "" using 2:7 with lines title "stent radius (middle)", "" using 2:8 with lines title "stent radius (ends)"
GP
echo "wrote $DOCS/s4_summary.md, s4_denergy.csv, s4_denergy.png, s4_energy.png, s4_metrics.png"
