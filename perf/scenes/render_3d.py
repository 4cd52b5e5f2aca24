#!/usr/bin/python3
"""Render 3D Stentor results from the HDF5 output, as a user would see them in ParaView:
the deformed boundary surface of every body coloured by a field, the rigid obstacles of the
same output step, one 3D panel (matplotlib mplot3d, orthographic view) per requested time.

usage: render_3d.py RESULTS_DIR BASENAME OUT.png FIELD LABEL T1[:TITLE1] T2[:TITLE2] ...
  FIELD   a cell field of the HDF5 (von_mises, J, ...) or one component NAME[k] of a
          multi-component one (principal_stress[0], ...); each boundary face takes the
          value of the cell that owns it. A node field (contact_pressure, ...) is averaged
          over the face's corners.
  LABEL   the colour bar's label, with units, e.g. "von Mises stress [MPa]"
  Ti      the output time to show (the nearest output step is taken); TITLEi its caption
The surface: the faces of the volume cells (tet4/tet10, hex8/hex20/hex27; corner nodes
only, so P2 faces are drawn flat) that belong to one cell only, in the deformed position
x = X + displacement of the step. Faces turned away from the viewer are not drawn; the
others are shaded by a light from the viewer's side (ambient 0.6), so a colour is the
colour bar's at full light.
Rigid obstacles: from <BASENAME>_obstacles.h5 (its quadrilaterals at /step_<k>/coordinates)
when the run wrote it; otherwise the planes (Contact pairs with obstacle = plane, their
point and normal) of the deck copy <BASENAME>_deck.xml in RESULTS_DIR, or of env DECK.
A single-quadrilateral obstacle (a plane) is cut to the bodies' extent (plus 10 % on each
side) so it does not dwarf the model.
env: SCALE (field multiplier, e.g. 1e-6 for Pa -> MPa), VMIN/VMAX (colour-bar range; VMIN
defaults to 0, or to the smallest value when that is negative), VIEW ("elev,azim" in
degrees, default "20,-25"), COLS (panels per row, default 2 for 4 panels, else all in
one row), TITLE (the figure's title; default the deck's Problem->title), OBSTACLE_LABEL
(legend of the rigid obstacles, default "rigid plane"), DECK (deck for the fallback),
ZOOM (of each panel's box, default 1.25), DPI (default 100). The colour bar gets an arrow at
an end that cuts off shown values (VMIN/VMAX inside the data's range).
Needs Debian's python3-matplotlib, python3-h5py, python3-numpy.
"""
import os
import re
import sys
import xml.etree.ElementTree as ET

import h5py
import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
from matplotlib import cm, colors
from mpl_toolkits.mplot3d.art3d import Poly3DCollection
import numpy as np

# Faces of the volume cells by corner nodes (gmsh and VTK agree on the corners), each with
# a corner of the cell off the face (to orient the face outwards).
TET = [((0, 2, 1), 3), ((0, 1, 3), 2), ((1, 2, 3), 0), ((0, 3, 2), 1)]
HEX = [((0, 3, 2, 1), 4), ((4, 5, 6, 7), 0), ((0, 1, 5, 4), 3), ((1, 2, 6, 5), 0),
       ((2, 3, 7, 6), 1), ((3, 0, 4, 7), 2)]
AMBIENT = 0.6
FACES = {4: TET, 10: TET, 8: HEX, 20: HEX, 27: HEX}


def output_times(xdmf):
    text = open(xdmf).read()
    return [float(v) for v in re.findall(r'<Time Value="([^"]+)"', text)]


def boundary_faces(conn_blocks):
    """(faces, owner cell (global index over the blocks), an off-face node) of the faces
    that belong to one cell only; faces of each cell type are returned separately."""
    out = []
    first = 0
    for conn in conn_blocks:
        table = FACES.get(conn.shape[1])
        if table is None:
            sys.exit("render_3d.py: cells with %d nodes are not volume cells (2D results: "
                     "use render_section.py)" % conn.shape[1])
        faces = np.vstack([conn[:, list(f)] for f, _ in table])
        opp = np.concatenate([conn[:, o] for _, o in table])
        owner = np.tile(np.arange(len(conn)) + first, len(table))
        out.append((faces, owner, opp))
        first += len(conn)
    # a face is interior when its sorted corner set occurs twice (in any block)
    nv = max(f.shape[1] for f, _, _ in out)
    keys = np.vstack([np.pad(np.sort(f, axis=1), ((0, 0), (0, nv - f.shape[1])), constant_values=-1)
                      for f, _, _ in out])
    _, inv, count = np.unique(keys, axis=0, return_inverse=True, return_counts=True)
    once = count[inv.ravel()] == 1
    result, start = [], 0
    for f, o, p in out:
        keep = once[start:start + len(f)]
        result.append((f[keep], o[keep], p[keep]))
        start += len(f)
    return result


