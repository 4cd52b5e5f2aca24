#!/usr/bin/env bash
# Scene S3 (talk): the S1 ring thrown onto a deformable foundation (contact between two
# meshed bodies). Runs inputs/s3_ring_foundation.xml variants, then writes energy plots
# (PNG), compact CSVs and a summary table into docs/scenes/.
#   usage: perf/scenes/run_s3.sh [build-dir]     (default build; needs gnuplot, python3)
#   env:   S3_RUNS (raw output dir, default <build>/scenes/s3)
# Variants: frictionless; mu = 0.3; a foundation 1000x stiffer (C1, C2, D x 1000), whose
# history is compared with S1 on the rigid plane (inputs/s1_ring.xml, same mesh size); the
# frictionless and mu = 0.3 runs again with the dual mortar discretization (s3_mortar_*).
set -euo pipefail
ROOT=$(cd "$(dirname "$0")/../.." && pwd)
BUILD=${1:-$ROOT/build}
EXE=$BUILD/stentor
RUNS=${S3_RUNS:-$BUILD/scenes/s3}
DOCS=$ROOT/docs/scenes
mkdir -p "$RUNS" "$DOCS"
[ -x "$EXE" ] || { echo "no $EXE: build it first"; exit 1; }

run() {  # name deck
  echo "== $1"
  /usr/bin/time -f "%e" -o "$RUNS/$1.time" "$EXE" --output "$RUNS/$1" "$2" > "$RUNS/$1.log" 2>&1 || {
    echo "   FAILED (see $RUNS/$1.log)"; tail -3 "$RUNS/$1.log"; }
  tail -2 "$RUNS/$1.log" | head -1
}
base=$ROOT/inputs/s3_ring_foundation.xml
geo="s|value=\"s3_ring_foundation.geo\"|value=\"$ROOT/inputs/s3_ring_foundation.geo\"|"
sed -e "$geo" -e "/name=\"basename\"/s|value=\"[^\"]*\"|value=\"s3_mu0\"|" "$base" > "$RUNS/s3_mu0.xml"
sed -e "$geo" -e "/name=\"friction\"/s|value=\"[^\"]*\"|value=\"0.3\"|" \
    -e "/name=\"basename\"/s|value=\"[^\"]*\"|value=\"s3_mu0.3\"|" "$base" > "$RUNS/s3_mu0.3.xml"
# Stiff foundation: the second material's constants x 1000 (lines after <ParameterList name="foundation">).
python3 - "$RUNS/s3_mu0.xml" "$RUNS/s3_stiff.xml" <<'PY'
import re, sys
s = open(sys.argv[1]).read()
i = s.index('<ParameterList name="foundation">')
j = s.index('</ParameterList>', i)
block = re.sub(r'name="(C1|C2|D)" type="double" value="([^"]*)"',
               lambda m: 'name="%s" type="double" value="%g"' % (m.group(1), float(m.group(2)) * 1000), s[i:j])
s = (s[:i] + block + s[j:]).replace('value="s3_mu0"', 'value="s3_stiff"')
open(sys.argv[2], "w").write(s)
PY
for v in s3_mu0 s3_mu0.3; do
  m=${v/s3_/s3_mortar_}
  sed -e "s|<Parameter name=\"master\" type=\"string\" value=\"foundation_top\"/>|&<Parameter name=\"discretization\" type=\"string\" value=\"mortar\"/>|" \
      -e "/name=\"basename\"/s|value=\"[^\"]*\"|value=\"$m\"|" "$RUNS/$v.xml" > "$RUNS/$m.xml"
done
sed -e "s|value=\"ring.geo\"|value=\"$ROOT/inputs/ring.geo\"|" \
    -e "/name=\"basename\"/s|value=\"[^\"]*\"|value=\"s1_rigid\"|" "$ROOT/inputs/s1_ring.xml" > "$RUNS/s1_rigid.xml"
if [ "${S3_SKIP_RUNS:-0}" != 1 ]; then   # S3_SKIP_RUNS=1: only redo the tables and plots
  for v in s3_mu0 s3_mu0.3 s3_stiff s1_rigid s3_mortar_mu0 s3_mortar_mu0.3; do run "$v" "$RUNS/$v.xml"; done
fi

python3 - "$RUNS" "$DOCS" <<'PY'
import csv, os, statistics, sys
runs, docs = sys.argv[1], sys.argv[2]
def read(path):
    with open(path) as f:
        rows = list(csv.DictReader(f))
    return {k: [float(x[k]) for x in rows] for k in rows[0]}
