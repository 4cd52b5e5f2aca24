#!/usr/bin/env bash
# Ironing (inputs/ironing.xml; docs/contact.md, Ironing): runs the ctest case
# ContactBenchmarks.IroningFrictionForcesAndDissipation on finer meshes, which prints one
# line per run (forces in steady sliding, Coulomb check, dissipation against the die's work)
# and writes <run>_dissipation.csv beside each results folder; then plots the force histories and the energy
# closure of the finest run into docs/scenes/ironing_forces.png and ironing_energy.png.
#   usage: perf/scenes/run_ironing.sh [build-dir]     (default build; needs python3-matplotlib)
#   env:   IRONING_RUNS (default "18 6 60 50; 36 12 60 100": slab cells x, y,
#          die facets, load steps; "54 18 90 150" and "72 24 120 200" fail, docs/contact.md)
set -euo pipefail
ROOT=$(cd "$(dirname "$0")/../.." && pwd)
BUILD=${1:-$ROOT/build}
EXE=$BUILD/test_contact_benchmarks
[ -x "$EXE" ] || { echo "no $EXE: build it first"; exit 1; }
RUNS=${IRONING_RUNS:-18 6 60 50; 36 12 60 100}
STENTOR_IRONING_RUNS="$RUNS" "$EXE" --gtest_filter=ContactBenchmarks.IroningFrictionForcesAndDissipation |
  grep -E '^\[ironing\]|OK|FAILED|Failure' || true
dirs=()
IFS=';' read -ra list <<< "$RUNS"
for r in "${list[@]}"; do
  set -- $r
  dirs+=("$BUILD/system_tests/contact_benchmarks/ironing_$1_$2_$3_$4")
done
/usr/bin/python3 - "$ROOT/docs/scenes" "${dirs[@]}" <<'PY'
import csv, os, sys
import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt

out, runs = sys.argv[1], sys.argv[2:]
def read(path):
    with open(path) as f:
        rows = list(csv.DictReader(f))
    return {k: [float(r[k]) for r in rows] for k in rows[0]}

fig, (a1, a2) = plt.subplots(2, 1, figsize=(8, 7), sharex=True)
for d in runs:
    h = read(os.path.join(d, "ironing_history.csv"))
    label = os.path.basename(d).replace("ironing_", "").split("_")
    label = "slab %sx%s, die %s facets, %s steps" % tuple(label)
    t = h["time"]
    a1.plot(t, h["contact_iron_force_x"], label="F_x (tangential), " + label)
    a1.plot(t, [-v for v in h["contact_iron_force_y"]], "--", label="-F_y (normal), " + label)
    a2.plot(t, [abs(x / y) if y else float("nan") for x, y in zip(h["contact_iron_force_x"], h["contact_iron_force_y"])], label=label)
a2.axhline(0.3, color="k", lw=0.8, ls=":", label="mu = 0.3")
a1.set_ylabel("contact force on the slab [force / unit thickness]")
a1.set_title("Ironing (plane strain, mu = 0.3): press 1.4 (t < 1), then slide 4 (1 < t < 5)")
a1.legend(fontsize=7)
a2.set_ylabel("|F_x / F_y| [-]")
a2.set_xlabel("load time t [-] (die x = 4 (t - 1) / 4 for t > 1)")
a2.set_ylim(0, 0.5)
a2.legend(fontsize=7)
fig.tight_layout()
fig.savefig(os.path.join(out, "ironing_forces.png"), dpi=110)

d = runs[-1]
e = read(d + "_dissipation.csv")
fig, a = plt.subplots(figsize=(8, 4.5))
a.plot(e["time"], e["support_work"], label="work of the die's supports W")
a.plot(e["time"], e["strain_energy"], label="stored energy E")
a.plot(e["time"], e["friction_dissipation"], label="frictional dissipation D (sum of lambda_t . slip)")
a.plot(e["time"], [w - s - x for w, s, x in zip(e["support_work"], e["strain_energy"], e["friction_dissipation"])], "k--",
       label="W - E - D")
a.set_xlabel("load time t [-]")
a.set_ylabel("energy [energy / unit thickness]")
a.set_title("Ironing energy closure: " + os.path.basename(d))
a.legend(fontsize=8)
fig.tight_layout()
fig.savefig(os.path.join(out, "ironing_energy.png"), dpi=110)
last = {k: v[-1] for k, v in e.items()}
print("finest run at t = %g: W %.5f, E %.5f, D %.5f, (W - E - D) / D = %+.2e" % (
    last["time"], last["support_work"], last["strain_energy"], last["friction_dissipation"],
    (last["support_work"] - last["strain_energy"] - last["friction_dissipation"]) / last["friction_dissipation"]))
PY
