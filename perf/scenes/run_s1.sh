#!/usr/bin/env bash
# Scene S1 (talk): 2D hyper-viscoelastic ring impacting a rigid plane, sweeps (a)-(d).
# Runs inputs/s1_ring.xml variants with the stentor executable, then writes the energy
# plots (PNG), compact CSVs and a summary table into docs/scenes/.
#   usage: perf/scenes/run_s1.sh [build-dir]     (default build-scenes; needs gnuplot, python3)
#   env:   S1_STEPS (default 400), S1_SIZE (mesh size, default 0.05), S1_RUNS (raw output dir),
#          S2=0 to skip scene S2 (3D torus, inputs/s2_torus.xml, about 1 min) run at the end
set -euo pipefail
ROOT=$(cd "$(dirname "$0")/../.." && pwd)
BUILD=${1:-$ROOT/build-scenes}
EXE=$BUILD/stentor
RUNS=${S1_RUNS:-$BUILD/scenes/s1}
DOCS=$ROOT/docs/scenes
STEPS=${S1_STEPS:-400}
SIZE=${S1_SIZE:-0.05}
mkdir -p "$RUNS" "$DOCS"
[ -x "$EXE" ] || { echo "no $EXE: build it first (ninja -C $BUILD stentor)"; exit 1; }

# variant name, scheme, formulation, viscosity eta [Pa s], friction mu
VARIANTS=(
  "a_gonzalez_persistence gonzalez persistence 0 0"
  "a_midpoint_persistence midpoint persistence 0 0"
  "a_gonzalez_gap gonzalez gap 0 0"
  "b_eta100 gonzalez persistence 100 0"
  "b_eta1000 gonzalez persistence 1000 0"
  "b_eta5000 gonzalez persistence 5000 0"
  "c_mu0.1 gonzalez persistence 0 0.1"
  "c_mu0.2 gonzalez persistence 0 0.2"
  "c_mu0.3 gonzalez persistence 0 0.3"
  "c_mu0.5 gonzalez persistence 0 0.5"
  "d_mu0.3_eta1000 gonzalez persistence 1000 0.3"
  "d_mu0.1_eta5000 gonzalez persistence 5000 0.1"
)
for v in "${VARIANTS[@]}"; do
  read -r name scheme form eta mu <<<"$v"
  deck=$RUNS/$name.xml
  sed -e "s|value=\"ring.geo\"|value=\"$ROOT/inputs/ring.geo\"|" \
      -e "/name=\"size\"/s|value=\"[^\"]*\"|value=\"$SIZE\"|" \
      -e "/name=\"scheme\"/s|value=\"[^\"]*\"|value=\"$scheme\"|" \
      -e "/name=\"formulation\"/s|value=\"[^\"]*\"|value=\"$form\"|" \
      -e "/name=\"viscosity\"/s|value=\"[^\"]*\"|value=\"$eta\"|" \
      -e "/name=\"friction\"/s|value=\"[^\"]*\"|value=\"$mu\"|" \
      -e "/name=\"steps\"/s|value=\"[^\"]*\"|value=\"$STEPS\"|" \
      -e "/name=\"basename\"/s|value=\"[^\"]*\"|value=\"$name\"|" \
      "$ROOT/inputs/s1_ring.xml" > "$deck"
  echo "== $name ($scheme, $form, eta $eta, mu $mu)"
  /usr/bin/time -f "%e" -o "$RUNS/$name.time" "$EXE" "$deck" --output "$RUNS/$name" > "$RUNS/$name.log" 2>&1 || {
    echo "   FAILED (see $RUNS/$name.log)"; tail -3 "$RUNS/$name.log"; }
  tail -2 "$RUNS/$name.log" | head -1
done

python3 - "$RUNS" "$DOCS" <<'PY'
import csv, os, statistics, sys
runs, docs = sys.argv[1], sys.argv[2]
def read(path):
    with open(path) as f:
        r = csv.DictReader(f)
        rows = list(r)
    return {k: [float(x[k]) for x in rows] for k in rows[0]} if rows else {}
data = {}
for name in sorted(os.listdir(runs)):
    d = os.path.join(runs, name)
    if not os.path.isdir(d): continue
    e = os.path.join(d, name + "_energy.csv"); h = os.path.join(d, name + "_history.csv")
    if os.path.exists(e) and os.path.exists(h):
        data[name] = (read(e), read(h))
