#!/usr/bin/env bash
# Scene S5 (talk: the stent-artery procedure with plasticity), cross-section: runs
# inputs/s4_ring_section.xml (elastic ring, the S4 cross-section) and
# inputs/s5_ring_plastic.xml for a sweep of the stent's yield stress Y (hardening as in the
# deck), then writes into docs/scenes/:
#   s5_summary.md     per run: completion, steps, cut-backs, Newton iterations, energy
#                     balance, wall time; per stage: lumen gain, stent radius, radial
#                     recoil, plastic dissipation, largest equivalent plastic strain;
#                     and how far Y >> 1 is from the elastic run (histories)
#   s5_radii.png      stent and lumen radius over the procedure, one curve per Y
#   s5_energy.png     plastic dissipation over the procedure, one curve per Y
#   s4_ring_stages.png, s5_ring_Y<Y>.png   the deformed ring at the end of each stage
#                     (perf/scenes/render_section.py; von Mises / equivalent plastic strain)
#   usage: perf/scenes/run_s5.sh [build-dir]    (default build; needs gnuplot, python3,
#          and for the pictures Debian's python3-matplotlib, python3-h5py)
#   env:   S5_SECTION (ring: the cross-section, default; axial: the axial section,
#          inputs/s4_stent_artery.xml and inputs/s5_stent_plastic.xml, whose files in
#          docs/scenes/ start with s5ax_); S5_YIELDS (Y values in MPa, default "2 20 100
#          1e6", axial "0.01 0.2 0.5 1e6"); S5_RUNS (raw output dir, default
#          <build>/scenes/s5 or s5ax); S5_SKIP_RUNS=1 (tables only); S5_JOBS (runs at a
#          time, default 1)
set -euo pipefail
ROOT=$(cd "$(dirname "$0")/../.." && pwd)
BUILD=${1:-$ROOT/build}
EXE=$BUILD/stentor
SECTION=${S5_SECTION:-ring}
case $SECTION in
ring) P=s5 ELASTIC=s4_ring_section PLASTIC=s5_ring_plastic GEO=s4_ring_section.geo DEFAULT_YIELDS="2 20 100 1e6"
      STAGES="1 inflation, 2 deflation, 3 recoil" TAXIS="inflation 0-1, deflation 1-1.5, recoil 1.5-2" WHAT="cross-section" ;;
axial) P=s5ax ELASTIC=s4_stent_artery PLASTIC=s5_stent_plastic GEO=s4_stent_artery.geo DEFAULT_YIELDS="0.01 0.2 0.5 1e6"
       STAGES="1 insertion, 2 inflation, 3 extraction" TAXIS="insertion 0-1, inflation 1-2, extraction 2-3" WHAT="axial section" ;;
*) echo "S5_SECTION must be ring or axial"; exit 2 ;;
esac
RUNS=${S5_RUNS:-$BUILD/scenes/$P}
DOCS=$ROOT/docs/scenes
YIELDS=${S5_YIELDS:-$DEFAULT_YIELDS}
mkdir -p "$RUNS" "$DOCS"
[ -x "$EXE" ] || { echo "no $EXE: build it first"; exit 1; }

geo="s|value=\"$GEO\"|value=\"$ROOT/inputs/$GEO\"|"
sed -e "$geo" -e "/name=\"basename\"/s|value=\"[^\"]*\"|value=\"s5_elastic\"|" "$ROOT/inputs/$ELASTIC.xml" > "$RUNS/s5_elastic.xml"
NAMES="s5_elastic"
for y in $YIELDS; do
  pa=$(python3 -c "print('%g' % ($y * 1e6))")
  sed -e "$geo" -e "/name=\"yield stress\"/s|value=\"[^\"]*\"|value=\"$pa\"|" \
      -e "/name=\"basename\"/s|value=\"[^\"]*\"|value=\"s5_Y$y\"|" "$ROOT/inputs/$PLASTIC.xml" > "$RUNS/s5_Y$y.xml"
  NAMES="$NAMES s5_Y$y"
done

run() {  # name
  /usr/bin/time -f "%e" -o "$RUNS/$1.time" "$EXE" --overwrite --output "$RUNS/$1" "$RUNS/$1.xml" > "$RUNS/$1.log" 2>&1 &&
    echo "== $1: done in $(cat "$RUNS/$1.time") s" || echo "== $1: FAILED (see $RUNS/$1.log)"
}
if [ "${S5_SKIP_RUNS:-0}" != 1 ]; then
  export -f run; export EXE RUNS
  printf '%s\n' $NAMES | xargs -P "${S5_JOBS:-1}" -I{} bash -c 'run {}'
fi