data = {}
for n in ["s3_mu0", "s3_mu0.3", "s3_stiff", "s1_rigid", "s3_mortar_mu0", "s3_mortar_mu0.3"]:
    d = os.path.join(runs, n)
    data[n] = (read(os.path.join(d, n + "_energy.csv")), read(os.path.join(d, n + "_history.csv")),
               float(open(os.path.join(runs, n + ".time")).read().split()[-1]))
with open(os.path.join(docs, "s3_energy.csv"), "w") as f:
    w = csv.writer(f)
    w.writerow(["time"] + [n + "_" + k for n in data for k in ("total", "friction_dissipation")])
    e0 = data["s3_mu0"][0]
    for i in range(len(e0["time"])):
        row = [e0["time"][i]]
        for n in data:
            e = data[n][0]
            row += [e["total"][i] if i < len(e["total"]) else "", e.get("friction_dissipation", [0] * (i + 1))[i] if i < len(e["total"]) else ""]
        w.writerow(row)
lines = ["| run | E0 [J/m] | max \\|E - E0\\|/E0 | E(T) + D_fric(T) - E0 (rel.) | max \\|balance\\| per step | contact steps | Newton median / max | wall [s] |",
         "|---|---|---|---|---|---|---|---|"]
for n, (e, h, t) in data.items():
    E0 = e["total"][0]
    dev = max(abs(x - E0) for x in e["total"]) / E0
    fr = e.get("friction_dissipation", [0.0] * len(e["total"]))
    closure = (e["total"][-1] + fr[-1] - E0) / E0
    bal = max(abs(x) for x in e["balance_residual"])
    act = [k for k in h if k.endswith("_active")][0]
    nc = sum(1 for a in h[act] if a > 0)
    newton = h["newton_iterations"]
    lines.append("| %s | %.6g | %.2e | %.2e | %.2e | %d | %g / %d | %.1f |" % (n, E0, dev, closure, bal, nc, statistics.median(newton), max(newton), t))
# Stiff foundation vs S1: ring's contact force history (y) against the rigid plane's.
fs, fr_ = data["s3_stiff"][1], data["s1_rigid"][1]
ks = [k for k in fs if k.endswith("_force_y")][0]; kr = [k for k in fr_ if k.endswith("_force_y")][0]
m = min(len(fs[ks]), len(fr_[kr]))
def impulse(h, k):
    return sum(h[k][i] * h["dt"][i] for i in range(m))
Is, Ir = impulse(fs, ks), impulse(fr_, kr)
lines.append("")
lines.append("Stiff foundation (x1000) vs S1 on the rigid plane (same ring mesh, same steps): normal impulse on the ring "
             "%.6g vs %.6g N s/m (%.2f %%); peak contact force %.6g vs %.6g N/m; kinetic energy at T %.6g vs %.6g J/m (%.2f %%)."
             % (Is, Ir, 100 * (Is - Ir) / Ir, max(abs(x) for x in fs[ks][:m]), max(abs(x) for x in fr_[kr][:m]),
                data["s3_stiff"][0]["kinetic"][-1], data["s1_rigid"][0]["kinetic"][-1],
                100 * (data["s3_stiff"][0]["kinetic"][-1] - data["s1_rigid"][0]["kinetic"][-1]) / data["s1_rigid"][0]["kinetic"][-1]))
open(os.path.join(docs, "s3_summary.md"), "w").write("\n".join(lines) + "\n")
print("\n".join(lines))
PY
gnuplot <<GP
set terminal pngcairo size 900,560 noenhanced
set output "$DOCS/s3_energy.png"
set datafile separator ","
set key autotitle columnhead outside bottom horizontal
set title "S3: ring on a deformable foundation - total energy of both bodies"
set xlabel "time [s]"; set ylabel "energy [J/m]"
plot "$DOCS/s3_energy.csv" using 1:2 with lines lw 2 title "frictionless: E", \
     "" using 1:4 with lines lw 2 title "mu = 0.3: E", \
     "" using 1:(\$4+\$5) with lines dt 2 lw 2 title "mu = 0.3: E + D_fric", \
     "" using 1:6 with lines lw 1 title "stiff foundation: E", \
     "" using 1:8 with lines lw 1 dt 3 title "S1 rigid plane: E"
GP
echo "wrote $DOCS/s3_summary.md, s3_energy.csv, s3_energy.png"
