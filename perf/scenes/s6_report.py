#!/usr/bin/python3
"""The plot and the tables of docs/scenes/s6_summary.md from two runs of the S6 procedure
(inputs/s6_stent_procedure.xml and inputs/s6_ring_sector.xml, or any generated stent taken
through stages): reads each run's <basename>_metrics.csv, _history.csv, _stages.csv, the
log's stage tables and the deck copy, writes

  OUT.png   two panels: (a) the stent's mean outer diameter against time (its smallest and
            largest shaded), the ring's alone, and the rigid tools' diameters, the stages'
            ends dashed and named; (b) each rigid
            tool's radial force against its diameter (crimper and balloon), the force of
            the whole device (the modelled part's times the number of copies that make it)

and prints the tables (markdown) on stdout: the runs (steps, cut-backs, Newton iterations,
wall time), each stage's end for the whole stent / ring, and the stent's rings at the
procedure's key points.

usage: s6_report.py OUT.png STENT_DIR:BASENAME[:LABEL] [RING_DIR:BASENAME[:LABEL]]
Needs Debian's python3-matplotlib, python3-h5py, python3-numpy.
"""
import csv
import os
import re
import sys
import xml.etree.ElementTree as ET

import h5py
import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np


def deck(path):
    root = ET.parse(path).getroot()
    params = {p.get("name"): p.get("value") for p in root.iter("Parameter")}
    stages = []
    for pl in root.iter("ParameterList"):
        if pl.get("name") == "Stages":
            stages = [s.get("name") for s in pl.findall("ParameterList")]
    return params, stages


def copies(run, params):
    """How many copies of the model make the whole stent: 360 / Theta around (the sector
    0 <= theta <= Theta), times 2 for a half length."""
    with h5py.File(os.path.join(run["dir"], run["base"] + ".h5"), "r") as f:
        x = f["mesh/coordinates"][()]
    theta = np.degrees(np.arctan2(x[:, 1], x[:, 0]))
    around = 1 if theta.min() < -1.0 else int(round(360.0 / theta.max()))
    return around * (2 if params.get("half length", "false").lower() == "true" else 1)


def rows(path):
    return [{k: float(v) if v not in ("", "nan", "-nan") else float("nan") for k, v in r.items()}
            for r in csv.DictReader(open(path))]


def log_tables(path):
    """{stage: {ring: [D start, D peak, D now, change %, recoil %, foreshortening %,
    dogboning % or None, max eps_p], 'links': eps_p, 'energy': (dE, D_plastic)}} from the
    log's stage tables, and the summary line."""
    out, cur, summary = {}, None, ""
    for line in open(path):
        m = re.match(r"\s*metrics at the end of '([^']+)'", line)
        if m:
            cur = out.setdefault(m.group(1), {})
            continue
        m = re.match(r"\s*(\d+|all)\s*\|(.*)", line)
        if cur is not None and m:
            vals = [v.strip() for v in m.group(2).split("|")]
            cur[m.group(1)] = [None if v == "-" else float(v) for v in vals]
            continue
        m = re.match(r"\s*links: max eps_p (\S+)", line)
        if cur is not None and m:
            cur["links"] = float(m.group(1))
        m = re.match(r"\s*stage energy: dE (\S+), D_plastic (\S+)", line)
        if cur is not None and m:
            cur["energy"] = (float(m.group(1)), float(m.group(2).rstrip(",")))
            cur = None
        if line.startswith("Summary:"):
            summary = line.strip()
    return out, summary


def output_path(run, suffix):
    """<run dir>/<basename><suffix>."""
    return os.path.join(run["dir"], run["base"] + suffix)


def load_run(spec):
    """A run's outputs from RUN_DIR:BASENAME[:LABEL]: the deck copy, the metrics, history and
    stages CSVs, the log's stage tables and summary, the model's symmetry copies."""
    parts = spec.split(":")
    run = {"dir": parts[0], "base": parts[1]}
    run["label"] = parts[2] if len(parts) > 2 else parts[1]
    run["params"], run["stages"] = deck(output_path(run, "_deck.xml"))
    run["metrics"] = rows(output_path(run, "_metrics.csv"))
    run["history"] = rows(output_path(run, "_history.csv"))
    run["stage_rows"] = rows(output_path(run, "_stages.csv"))
    run["log"], run["summary"] = log_tables(output_path(run, ".log"))
    run["copies"] = copies(run, run["params"])
    return run


