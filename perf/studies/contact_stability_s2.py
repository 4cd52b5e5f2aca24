#!/usr/bin/python3
"""Stability map of the contact schemes on scene S2 (docs/studies/README.md, section 4, "S2:
stability map"); the S3 map is contact_stability.py, whose run classification and colour map
this script reuses.

Scene S2 (inputs/s2_torus.xml: a 3D hyperelastic torus, R = 1, r = 0.25, thrown at the rigid
plane z = 0, frictionless, persistence contact). S2 has one body against a rigid wall, so the
"stiffness contrast" of the S3 map becomes a STIFFNESS FACTOR: the torus's C1, C2 and D are
FACTOR times the talk's soft artery constants (C1 = 0.5 MPa, C2 = 5 kPa, D = 0.35 MPa, those
of S2 as shipped and of the S3 map's foundation), at the same density (1000 kg/m^3). Factor 1
is S2 as shipped; 400 is the talk's stent/artery ratio (C1 = 200 MPa); 1e4 is extreme. Wave
speeds scale with sqrt(FACTOR) (x 1, 20, 100) and the contact and wave-transit times shrink
with it, so a fixed dt resolves fewer and fewer of them: the hard case for the step.

The torus is thrown in S2's direction (1, 0, -4)/sqrt(17) at V m/s (sqrt(17) = 4.12: S2's speed;
50: an extreme impact), integrated to T (default 0.096 s: the first impact, t = 0.013 ... 0.053 s
at S2's speed, and 43 ms of rebound) with dt = DT0 * factor (DT0 = the deck's 2 ms; factor 1 or
16), by each scheme with the persistence condition (and gonzalez with the gap condition), with
the deck's default step control (cut-backs allowed, Stepping->min dt and max steps as
documented in docs/deck.md). Every run has a wall-time limit (LIMIT s).

Recorded per run (the columns of contact_stability.py, "contrast" = the stiffness factor, plus
t_end, the time of the last step in the log, and min_gap, the smallest end-of-step gap of the
torus to the plane over the run (< 0: penetration, in m), and contact_time, the sum of dt over
the steps that end with a node in contact): outcome (completed, exit 3 with the reason, or
killed at the limit), steps, cut-backs, Newton iterations per accepted step, the energy error
max |E - E0| / E0 and the balance residual max |balance| / E0, wall and CPU time.

  perf/studies/contact_stability_s2.py [stentor]     (default build-dev/stentor)
Environment: SCHEMES="gonzalez newmark midpoint" (run in this order), GAP=1 (also gonzalez +
  gap; GAP=0: not), FACTORS_K="1 400 1e4" (stiffness factors), SPEEDS="4.1231056 50",
  FACTORS="1 16" (dt multiples), DT0=0.002, T=0.096, SIZE=0.12 (S2's mesh size), LIMIT=150,
  BUDGET=3600 (s of run wall time: no run is started once the study has used it; the cells
  not run are left out of the CSV and blank in the PNG), WORK=<run folder> (default
  /tmp/stentor_contact_stability_s2), REUSE=1 (reuse the runs already in WORK), PLOT_ONLY=1,
  CSV=<file> (default docs/studies/contact_stability_s2.csv; the PNG and _machine.txt take
  its name). The CSV is rewritten after every run. The PNG adds to each cell the deepest
  penetration below the plane at the end of a step (an arrow, from min_gap) when there is one,
  and the time reached by a run that did not complete.
"""
import math
import os
import re
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import studylib as sl  # noqa: E402
import contact_stability as cs  # noqa: E402  (S3 map: measure_deck, plot, HEADER, ARTERY)

env = os.environ.get
STENTOR = os.path.abspath(sys.argv[1] if len(sys.argv) > 1 else os.path.join(sl.ROOT, "build-dev", "stentor"))
SCHEMES = env("SCHEMES", "gonzalez newmark midpoint").split()
GAP = env("GAP", "1") != "0"
STIFF = [float(c) for c in env("FACTORS_K", "1 400 1e4").split()]
SPEEDS = [float(v) for v in env("SPEEDS", "4.1231056 50").split()]
FACTORS = [int(f) for f in env("FACTORS", "1 16").split()]
DT0 = float(env("DT0", "0.002"))
T = float(env("T", "0.096"))
SIZE = float(env("SIZE", "0.12"))
LIMIT = int(env("LIMIT", "150"))
BUDGET = float(env("BUDGET", "3600"))
WORK = os.path.abspath(env("WORK", "/tmp/stentor_contact_stability_s2"))
OUT = os.path.join(sl.ROOT, "docs", "studies")
CSV = os.path.abspath(env("CSV", os.path.join(OUT, "contact_stability_s2.csv")))
PNG = os.path.splitext(CSV)[0] + ".png"
DECK = os.path.join(sl.INPUTS, "s2_torus.xml")
DIRECTION = (1 / math.sqrt(17), 0.0, -4 / math.sqrt(17))  # S2's initial velocity (1, 0, -4) m/s
COMBOS = [(s, "persistence") for s in SCHEMES] + ([("gonzalez", "gap")] if GAP and "gonzalez" in SCHEMES else [])
HEADER = cs.HEADER + ["t_end", "min_gap", "contact_time"]