label = {
 "a_gonzalez_persistence": "gonzalez+persistence (PDAS-leapfrog)", "a_midpoint_persistence": "midpoint+persistence",
 "a_gonzalez_gap": "gonzalez+gap", "b_eta100": "eta=100", "b_eta1000": "eta=1000", "b_eta5000": "eta=5000",
 "c_mu0.1": "mu=0.1", "c_mu0.2": "mu=0.2", "c_mu0.3": "mu=0.3", "c_mu0.5": "mu=0.5",
 "d_mu0.3_eta1000": "mu=0.3 eta=1000", "d_mu0.1_eta5000": "mu=0.1 eta=5000"}
groups = {
 "s1a": [("a_gonzalez_persistence", None), ("a_midpoint_persistence", None), ("a_gonzalez_gap", None)],
 "s1b": [("a_gonzalez_persistence", "eta=0"), ("b_eta100", None), ("b_eta1000", None), ("b_eta5000", None)],
 "s1c": [("a_gonzalez_persistence", "mu=0"), ("c_mu0.1", None), ("c_mu0.2", None), ("c_mu0.3", None), ("c_mu0.5", None)],
 "s1d": [("c_mu0.3", "mu=0.3 eta=0"), ("b_eta1000", "mu=0 eta=1000"), ("d_mu0.3_eta1000", None), ("d_mu0.1_eta5000", None)],
}
def write_group(fname, cols, key):
    cols = [(n, l) for n, l in cols if n in data]
    if not cols: return
    t = data[cols[0][0]][0]["time"]
    with open(os.path.join(docs, fname), "w") as f:
        f.write("time," + ",".join(l or label.get(n, n) for n, l in cols) + "\n")
        series = [key(data[n][0]) for n, _ in cols]
        for i in range(len(series[0])):
            f.write("%.6g," % series[0][i][0] + ",".join("%.10g" % s[i][1] if i < len(s) else "" for s in series) + "\n")
for g, cols in groups.items():
    write_group(g + "_energy.csv", cols, lambda e: list(zip(e["time"], e["total"])))
    write_group(g + "_denergy.csv", cols, lambda e: [(e["time"][i], e["total"][i] - e["total"][i - 1]) for i in range(1, len(e["time"]))])
write_group("s1_balance.csv", [(n, None) for n in data if not n.startswith("a_midpoint")],
            lambda e: list(zip(e["time"][1:], e["balance_residual"][1:])))
rows = []
for n, (e, h) in data.items():
    E, E0 = e["total"], e["total"][0]
    W, Dv, Df = e["contact_work"], e["dissipation"], e["friction_dissipation"]
    closure = max(abs(E[i] - E0 - (W[i] - Dv[i] - Df[i])) for i in range(len(E)))
    it = h["newton_iterations"]; act = h["contact_floor_active"]
    itc = [i for i, a in zip(it, act) if a > 0]
    tm = open(os.path.join(runs, n + ".time")).read().split()[-1] if os.path.exists(os.path.join(runs, n + ".time")) else ""
    rows.append(dict(variant=n, E0=E0, E_end=E[-1], drift_end_rel=(E[-1] - E0) / E0,
        max_dev_rel=max(abs(x - E0) for x in E) / E0, contact_work=W[-1], viscous_diss=Dv[-1], friction_diss=Df[-1],
        max_balance=max(abs(x) for x in e["balance_residual"]), closure_max=closure, closure_rel=closure / E0,
        min_gap=min(h["contact_floor_min_gap"]), steps=len(it), contact_steps=len(itc),
        newton_median=statistics.median(it), newton_median_contact=statistics.median(itc) if itc else 0,
        newton_max=max(it), newton_total=sum(it), wall_s=tm))
keys = list(rows[0].keys())
with open(os.path.join(docs, "s1_summary.csv"), "w") as f:
    f.write(",".join(keys) + "\n")
    for r in rows: f.write(",".join(("%.6g" % r[k]) if isinstance(r[k], float) else str(r[k]) for k in keys) + "\n")
with open(os.path.join(docs, "s1_summary.md"), "w") as f:
    f.write("| variant | E0 | E_end − E0 (rel) | max abs(E − E0)/E0 | contact work | viscous D | friction D | max abs(balance)/step | closure max abs(E−E0−(W_c−D_v−D_f)) (rel) | min gap | Newton median (all / contact steps) | max | wall s |\n")
    f.write("|" + "---|" * 13 + "\n")
    for r in rows:
        f.write("| %s | %.6g | %.3e | %.3e | %.4g | %.4g | %.4g | %.2e | %.2e (%.1e) | %.2e | %g / %g | %d | %s |\n" % (
            r["variant"], r["E0"], r["drift_end_rel"], r["max_dev_rel"], r["contact_work"], r["viscous_diss"], r["friction_diss"],
            r["max_balance"], r["closure_max"], r["closure_rel"], r["min_gap"], r["newton_median"], r["newton_median_contact"],
            r["newton_max"], r["wall_s"]))