def load(spec):
    run = load_run(spec)
    run["rings"] = sorted({int(m.group(1)) for k in run["metrics"][0]
                           for m in [re.match(r"ring(\d+)_D_mean", k)] if m})
    return run


def col(rows_, name):
    return np.array([r[name] for r in rows_])


def plot(out, runs):
    fig, (ax, bx) = plt.subplots(1, 2, figsize=(12, 4.6), gridspec_kw={"width_ratios": [1.25, 1]})
    stent = runs[0]
    t = col(stent["metrics"], "time")
    ax.fill_between(t, col(stent["metrics"], "D_min [mm]"), col(stent["metrics"], "D_max [mm]"), color="0.8",
                    label="%s: smallest to largest outer D" % stent["label"])
    ax.plot(t, col(stent["metrics"], "D_mean [mm]"), color="k", lw=1.2, label="%s: mean outer D" % stent["label"])
    for run in runs[1:]:
        ax.plot(col(run["metrics"], "time"), col(run["metrics"], "D_mean [mm]"), "o", ms=2.2, color="C2",
                label="%s: mean outer D" % run["label"])
    th = col(stent["history"], "time")
    for tool, color in (("crimper", "C0"), ("balloon", "C3")):
        ax.plot(th, col(stent["history"], "contact_%s_obstacle_diameter" % tool), ":", color=color, lw=1.2,
                label="%s diameter" % tool)
    ends = col(stent["stage_rows"], "time")
    ax.set_ylim(1.5, 4.45)
    for name, te, ts in zip(stent["stages"], ends, np.concatenate([[0.0], ends[:-1]])):
        ax.axvline(te, ls="--", color="0.6", lw=0.8)
        ax.text((ts + te) / 2, 4.4, name, ha="center", va="top", fontsize=8, color="0.3")
    ax.set_xlabel("pseudo-time t [s] (static stages)")
    ax.set_ylabel("diameter [mm]")
    ax.set_title("(a) diameters through the procedure", fontsize=10)
    ax.legend(fontsize=7.5, loc="lower right")
    ax.grid(alpha=0.3)

    marks = ["-", "--"]
    for i, run in enumerate(runs):
        h = run["history"]
        for tool, color in (("crimper", "C0"), ("balloon", "C3")):
            f = col(h, "contact_%s_normal_force" % tool) * run["copies"]
            d = col(h, "contact_%s_obstacle_diameter" % tool)
            on = np.nonzero(f > 0)[0]
            if not len(on):
                continue
            # from the step before the first contact to the last contact, then down to 0:
            # at the next step's diameter when the tool moved little, else at the last one
            idx = list(range(max(on[0] - 1, 0), on[-1] + 1))
            dd, ff = list(d[idx]), list(f[idx])
            nxt = on[-1] + 1
            if nxt < len(d) and abs(d[nxt] - d[on[-1]]) < 0.15:
                dd.append(d[nxt])
            else:
                dd.append(d[on[-1]])
            ff.append(0.0)
            bx.plot(dd, ff, marks[i % 2], color=color, lw=1.3,
                    label="%s, %s (model x %d)" % (tool, run["label"], run["copies"]))
    bx.annotate("crimp", xy=(2.5, 0.3), xytext=(2.9, 0.3), fontsize=8, color="C0", va="center",
                arrowprops=dict(arrowstyle="->", color="C0"))
    bx.annotate("expansion", xy=(3.3, 2.2), xytext=(2.55, 2.2), fontsize=8, color="C3", va="center",
                arrowprops=dict(arrowstyle="->", color="C3"))
    bx.set_xlabel("tool diameter [mm]")
    bx.set_ylabel("radial force on the tool, whole device [N]")
    bx.set_title("(b) rigid crimper and balloon: force against diameter", fontsize=10)
    bx.legend(fontsize=7.5)
    bx.grid(alpha=0.3)
    fig.suptitle("S6: the stent and its ring through crimp, spring-back, expansion and deflation "
                 "(316L, F-bar hex8)", fontsize=11)
    fig.tight_layout()
    fig.savefig(out, dpi=100)
    print("wrote", out, file=sys.stderr)


