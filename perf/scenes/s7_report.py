#!/usr/bin/python3
"""The plots and the tables of docs/scenes/s7_summary.md from runs of the S7 deck
(inputs/s7_ring_artery.xml: one strut of the S6 ring crimped, expanded into a stenosed
layered artery and deflated), e.g. frictionless and with friction on the wall: reads each
run's <basename>_metrics.csv, _history.csv, _stages.csv, the log's stage paragraphs, the
deck copy and the wall time render_s7.sh wrote (<run>.wall beside the run folder), writes

  DIAM.png     (a) the stent's mean outer diameter, the lumen's mean and minimum diameter
               (over the stented segment) and the balloon's diameter against time, every
               run, the stages' ends dashed and named; (b) the radial contact force of the
               wall on the stent and of the balloon, the whole ring's (the model's times
               the copies around)
  STRESS.png   the largest principal stress of each layer, its maximum and its 99th
               percentile over the layer's cells, against time (expansion and deflation),
               one panel per run

and prints the tables (markdown) on stdout.

usage: s7_report.py DIAM.png STRESS.png RUN_DIR:BASENAME[:LABEL] ...
Needs Debian's python3-matplotlib, python3-h5py, python3-numpy.
"""
import os
import re
import sys

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from s6_report import col, load_run, output_path  # noqa: E402

LAYERS = ["plaque", "intima", "media", "adventitia"]


def artery_lines(path):
    """{stage: {'lumen': (D0, D, gain %), 'mld': (D0, D, acute gain mm)}} from the log."""
    out, cur = {}, None
    num = r"([-+0-9.eE]+)"
    for line in open(path):
        m = re.match(r"\s*metrics at the end of '([^']+)'", line)
        if m:
            cur = out.setdefault(m.group(1), {})
            continue
        m = re.search(r"lumen D mean %s -> %s mm \(gain %s %%\), minimum lumen diameter %s -> %s mm "
                      r"\(acute gain %s mm\)" % ((num,) * 6), line)
        if cur is not None and m:
            v = [float(g) for g in m.groups()]
            cur["lumen"], cur["mld"] = tuple(v[:3]), tuple(v[3:])
    return out


def load(spec):
    run = load_run(spec)
    run["artery"] = artery_lines(output_path(run, ".log"))
    wall = os.path.normpath(run["dir"]) + ".wall"
    run["wall"] = open(wall).read().split(";")[0].split(":")[1].strip() if os.path.exists(wall) else "-"
    run["layers"] = [l for l in LAYERS if "%s_sigma1_max [MPa]" % l in run["metrics"][0]]
    return run


def at(rows_, t, name):
    r = min(rows_, key=lambda r: abs(r["time"] - t))
    return r[name]


def mark_stages(ax, run, top, t0=0.0):
    ends = col(run["stage_rows"], "time")
    for name, te, ts in zip(run["stages"], ends, np.concatenate([[0.0], ends[:-1]])):
        if te <= t0:
            continue
        ax.axvline(te, ls="--", color="0.6", lw=0.8)
        ax.text((max(ts, t0) + te) / 2, top, name, ha="center", va="top", fontsize=8, color="0.3",
                transform=ax.get_xaxis_transform())


def save(fig, out):
    """The figure as a PNG with a 256-colour palette (as render_stent.py; Debian's python3-pil,
    matplotlib's own dependency; a full-colour PNG without it)."""
    fig.savefig(out, dpi=100)
    try:
        from PIL import Image
        rgb = Image.open(out).convert("RGB")
        rgb.quantize(256, method=Image.Quantize.MEDIANCUT).save(out, optimize=True)
    except ImportError:
        pass
    print("wrote", out, file=sys.stderr)


