#!/usr/bin/python3
"""Scene S4: error of the stent metrics against cost (docs/studies/README.md, section 5).

Each run is inputs/s4_stent_artery.xml (stent in an artery: insertion, inflation,
extraction of a rigid capsule balloon; gonzalez + persistence; mu = 0.2 on the
stent-artery pair; the deck's cut-backs allowed) with
  - the stent-artery pair's Contact->stent_artery->discretization (DISCS:
    node-to-segment, mortar),
  - the time step: every stage's `steps` (50 in the deck) times F (FACTORS; F = 2 halves
    dt); the deck's step control (cut-backs) stays on, so dt is the largest step,
  - the mesh: refinement r (MESHES) divides both mesh-size parameters of
    inputs/s4_stent_artery.geo, the artery's h = 0.1 and the struts' hs = 0.04, by r
    (a wrapper .geo sets h and hs and includes the shipped one, as tests/cli/decks/par_s4.geo
    does). The .geo keeps the segment count of the struts' 120-degree arcs odd (5 in the
    deck, 7 at r = 1.5, 11 at r = 2), so a facet, not a node, faces the wall; the strut
    centres x = 1.55 + k are half a wall element off the wall's nodes at r = 1, a quarter at
    r = 1.5 and on a node at r = 2 (then the strut facet's midpoint faces the node: the odd
    arcs alone made mu = 0 complete, docs/scenes/README.md "Robustness").
Measured per run: the stent metrics at the end of each stage (the log's "metrics at the
end of '<stage>': ..." and "stage maxima: ..." lines; the full-precision values of
<basename>_stages.csv when the run wrote it), steps, cut-backs and Newton iterations (the
Summary line), wall and CPU (user + system) time (/usr/bin/time), the largest per-step
energy-balance residual |balance_residual| [J/m] (<basename>_energy.csv).
Error of a metric = |value - value of the reference|, where the reference is the run of the
SAME discretization on the finest mesh (largest r) with F = FREF; the CSV also has the
difference to the OTHER discretization's reference (xerr_*), and the plots draw the gap
between the two references, so that one sees whether both converge to the same answer.

  perf/studies/s4_precision.py [stentor]          (default build-study/stentor)
Environment: DISCS="node-to-segment mortar", FACTORS="0.5 1 2", MESHES="1 1.5" (the grid
  MESHES x FACTORS is run), FREF=4 and RREF (default: the largest r) the reference's F and
  mesh, EXTRA="r:F ..." more runs outside the grid (e.g. "1:4 2:8"), MU=0.2,
  WORK=/tmp/stentor_s4_precision, LIMIT=900 (s per run), REUSE=1 (load runs already made
  in WORK), NO_NEW_RUNS=1 (with REUSE: runs not in WORK are left out, not run),
  PLOT_ONLY=1 (redraw from the CSV), TABLE=1 (print the README's tables from the CSVs),
  ORDER="ref" (run the references first).
  SWEEP=mu: instead, the cost of the default deck per mu (MUS="0 0.1 0.2 0.3 0.4") and
  discretization, on the deck's mesh, at each F of SWEEP_F (default "1")
  -> docs/studies/s4_mu_cost.csv.
Writes docs/studies/s4_precision.csv, s4_precision_machine.txt, s4_precision_*.png.
"""
import math
import os
import re
import subprocess
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import studylib as sl  # noqa: E402

