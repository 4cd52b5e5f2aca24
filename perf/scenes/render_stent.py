"""Render a generated stent (Mesh->generator = stent) from Stentor's HDF5 output with
ParaView, the reduced model put back together into the whole stent: a one-strut or quarter
sector is mirrored about y = 0 and rotated around the axis into the full circumference, a
half length mirrored about its middle plane, the deformed positions x = X + u of every copy
mapped the same way (the symmetry planes are those of the solution), each cell keeping its
value. One panel per requested output time, composed with matplotlib into one PNG with a
title, the panels' captions and one colour bar.

usage: xvfb-run -a -s "-noreset -screen 0 1600x1200x24" pvbatch render_stent.py \
           RESULTS_DIR BASENAME OUT.png FIELD LABEL T1[:TITLE1] T2[:TITLE2] ...
  FIELD   a cell field of the HDF5 (equivalent_plastic_strain, von_mises, ...), or a node
          field (wall_gap, ...) averaged over each cell's nodes that carry a value (NaN
          elsewhere); cells with none are drawn light grey
  LABEL   the colour bar's label, with units, e.g. "von Mises stress [MPa]"
  Ti      the output time to show (the nearest output step); TITLEi its caption. When
          <BASENAME>_metrics.csv is there the caption gets the stent's mean outer diameter
          at that time.
env:
  VIEW    side (default): the whole stent seen from the side, its axis horizontal, one
          panel per row at one scale (the diameters compare across panels);
          end: seen from TILT degrees off the axis (default 35; 0: along the axis), tilted
          towards -y turned by AZIM degrees about the axis (default 0), the panels side
          by side;
          crown: a close-up of one crown, seen from outside along the radius, with the
          mesh's edges: the cell of the largest FIELD at time CROWN_T (default the last
          requested time) and the cells of the whole stent within RADIUS (default 0.45,
          the deck's length unit) of it in the reference configuration, each panel centred
          on that cell's current position, half the panel's height ZOOM (default 0.7 RADIUS)
  SCALE   field multiplier (default 1); VMIN (default 0) / VMAX (default the largest shown)
  TITLE   the figure's title (default the deck's Problem->title)
  LENGTH  the unit of length in the axis captions (default from the deck's units: mm)
  CMAP    matplotlib colour map (default YlOrRd: 0 pale, the largest values dark red), given to ParaView as its colour table
  COLS    panels per row (default: side 2 for an even number of panels, else 1; end and
          crown all in one row)
  DPI     of the output (default 100); PANEL "W,H" pixels of one rendered panel
A stent with an artery around it (Mesh->Artery: the stent is the mesh's first block, the
artery's layers the others; without these variables every block is drawn alike):
  ARTERY_FIELD  colour the artery's cells by this field (its first component: the largest
          principal stress of principal_stress) with a colour table and bar of their own,
          the stent's by FIELD; ARTERY_LABEL its bar's label, ARTERY_CMAP (default Blues),
          ARTERY_SCALE, ARTERY_VMIN (default 0) / ARTERY_VMAX (default the largest shown)
  CUT     +y, -y, +x or -x: show only the artery's cells whose centroid (reference
          configuration, after the symmetry map) lies on that side of the plane through
          the axis (+y: y > 0, the far half in the side view), the artery cut open along
          its axis so that the stent shows inside; the stent is drawn whole
  The captions add the lumen's mean and minimum diameter (lumen_D_mean, lumen_D_min of the
  metrics CSV) where the CSV has them.
The panels are cut to the same box (the union of what they draw), so they keep one scale;
the PNG is written with a 256-colour palette (Debian's python3-pil, matplotlib's own
dependency; a full-colour PNG without it).
Needs ParaView's pvbatch (Debian: paraview, python3-paraview, xvfb) and Debian's
python3-h5py, python3-numpy, python3-matplotlib. Exit status 77 when not run by pvbatch.
"""
import csv
import os
import re
import sys
import tempfile
import xml.etree.ElementTree as ET