def deck_planes(deck):
    """(point, normal) of every Contact pair with obstacle = plane in a deck."""
    if not deck or not os.path.exists(deck):
        return []
    root = ET.parse(deck).getroot()
    planes = []
    for contact in root.iter("ParameterList"):
        if contact.get("name") != "Contact":
            continue
        for pair in contact.findall("ParameterList"):
            p = {q.get("name"): q.get("value") for q in pair.findall("Parameter")}
            if p.get("obstacle", "").lower() == "plane":
                vec = lambda s: np.array([float(v) for v in s.strip("{} ").split(",")] + [0.0] * 3)[:3]
                planes.append((vec(p["point"]), vec(p["normal"])))
    return planes


def plane_quad(point, normal, pts, pad=0.1):
    """A rectangle of the plane through point with that normal covering the projection of
    pts onto it, enlarged by pad on each side."""
    n = normal / np.linalg.norm(normal)
    e1 = np.cross(n, [1.0, 0, 0] if abs(n[0]) < 0.9 else [0, 1.0, 0])
    e1 /= np.linalg.norm(e1)
    e2 = np.cross(n, e1)
    a, b = (pts - point) @ e1, (pts - point) @ e2
    (a0, a1), (b0, b1) = (a.min(), a.max()), (b.min(), b.max())
    da, db = pad * (a1 - a0), pad * (b1 - b0)
    a0, a1, b0, b1 = a0 - da, a1 + da, b0 - db, b1 + db
    return np.array([point + u * e1 + v * e2 for u, v in ((a0, b0), (a1, b0), (a1, b1), (a0, b1))]), n


def obstacle_quads(res, base, k, pts):
    """[(quads (m x 4 x 3), normal of a plane or None)] of the rigid obstacles at step k."""
    path = os.path.join(res, base + "_obstacles.h5")
    if os.path.exists(path):
        with h5py.File(path, "r") as f:
            top = f["mesh/topology"][()]
            xyz = f["step_%d/coordinates" % k][()]
            block = f["mesh/cell_block"][()].ravel() if "mesh/cell_block" in f else np.zeros(len(top), int)
        out = []
        for b in np.unique(block):
            quads = xyz[top[block == b]]
            if len(quads) == 1 and quads.shape[1] == 4:  # a plane: cut it to the model
                q = quads[0]
                n = np.cross(q[1] - q[0], q[3] - q[0])
                out.append(plane_quad(q.mean(axis=0), n, pts))
                out[-1] = (out[-1][0][None], out[-1][1])
            else:
                out.append((quads, None))
        return out
    deck = os.environ.get("DECK", os.path.join(res, base + "_deck.xml"))
    return [(q[None], n) for q, n in (plane_quad(p, n, pts) for p, n in deck_planes(deck))]


def problem_title(res, base):
    deck = os.environ.get("DECK", os.path.join(res, base + "_deck.xml"))
    if os.path.exists(deck):
        for p in ET.parse(deck).getroot().iter("Parameter"):
            if p.get("name") == "title":
                return p.get("value")
    return base


