#!/usr/bin/python3
"""Stability map of the contact scheme combinations (docs/studies/README.md, section 4).

Scene S3 (inputs/s3_ring_foundation.xml: a ring thrown at a deformable foundation block,
frictionless, node-to-segment contact) with the foundation at the talk's artery constants
(C1 = 0.5 MPa, C2 = 5 kPa, D = 0.35 MPa) and the ring CONTRAST times stiffer (1: S3 as
shipped; 400: the talk's stent/artery ratio, C1 = 200 MPa; 1e4), thrown in S3's direction
(3, -5)/|(3, -5)| at V m/s (5.83: S3's speed; 50: an extreme impact), integrated to T with dt = DT0 * factor
(factor 1, 4, 16) by each scheme with the persistence condition (and gonzalez with the gap
condition), with the deck's default step control (cut-backs allowed, Stepping->min dt and
max steps as documented). Every run has a wall-time limit (LIMIT s); none should need it.

Recorded per run: outcome (completed, exit 3 with the reason, or killed at the limit),
cut-backs, Newton iterations per accepted step, the energy error max |E - E0| / E0 and the
balance residual max |balance| / E0 over the run, wall time.

  perf/studies/contact_stability.py [stentor]        (default build-dev/stentor)
Environment: SCHEMES="gonzalez midpoint newmark hht", CONTRASTS="1 400 1e4", SPEEDS="5.83 50",
  DIRECTION="0.514 -0.857" (unit vector of the throw),
  FACTORS="1 4 16", OTHER_CONTRASTS (for the combinations other than gonzalez +
  persistence; default CONTRASTS), DT0=0.001, T=0.1, SIZE=0.1 (ring mesh size), LIMIT=300,
  WORK=<run folder> (default /tmp/stentor_contact_stability), PLOT_ONLY=1,
  CSV=<file> (default docs/studies/contact_stability.csv; the PNG takes its name).
Writes docs/studies/contact_stability.csv and contact_stability.png.
"""
import os
import re
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import studylib as sl  # noqa: E402

env = os.environ.get
STENTOR = os.path.abspath(sys.argv[1] if len(sys.argv) > 1 else os.path.join(sl.ROOT, "build-dev", "stentor"))
SCHEMES = env("SCHEMES", "gonzalez midpoint newmark hht").split()
CONTRASTS = [float(c) for c in env("CONTRASTS", "1 400 1e4").split()]
SPEEDS = [float(v) for v in env("SPEEDS", "5.83 50").split()]
FACTORS = [int(f) for f in env("FACTORS", "1 4 16").split()]
# contrasts for the combinations other than gonzalez + persistence (default: the same)
OTHER_CONTRASTS = [float(c) for c in env("OTHER_CONTRASTS", env("CONTRASTS", "1 400 1e4")).split()]
DT0 = float(env("DT0", "0.001"))
T = float(env("T", "0.1"))
SIZE = float(env("SIZE", "0.1"))
LIMIT = int(env("LIMIT", "300"))
WORK = os.path.abspath(env("WORK", "/tmp/stentor_contact_stability"))
OUT = os.path.join(sl.ROOT, "docs", "studies")
CSV = os.path.abspath(env("CSV", os.path.join(OUT, "contact_stability.csv")))
PNG = os.path.splitext(CSV)[0] + ".png"
ARTERY = (0.5e6, 0.005e6, 0.35e6)
# S3's direction (3, -5)/|(3, -5)|. Straight down (DIRECTION="0 -1") the ring's lowest node
# lands exactly on a foundation node and Newton cycles there (docs/studies/README.md).
DIRECTION = [float(c) for c in env("DIRECTION", "0.5144957554 -0.8574929257").split()]
COMBOS = [(s, "persistence") for s in SCHEMES] + ([("gonzalez", "gap")] if "gonzalez" in SCHEMES else [])
HEADER = ["scheme", "formulation", "contrast", "speed", "factor", "dt", "outcome", "reason", "steps", "cutbacks",
          "newton", "newton_per_step", "drift", "balance", "wall_s", "cpu_s"]


def deck(scheme, form, contrast, v, factor):
    name = "%s_%s_c%g_v%g_f%d" % (scheme, form, contrast, v, factor)
    d = sl.Deck(os.path.join(sl.INPUTS, "s3_ring_foundation.xml"))
    d.set("Mesh/size", SIZE, "double")
    for k, c in zip(("C1", "C2", "D"), ARTERY):
        d.set("Materials/foundation/%s" % k, c)
        d.set("Materials/rubber/%s" % k, c * contrast)
    d.set("Bodies/ring/initial velocity", (DIRECTION[0] * v, DIRECTION[1] * v))
    d.set("Time Integration/scheme", scheme)
    d.set("Contact/impact/formulation", form)
    d.set("Stepping/end time", T)
    d.set("Stepping/steps", max(1, int(round(T / (DT0 * factor)))))
    d.set("Output/basename", "run")
    d.set("Output/fields", False, "bool")
    return name, d.write(os.path.join(WORK, name + ".xml"))