env = os.environ.get
STENTOR = os.path.abspath(sys.argv[1] if len(sys.argv) > 1 else os.path.join(sl.ROOT, "build-study", "stentor"))
DISCS = env("DISCS", "node-to-segment mortar").split()
FACTORS = [float(f) for f in env("FACTORS", "0.5 1 2").split()]
MESHES = [float(r) for r in env("MESHES", "1 1.5").split()]
FREF = float(env("FREF", "4"))
# extra runs outside the MESHES x FACTORS grid, "r:F r:F ..." (e.g. the reference's own checks)
EXTRA = [tuple(float(x) for x in p.split(":")) for p in env("EXTRA", "").split()]
RREF = float(env("RREF", "0")) or max(MESHES + [r for r, _ in EXTRA])  # the reference's mesh
MU = float(env("MU", "0.2"))
MUS = [float(m) for m in env("MUS", "0 0.1 0.2 0.3 0.4").split()]
WORK = os.path.abspath(env("WORK", "/tmp/stentor_s4_precision"))
LIMIT = int(env("LIMIT", "900"))
REUSE = bool(env("REUSE"))
NO_NEW_RUNS = bool(env("NO_NEW_RUNS"))
OUT = os.path.join(sl.ROOT, "docs", "studies")
CSV = os.path.join(OUT, "s4_precision.csv")
MU_CSV = os.path.join(OUT, "s4_mu_cost.csv")
DECK = os.path.join(sl.INPUTS, "s4_stent_artery.xml")
GEO = os.path.join(sl.INPUTS, "s4_stent_artery.geo")
H, HS, STEPS = 0.1, 0.04, 50  # the .geo's h and hs, the deck's steps per stage
STAGES = ["insertion", "inflation", "extraction"]

# metrics per stage: (CSV column of <basename>_stages.csv, log key, scale to the reported unit)
METRICS = ["lumen_radius", "lumen_gain", "stent_radius", "radial_recoil", "dogboning", "foreshortening",
           "pressure_max", "von_mises_max"]
STAGE_COL = {"lumen_radius": "lumen_radius_mean", "lumen_gain": "lumen_gain", "stent_radius": "stent_radius_mean",
             "radial_recoil": "radial_recoil", "dogboning": "dogboning", "foreshortening": "foreshortening",
             "pressure_max": "stage_contact_pressure_max", "von_mises_max": "stage_artery_von_mises_max"}
PERCENT = {"lumen_gain", "radial_recoil", "dogboning", "foreshortening"}  # stored in % (points)
# the metrics the errors, plots and README use: (stage index 1..3, metric, label)
ERRORS = [(2, "lumen_gain", "lumen gain, end of inflation [% points]"),
          (2, "dogboning", "dogboning, end of inflation [% points]"),
          (2, "foreshortening", "foreshortening, end of inflation [% points]"),
          (2, "pressure_max", "peak contact pressure, inflation [relative]"),
          (3, "radial_recoil", "radial recoil, end of extraction [% points]"),
          (3, "lumen_gain", "lumen gain, end of extraction [% points]")]


def fmt(x):
    return "%g" % x


def run_name(disc, r, f, mu=None):
    short = {"node-to-segment": "nts", "mortar": "mortar"}[disc]
    return "s4_%s_r%s_F%s%s" % (short, fmt(r), fmt(f), "" if mu is None else "_mu%s" % fmt(mu))


def deck(disc, r, f, mu):
    name = run_name(disc, r, f, None if mu == MU else mu)
    folder = os.path.join(WORK, name)
    d = sl.Deck(DECK)
    if r != 1:
        geo = os.path.join(WORK, "s4_r%s.geo" % fmt(r))
        os.makedirs(WORK, exist_ok=True)
        with open(geo, "w") as g:
            g.write("// S4 mesh refined by %s (perf/studies/s4_precision.py)\nh = %.17g;\nhs = %.17g;\nInclude \"%s\";\n"
                    % (fmt(r), H / r, HS / r, GEO))
        d.set("Mesh/file", geo)
    d.set("Contact/stent_artery/discretization", disc, "string")
    d.set("Contact/stent_artery/friction", mu)
    for s in STAGES:
        d.set("Stages/%s/steps" % s, int(round(STEPS * f)))
    d.set("Output/basename", "run")
    d.set("Output/fields", False, "bool")
    return name, d.write(os.path.join(folder + ".xml")), folder


def timed_run(name, deck_path, folder):
    """stentor under /usr/bin/time (wall %e, CPU %U + %S) and a wall-time limit."""
    meta = os.path.splitext(deck_path)[0] + ".json"
    if REUSE and os.path.exists(meta):
        return sl.Run.load(meta)
    if NO_NEW_RUNS:
        return None
    tf = os.path.splitext(deck_path)[0] + ".time"
    cmd = ["/usr/bin/time", "-f", "%e %U %S", "-o", tf, "timeout", str(LIMIT), STENTOR, "--overwrite", "--output",
           folder, deck_path]
    p = subprocess.run(cmd, capture_output=True, text=True)
    log = p.stdout + p.stderr
    with open(os.path.join(os.path.dirname(deck_path), name + ".log"), "w") as f:
        f.write(log)
    wall, user, sys_ = (float(x) for x in open(tf).read().split()[-3:])
    r = sl.Run(name, folder, p.returncode, wall, user + sys_, log)
    r.save(meta)
    return r