print(open(os.path.join(docs, "s1_summary.md")).read())
PY

cd "$DOCS"
plot() {  # png, title, ylabel, csv, ncols
  local png=$1 title=$2 ylab=$3 csv=$4
  local n; n=$(head -1 "$csv" | awk -F, '{print NF}')
  gnuplot <<GP
set terminal pngcairo size 900,560 font ",11"
set output "$png"
set datafile separator ","
set key autotitle columnhead bottom left opaque box
set title "$title"
set xlabel "time [s]"
set ylabel "$ylab"
set grid
plot for [i=2:$n] "$csv" using 1:i with lines lw 2
GP
}
plot s1a_energy.png "S1(a) ring impact, eta = 0, frictionless: total energy" "E = K + W [J/m]" s1a_energy.csv
plot s1a_denergy.png "S1(a): E_{n+1} - E_n per step" "E_{n+1} - E_n [J/m]" s1a_denergy.csv
plot s1b_energy.png "S1(b) persistence, viscosity sweep (mu = 0): total energy" "E [J/m]" s1b_energy.csv
plot s1b_denergy.png "S1(b): E_{n+1} - E_n per step" "E_{n+1} - E_n [J/m]" s1b_denergy.csv
plot s1c_energy.png "S1(c) persistence, friction sweep (eta = 0): total energy" "E [J/m]" s1c_energy.csv
plot s1c_denergy.png "S1(c): E_{n+1} - E_n per step" "E_{n+1} - E_n [J/m]" s1c_denergy.csv
plot s1d_energy.png "S1(d) persistence, friction + viscosity: total energy" "E [J/m]" s1d_energy.csv
plot s1d_denergy.png "S1(d): E_{n+1} - E_n per step" "E_{n+1} - E_n [J/m]" s1d_denergy.csv
plot s1_balance.png "S1: balance residual E_{n+1} - E_n - (W_contact - D_visc - D_fric) per step" "residual [J/m]" s1_balance.csv

if [ "${S2:-1}" != 0 ]; then
  echo "== S2 torus"
  S2RUN=$(dirname "$RUNS")/s2
  /usr/bin/time -f "%e" -o "$S2RUN.time" "$EXE" "$ROOT/inputs/s2_torus.xml" --output "$S2RUN" > "$S2RUN.log" 2>&1
  python3 - "$S2RUN" "$DOCS" <<'PY'
import csv, statistics, sys
run, docs = sys.argv[1], sys.argv[2]
e = list(csv.DictReader(open(run + "/s2_torus_energy.csv"))); h = list(csv.DictReader(open(run + "/s2_torus_history.csv")))
with open(docs + "/s2_energy.csv", "w") as f:
    f.write("time,kinetic,strain,total,contact_work,balance_residual\n")
    for r in e: f.write(",".join(r[k] for k in ("time", "kinetic", "strain", "total", "contact_work", "balance_residual")) + "\n")
E0 = float(e[0]["total"]); it = [int(r["newton_iterations"]) for r in h]; act = [float(r["contact_floor_active"]) for r in h]
with open(docs + "/s2_summary.md", "w") as f:
    f.write("| E0 | max abs(E − E0)/E0 | max abs(balance)/step | contact work | p_z start → end | steps with contact | max active nodes | min gap | Newton median (all / contact steps), max | wall s |\n|---|---|---|---|---|---|---|---|---|---|\n")
    f.write("| %.6g | %.2e | %.2e | %s | %.5g → %.5g | %d | %d | %.2e | %g / %g, %d | %s |\n" % (E0, max(abs(float(r["total"]) - E0) for r in e) / E0,
        max(abs(float(r["balance_residual"])) for r in e), e[-1]["contact_work"], float(e[0]["momentum_z"]), float(e[-1]["momentum_z"]),
        sum(a > 0 for a in act), max(act), min(float(r["contact_floor_min_gap"]) for r in h), statistics.median(it),
        statistics.median([i for i, a in zip(it, act) if a > 0]), max(it), open(run + ".time").read().split()[-1]))
print(open(docs + "/s2_summary.md").read())
PY
  gnuplot <<GP
set terminal pngcairo size 900,560 font ",11"
set output "$DOCS/s2_energy.png"
set datafile separator ","
set key autotitle columnhead center right opaque box
set title "S2 torus on a rigid plane (frictionless, Gonzalez + persistence): energies"
set xlabel "time [s]"; set ylabel "energy [J]"; set grid
plot for [i=2:4] "$DOCS/s2_energy.csv" using 1:i with lines lw 2
GP
fi
echo "plots and CSVs in $DOCS"