def plot_diameters(out, runs):
    fig, (ax, bx) = plt.subplots(1, 2, figsize=(12.5, 4.8), gridspec_kw={"width_ratios": [1.2, 1]})
    styles = ["-", "--", ":"]
    for i, run in enumerate(runs):
        m, ls = run["metrics"], styles[i % 3]
        t = col(m, "time")
        ax.plot(t, col(m, "D_mean [mm]"), ls, color="k", lw=1.3, label="stent: mean outer D, %s" % run["label"])
        ax.plot(t, col(m, "lumen_D_mean [mm]"), ls, color="C0", lw=1.3, label="lumen: mean D, %s" % run["label"])
        ax.plot(t, col(m, "lumen_D_min [mm]"), ls, color="C1", lw=1.3,
                label="lumen: minimum D (MLD), %s" % run["label"])
    h = runs[0]["history"]
    th = col(h, "time")
    for tool, color in (("crimper", "C2"), ("balloon", "C3")):
        ax.plot(th, col(h, "contact_%s_obstacle_diameter" % tool), ":", color=color, lw=1.1,
                label="%s diameter" % tool)
    ax.set_ylim(1.5, 4.3)
    mark_stages(ax, runs[0], 0.99)
    ax.set_xlabel("pseudo-time t [s] (static stages)")
    ax.set_ylabel("diameter [mm]")
    ax.set_title("(a) stent and lumen diameters (stented segment)", fontsize=10)
    ax.legend(fontsize=7, loc="lower right", ncol=1)
    ax.grid(alpha=0.3)

    cx = bx.twinx()  # the wall's force is some 4 % of the balloon's: its own scale
    for i, run in enumerate(runs):
        h, ls = run["history"], styles[i % 3]
        th = col(h, "time")
        n = run["copies"]
        bx.plot(th, col(h, "contact_balloon_normal_force") * n, ls, color="C3", lw=1.3,
                label="balloon on the stent (left axis), %s" % run["label"])
        cx.plot(th, col(h, "contact_wall_normal_force") * n, ls, color="C0", lw=1.3,
                label="wall on the stent (right axis), %s" % run["label"])
    cx.set_ylabel("wall: radial force, whole ring [N]", color="C0")
    cx.set_ylim(0, 0.07)
    cx.tick_params(axis="y", colors="C0")
    bx.set_xlim(1.25, th.max() + 0.02)
    mark_stages(bx, runs[0], 0.99, t0=1.25)
    bx.set_xlabel("pseudo-time t [s]")
    bx.set_ylabel("balloon: radial force, whole ring (x %d) [N]" % runs[0]["copies"])
    bx.set_ylim(0, None)
    bx.set_title("(b) contact forces in the expansion and the deflation", fontsize=10)
    lines = bx.get_legend_handles_labels()[0] + cx.get_legend_handles_labels()[0]
    bx.legend(lines, [l.get_label() for l in lines], fontsize=7, loc="upper left")
    bx.grid(alpha=0.3)
    fig.suptitle("S7: one strut of the 316L ring (F-bar hex8) crimped, expanded into a stenosed layered "
                 "artery (12 % plaque) and deflated", fontsize=11)
    fig.tight_layout()
    save(fig, out)


def plot_stresses(out, runs):
    fig, axes = plt.subplots(1, len(runs), figsize=(6.2 * len(runs), 4.6), sharey=True, squeeze=False)
    for ax, run in zip(axes[0], runs):
        m = [r for r in run["metrics"] if r["time"] >= 1.25 - 1e-9]
        t = col(m, "time")
        for j, layer in enumerate(run["layers"]):
            ax.semilogy(t, col(m, "%s_sigma1_max [MPa]" % layer), "-", color="C%d" % j, lw=1.3,
                        label="%s: max" % layer)
            ax.semilogy(t, col(m, "%s_sigma1_p99 [MPa]" % layer), "--", color="C%d" % j, lw=1.1,
                        label="%s: 99th percentile" % layer)
        ax.set_ylim(1e-5, 3)
        mark_stages(ax, run, 0.99, t0=1.25)
        ax.set_xlabel("pseudo-time t [s]")
        ax.set_title("%s" % run["label"], fontsize=10)
        ax.grid(alpha=0.3, which="both")
    axes[0][0].set_ylabel("largest principal Cauchy stress of the cells [MPa]")
    axes[0][0].legend(fontsize=7, loc="center left", ncol=2)
    fig.suptitle("S7: the layers of the artery, largest principal stress of the cells "
                 "(cell averages)", fontsize=11)
    fig.tight_layout()
    save(fig, out)


