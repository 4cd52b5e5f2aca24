#!/usr/bin/env bash
# Mesh convergence of the S6 ring's metrics (docs/stent.md, "Mesh convergence"):
# inputs/s6_ring_quarter.xml with N x N cells through the strut's width and thickness for
# each N given (default 3 4 5; a plastic body needs 3 or more), the cells along the struts
# refined in proportion (the default `element length` is the strut width / N), run one
# after the other on 1 rank. Printed per mesh: cells, wall time, Newton iterations, and
# from <basename>_metrics.csv the mean outer diameter at the peak of the expansion and at
# the end, the radial recoil, the foreshortening at the peak and at the end, the
# longitudinal recoil and the largest equivalent plastic strain; then, for three meshes,
# the observed order p of each metric, solving
#   (f1 - f2) / (f2 - f3) = (h1^p - h2^p) / (h2^p - h3^p),  h = 1 / N,
# and the extrapolated value f3 + (f3 - f2) h3^p / (h2^p - h3^p).
# A run that fails or runs past TIMEOUT (seconds, env; none by default) gives its metrics
# up to where it stopped: the peak's columns, "-" for the end's. TECH=f-bar (env) runs the
# stent with `element technology` = f-bar instead of the fully integrated hex8. DECK (env, a
# deck of inputs/; default s6_ring_quarter.xml) studies another generated stent, e.g.
# DECK=s6_stent.xml (the 6-ring stent's sector), which adds the dogboning at the peak.
# Usage: perf/studies/s6_mesh_convergence.sh [STENTOR] [N ...]
#   STENTOR defaults to build/stentor; output folders in a temporary directory (KEEP=1 keeps it).
set -euo pipefail
here=$(cd "$(dirname "$0")/../.." && pwd)
stentor=${1:-$here/build/stentor}
shift || true
meshes=("$@")
[ ${#meshes[@]} -eq 0 ] && meshes=(3 4 5)
tmp=$(mktemp -d)
[ "${KEEP:-0}" = 1 ] || trap 'rm -rf "$tmp"' EXIT
deck=$here/inputs/${DECK:-s6_ring_quarter.xml}
base=$(sed -n 's|.*name="basename" type="string" value="\([^"]*\)".*|\1|p' "$deck")
[ -n "$base" ] || { echo "no Output->basename in $deck"; exit 1; }
for n in "${meshes[@]}"; do
  sed -e "s|\"elements through width\" type=\"int\" value=\"3\"|\"elements through width\" type=\"int\" value=\"$n\"|" \
      -e "s|\"elements through thickness\" type=\"int\" value=\"3\"|\"elements through thickness\" type=\"int\" value=\"$n\"|" \
      -e 's|"every" type="int" value="5"|"every" type="int" value="40"|' \
      -e "s|<Parameter name=\"material\" type=\"string\" value=\"steel\"/>|&${TECH:+<Parameter name=\"element technology\" type=\"string\" value=\"$TECH\"/>}|" \
      "$deck" > "$tmp/n$n.xml"
  start=$(date +%s.%N)
  OMP_NUM_THREADS=1 ${TIMEOUT:+timeout $TIMEOUT} "$stentor" --output "$tmp/out$n" "$tmp/n$n.xml" > "$tmp/log$n.txt" 2>&1 \
    || { tail -3 "$tmp/log$n.txt"; echo "N = $n stopped (exit status $?): its metrics up to there (the partial folder)"; }
  [ -d "$tmp/out$n" ] || mv "$tmp/out$n.partial" "$tmp/out$n"
  end=$(date +%s.%N)
  echo "$n $(echo "$end - $start" | bc)" >> "$tmp/times.txt"
  echo "N = $n done: $(grep -m1 '^Summary' "$tmp/log$n.txt")"
done
python3 - "$tmp" "$base" "${meshes[@]}" <<'PY'
import csv, math, re, sys
tmp, base, meshes = sys.argv[1], sys.argv[2], [int(n) for n in sys.argv[3:]]
times = dict(l.split() for l in open(f"{tmp}/times.txt"))
rows = {}
for n in meshes:
    log = open(f"{tmp}/log{n}.txt").read()
    cells = re.search(r"(\d+) cells", log)
    summ = re.search(r"Summary: (\d+) steps, (\d+) cut-backs, (\d+) Newton", log)
    done = summ is not None and "FAILED" not in log
    with open(f"{tmp}/out{n}/{base}_metrics.csv") as f:
        data = list(csv.DictReader(f))
    D = [float(r["D_mean [mm]"]) for r in data]
    ip = max(range(len(D)), key=lambda i: D[i])
    peak, end = data[ip], data[-1]
    nan = float("nan")
    m = {"D peak [mm]": D[ip], "D min at peak [mm]": float(peak["D_min [mm]"]), "D max at peak [mm]": float(peak["D_max [mm]"]),
         "foreshortening peak %": 100 * float(peak["foreshortening [-]"]), "max eps_p at peak": float(peak["eps_p_max [-]"]),
         "D end [mm]": D[-1] if done else nan, "radial recoil %": 100 * float(end["radial_recoil [-]"]) if done else nan,
         "foreshortening end %": 100 * float(end["foreshortening [-]"]) if done else nan,
         "longitudinal recoil %": 100 * float(end["longitudinal_recoil [-]"]) if done else nan}
    if "dogboning [-]" in peak:
        m["dogboning at peak %"] = 100 * float(peak["dogboning [-]"])
    rows[n] = m
    print(f"N = {n}: {cells.group(1) if cells else '?'} cells, {float(times[str(n)]):.0f} s wall, "
          + (f"{summ.group(1)} steps, {summ.group(2)} cut-backs, {summ.group(3)} Newton iterations" if done else
             f"stopped at t = {end['time']}") + f" (peak at t = {peak['time']})")
names = list(rows[meshes[0]].keys())
print("| metric | " + " | ".join(f"N = {n}" for n in meshes) + (" | observed order p | extrapolated |" if len(meshes) == 3 else " |"))
print("|---" * (len(meshes) + 1 + (2 if len(meshes) == 3 else 0)) + "|")
for k in names:
    f = [rows[n][k] for n in meshes]
    line = f"| {k} | " + " | ".join(f"{v:.5f}" if v == v else "-" for v in f)
    if len(meshes) == 3 and all(v == v for v in f):
        h = [1.0 / n for n in meshes]
        d1, d2 = f[0] - f[1], f[1] - f[2]
        p = float("nan")
        if d2 != 0 and d1 / d2 > 0:
            g = lambda p: (h[0]**p - h[1]**p) / (h[1]**p - h[2]**p) - d1 / d2
            lo, hi = 0.05, 12.0
            if g(lo) * g(hi) < 0:
                for _ in range(200):
                    mid = 0.5 * (lo + hi)
                    (lo, hi) = (mid, hi) if g(lo) * g(mid) > 0 else (lo, mid)
                p = 0.5 * (lo + hi)
        ext = f[2] - d2 * h[2]**p / (h[1]**p - h[2]**p) if p == p else float("nan")  # f3 + (f3 - f2) ...
        line += f" | {p:.2f} | {ext:.5f}" if p == p else " | none (not in the asymptotic range) | -"
    elif len(meshes) == 3:
        line += " | - | -"
    print(line + " |")
PY