def tables(runs):
    print("\n### Runs\n")
    print("| deck | cells (model) | copies | summary |")
    print("|---|---|---|---|")
    for run in runs:
        with h5py.File(os.path.join(run["dir"], run["base"] + ".h5"), "r") as f:
            ncell = len(f["mesh/topology"])
        print("| %s | %d | %d | %s |" % (run["base"], ncell, run["copies"], run["summary"].replace("Summary: ", "")))
    for run in runs:
        n = run["copies"]
        print("\n### %s: each stage's end (whole %s)\n" % (run["base"], "stent" if len(run["rings"]) > 1 else "ring"))
        print("| stage end | t [s] | D at start [mm] | D at peak [mm] | D now [mm] | change | radial recoil "
              "| foreshortening | max eq. plastic strain | stored energy change [mJ] | plastic dissipation [mJ] |")
        print("|---|---|---|---|---|---|---|---|---|---|---|")
        for name, sr in zip(run["stages"], run["stage_rows"]):
            a = run["log"][name]["all"]
            de, dp = run["log"][name]["energy"]
            print("| %s | %.4g | %.4f | %.4f | %.4f | %+.3f %% | %.3f %% | %.3f %% | %.4f | %+.4f | %.4f |"
                  % (name, sr["time"], a[0], a[1], a[2], a[3], a[4], a[5], a[7], de * n, dp * n))
    stent = runs[0]
    if len(stent["rings"]) > 1 and len(stent["stages"]) == 4:
        c, s, e, d = stent["stages"]
        lg = stent["log"]
        print("\n### %s: per ring\n" % stent["base"])
        print("| ring | crimped [mm] | sprung back [mm] | spring-back | D at the peak [mm] | deflated [mm] "
              "| radial recoil | foreshortening (end) | dogboning at the peak | max eq. plastic strain |")
        print("|---|---|---|---|---|---|---|---|---|---|")
        last = str(stent["rings"][-1])
        for k in [str(r) for r in stent["rings"]] + ["all"]:
            name = {"0": "0 (end)", last: "%s (centre)" % last, "all": "stent"}.get(k, k)
            dog = lg[e][k][6]
            print("| %s | %.4f | %.4f | %.3f %% | %.4f | %.4f | %.3f %% | %.3f %% | %s | %.4f |"
                  % (name, lg[c][k][2], lg[s][k][2], lg[s][k][3], lg[e][k][1], lg[d][k][2], lg[d][k][4],
                     lg[d][k][5], "-" if dog is None else "%.3f %%" % dog, lg[d][k][7]))
        print("\n(links: max eq. plastic strain %.4f at the end)" % lg[d].get("links", float("nan")))
        m = stent["metrics"]
        print("\nLength as cut %.4f mm, at the peak %.4f mm, at the end %.4f mm; largest plastic strain %.4f "
              "in ring %d at crown %d, reference cell centroid (%.3f, %.3f, %.3f) mm"
              % (m[0]["length [mm]"], [r for r in m if abs(r["time"] - stent["stage_rows"][2]["time"]) < 1e-9][0]["length [mm]"],
                 m[-1]["length [mm]"], m[-1]["eps_p_max [-]"], m[-1]["eps_p_max_ring [-]"], m[-1]["eps_p_max_crown [-]"],
                 m[-1]["eps_p_max_x [mm]"], m[-1]["eps_p_max_y [mm]"], m[-1]["eps_p_max_z [mm]"]))
    for run in runs:
        h = run["history"]
        for tool in ("crimper", "balloon"):
            f = col(h, "contact_%s_normal_force" % tool) * run["copies"]
            d = col(h, "contact_%s_obstacle_diameter" % tool)
            if (f > 0).any():
                on = np.nonzero(f > 0)[0]
                print("%s %s: contact from tool diameter %.3f to %.3f mm, largest force %.3f N at %.3f mm "
                      "(whole device, model x %d)" % (run["base"], tool, d[on[0]], d[on[-1]], f.max(),
                                                      d[np.argmax(f)], run["copies"]))


def main():
    if len(sys.argv) < 3:
        sys.exit(__doc__)
    runs = [load(s) for s in sys.argv[2:]]
    plot(sys.argv[1], runs)
    tables(runs)


if __name__ == "__main__":
    main()