def measure_deck(name, path, key, dt, stentor, work, limit):
    """Run one generated deck (wall-time limit `limit` s, outputs under work/name) and return its CSV
    row (HEADER); key = (scheme, formulation, contrast, speed, factor). Shared with
    contact_stability_s2.py."""
    scheme, form, contrast, v, factor = key
    r = sl.run(stentor, path, os.path.join(work, name), name, limit_s=limit, reuse=bool(env("REUSE")))
    e = r.csv("energy", "run")
    if r.timed_out:
        outcome, reason = "killed", "wall-time limit %d s" % limit
    elif r.rc == 0:
        outcome, reason = "completed", ""
    else:
        outcome = "exit %d" % r.rc
        reason = r.failure()[:160]
    drift = balance = ""
    if e and len(e["total"]) > 1:
        e0 = e["total"][0]
        drift = max(abs(x - e0) for x in e["total"]) / e0
        balance = max(abs(x) for x in e["balance_residual"]) / e0
    row = [scheme, form, contrast, v, factor, dt, outcome, reason, r.steps, r.cutbacks, r.newton,
           r.newton / r.steps if r.steps else "", drift, balance, r.wall, r.cpu]
    print("  %-9s %-11s contrast %-6g v %-3g dt x%-3d %-9s steps %-4d cut-backs %-4d newton/step %-5s drift %-8s %6.1f s %s"
          % (scheme, form, contrast, v, factor, outcome, r.steps, r.cutbacks,
             "%.1f" % row[11] if r.steps else "-", "%.1e" % drift if drift != "" else "-", r.wall, reason[:60]),
          flush=True)
    return row


def measure(scheme, form, contrast, v, factor):
    name, path = deck(scheme, form, contrast, v, factor)
    return measure_deck(name, path, (scheme, form, contrast, v, factor), DT0 * factor, STENTOR, WORK, LIMIT)


def plot(csv_path=None, png=None, dt0=None, title=None, xlabel="stiffness contrast ring:foundation, impact speed",
         xtick="%g:1\n%g m/s", note=None):
    """The colour map of a stability CSV (HEADER); defaults: this study's CSV, PNG, DT0 and title.
    note(row): an optional extra line of text for a cell (None: none). Shared with
    contact_stability_s2.py."""
    csv_path = csv_path or CSV
    png = png or PNG
    dt0 = DT0 if dt0 is None else dt0
    title = title or "S3 stability map, T = %g s" % T
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.colors import ListedColormap, BoundaryNorm
    rows = sl.read_rows(csv_path)
    combos = []
    for r in rows:
        if (r["scheme"], r["formulation"]) not in combos:
            combos.append((r["scheme"], r["formulation"]))
    cols = sorted({(float(r["contrast"]), float(r["speed"])) for r in rows})
    facs = sorted({int(r["factor"]) for r in rows})
    # cell value: 0 completed without cut-back, 1 completed with cut-backs, 2 exit 3, 3 killed
    cmap = ListedColormap(["#4caf50", "#ffeb3b", "#ff9800", "#d32f2f"])
    fig, axes = plt.subplots(1, len(combos), figsize=(4.2 * len(combos), 4.2), squeeze=False)
    for ax, (s, f) in zip(axes[0], combos):
        grid = [[float("nan")] * len(cols) for _ in facs]  # not run: blank
        text = [["not run"] * len(cols) for _ in facs]
        for r in rows:
            if (r["scheme"], r["formulation"]) != (s, f):
                continue
            i, j = facs.index(int(r["factor"])), cols.index((float(r["contrast"]), float(r["speed"])))
            o = r["outcome"]
            grid[i][j] = 0 if o == "completed" and int(r["cutbacks"]) == 0 else 1 if o == "completed" else \
                3 if o == "killed" else 2
            nps = float(r["newton_per_step"]) if r["newton_per_step"] else 0.0
            text[i][j] = ("%s/%d\n%.0e" % ("%.1f" % nps if nps < 10 else "%.0f" % nps, int(r["cutbacks"]), float(r["drift"]))
                          if o == "completed" and r["drift"] else o)
            if note and note(r):
                text[i][j] += "\n" + note(r)
        ax.imshow(grid, cmap=cmap, norm=BoundaryNorm([-0.5, 0.5, 1.5, 2.5, 3.5], 4), aspect="auto", origin="lower")
        for i in range(len(facs)):
            for j in range(len(cols)):
                ax.text(j, i, text[i][j], ha="center", va="center", fontsize=7)
        ax.set_xticks(range(len(cols)), [xtick % c for c in cols], fontsize=7)
        ax.set_yticks(range(len(facs)), ["%g ms" % (dt0 * x * 1e3) for x in facs])
        ax.set_xlabel(xlabel)
        ax.set_ylabel("time step")
        ax.set_title("%s + %s" % (s, f))
    fig.suptitle("%s. Cells: Newton iterations per step / cut-backs, energy error "
                 "max|E-E0|/E0. Green: completed; yellow: with cut-backs; orange: exit 3; red: killed" % title,
                 fontsize=9)
    fig.tight_layout()
    fig.savefig(png, dpi=90)
    plt.close(fig)


def main():
    if env("PLOT_ONLY"):
        plot()
        return
    print(sl.banner(STENTOR), flush=True)
    rows = []
    for s, f in COMBOS:
        for c in (CONTRASTS if (s, f) == ("gonzalez", "persistence") else OTHER_CONTRASTS):
            for v in SPEEDS:
                for k in FACTORS:
                    rows.append(measure(s, f, c, v, k))
    os.makedirs(OUT, exist_ok=True)
    sl.write_csv(CSV, HEADER, rows)
    with open(os.path.splitext(CSV)[0] + "_machine.txt", "w") as fh:
        fh.write(sl.banner(STENTOR) + "\n")
    plot()
    print("== wrote %s and %s" % (CSV, PNG))


if __name__ == "__main__":
    main()