def parse_stages(log):
    """{stage name: {metric: value}} from the log's end-of-stage lines (percent metrics in %)."""
    out = {}
    num = r"([-+0-9.eE]+)"
    for m in re.finditer(r"metrics at the end of '([^']+)': (.*)\n\s*stage maxima: (.*)", log):
        a, b = m.group(2), m.group(3)
        v = {}
        for key, pat in (("lumen_radius", r"lumen radius " + num), ("lumen_gain", r"gain " + num + "%"),
                         ("stent_radius", r"stent radius " + num), ("radial_recoil", r"recoil " + num + "%"),
                         ("dogboning", r"dogboning " + num + "%"), ("foreshortening", r"foreshortening " + num + "%")):
            mm = re.search(pat, a)
            if mm:
                v[key] = float(mm.group(1))
        for key, pat in (("pressure_max", r"contact pressure " + num), ("von_mises_max", r"von Mises " + num)):
            mm = re.search(pat, b)
            if mm:
                v[key] = float(mm.group(1))
        out[m.group(1)] = v
    return out


def measure(disc, r, f, mu=MU):
    name, path, folder = deck(disc, r, f, mu)
    run = timed_run(name, path, folder)
    row = {"discretization": disc, "mesh_r": r, "h": H / r, "hs": HS / r, "F": f, "mu": mu,
           "dt_nominal": 1.0 / (STEPS * f), "name": name}
    if run is None:
        print("  %-34s not run (NO_NEW_RUNS)" % name, flush=True)
        return None
    done = run.rc == 0 and "Results in" in run.log
    row.update(rc=run.rc, completed=int(done), steps=run.steps, cutbacks=run.cutbacks, newton=run.newton,
               wall_s=run.wall, cpu_s=run.cpu, failure="" if done else run.failure())
    m = re.search(r"(\d+) nodes", run.log)
    row["nodes"] = m.group(1) if m else ""
    stages = parse_stages(run.log)
    csvd = folder if os.path.isdir(folder) else folder + ".partial"
    full = sl.read_csv(os.path.join(csvd, "run_stages.csv"))
    for i, s in enumerate(STAGES, start=1):
        v = stages.get(s, {})
        for k in METRICS:
            x = v.get(k)
            if full and len(full.get("stage", [])) >= i and STAGE_COL[k] in full:
                x = full[STAGE_COL[k]][i - 1] * (100.0 if k in PERCENT else 1.0)
            if x is not None:
                row["s%d_%s" % (i, k)] = x
    e = sl.read_csv(os.path.join(csvd, "run_energy.csv"))
    if e:
        row["balance_max"] = max(abs(x) for x in e["balance_residual"])
        row["energy_max"] = max(abs(x) for x in e["total"])
    print("  %-34s rc=%d steps=%-4d cut-backs=%-4d newton=%-6d wall=%6.1f s cpu=%6.1f s%s" %
          (name, run.rc, run.steps, run.cutbacks, run.newton, run.wall, run.cpu,
           "  gain2 %.2f%% dog2 %.2f%% recoil3 %.2f%%" % (row.get("s2_lumen_gain", float("nan")),
                                                        row.get("s2_dogboning", float("nan")),
                                                        row.get("s3_radial_recoil", float("nan")))
           if done else "  (failed: %s)" % row["failure"][:100]), flush=True)
    return row


def err_key(stage, metric):
    return "s%d_%s" % (stage, metric)


def diff(a, b, metric):
    if metric == "pressure_max":
        return abs(a - b) / abs(b) if b else float("nan")
    return abs(a - b)


HEADER = (["name", "discretization", "mesh_r", "h", "hs", "F", "dt_nominal", "mu", "nodes", "rc", "completed",
           "steps", "cutbacks", "newton", "wall_s", "cpu_s", "balance_max", "energy_max", "reference"] +
          ["s%d_%s" % (i, k) for i in (1, 2, 3) for k in METRICS] +
          ["err_" + err_key(s, m) for s, m, _ in ERRORS] + ["xerr_" + err_key(s, m) for s, m, _ in ERRORS] +
          ["failure"])