/usr/bin/python3 - "$RUNS" "$DOCS" "$P" "$STAGES" $NAMES <<'PY'
import csv, os, re, statistics, sys
runs, docs, prefix, stages, names = sys.argv[1], sys.argv[2], sys.argv[3], sys.argv[4], sys.argv[5:]
try:
    import h5py
except ImportError:
    h5py = None
def read(path):
    if not os.path.exists(path):
        return None
    with open(path) as f:
        rows = list(csv.DictReader(f))
    return {k: [float(x[k]) for x in rows] for k in rows[0]} if rows else None
def folder(n):
    d = os.path.join(runs, n)
    return d if os.path.exists(os.path.join(d, n + "_energy.csv")) else d + ".partial"
def label(n):
    return "elastic" if n == "s5_elastic" else "Y = %s MPa" % n[4:]
def max_plastic_strain(d, n):  # (time, largest equivalent plastic strain) per output step
    p, x = os.path.join(d, n + ".h5"), os.path.join(d, n + ".xdmf")
    if h5py is None or not os.path.exists(p) or not os.path.exists(x):
        return None
    times = [float(v) for v in re.findall(r'<Time Value="([^"]+)"', open(x).read())]
    with h5py.File(p, "r") as f:
        return [(t, float(f["step_%d/equivalent_plastic_strain" % i][:].max())) for i, t in enumerate(times)
                if "equivalent_plastic_strain" in f["step_%d" % i]]
runs_md = ["| run | completed | steps | cut-backs | Newton median / max | max \\|balance\\| per step [J/m] | plastic dissipation [J/m] | wall [s] |",
           "|---|---|---|---|---|---|---|---|"]
# The cross-section has a lumen area, the axial section dogboning and foreshortening.
axial = prefix == "s5ax"
shape_cols = "dogboning | foreshortening" if axial else "lumen area [m²]"
stage_md = ["| run | stage | lumen radius [m] | %s | lumen gain | stent radius [m] | radial recoil | max contact pressure [MPa] | max wall von Mises [kPa] | D_plastic in stage [J/m] | max eq. plastic strain |" % shape_cols,
            "|---|---|---|---|---|---|---|---|---|---|---|" + ("---|" if axial else "")]
series, hist = {}, {}
for n in names:
    d = folder(n)
    e, h, s, m = (read(os.path.join(d, n + suf)) for suf in ("_energy.csv", "_history.csv", "_stages.csv", "_metrics.csv"))
    logp = os.path.join(runs, n + ".log")
    log = open(logp).read() if os.path.exists(logp) else ""
    t = open(os.path.join(runs, n + ".time")).read().split()[-1] if os.path.exists(os.path.join(runs, n + ".time")) else "-"
    if e is None or h is None:
        runs_md.append("| %s | no output | | | | | | %s |" % (label(n), t)); continue
    hist[n] = h
    series[n] = (m, e)
    nw = h["newton_iterations"]
    mm = re.search(r"Summary: (\d+) steps, (\d+) cut-backs", log)
    cuts = int(mm.group(2)) if mm else int(h["cutbacks"][-1])
    done = "Results in" in log
    dp = e["plastic_dissipation"][-1] if "plastic_dissipation" in e else 0.0
    runs_md.append("| %s | %s | %d | %d | %g / %d | %.2e | %.4g | %s |" % (label(n), "yes" if done else "no (stopped at t = %.4g)" % h["time"][-1],
                   len(nw), cuts, statistics.median(nw), max(nw), max(abs(x) for x in e["balance_residual"]), dp, t))
    eps = max_plastic_strain(d, n)
    for i in range(len(s["stage"]) if s else 0):
        g = lambda k: s[k][i]
        dps = g("stage_plastic_dissipation") if "stage_plastic_dissipation" in s else 0.0
        # largest over the output steps up to the stage's end (the field is cumulative)
        upto = [v for (tt, v) in eps or [] if tt <= g("time") + 1e-9]
        ep = "%.3f" % max(upto) if upto else "-"
        shape = "%.2f %% | %.2f %%" % (100 * g("dogboning"), 100 * g("foreshortening")) if axial else "%.4f" % g("lumen_area")
        stage_md.append("| %s | %d | %.4f | %s | %.2f %% | %.4f | %.2f %% | %.3g | %.3g | %.4g | %s |" % (
            label(n), g("stage"), g("lumen_radius_mean"), shape, 100 * g("lumen_gain"), g("stent_radius_mean"),
            100 * g("radial_recoil"), 1e-6 * g("stage_contact_pressure_max"), 1e-3 * g("stage_artery_von_mises_max"), dps, ep))
