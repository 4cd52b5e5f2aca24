#!/usr/bin/python3
"""Render 2D Stentor results (plane strain) from the HDF5 output, as a user would see
them in ParaView: the deformed mesh of every body coloured by a cell field, the rigid
obstacles of the same output step (from <basename>_obstacles.h5: its /mesh/topology
segments at /step_<k>/coordinates), one panel per requested time.

usage: render_section.py RESULTS_DIR BASENAME OUT.png FIELD LABEL T1[:TITLE1] T2[:TITLE2] ...
  FIELD   a cell field of the HDF5 (von_mises, equivalent_plastic_strain, J, ...), or one
          component of a multi-component one as NAME[k]: principal_stress[0] (the largest),
          log_strain[4] (yy of the 3 x 3 row-major tensor), ...
  LABEL   the colour bar's label, with units, e.g. "von Mises stress [MPa]"
  Ti      the output time to show (the nearest output step is taken); TITLEi its caption
env: SCALE (field multiplier, e.g. 1e-6 for Pa -> MPa), VMIN/VMAX (colour-bar range; VMIN
defaults to 0, or to the smallest value when that is negative), XLIM/YLIM ("a,b"),
OBSTACLE_LABEL (legend of the rigid obstacles, default "rigid balloon").
Needs Debian's python3-matplotlib, python3-h5py, python3-numpy.
"""
import os
import re
import sys

import h5py
import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
import matplotlib.tri as mtri
import numpy as np

# P2 triangles (gmsh order: corners 0 1 2, mid-edges 3 = 01, 4 = 12, 5 = 20) are drawn as
# four straight sub-triangles, so the curved struts keep their shape.
SUB = {3: [(0, 1, 2)], 6: [(0, 3, 5), (3, 1, 4), (5, 4, 2), (3, 4, 5)]}


def output_times(xdmf):
    text = open(xdmf).read()
    return [float(v) for v in re.findall(r'<Time Value="([^"]+)"', text)]


def obstacle_lines(path, k):
    """The rigid obstacles' segments at output step k as one (x, y) polyline with NaN
    breaks between segments; None without an obstacle file."""
    if not os.path.exists(path):
        return None
    with h5py.File(path, "r") as f:
        seg = f["mesh/topology"][()]
        xy = f["step_%d/coordinates" % k][:, :2]
    line = np.full((3 * len(seg), 2), np.nan)
    line[0::3], line[1::3] = xy[seg[:, 0]], xy[seg[:, 1]]
    return line


def main():
    if len(sys.argv) < 7:
        sys.exit(__doc__)
    res, base, out, field, label = sys.argv[1:6]
    shots = [a.split(":", 1) if ":" in a else (a, "") for a in sys.argv[6:]]
    scale = float(os.environ.get("SCALE", "1"))
    times = output_times(os.path.join(res, base + ".xdmf"))
    h5 = h5py.File(os.path.join(res, base + ".h5"), "r")
    xy0 = h5["mesh/coordinates"][:, :2]
    blocks = sorted(k for k in h5["mesh"] if k.startswith("block_"))
    conn = [h5["mesh/" + b + "/connectivity"][:] for b in blocks]
    steps = [int(np.argmin([abs(t - float(s[0])) for t in times])) for s in shots]
    m = re.fullmatch(r"(.+)\[(\d+)\]", field)
    name, comp = (m.group(1), int(m.group(2))) if m else (field, None)
    vals = [h5["step_%d/%s" % (k, name)][:] for k in steps]
    vals = [(v if comp is None else v[:, comp]) * scale for v in vals]
    vmax = float(os.environ.get("VMAX", max(v.max() for v in vals) or 1.0))
    vmin = float(os.environ.get("VMIN", min(0.0, min(v.min() for v in vals))))
    fig, axes = plt.subplots(1, len(shots), figsize=(3.6 * len(shots) + 1.2, 3.9), squeeze=False)
    for ax, (t, title), k, v in zip(axes[0], shots, steps, vals):
        xy = xy0 + h5["step_%d/displacement" % k][:, :2]
        first = 0
        for c in conn:
            sub = SUB[c.shape[1]]
            tris = np.vstack([c[:, list(s)] for s in sub])
            colours = np.concatenate([v[first:first + len(c)]] * len(sub))
            tri = mtri.Triangulation(xy[:, 0], xy[:, 1], tris)
            pc = ax.tripcolor(tri, facecolors=colours, cmap="viridis", vmin=vmin, vmax=vmax, edgecolors="none")
            first += len(c)
        line = obstacle_lines(os.path.join(res, base + "_obstacles.h5"), k)
        if line is not None:
            ax.plot(line[:, 0], line[:, 1], color="crimson", lw=1.2, label=os.environ.get("OBSTACLE_LABEL", "rigid balloon"))
        ax.set_aspect("equal")
        ax.set_title(("%s (t = %.3g s)" if title else "%st = %.3g s") % (title, times[k]), fontsize=10)
        ax.set_xlabel("x [m]")
        if "XLIM" in os.environ:
            ax.set_xlim(*map(float, os.environ["XLIM"].split(",")))
        if "YLIM" in os.environ:
            ax.set_ylim(*map(float, os.environ["YLIM"].split(",")))
    axes[0][0].set_ylabel("y [m]")
    handles, labels = axes[0][0].get_legend_handles_labels()
    if handles:
        axes[0][0].legend(handles[:1], labels[:1], loc="lower left", fontsize=8)
    fig.colorbar(pc, ax=axes[0].tolist(), label=label, shrink=0.85)
    fig.savefig(out, dpi=110, bbox_inches="tight")
    print("wrote", out)


if __name__ == "__main__":
    main()