def errors(rows):
    refs = {r["discretization"]: r for r in rows if r["mesh_r"] == RREF and r["F"] == FREF and r.get("completed")}
    for r in rows:
        r["reference"] = int(r["mesh_r"] == RREF and r["F"] == FREF)
        if not r.get("completed"):
            continue
        own = refs.get(r["discretization"])
        other = next((v for k, v in refs.items() if k != r["discretization"]), None)
        for s, m, _ in ERRORS:
            k = err_key(s, m)
            if own is not None and k in r and k in own:
                r["err_" + k] = diff(r[k], own[k], m)
            if other is not None and k in r and k in other:
                r["xerr_" + k] = diff(r[k], other[k], m)
    return [[r.get(k, "") for k in HEADER] for r in rows]


def plot():
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    rows = sl.read_rows(CSV)
    refs = {r["discretization"]: r for r in rows if r["reference"] == "1" and r["completed"] == "1"}
    rref, fref = (float(next(iter(refs.values()))[k]) for k in ("mesh_r", "F")) if refs else (RREF, FREF)
    meshes = sorted({float(r["mesh_r"]) for r in rows})
    colors = {"node-to-segment": "tab:blue", "mortar": "tab:red"}
    styles = ["-o", "--s", ":^", "-.v"]
    fig, axes = plt.subplots(2, 3, figsize=(17, 9.5))
    for ax, (s, m, label) in zip(axes.flat, ERRORS):
        k = err_key(s, m)
        for disc in DISCS:
            for j, rr in enumerate(meshes):
                pts = [r for r in rows if r["discretization"] == disc and float(r["mesh_r"]) == rr
                       and r["reference"] == "0" and r.get("err_" + k, "") != ""]
                pts.sort(key=lambda r: float(r["F"]))
                if not pts:
                    continue
                x = [float(r["cpu_s"]) for r in pts]
                y = [max(float(r["err_" + k]), 1e-4) for r in pts]
                ax.loglog(x, y, styles[j % len(styles)], color=colors.get(disc), label="%s, h/%s" % (disc, fmt(rr)))
                for xi, yi, r in zip(x, y, pts):
                    ax.annotate("F=%s" % fmt(float(r["F"])), (xi, yi), fontsize=7, textcoords="offset points",
                                xytext=(3, 3))
        if len(refs) == 2 and all(k in r and r[k] != "" for r in refs.values()):
            a, b = (float(refs[d][k]) for d in DISCS)
            g = diff(a, b, m)
            ax.axhline(max(g, 1e-4), color="k", ls="--", lw=1, label="|mortar - node-to-segment| of the references")
        ax.set(xlabel="CPU time of the run [s]", ylabel="error " + ("(relative)" if m == "pressure_max" else
                                                                    "[% points]"), title=label)
        ax.grid(True, which="both", alpha=0.3)
    h_, l_ = axes.flat[0].get_legend_handles_labels()
    fig.legend(h_, l_, loc="lower center", ncol=5, fontsize=8)
    fig.suptitle("S4 (mu = %g): |metric - reference of the same discretization| against CPU time; reference: "
                 "mesh h/%s, F = %s (dt = 1/%d s), one per discretization; floor 1e-4" %
                 (MU, fmt(rref), fmt(fref), int(round(STEPS * fref))))
    fig.tight_layout(rect=(0, 0.06, 1, 1))
    fig.savefig(os.path.join(OUT, "s4_precision_error.png"), dpi=80)
    plt.close(fig)
    # the values themselves against the mesh: does each discretization settle, and on what?
    fig, axes = plt.subplots(2, 3, figsize=(17, 9.5))
    factors = sorted({float(r["F"]) for r in rows})
    fstyle = {f: st for f, st in zip(factors, ["o", "s", "^", "v", "D", "P"])}
    for ax, (s, m, label) in zip(axes.flat, ERRORS):
        k = err_key(s, m)
        for disc in DISCS:
            for f in factors:
                pts = sorted([r for r in rows if r["discretization"] == disc and float(r["F"]) == f
                              and r["completed"] == "1" and r.get(k, "") != ""], key=lambda r: float(r["mesh_r"]))
                if not pts:
                    continue
                scale = 1e-3 if m == "pressure_max" else 1.0
                ax.plot([float(r["mesh_r"]) for r in pts], [scale * float(r[k]) for r in pts],
                        "-" + fstyle[f], color=colors.get(disc), alpha=0.35 + 0.65 * (f / max(factors)),
                        label="%s, F = %s (dt = 1/%d s)" % (disc, fmt(f), int(round(STEPS * f))))
        ax.set(xlabel="mesh refinement r (h = 0.1/r, hs = 0.04/r)",
               ylabel=label.split("[")[0].strip() + (" [kPa]" if m == "pressure_max" else " [%]"),
               title=label.replace(" [relative]", " [kPa]").replace("% points", "%"))
        ax.grid(True, alpha=0.3)
    h_, l_ = axes.flat[0].get_legend_handles_labels()
    fig.legend(h_, l_, loc="lower center", ncol=5, fontsize=8)
    fig.suptitle("S4 (mu = %g): the metrics against the mesh, per discretization (colour) and time step (marker)" % MU)
    fig.tight_layout(rect=(0, 0.07, 1, 1))
    fig.savefig(os.path.join(OUT, "s4_precision_values.png"), dpi=80)
    plt.close(fig)
    # cost: CPU time and cut-backs against the nominal step
    fig, ax = plt.subplots(1, 3, figsize=(17, 5))
    for disc in DISCS:
        for j, rr in enumerate(meshes):
            pts = sorted([r for r in rows if r["discretization"] == disc and float(r["mesh_r"]) == rr
                          and r["completed"] == "1"], key=lambda r: float(r["F"]))
            if not pts:
                continue
            lbl = "%s, h/%s" % (disc, fmt(rr))
            dt = [1e3 * float(r["dt_nominal"]) for r in pts]
            ax[0].loglog(dt, [float(r["cpu_s"]) for r in pts], styles[j % 4], color=colors.get(disc), label=lbl)
            ax[1].semilogx(dt, [int(r["cutbacks"]) for r in pts], styles[j % 4], color=colors.get(disc), label=lbl)
            ax[2].semilogx(dt, [int(r["newton"]) / int(r["steps"]) for r in pts], styles[j % 4],
                           color=colors.get(disc), label=lbl)
    ax[0].set(xlabel="nominal time step 1/(50 F) [ms]", ylabel="CPU time [s]", title="cost")
    ax[1].set(xlabel="nominal time step 1/(50 F) [ms]", ylabel="cut-backs per run", title="cut-backs")
    ax[2].set(xlabel="nominal time step 1/(50 F) [ms]", ylabel="Newton iterations per accepted step",
              title="Newton iterations (failed attempts included) / steps")
    for a in ax:
        a.grid(True, which="both", alpha=0.3)
    ax[0].legend(fontsize=8)
    fig.suptitle("S4 (mu = %g): cost against the step, per discretization and mesh" % MU)
    fig.tight_layout()
    fig.savefig(os.path.join(OUT, "s4_precision_cost.png"), dpi=80)
    plt.close(fig)