def tables(runs):
    print("\n### Runs\n")
    print("| run | cells (model) | copies | wall | summary |")
    print("|---|---|---|---|---|")
    import h5py
    for run in runs:
        with h5py.File(os.path.join(run["dir"], run["base"] + ".h5"), "r") as f:
            ncell = len(f["mesh/topology"])
        print("| %s | %d | %d | %s | %s |" % (run["label"], ncell, run["copies"], run["wall"],
                                             run["summary"].replace("Summary: ", "")))
    for run in runs:
        n = run["copies"]
        print("\n### %s: each stage's end (whole ring: forces = the model's x %d)\n" % (run["label"], n))
        print("| stage end | t [s] | stent D now [mm] | change | radial recoil | foreshortening | max eq. plastic "
              "strain | lumen D mean [mm] | gain | MLD [mm] | acute gain [mm] | wall force [N] | balloon force [N] |")
        print("|---|---|---|---|---|---|---|---|---|---|---|---|---|")
        for name, sr in zip(run["stages"], run["stage_rows"]):
            a = run["log"][name]["all"]
            lu, mld = run["artery"][name]["lumen"], run["artery"][name]["mld"]
            h = run["history"]
            print("| %s | %.4g | %.4f | %+.3f %% | %.3f %% | %.3f %% | %.4f | %.4f | %+.2f %% | %.4f | %+.4f | %.4f | %.4f |"
                  % (name, sr["time"], a[2], a[3], a[4], a[5], a[7], lu[1], lu[2], mld[1], mld[2],
                     at(h, sr["time"], "contact_wall_normal_force") * n,
                     at(h, sr["time"], "contact_balloon_normal_force") * n))
        print("\n(before the procedure: lumen D mean %.4f mm, MLD %.4f mm; peak of the stent D %.4f mm)"
              % (run["artery"][run["stages"][0]]["lumen"][0], run["artery"][run["stages"][0]]["mld"][0],
                 run["log"][run["stages"][-1]]["all"][1]))
        h = run["history"]
        for tool in ("balloon", "wall"):
            f = col(h, "contact_%s_normal_force" % tool) * n
            k = int(np.argmax(f))
            print("largest %s force %.4f N at t = %.4g" % (tool, f[k], h[k]["time"]))
    print("\n### The stent against the wall at each stage's end\n")
    print("| run | stage end | t [s] | largest gap [mm] | malapposed [% of the outer surface] | tissue prolapse [mm] |")
    print("|---|---|---|---|---|---|")
    for run in runs:
        m = run["metrics"]
        for name, sr in zip(run["stages"], run["stage_rows"]):
            t = sr["time"]
            print("| %s | %s | %.4g | %.4f | %.2f | %.4f |" % (run["label"], name, t, at(m, t, "stent_wall_gap_max [mm]"),
                                                              at(m, t, "malapposed_area [%]"), at(m, t, "prolapse_max [mm]")))
    print("\n### The layers' largest principal stress, max / 99th percentile [MPa]\n")
    hdr = "| run | t [s] | " + " | ".join(runs[0]["layers"]) + " |"
    print(hdr)
    print("|---" * (2 + len(runs[0]["layers"])) + "|")
    for run in runs:
        ends = {n: r["time"] for n, r in zip(run["stages"], run["stage_rows"])}
        m = run["metrics"]
        t_peak = max(m, key=lambda r: r["intima_sigma1_max [MPa]"] if "intima_sigma1_max [MPa]" in r else 0)["time"]
        for label, t in (("largest intima max", t_peak), ("expand end", ends.get("expand")),
                         ("deflate end", ends.get("deflate"))):
            if t is None:
                continue
            cells = ["%.4g / %.4g" % (at(m, t, "%s_sigma1_max [MPa]" % l), at(m, t, "%s_sigma1_p99 [MPa]" % l))
                     for l in run["layers"]]
            print("| %s, %s | %.4g | %s |" % (run["label"], label, t, " | ".join(cells)))
        for l in run["layers"]:
            v = col(m, "%s_sigma1_max [MPa]" % l)
            k = int(np.argmax(v))
            print("<!-- %s %s: largest max %.4g MPa at t = %.4g -->" % (run["label"], l, v[k], m[k]["time"]))


def lumen_stations(run):
    """The lumen's diameter per axial station (2 r_mean of the lumen nodes of a reference z:
    the innermost artery nodes of that z; every node weighs the same here) at the output
    steps of the HDF5: [(z, [D at each step])], and the stent's current z range at each."""
    import h5py
    with h5py.File(os.path.join(run["dir"], run["base"] + ".h5"), "r") as f:
        x0 = f["mesh/coordinates"][()]
        ns = int(f["mesh/block_0/connectivity"][()].max()) + 1  # the stent's nodes come first
        steps = sorted((k for k in f if k.startswith("step_")), key=lambda s: int(s[5:]))
        us = [f[k + "/displacement"][()] for k in steps]
    times = [float(v) for v in re.findall(r'<Time Value="([^"]+)"',
                                          open(os.path.join(run["dir"], run["base"] + ".xdmf")).read())]
    X = x0[ns:]
    r0 = np.hypot(X[:, 0], X[:, 1])
    zs = np.round(X[:, 2], 9)
    out = []
    for z in np.unique(zs):
        m = zs == z
        sel = m & (np.abs(r0 - r0[m].min()) < 1e-9)
        out.append((z, [2 * np.hypot(*(X[sel] + u[ns:][sel])[:, :2].T).mean() for u in us]))
    span = [((x0[:ns] + u[:ns])[:, 2].min(), (x0[:ns] + u[:ns])[:, 2].max()) for u in us]
    return times, out, span


def print_stations(runs):
    for run in runs:
        times, st, span = lumen_stations(run)
        print("\n### %s: the lumen's diameter per station [mm] (unweighted mean of its nodes)\n" % run["label"])
        print("| z [mm] | " + " | ".join("t = %.4g" % t for t in times) + " |")
        print("|---" * (1 + len(times)) + "|")
        for z, d in st:
            print("| %.2f | %s |" % (z, " | ".join("%.3f" % v for v in d)))
        print("| stent z range | %s |" % " | ".join("%.3f to %.3f" % s for s in span))


def main():
    if len(sys.argv) < 4:
        sys.exit(__doc__)
    runs = [load(s) for s in sys.argv[3:]]
    plot_diameters(sys.argv[1], runs)
    plot_stresses(sys.argv[2], runs)
    tables(runs)
    print_stations(runs)


if __name__ == "__main__":
    main()