ref = None
big = [n for n in names if n != "s5_elastic" and float(n[4:]) >= 1e5]
if "s5_elastic" in hist and big and big[0] in hist:
    a, b = hist["s5_elastic"], hist[big[0]]
    if len(a["time"]) == len(b["time"]):
        cols = [k for k in a if k in b and k not in ("step", "time", "dt", "newton_iterations", "linear_iterations", "cutbacks", "stage", "plastic_dissipation")]
        ref = max(abs(x - y) / max(max(abs(v) for v in a[k]), 1e-300) for k in cols for x, y in zip(a[k], b[k]))
        ref = "%s against the elastic run: same %d steps, largest history difference %.2e (relative to each column's largest value)" % (label(big[0]), len(a["time"]), ref)
    else:
        ref = "%s against the elastic run: different step sequences (%d and %d steps)" % (label(big[0]), len(a["time"]), len(b["time"]))
with open(os.path.join(docs, prefix + "_summary.md"), "w") as f:
    f.write("<!-- written by perf/scenes/run_s5.sh -->\n## Runs\n\n" + "\n".join(runs_md) + "\n\n## Metrics at the end of each stage (" + stages + ")\n\n"
            + "\n".join(stage_md) + "\n")
    if ref:
        f.write("\n" + ref + ".\n")
with open(os.path.join(runs, "s5_radii.dat"), "w") as f:
    for n, (m, e) in series.items():
        if m is None:
            continue
        f.write('"%s"\n' % label(n))
        for i in range(len(m["time"])):
            f.write("%g %g %g %g\n" % (m["time"][i], m["stent_radius_mean"][i], m["lumen_radius_mean"][i], 0.0))
        f.write("\n\n")
with open(os.path.join(runs, "s5_energy.dat"), "w") as f:
    for n, (m, e) in series.items():
        if n == "s5_elastic":
            continue
        f.write('"%s"\n' % label(n))
        for i in range(len(e["time"])):
            f.write("%g %g\n" % (e["time"][i], e["plastic_dissipation"][i]))
        f.write("\n\n")
PY

n=$(grep -c '^"' "$RUNS/s5_radii.dat" || true)
gnuplot <<GP
set terminal pngcairo size 900,500 font ",10"
set output "$DOCS/${P}_radii.png"
set title "S5 $WHAT: stent (solid) and lumen (dashed) mean radius"
set xlabel "time [s] ($TAXIS)"
set ylabel "radius [m]"
set key outside right
plot for [i=0:$n-1] "$RUNS/s5_radii.dat" index i using 1:2 with lines lw 2 lc i+1 title columnheader(1), \
     for [i=0:$n-1] "$RUNS/s5_radii.dat" index i using 1:3 with lines dt 2 lc i+1 notitle
set output "$DOCS/${P}_energy.png"
set title "S5 $WHAT: plastic dissipation of the stent"
set ylabel "cumulative plastic dissipation [J/m]"
plot for [i=0:$n-2] "$RUNS/s5_energy.dat" index i using 1:2 with lines lw 2 lc i+2 title columnheader(1)
GP

# Pictures: the deformed section at the end of each stage.
R=$ROOT/perf/scenes/render_section.py
if [ "$SECTION" = axial ]; then
  for y in $YIELDS; do
    [ -f "$RUNS/s5_Y$y/s5_Y$y.h5" ] || continue
    XLIM=-0.2,8.2 YLIM=-1.7,1.7 /usr/bin/python3 "$R" "$RUNS/s5_Y$y" "s5_Y$y" "$DOCS/s5ax_Y$y.png" equivalent_plastic_strain \
      "equivalent plastic strain [-]" "2:inflated, Y = $y MPa" "3:after extraction" || true
  done
  echo "wrote $DOCS/${P}_summary.md and the plots"
  exit 0
fi
if [ -f "$RUNS/s5_elastic/s5_elastic.h5" ]; then
  XLIM=-1.65,1.65 YLIM=-1.65,1.65 SCALE=1e-6 /usr/bin/python3 "$R" "$RUNS/s5_elastic" s5_elastic "$DOCS/s4_ring_stages.png" von_mises "von Mises stress [MPa]" \
    "0:crimped" "1:inflated" "1.5:deflated" "2:after recoil" || true
fi
for y in $YIELDS; do
  [ -f "$RUNS/s5_Y$y/s5_Y$y.h5" ] || continue
  XLIM=-1.65,1.65 YLIM=-1.65,1.65 /usr/bin/python3 "$R" "$RUNS/s5_Y$y" "s5_Y$y" "$DOCS/s5_ring_Y$y.png" equivalent_plastic_strain "equivalent plastic strain [-]" \
    "1:inflated, Y = $y MPa" "1.5:deflated" "2:after recoil" || true
done
echo "wrote $DOCS/${P}_summary.md and the plots"
