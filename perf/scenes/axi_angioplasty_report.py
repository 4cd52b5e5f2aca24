#!/usr/bin/env python3
"""Metrics and plot of the balloon angioplasty scene (inputs/axi_angioplasty.xml).

Reads the run's fields (<out>/axi_angioplasty.h5: displacement, cauchy_stress per cell)
and writes:
  <csv>  one row per state (reference; peak inflation, the end of 'inflate'; the end of
         'deflate'; the end of 'withdrawn'): the smallest lumen radius and where, the lumen
         gain over the stenosed throat, the elastic recoil of the lumen (the part of the peak
         gain lost after deflation), the balloon's outer radius at z = 0, and the largest hoop
         stress sigma_thth of each layer and of the plaque (cell means) [MPa];
  <png>  the lumen and balloon profiles r(z) at the three states, and the largest hoop stress
         per layer over the procedure.
The lumen is the artery's node of least reference radius on each node line z = const.
usage: axi_angioplasty_report.py OUT_DIR CSV PNG       (Debian's python3-h5py, -numpy, -matplotlib)
"""
import sys

import h5py
import matplotlib
import numpy as np

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

out, csv_path, png_path = sys.argv[1:4]
f = h5py.File(f"{out}/axi_angioplasty.h5", "r")
X = f["mesh/coordinates"][:, :2]
blocks = {}
first = 0
for k in sorted((k for k in f["mesh"] if k.startswith("block_")), key=lambda s: int(s[6:])):
    b = f["mesh"][k]
    conn = b["connectivity"][:]
    blocks[b.attrs["name"].decode()] = (first, first + len(conn), conn)
    first += len(conn)
layers = ["plaque", "intima", "media", "adventitia"]
artery_nodes = np.unique(np.concatenate([blocks[n][2].ravel() for n in layers]))
zs = np.round(X[artery_nodes, 1], 9)
lumen = []
for z in np.unique(zs):
    on = artery_nodes[zs == z]
    lumen.append(on[np.argmin(X[on, 0])])
lumen = np.array(lumen)
bnodes = np.unique(blocks["balloon"][2].ravel())
bout = bnodes[np.isclose(X[bnodes, 0], X[bnodes, 0].max())]
bout = bout[np.argsort(X[bout, 1])]

steps = sorted((k for k in f if k.startswith("step_")), key=lambda s: int(s[5:]))
times = np.array([f[s].attrs["time"] for s in steps])
hoop = {n: [] for n in layers}
for s in steps:
    sig = f[s]["cauchy_stress"][:]
    for n in layers:
        a, b, _ = blocks[n]
        hoop[n].append(sig[a:b, 8].max())  # (theta, theta) of the 3 x 3 rows: sigma_thth
hoop = {n: np.array(v) for n, v in hoop.items()}


def state(t):
    k = int(np.argmin(abs(times - t)))
    u = f[steps[k]]["displacement"][:, :2]
    return k, X + u


r0 = X[lumen, 0].min()
rows = []
states = [("reference", 0.0), ("peak inflation (0.6 MPa)", 1.0), ("deflated", 2.0), ("balloon withdrawn", 3.0)]
profiles = {}
r_peak = None
for name, t in states:
    k, x = state(t)
    rl = x[lumen, 0]
    i = int(np.argmin(rl))
    rmin = rl[i]
    if t == 1.0:
        r_peak = rmin
    gain = rmin - r0
    recoil = "" if r_peak is None or t < 2 else f"{(r_peak - rmin) / (r_peak - r0):.4f}"
    rb = np.interp(0.0, x[bout, 1], x[bout, 0])
    rows.append([name, f"{times[k]:g}", f"{rmin:.5f}", f"{x[lumen[i], 1]:.4f}", f"{gain:.5f}",
                 f"{100 * gain / r0:.2f}", f"{100 * ((rmin / r0) ** 2 - 1):.2f}", recoil, f"{rb:.5f}"]
                + [f"{hoop[n][k]:.5f}" for n in layers])
    profiles[name] = (x[lumen, 1], rl, x[bout, 1], x[bout, 0])
with open(csv_path, "w") as fh:
    fh.write("state,time,lumen_radius_min_mm,z_of_min_mm,lumen_gain_mm,lumen_gain_percent,lumen_area_gain_percent,"
             "recoil_of_peak_gain,balloon_outer_radius_z0_mm," + ",".join(f"hoop_max_{n}_MPa" for n in layers) + "\n")
    for r in rows:
        fh.write(",".join(r) + "\n")
for r in rows:
    print(" | ".join(r))

fig, ax = plt.subplots(2, 1, figsize=(9, 8.5))
colours = {"reference": "k", "peak inflation (0.6 MPa)": "tab:red", "deflated": "tab:blue"}
for name, c in colours.items():
    zl, rl, zb, rb = profiles[name]
    ax[0].plot(zl, rl, color=c, lw=2, label=f"lumen, {name}")
    ax[0].plot(zb, rb, color=c, lw=1, ls="--", label=f"balloon outer line, {name}")
ax[0].set_xlabel("z [mm]")
ax[0].set_ylabel("radius r [mm]")
ax[0].set_xlim(-5.5, 5.5)
ax[0].set_title("Balloon angioplasty of a 60 % (area) stenosis, axisymmetric: lumen and balloon profiles")
ax[0].legend(fontsize=7, loc="lower right")
ax[0].grid(alpha=0.3)
for n, c in zip(layers, ["tab:brown", "tab:orange", "tab:green", "tab:purple"]):
    ax[1].plot(times, hoop[n], marker="o", ms=3, color=c, label=n)
ax[1].set_xlabel("time [s]  (inflate 0-1: pressure 0 to 0.6 MPa; deflate 1-2; balloon withdrawn 2-3)")
ax[1].set_ylabel("largest hoop stress sigma_thth [MPa]")
ax[1].set_yscale("symlog", linthresh=1e-3)
ax[1].legend()
ax[1].grid(alpha=0.3)
fig.tight_layout()
fig.savefig(png_path, dpi=110)
print(f"wrote {csv_path}, {png_path}")
