#!/usr/bin/env bash
# Scene S4-axi, dynamic (inputs/s4_axi_dynamic.xml: the procedure of inputs/s4_axi.xml with
# every stage dynamic, Gonzalez, persistence contact). Runs the deck once on one rank, times
# it (wall and CPU: /usr/bin/time, the whole process with meshing and plots), prints the
# energy audit of <basename>_energy.csv (the per-step defect of E_{n+1} - E_n = W_ext + W_sup
# - D + W_contact - D_friction and its sum over the run, relative to the largest total
# energy E = K + W and to the largest energy column) and writes docs/scenes/
# s4axi_dynamic_stages.csv (the metrics and energies of each stage).
#   usage: perf/scenes/run_s4axi_dynamic.sh [build-dir]     (default build)
#   env:   S4AXI_RUNS (raw output dir, default <build>/scenes/s4axi_dynamic); S4AXI_SKIP_RUN=1
#          (report the last run again)
set -euo pipefail
ROOT=$(cd "$(dirname "$0")/../.." && pwd)
BUILD=${1:-$ROOT/build}
EXE=$BUILD/stentor
RUNS=${S4AXI_RUNS:-$BUILD/scenes/s4axi_dynamic}
DOCS=$ROOT/docs/scenes
[ -x "$EXE" ] || { echo "no $EXE: build it first"; exit 1; }
mkdir -p "$RUNS" "$DOCS"
if [ "${S4AXI_SKIP_RUN:-0}" != 1 ]; then
  rm -rf "$RUNS/out" "$RUNS/out.partial"
  /usr/bin/time -f "%e %U %S" -o "$RUNS/time" "$EXE" --output "$RUNS/out" "$ROOT/inputs/s4_axi_dynamic.xml" > "$RUNS/log" 2>&1 ||
    { echo "S4-axi dynamic FAILED (see $RUNS/log)"; exit 1; }
fi
read -r wall user sys < "$RUNS/time"
grep -E "^Summary|^Energy balance|^  (mesh|newton|contact|assembly) +[0-9]|metrics at the end" "$RUNS/log"
echo "S4-axi dynamic: wall $wall s, CPU $(echo "$user + $sys" | bc) s (user $user, sys $sys), load average $(cut -d' ' -f1 /proc/loadavg)"
python3 - "$RUNS/out/s4_axi_dynamic_energy.csv" <<'PY'
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
f = lambda r, k: float(r[k])
E = max(abs(f(r, "total")) for r in rows)
big = max(abs(f(r, k)) for r in rows for k in ("total", "contact_work", "dissipation", "friction_dissipation"))
step = max(abs(f(r, "balance_residual")) for r in rows)
a, b = rows[0], rows[-1]
run = f(b, "total") - f(a, "total") - (f(b, "external_work") + f(b, "support_work") - f(b, "dissipation")
                                       + f(b, "contact_work") - f(b, "friction_dissipation"))
K = max(f(r, "kinetic") for r in rows)
print(f"energy audit ({len(rows)} rows): largest E = K + W {E:.6g}, largest energy column {big:.6g}")
print(f"  max |defect| per step {step:.3e} = {step / E:.2e} E = {step / big:.2e} of the largest column")
print(f"  defect over the run   {run:.3e} = {run / E:.2e} E")
print(f"  at the end: E {f(b, 'total'):.6g}, W_contact {f(b, 'contact_work'):.6g}, D_plastic {f(b, 'plastic_dissipation'):.6g}, "
      f"D_friction {f(b, 'friction_dissipation'):.4g}; largest kinetic energy {K:.3e} = {K / E:.2e} E")
PY
cp "$RUNS/out/s4_axi_dynamic_stages.csv" "$DOCS/s4axi_dynamic_stages.csv"
echo "wrote $DOCS/s4axi_dynamic_stages.csv"