def main():
    if len(sys.argv) < 7:
        sys.exit(__doc__)
    res, base, out, field, label = sys.argv[1:6]
    shots = [a.split(":", 1) if ":" in a else (a, "") for a in sys.argv[6:]]
    scale = float(os.environ.get("SCALE", "1"))
    elev, azim = map(float, os.environ.get("VIEW", "20,-25").split(","))
    times = output_times(os.path.join(res, base + ".xdmf"))
    h5 = h5py.File(os.path.join(res, base + ".h5"), "r")
    x0 = h5["mesh/coordinates"][()]
    blocks = sorted((k for k in h5["mesh"] if k.startswith("block_")), key=lambda s: int(s[6:]))
    surf = boundary_faces([h5["mesh/" + b + "/connectivity"][()] for b in blocks])
    steps = [int(np.argmin([abs(t - float(s[0])) for t in times])) for s in shots]
    m = re.fullmatch(r"(.+)\[(\d+)\]", field)
    name, comp = (m.group(1), int(m.group(2))) if m else (field, None)

    def face_values(k):
        v = h5["step_%d/%s" % (k, name)][()]
        v = v.reshape(len(v), -1)[:, 0 if comp is None else comp] * scale
        if len(v) == len(x0) and len(v) != sum(len(h5["mesh/" + b + "/connectivity"]) for b in blocks):
            return [v[f].mean(axis=1) for f, _, _ in surf]  # a node field
        return [v[o] for _, o, _ in surf]

    xs = [x0 + h5["step_%d/displacement" % k][()] for k in steps]
    vals = [face_values(k) for k in steps]
    allv = np.concatenate([np.concatenate(v) for v in vals])
    vmax = float(os.environ.get("VMAX", allv.max() or 1.0))
    vmin = float(os.environ.get("VMIN", min(0.0, allv.min())))
    norm = colors.Normalize(vmin, vmax)
    cmap = matplotlib.colormaps["viridis"]

    used = np.unique(np.concatenate([f.ravel() for f, _, _ in surf]))
    body_pts = np.vstack([x[used] for x in xs])
    obst = [obstacle_quads(res, base, k, body_pts) for k in steps]
    allpts = np.vstack([body_pts] + [q.reshape(-1, 3) for ob in obst for q, _ in ob])
    lo, hi = allpts.min(axis=0), allpts.max(axis=0)
    ctr, half = (lo + hi) / 2, (hi - lo) / 2 + 1e-12

    el, az = np.radians(elev), np.radians(azim)
    eye = np.array([np.cos(el) * np.cos(az), np.cos(el) * np.sin(az), np.sin(el)])
    light = eye + np.array([0.0, 0.0, 0.6])
    light /= np.linalg.norm(light)

    cols = int(os.environ.get("COLS", 2 if len(shots) == 4 else len(shots)))
    rows = -(-len(shots) // cols)
    width = 4.4 * cols + 1.3
    fig = plt.figure(figsize=(width, 3.4 * rows + 0.4))
    fig.subplots_adjust(left=0.01, right=1 - 1.4 / width, bottom=0.02, top=0.92, wspace=0.02, hspace=0.08)
    axes = []
    for i, ((t, title), k, x, v, ob) in enumerate(zip(shots, steps, xs, vals, obst)):
        ax = fig.add_subplot(rows, cols, i + 1, projection="3d")
        axes.append(ax)
        ax.set_proj_type("ortho")
        ax.computed_zorder = False
        polys, fc = [], []
        for (f, _, opp), fv in zip(surf, v):
            p = x[f]
            n = np.cross(p[:, 1] - p[:, 0], p[:, 2] - p[:, 0])
            n *= -np.sign(np.einsum("ij,ij->i", n, x[opp] - p[:, 0]))[:, None]  # outwards
            n /= np.linalg.norm(n, axis=1)[:, None] + 1e-300
            front = n @ eye > 0
            shade = AMBIENT + (1 - AMBIENT) * np.clip(n[front] @ light, 0, 1)
            c = cmap(norm(fv[front]))
            c[:, :3] *= shade[:, None]
            polys.extend(p[front])
            fc.append(c)
        body = Poly3DCollection(polys, facecolors=np.vstack(fc), edgecolors=(0, 0, 0, 0.12), linewidths=0.15)
        for quads, pn in ob:
            behind = pn is not None and pn @ eye > 0  # the viewer is on the body's side
            pc = Poly3DCollection(list(quads), facecolors=(0.86, 0.08, 0.24, 0.18),
                                  edgecolors="crimson" if pn is not None else (0.86, 0.08, 0.24, 0.3),
                                  linewidths=0.8 if pn is not None else 0.2, zorder=0 if behind else 2,
                                  label=os.environ.get("OBSTACLE_LABEL", "rigid plane"))
            ax.add_collection3d(pc)
        body.set_zorder(1)
        ax.add_collection3d(body)
        ax.set_xlim(ctr[0] - half[0], ctr[0] + half[0])
        ax.set_ylim(ctr[1] - half[1], ctr[1] + half[1])
        ax.set_zlim(ctr[2] - half[2], ctr[2] + half[2])
        ax.set_box_aspect(half.copy(), zoom=float(os.environ.get("ZOOM", "1.25")))
        ax.view_init(elev, azim)
        ax.set_title(("%s (t = %.3g s)" if title else "%st = %.3g s") % (title, times[k]), fontsize=10, y=0.98)
        ax.set_xlabel("x [m]", fontsize=8, labelpad=-2)
        ax.set_ylabel("y [m]", fontsize=8, labelpad=-2)
        ax.set_zlabel("z [m]", fontsize=8, labelpad=-4)
        ax.tick_params(labelsize=7, pad=0)
        ax.locator_params(nbins=4)
    if obst[0]:
        handles = [plt.Rectangle((0, 0), 1, 1, fc=(0.86, 0.08, 0.24, 0.18), ec="crimson")]
        fig.legend(handles, [os.environ.get("OBSTACLE_LABEL", "rigid plane")], loc="lower right",
                   bbox_to_anchor=(0.99, 0.02), fontsize=8)
    fig.suptitle(os.environ.get("TITLE", problem_title(res, base)), fontsize=11)
    extend = {(False, False): "neither", (True, False): "min", (False, True): "max", (True, True): "both"}[
        (vmin > allv.min(), vmax < allv.max())]
    fig.colorbar(cm.ScalarMappable(norm, cmap), cax=fig.add_axes([1 - 1.0 / width, 0.22, 0.18 / width, 0.56]), label=label,
                 extend=extend)
    fig.savefig(out, dpi=int(os.environ.get("DPI", "100")), bbox_inches="tight", pad_inches=0.1)
    print("wrote", out, "(steps %s)" % ", ".join(str(k) for k in steps))


if __name__ == "__main__":
    main()