def deck(scheme, form, k, v, factor):
    name = "%s_%s_k%g_v%g_f%d" % (scheme, form, k, v, factor)
    d = sl.Deck(DECK)
    d.set("Mesh/size", SIZE, "double")
    for p, c in zip(("C1", "C2", "D"), cs.ARTERY):
        d.set("Materials/rubber/%s" % p, c * k)
    d.set("Initial Conditions/velocity", [u * v for u in DIRECTION])
    d.set("Time Integration/scheme", scheme)
    d.set("Contact/floor/formulation", form)
    d.set("Stepping/end time", T)
    d.set("Stepping/steps", max(1, int(round(T / (DT0 * factor)))))
    d.set("Output/basename", "run")
    d.set("Output/fields", False, "bool")
    return name, d.write(os.path.join(WORK, name + ".xml"))


def measure(scheme, form, k, v, factor):
    name, path = deck(scheme, form, k, v, factor)
    row = cs.measure_deck(name, path, (scheme, form, k, v, factor), T / max(1, int(round(T / (DT0 * factor)))),
                          STENTOR, WORK, LIMIT)
    # t_end: the last step in the log (a killed run writes no history); min_gap: the deepest
    # penetration at the end of a step (the history's contact_floor_min_gap; < 0: below the plane)
    with open(os.path.join(WORK, name + ".log")) as fh:
        times = re.findall(r"^\s*step\s+\d+\s+t\s+(\S+)", fh.read(), re.M)
    h = sl.read_csv(os.path.join(WORK, name, "run_history.csv"))
    gaps = h.get("contact_floor_min_gap", []) if h else []
    # contact_time: the time spent in contact, sum of dt over the steps with an active node
    tc = sum(dt for dt, a in zip(h["dt"], h["contact_floor_active"]) if a > 0) if gaps else ""
    return row + [float(times[-1]) if times else 0.0, min(gaps) if gaps else "", tc]


def plot():
    cs.plot(CSV, PNG, DT0, "S2 stability map (torus on a rigid plane, h = %g), T = %g s; \u2193: deepest penetration below the "
            "plane at a step end [m]" % (SIZE, T),
            "torus stiffness factor (x artery constants), impact speed", "x%g\n%.3g m/s",
            note)


def note(r):
    """Extra cell text: the deepest penetration (arrow), and the time reached by a run that did not complete."""
    t = [] if r["outcome"] == "completed" else ["t = %.2g s" % float(r["t_end"])]
    if r.get("min_gap") and float(r["min_gap"]) < 0:
        t.append("\u2193%.2g" % -float(r["min_gap"]))
    return "\n".join(t)


def main():
    if env("PLOT_ONLY"):
        plot()
        return
    print(sl.banner(STENTOR), flush=True)
    os.makedirs(OUT, exist_ok=True)
    rows, used, skipped = [], 0.0, []
    for s, f in COMBOS:
        for k in STIFF:
            for v in SPEEDS:
                for n in FACTORS:
                    if used >= BUDGET:
                        skipped.append("%s + %s, x%g, %g m/s, dt x%d" % (s, f, k, v, n))
                        continue
                    rows.append(measure(s, f, k, v, n))
                    used += rows[-1][cs.HEADER.index("wall_s")]
                    sl.write_csv(CSV, HEADER, rows)
    with open(os.path.splitext(CSV)[0] + "_machine.txt", "w") as fh:
        fh.write(sl.banner(STENTOR) + "\n")
    plot()
    print("== %d runs, %.0f s of run wall time; wrote %s and %s" % (len(rows), used, CSV, PNG))
    if skipped:
        print("== not run (BUDGET = %g s used up): %s" % (BUDGET, "; ".join(skipped)))


if __name__ == "__main__":
    main()