def machine_text():
    """The studies' banner plus `stentor --version` (the executable's commit)."""
    try:
        v = subprocess.run([STENTOR, "--version"], capture_output=True, text=True).stdout.strip().replace("\n", "; ")
    except OSError:
        v = "?"
    return sl.banner(STENTOR) + "\nstentor --version: " + v + "\n"


def mu_sweep():
    print(machine_text(), flush=True)
    header = ["name", "discretization", "mu", "F", "rc", "completed", "steps", "cutbacks", "newton", "wall_s", "cpu_s",
              "balance_max", "s2_lumen_gain", "s2_dogboning", "s3_radial_recoil", "failure"]
    rows = []
    for f in [float(x) for x in env("SWEEP_F", "1").split()]:
        for mu in MUS:
            for disc in DISCS:
                r = measure(disc, 1.0, f, mu)
                if r is not None:
                    rows.append([r.get(k, "") for k in header])
    sl.write_csv(MU_CSV, header, rows)
    with open(os.path.join(OUT, "s4_mu_cost_machine.txt"), "w") as f:
        f.write(machine_text())
    print("== wrote %s" % MU_CSV)


def table():
    """The README's tables (markdown) from the CSVs."""
    rows = sl.read_rows(CSV)
    rows.sort(key=lambda r: (r["discretization"] != "node-to-segment", float(r["mesh_r"]), float(r["F"])))
    g = lambda r, k, f="%.2f": (f % float(r[k])) if r.get(k, "") != "" else "–"
    print("| discretization | mesh | F (dt) | steps | cut-backs | Newton | CPU [s] | wall [s] | max balance [J/m] |"
          " lumen gain 2 [%] | dogboning 2 [%] | foreshortening 2 [%] | p_max 2 [kPa] | recoil 3 [%] | lumen gain 3 [%] |"
          " error gain 2 / dog 2 / fore 2 / p 2 / recoil 3 / gain 3 |")
    print("|" + "---|" * 16)
    for r in rows:
        errs = " / ".join(("%.0f%%" % (100 * float(r["err_" + err_key(s, m)])) if m == "pressure_max" else
                           "%.2f" % float(r["err_" + err_key(s, m)])) if r.get("err_" + err_key(s, m), "") != ""
                          else "–" for s, m, _ in ERRORS)
        print("| %s | h/%s (%s nodes) | %s (1/%d s)%s | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s |" % (
            r["discretization"], r["mesh_r"], r["nodes"], r["F"], int(round(STEPS * float(r["F"]))),
            " **ref**" if r["reference"] == "1" else "", r["steps"], r["cutbacks"], r["newton"], g(r, "cpu_s", "%.1f"),
            g(r, "wall_s", "%.1f"), g(r, "balance_max", "%.1e"), g(r, "s2_lumen_gain"), g(r, "s2_dogboning"),
            g(r, "s2_foreshortening"), "%.0f" % (float(r["s2_pressure_max"]) / 1e3) if r.get("s2_pressure_max") else "–",
            g(r, "s3_radial_recoil"), g(r, "s3_lumen_gain"), errs if r["reference"] == "0" else "(reference)"))
    if os.path.exists(MU_CSV):
        print()
        print("| mu | discretization | F | steps | cut-backs | Newton | CPU [s] | wall [s] | lumen gain 2 [%] | recoil 3 [%] |")
        print("|" + "---|" * 10)
        for r in sorted(sl.read_rows(MU_CSV), key=lambda r: (float(r["F"]), float(r["mu"]), r["discretization"])):
            print("| %s | %s | %s | %s | %s | %s | %s | %s | %s | %s |" % (
                r["mu"], r["discretization"], r["F"], r["steps"], r["cutbacks"], r["newton"], g(r, "cpu_s", "%.1f"),
                g(r, "wall_s", "%.1f"), g(r, "s2_lumen_gain"), g(r, "s3_radial_recoil")))


def main():
    if env("TABLE"):
        table()
        return
    if env("PLOT_ONLY"):
        plot()
        return
    if env("SWEEP") == "mu":
        mu_sweep()
        return
    text = machine_text()
    print(text, flush=True)
    if not NO_NEW_RUNS:  # the machine as the runs start
        os.makedirs(OUT, exist_ok=True)
        with open(os.path.join(OUT, "s4_precision_machine.txt"), "w") as f:
            f.write(text)
    t0 = time.monotonic()
    plan = [(d, RREF, FREF) for d in DISCS]
    grid = sorted(set([(r, f) for r in MESHES for f in FACTORS] + EXTRA) - {(RREF, FREF)})
    plan += [(d, r, f) for r, f in grid for d in DISCS]
    if env("ORDER") != "ref":  # the references last
        plan = plan[len(DISCS):] + plan[:len(DISCS)]
    rows = [x for x in (measure(*p) for p in plan) if x is not None]
    os.makedirs(OUT, exist_ok=True)
    sl.write_csv(CSV, HEADER, errors(rows))
    plot()
    print("== wrote %s and s4_precision_*.png (%.0f s)" % (CSV, time.monotonic() - t0))


if __name__ == "__main__":
    main()