import h5py
import numpy as np

try:
    from paraview import simple as pv
    from vtkmodules.util.numpy_support import numpy_to_vtk, numpy_to_vtkIdTypeArray
    from vtkmodules.vtkCommonCore import vtkPoints
    from vtkmodules.vtkCommonDataModel import VTK_HEXAHEDRON, vtkCellArray, vtkUnstructuredGrid
    from vtkmodules.vtkIOXML import vtkXMLUnstructuredGridWriter
except ImportError as e:  # pragma: no cover
    print("render_stent.py: %s (run it with ParaView's pvbatch: xvfb-run -a -s \"-noreset -screen 0 "
          "1600x1200x24\" pvbatch %s ...)" % (e, sys.argv[0]), file=sys.stderr)
    sys.exit(77)

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
from matplotlib import cm, colors

# A mirrored hex8 is inside out; this order of its corners turns it back.
HEX_FLIP = [0, 3, 2, 1, 4, 7, 6, 5]


def deck_params(path):
    """{name: value} of every Parameter of a deck (the last one of a name wins)."""
    out = {}
    if os.path.exists(path):
        for p in ET.parse(path).getroot().iter("Parameter"):
            out[p.get("name")] = p.get("value")
    return out


def output_times(xdmf):
    return [float(v) for v in re.findall(r'<Time Value="([^"]+)"', open(xdmf).read())]


def symmetry_copies(x0, half_length):
    """The maps (R 3x3, z mirror plane or None) that rebuild the whole stent from the model:
    the sector 0 <= theta <= Theta mirrored about y = 0 and rotated by multiples of 2 Theta,
    the half length (z <= z_max) mirrored about z = z_max."""
    theta = np.degrees(np.arctan2(x0[:, 1], x0[:, 0]))
    span = theta.max() - min(theta.min(), 0.0)
    maps = []
    if theta.min() < -1.0 or span > 359.0:  # the whole circumference
        base = [np.eye(3)]
    else:
        n = int(round(360.0 / (2.0 * theta.max())))
        base = []
        for k in range(n):
            a = np.radians(2.0 * theta.max() * k)
            rot = np.array([[np.cos(a), -np.sin(a), 0], [np.sin(a), np.cos(a), 0], [0, 0, 1.0]])
            base += [rot, rot @ np.diag([1.0, -1.0, 1.0])]
    zc = x0[:, 2].max()
    for r in base:
        maps.append((r, None))
        if half_length:
            maps.append((r, zc))
    return maps


def apply_map(x, m):
    r, zc = m
    y = x @ r.T
    if zc is not None:
        y[:, 2] = 2.0 * zc - y[:, 2]
    return y


def flips(m):
    r, zc = m
    return (np.linalg.det(r) < 0) != (zc is not None)


def write_grid(path, xs, conns, values, name="value"):
    """A .vtu of hex8 cells: the copies' points xs, connectivities conns (into each copy's
    points) and cell values (the cell array `name`)."""
    pts, cells, off = [], [], 0
    for x, c in zip(xs, conns):
        pts.append(x)
        cells.append(c + off)
        off += len(x)
    pts, cells = np.vstack(pts), np.vstack(cells).astype(np.int64)
    grid = vtkUnstructuredGrid()
    p = vtkPoints()
    p.SetData(numpy_to_vtk(np.ascontiguousarray(pts), deep=True))
    grid.SetPoints(p)
    ca = vtkCellArray()
    ids = np.hstack([np.full((len(cells), 1), 8, np.int64), cells]).ravel()
    ca.SetCells(len(cells), numpy_to_vtkIdTypeArray(ids, deep=True))
    grid.SetCells(VTK_HEXAHEDRON, ca)
    arr = numpy_to_vtk(np.ascontiguousarray(np.concatenate(values)), deep=True)
    arr.SetName(name)
    grid.GetCellData().AddArray(arr)
    w = vtkXMLUnstructuredGridWriter()
    w.SetFileName(path)
    w.SetInputData(grid)
    w.Write()


