#!/usr/bin/env bash
# Time to solution of the whole 4-step cube stretch (perf/decks/cube_p1.xml, cube_p2.xml:
# uniaxial 20%, Ciarlet-Geymonat rubber, symmetry constraints) and of the dynamic contact
# case (perf/decks/s2_torus_dynamic.xml: S2 through its first impact) with the
# Newton/linear solver variants of issue 14, on any number of ranks. One stentor run per row; prints a
# Markdown table (wall, CPU, peak memory per rank, Newton and GMRES iterations, linear
# set-up and solve time, final reaction of the pulled face) and keeps the logs.
#
#   perf/solve/time_to_solution.sh                              # P1 h=0.05, P2 h=0.1 (~24k DOF)
#   CASES="cube_p2:0.064" RANKS="1 2" perf/solve/time_to_solution.sh   # ~80k DOF P2
#   VARIANTS="base:predictor=none" perf/solve/time_to_solution.sh
#
# Environment: CASES ("deck:h" list), RANKS ("1"), VARIANTS (name:key=value,... with keys
# predictor (Stepping), forcing (Newton), reuse (Linear Solver->preconditioner reuse),
# preconditioner (Linear Solver), smoother (Linear Solver->MueLu->smoother: type)),
# BUILD (default build), OUT (default /tmp/stentor-tts), MPIFLAGS (mpirun options, default --bind-to none), PY (python3 with the standard library).
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
BUILD=$(cd "${BUILD:-$root/build}" && pwd)
STENTOR=$BUILD/stentor
CASES=${CASES:-"cube_p1:0.05 cube_p2:0.1"}
RANKS=${RANKS:-1}
VARIANTS=${VARIANTS:-"before:predictor=none default:predictor=auto ew:forcing=eisenstat-walker ew+reuse:forcing=eisenstat-walker,reuse=5"}
OUT=${OUT:-/tmp/stentor-tts}
PY=${PY:-/usr/bin/python3}
MPIFLAGS=${MPIFLAGS:---bind-to none}
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1
[ -x "$STENTOR" ] || { echo "time_to_solution: $STENTOR not found (build first, or set BUILD)" >&2; exit 2; }
mkdir -p "$OUT"
echo "machine: $(getconf _NPROCESSORS_ONLN) cores, load $(cut -d' ' -f1-3 /proc/loadavg), $(git -C "$root" rev-parse --short HEAD 2>/dev/null || echo "no git")"
echo "| case | DOF | ranks | variant | Newton | GMRES | wall [s] | CPU [s] | lin. set-up [s] | lin. solve [s] | peak RSS/rank [MB] | reaction x [N] |"
echo "|---|---|---|---|---|---|---|---|---|---|---|---|"
for c in $CASES; do
  deck=${c%%:*} h=${c#*:}
  for v in $VARIANTS; do
    name=${v%%:*} opts=${v#*:}
    for r in $RANKS; do
      tag=${deck}_h${h}_${name}_np${r}
      xml=$OUT/$tag.xml
      # The deck with Mesh->size, basename and the variant's parameters set.
      $PY - "$root/perf/decks/$deck.xml" "$xml" "$h" "$tag" "$opts" "$root" <<'PYEOF'
import sys, xml.etree.ElementTree as ET
src, dst, h, tag, opts, root = sys.argv[1:]
t = ET.parse(src); top = t.getroot()
def sub(name):
    for e in top.findall("ParameterList"):
        if e.get("name") == name: return e
    e = ET.SubElement(top, "ParameterList", name=name); return e
def setp(lst, name, typ, val):
    for e in lst.findall("Parameter"):
        if e.get("name") == name: e.set("value", val); return
    ET.SubElement(lst, "Parameter", name=name, type=typ, value=val)
mesh = sub("Mesh")
setp(mesh, "size", "double", h)
# The deck's mesh file, relative to perf/decks, made absolute (the copy lives in OUT).
import os
for e in mesh.findall("Parameter"):
    if e.get("name") == "file" and not os.path.isabs(e.get("value")):
        e.set("value", os.path.normpath(os.path.join(os.path.dirname(src), e.get("value"))))
setp(sub("Output"), "basename", "string", tag)
lin = sub("Linear Solver")
for e in list(lin.findall("Parameter")):
    if e.get("name") == "preconditioner": lin.remove(e)   # the default (auto) unless a variant sets it
keys = {"predictor": ("Stepping", "predictor", "string"), "forcing": ("Newton", "forcing", "string"),
        "reuse": ("Linear Solver", "preconditioner reuse", "int"),
        "preconditioner": ("Linear Solver", "preconditioner", "string")}
for kv in filter(None, opts.split(",")):
    k, v = kv.split("=")
    if k == "smoother":   # MueLu's smoother type (Linear Solver->MueLu->smoother: type)
        ml = next((e for e in lin.findall("ParameterList") if e.get("name") == "MueLu"), None)
        if ml is None: ml = ET.SubElement(lin, "ParameterList", name="MueLu")
        setp(ml, "smoother: type", "string", v); continue
    l, n, ty = keys[k]; setp(sub(l), n, ty, v)
t.write(dst)
PYEOF
      log=$OUT/$tag.log
      (cd "$OUT" && /usr/bin/time -f "TIME %e %U %S %M" mpirun -np "$r" $MPIFLAGS "$STENTOR" "$xml") >"$log" 2>&1 || true
      $PY - "$log" "$OUT/results/$tag/${tag}_history.csv" "$deck" "$h" "$r" "$name" <<'PYEOF'
import sys, re, csv
log, hist, deck, h, r, name = sys.argv[1:]
s = open(log).read()
g = lambda p, d="?": (re.search(p, s).group(1) if re.search(p, s) else d)
dofs = g(r"dofs\s+(\d+)")
summ = re.search(r"Summary: (\d+) steps, (\d+) cut-backs, (\d+) Newton iterations, (\d+) linear iterations", s)
newton, gmres = (summ.group(3), summ.group(4)) if summ else ("failed", "-")
t = re.search(r"TIME ([\d.]+) ([\d.]+) ([\d.]+) (\d+)", s)
wall, cpu, rss = (t.group(1), "%.1f" % (float(t.group(2)) + float(t.group(3))), "%.0f" % (int(t.group(4)) / 1024)) if t else ("?",) * 3
ls = re.search(r"linear set-up ([\d.]+) s in \d+ calls, \d+ preconditioner builds; linear solve ([\d.]+) s", s)
setup, solve = (ls.group(1), ls.group(2)) if ls else ("?", "?")
rx = "?"
try:
    rows = list(csv.DictReader(open(hist)))
    rx = "%.6g" % float(rows[-1]["reaction_pull_x"])
except Exception:
    pass
print(f"| {deck} h={h} | {dofs} | {r} | {name} | {newton} | {gmres} | {wall} | {cpu} | {setup} | {solve} | {rss} | {rx} |")
PYEOF
    done
  done
done