def metrics_row(res, base, t):
    path = os.path.join(res, base + "_metrics.csv")
    if not os.path.exists(path):
        return None
    rows = list(csv.DictReader(open(path)))
    return min(rows, key=lambda r: abs(float(r["time"]) - t))


def main():
    if len(sys.argv) < 7:
        sys.exit(__doc__)
    res, base, out, field, label = sys.argv[1:6]
    shots = [a.split(":", 1) if ":" in a else (a, "") for a in sys.argv[6:]]
    view_kind = os.environ.get("VIEW", "side")
    scale = float(os.environ.get("SCALE", "1"))
    deck = deck_params(os.path.join(res, base + "_deck.xml"))
    unit = os.environ.get("LENGTH", "m" if deck.get("units", "SI") == "SI" else "mm")

    times = output_times(os.path.join(res, base + ".xdmf"))
    h5 = h5py.File(os.path.join(res, base + ".h5"), "r")
    x0 = h5["mesh/coordinates"][()]
    blocks = sorted((k for k in h5["mesh"] if k.startswith("block_")), key=lambda s: int(s[6:]))
    conn = np.vstack([h5["mesh/" + b + "/connectivity"][()] for b in blocks])
    if conn.shape[1] != 8:
        sys.exit("render_stent.py: hex8 meshes only (the stent generator's)")
    steps = [int(np.argmin([abs(t - float(s[0])) for t in times])) for s in shots]
    artery_field = os.environ.get("ARTERY_FIELD")
    cut = os.environ.get("CUT")
    n_first = len(h5["mesh/" + blocks[0] + "/connectivity"])
    in_artery = np.arange(len(conn)) >= n_first  # the cells after the first block's
    maps = symmetry_copies(x0, deck.get("half length", "false").lower() == "true")
    centroid0 = x0[conn].mean(axis=1)

    def cell_values(k, name, sc):
        """The first component of field `name` at output step k per cell, times sc: a cell
        field as it is, a node field averaged over the cell's nodes that are not NaN."""
        v = h5["step_%d/%s" % (k, name)][()]
        v = v.reshape(len(v), -1)[:, 0]
        if len(v) == len(x0) and len(v) != len(conn):
            at = v[conn]
            n = np.sum(~np.isnan(at), axis=1)
            with np.errstate(invalid="ignore"):
                v = np.where(n > 0, np.nansum(at, axis=1) / np.maximum(n, 1), np.nan)
        return v * sc

    def field_at(k):
        return cell_values(k, field, scale)

    # crown close-up: the cell of the largest value at CROWN_T, and the cells near it
    keep = [np.ones(len(conn), bool) for _ in maps]
    if cut:
        if cut not in ("+y", "-y", "+x", "-x"):
            sys.exit("render_stent.py: CUT is +y, -y, +x or -x")
        axis, sign = "xy".index(cut[1]), 1.0 if cut[0] == "+" else -1.0
        keep = [~in_artery | (sign * apply_map(centroid0, m)[:, axis] > 0) for m in maps]
    if view_kind == "crown":
        kc = int(np.argmin([abs(t - float(os.environ.get("CROWN_T", shots[-1][0]))) for t in times]))
        hot = int(np.nanargmax(field_at(kc)))
        radius = float(os.environ.get("RADIUS", "0.45"))
        keep = [np.linalg.norm(apply_map(centroid0, m) - centroid0[hot], axis=1) < radius for m in maps]
        print("crown close-up: cell %d, reference centroid (%.4f, %.4f, %.4f), %s = %.4g at t = %g"
              % (hot, *centroid0[hot], field, field_at(kc)[hot], times[kc]))

    tmp = tempfile.mkdtemp(prefix="render_stent_")
    size = [int(v) for v in os.environ.get("PANEL", {"side": "1500,620", "end": "800,800",
                                                      "crown": "760,640"}[view_kind]).split(",")]
    vals_all, xs_all, art_all = [], [], []
    for k in steps:
        x = x0 + h5["step_%d/displacement" % k][()]
        v = field_at(k)
        xs = [apply_map(x, m) for m in maps]
        if artery_field:  # the stent's cells in step_k.vtu, the artery's in artery_k.vtu
            sk = [kp & ~in_artery for kp in keep]
            ak = [kp & in_artery for kp in keep]
            va = cell_values(k, artery_field, float(os.environ.get("ARTERY_SCALE", "1")))
            csa = [(conn[:, HEX_FLIP] if flips(m) else conn)[kp] for m, kp in zip(maps, ak)]
            write_grid(os.path.join(tmp, "artery_%d.vtu" % k), xs, csa, [va[kp] for kp in ak], "artery_value")
            art_all.append(np.concatenate([va[kp] for kp in ak]))
        else:
            sk = keep
        cs = [(conn[:, HEX_FLIP] if flips(m) else conn)[kp] for m, kp in zip(maps, sk)]
        vs = [v[kp] for kp in sk]
        write_grid(os.path.join(tmp, "step_%d.vtu" % k), xs, cs, vs)
        vals_all.append(np.concatenate(vs))
        xs_all.append(x)
    allv = np.concatenate(vals_all)
    if artery_field:
        alla = np.concatenate(art_all)
        avmin = float(os.environ.get("ARTERY_VMIN", min(0.0, np.nanmin(alla))))
        avmax = float(os.environ.get("ARTERY_VMAX", np.nanmax(alla) or 1.0))
        acmap = matplotlib.colormaps[os.environ.get("ARTERY_CMAP", "Blues")]
    vmin = float(os.environ.get("VMIN", min(0.0, np.nanmin(allv))))
    vmax = float(os.environ.get("VMAX", np.nanmax(allv) or 1.0))

    view = pv.CreateView("RenderView")
    view.ViewSize = size
    view.OrientationAxesVisibility = 0
    try:
        view.UseColorPaletteForBackground = 0
    except AttributeError:
        pass
    view.Background = [1.0, 1.0, 1.0]
    view.CameraParallelProjection = 1
    cmap = matplotlib.colormaps[os.environ.get("CMAP", "YlOrRd")]
    lut = pv.GetColorTransferFunction("value")
    lut.AutomaticRescaleRangeMode = "Never"
    samples = np.linspace(0.0, 1.0, 65)
    points = [float(c) for s in samples for c in (vmin + s * (vmax - vmin), *cmap(s)[:3])]
    lut.ColorSpace = "RGB"
    lut.NanColor = [0.82, 0.82, 0.82]  # cells without a value of a node field

    # one scale for every panel: the largest extent over the shown times
    rmax = max(np.hypot(apply_map(x, maps[0])[:, 0], apply_map(x, maps[0])[:, 1]).max() for x in xs_all)
    zs = np.concatenate([np.concatenate([apply_map(x, m)[:, 2] for m in maps]) for x in xs_all])
    zmid, zhalf = (zs.min() + zs.max()) / 2, (zs.max() - zs.min()) / 2
    aspect = size[0] / size[1]
    images = []
    for i, k in enumerate(steps):
        src = pv.XMLUnstructuredGridReader(FileName=[os.path.join(tmp, "step_%d.vtu" % k)])
        surf = pv.ExtractSurface(Input=src)
        disp = pv.Show(surf, view)
        pv.ColorBy(disp, ("CELLS", "value"))
        # ColorBy fits the table to this panel's values: one table for all panels instead
        lut.RGBPoints = points
        disp.LookupTable = lut
        if os.environ.get("DEBUG_LUT"):
            print("colour table from %g to %g" % (lut.RGBPoints[0], lut.RGBPoints[-4]))
        disp.SetScalarBarVisibility(view, False)
        disp.Specular = 0.2
        if view_kind == "side":
            d = np.array([0.28, -1.0, 0.16])
            d /= np.linalg.norm(d)
            focal = np.array([0.0, 0.0, zmid])
            view.CameraFocalPoint = focal.tolist()
            view.CameraPosition = (focal + 40.0 * d).tolist()
            up = np.array([1.0, 0, 0]) - d[0] * d
            view.CameraViewUp = (up / np.linalg.norm(up)).tolist()
            view.CameraParallelScale = max(1.06 * rmax, 1.04 * zhalf / aspect)
        elif view_kind == "end":
            a = np.radians(float(os.environ.get("TILT", "35")))
            b = np.radians(float(os.environ.get("AZIM", "0")))
            rz = np.array([[np.cos(b), -np.sin(b), 0], [np.sin(b), np.cos(b), 0], [0, 0, 1.0]])
            d = rz @ np.array([0.0, -np.sin(a), -np.cos(a)])
            focal = np.array([0.0, 0.0, zmid])
            view.CameraFocalPoint = focal.tolist()
            view.CameraPosition = (focal + 40.0 * d).tolist()
            view.CameraViewUp = (rz @ np.array([0.0, np.cos(a), -np.sin(a)])).tolist()
            view.CameraParallelScale = 1.03 * (rmax * np.cos(a) + zhalf * np.sin(a))
        else:  # crown
            disp.SetRepresentationType("Surface With Edges")
            disp.EdgeColor = [0.15, 0.15, 0.15]
            xc = xs_all[i][conn[hot]].mean(axis=0)
            er = np.array([xc[0], xc[1], 0.0]) / np.hypot(xc[0], xc[1])
            et = np.array([-er[1], er[0], 0.0])
            d = er + 0.25 * et
            d /= np.linalg.norm(d)
            view.CameraFocalPoint = xc.tolist()
            view.CameraPosition = (xc + 10.0 * d).tolist()
            view.CameraViewUp = [0.0, 0.0, 1.0]
            view.CameraParallelScale = float(os.environ.get("ZOOM", str(0.7 * radius)))
        if artery_field:
            asrc = pv.XMLUnstructuredGridReader(FileName=[os.path.join(tmp, "artery_%d.vtu" % k)])
            asurf = pv.ExtractSurface(Input=asrc)
            adisp = pv.Show(asurf, view)
            pv.ColorBy(adisp, ("CELLS", "artery_value"))
            alut = pv.GetColorTransferFunction("artery_value")
            alut.AutomaticRescaleRangeMode = "Never"
            alut.ColorSpace = "RGB"
            alut.RGBPoints = [float(c) for s in samples for c in (avmin + s * (avmax - avmin), *acmap(s)[:3])]
            adisp.LookupTable = alut
            adisp.SetScalarBarVisibility(view, False)
            adisp.Specular = 0.1
            if view_kind == "crown":
                adisp.SetRepresentationType("Surface With Edges")
                adisp.EdgeColor = [0.15, 0.15, 0.15]
        png = os.path.join(tmp, "panel_%d.png" % i)
        pv.SaveScreenshot(png, view, ImageResolution=size, TransparentBackground=0)
        pv.Hide(surf, view)
        if artery_field:
            pv.Hide(asurf, view)
        images.append(png)

    # compose: every panel cut to the same box (the union of the drawn parts), so that the
    # panels keep one scale
    n = len(images)
    pix = [plt.imread(png)[:, :, :3] for png in images]
    drawn = np.any([np.any(im < 0.98, axis=2) for im in pix], axis=0)
    rr, cc = np.nonzero(drawn)
    pad = 6
    r0, r1 = max(rr.min() - pad, 0), min(rr.max() + pad + 1, size[1])
    c0, c1 = max(cc.min() - pad, 0), min(cc.max() + pad + 1, size[0])
    pix = [im[r0:r1, c0:c1] for im in pix]
    cols = {"side": 2 if n % 2 == 0 else 1, "end": n, "crown": n}[view_kind]
    cols = int(os.environ.get("COLS", cols))
    rows = -(-n // cols)
    pw = {"side": 9.0 / cols, "end": 3.0, "crown": 3.2}[view_kind]
    ph = pw * (r1 - r0) / (c1 - c0)
    width = pw * cols + 1.3 + (1.1 if artery_field else 0.0)
    fig = plt.figure(figsize=(width, (ph + (0.3 if view_kind == "side" and cols == 1 else 0.45)) * rows + 0.45))
    top = 1 - 0.45 / fig.get_figheight()
    for i, im in enumerate(pix):
        t, title = shots[i]
        k = steps[i]
        row = metrics_row(res, base, times[k])
        cap = "t = %.3g s" % times[k]
        if row is not None and "D_mean [%s]" % unit in row:
            cap += ", mean outer D = %.3f %s" % (float(row["D_mean [%s]" % unit]), unit)
        if row is not None and "lumen_D_mean [%s]" % unit in row:
            cap += "\nlumen D mean %.3f, min %.3f %s" % (float(row["lumen_D_mean [%s]" % unit]),
                                                     float(row["lumen_D_min [%s]" % unit]), unit)
        if title:
            cap = "%s%s(%s)" % (title, " " if view_kind == "side" and cols == 1 else "\n", cap)
        r, c = divmod(i, cols)
        h = (top - 0.02) / rows
        ax = fig.add_axes([0.01 + c * pw / width, top - (r + 1) * h, pw / width * 0.98, h * 0.9])
        ax.imshow(im, interpolation="antialiased")
        ax.set_axis_off()
        ax.set_title(cap, fontsize=9, pad=2)
    fig.suptitle(os.environ.get("TITLE", deck.get("title", base)), fontsize=11, y=0.995)
    norm = colors.Normalize(vmin, vmax)
    extend = "max" if vmax < np.nanmax(allv) - 1e-12 * abs(np.nanmax(allv)) else "neither"
    cax = fig.add_axes([1 - 0.95 / width, 0.15, 0.16 / width, 0.65 * top])
    fig.colorbar(cm.ScalarMappable(norm, cmap), cax=cax, label=label, extend=extend)
    if artery_field:  # the stent's bar moves left, the artery's takes the right
        cax.set_position([1 - 2.05 / width, 0.15, 0.16 / width, 0.65 * top])
        aext = "max" if avmax < np.nanmax(alla) - 1e-12 * abs(np.nanmax(alla)) else "neither"
        if avmin > np.nanmin(alla) + 1e-12 * abs(np.nanmin(alla)):
            aext = "both" if aext == "max" else "min"
        bax = fig.add_axes([1 - 0.95 / width, 0.15, 0.16 / width, 0.65 * top])
        fig.colorbar(cm.ScalarMappable(colors.Normalize(avmin, avmax), acmap), cax=bax,
                     label=os.environ.get("ARTERY_LABEL", artery_field), extend=aext)
    fig.savefig(out, dpi=int(os.environ.get("DPI", "100")), bbox_inches="tight", pad_inches=0.05)
    if os.environ.get("PALETTE", "1") != "0":
        try:  # a 256-colour palette: a third of the size
            from PIL import Image
            rgb = Image.open(out).convert("RGB")
            pal = rgb.quantize(256, method=Image.Quantize.MEDIANCUT)
            rgb.quantize(palette=pal, dither=Image.Dither.FLOYDSTEINBERG).save(out, optimize=True)
        except ImportError:
            pass
    print("wrote %s (output steps %s; %s from %.4g to %.4g, shown %.4g to %.4g)"
          % (out, ", ".join(str(k) for k in steps), field, np.nanmin(allv), np.nanmax(allv), vmin, vmax))
    if artery_field:
        print("artery: %s from %.4g to %.4g, shown %.4g to %.4g" % (artery_field, alla.min(), alla.max(), avmin, avmax))


if __name__ == "__main__":
    main()
