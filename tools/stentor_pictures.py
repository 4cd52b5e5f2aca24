"""Pictures of Stentor results with ParaView, without opening its window.

usage: pvbatch tools/stentor_pictures.py RESULT.xdmf [--field NAME]
           [--time last | all | T] [--body NAME] [--warp S] [--out DIR] [--size WxH]
           [--no-obstacles] [--overwrite] [--list]

Without an X display (a cluster node, ssh): xvfb-run -a -s -noreset pvbatch tools/stentor_pictures.py ...
Renders the deformed bodies coloured by one field with a titled colour legend (with the
deck's units) and the time, as PNG files, the way one would in ParaView's window:
  --field NAME   a point or cell field of the result (default von_mises); vectors and
                 tensors are coloured by their magnitude; --list prints what there is
  --time last    the last output (the default); `all` one picture per output time
                 (frames for a movie); a number T: the output time nearest to T
  --body NAME    only that body (a volume group of the mesh, e.g. stent)
  --warp S       the shape drawn is x + S u (default 1: the true deformed shape; 0: the
                 reference shape)
  --no-obstacles leave out the rigid obstacles (<basename>_obstacles.xdmf, drawn in grey)
  --out DIR      where the pictures go (default: a folder beside the result's,
                 <result folder>_pictures, so that a later run into the result folder
                 does not meet them), named <basename>_<field>.png, or with --time all
                 <basename>_<field>_<K>.png for output K
  --size WxH     image size in pixels (default 1200x900)
Every picture of one call uses one colour range: the field's range over the times drawn
(over the bodies drawn). Existing pictures are not overwritten unless --overwrite is
given. 2D results are seen from +z, 3D ones from an oblique direction.
Exit status: 0 done, 2 bad arguments or input (the message names it), 77 not run by
ParaView's pvbatch or pvpython.
"""
import argparse
import math
import os
import sys
import xml.etree.ElementTree as ET

try:
    import h5py
    import numpy as np
    from paraview import simple as pv
except ImportError as e:  # pragma: no cover
    print("stentor_pictures: %s (run it with ParaView's pvbatch: pvbatch %s ..., without an X display xvfb-run -a -s -noreset pvbatch %s ...; "
          "Debian: apt install paraview python3-paraview xvfb)" % (e, sys.argv[0], sys.argv[0]), file=sys.stderr)
    sys.exit(77)

# The dimension of each field, for the legend: L length, S stress, 1 none.
DIMENSION = {"displacement": "L", "velocity": "V", "cauchy_stress": "S", "von_mises": "S",
             "contact_pressure": "S", "contact_master_pressure": "S", "contact_master_traction": "S", "contact_gap": "L", "contact_slip": "L",
             "equivalent_plastic_strain": "1", "J": "1"}
UNITS = {"SI": {"L": "m", "S": "Pa", "V": "m/s"}, "mm-N-s": {"L": "mm", "S": "MPa", "V": "mm/s"},
         "mm-g-ms": {"L": "mm", "S": "MPa", "V": "mm/ms"}}
TITLES = {"von_mises": "von Mises stress", "displacement": "displacement", "J": "J = det F",
          "cauchy_stress": "Cauchy stress", "contact_pressure": "contact pressure",
          "contact_master_pressure": "contact pressure (master side)", "contact_master_traction": "contact traction (master side)",
          "equivalent_plastic_strain": "equivalent plastic strain", "velocity": "velocity"}


def fail(msg):
    print("stentor_pictures: " + msg, file=sys.stderr)
    sys.exit(2)


def parse():
    p = argparse.ArgumentParser(prog="stentor_pictures.py",
                                description="PNG pictures of a Stentor result under ParaView's pvbatch.")
    p.add_argument("xdmf")
    p.add_argument("--field", default="von_mises")
    p.add_argument("--time", default="last")
    p.add_argument("--body")
    p.add_argument("--warp", type=float, default=1.0)
    p.add_argument("--out")
    p.add_argument("--size", default="1200x900")
    p.add_argument("--no-obstacles", action="store_true")
    p.add_argument("--overwrite", action="store_true")
    p.add_argument("--list", action="store_true")
    return p.parse_args()


class Result:
    """What the XDMF says (fields and where they live, bodies) and the HDF5 holds."""

    def __init__(self, xdmf):
        if not os.path.isfile(xdmf) or not xdmf.endswith(".xdmf"):
            fail("no such result file: %s (expected the <basename>.xdmf of a run)" % xdmf)
        self.xdmf = os.path.abspath(xdmf)
        self.base = os.path.basename(xdmf)[: -len(".xdmf")]
        try:
            root = ET.parse(self.xdmf).getroot()
            self.h5 = h5py.File(self.xdmf[: -len(".xdmf")] + ".h5", "r")
        except (ET.ParseError, OSError) as e:
            fail("cannot read %s or its .h5: %s" % (xdmf, e))
        self.center = {}
        for a in root.iter("Attribute"):
            self.center.setdefault(a.get("Name"), a.get("Center"))
        self.bodies = {}
        for info in root.iter("Information"):
            if info.get("Name") == "cell_block":
                for item in info.get("Value", "").split(";"):
                    k, _, name = item.partition(":")
                    if name.strip():
                        self.bodies[name.strip()] = int(k)
        self.steps = sorted((k for k in self.h5 if k.startswith("step_")), key=lambda k: int(k[5:]))
        if not self.steps:
            fail("%s holds no output step" % xdmf)
        self.times = [float(self.h5[k].attrs["time"]) for k in self.steps]
        x = np.asarray(self.h5["mesh/coordinates"])
        self.planar = x.shape[1] == 2 or float(np.max(np.abs(x[:, 2]))) == 0.0
        self.cell_block = np.asarray(self.h5["mesh/cell_block"]).ravel() if "cell_block" in self.h5["mesh"] else None
        self.units = self._units()

    def _units(self):
        deck = os.path.join(os.path.dirname(self.xdmf), self.base + "_deck.xml")
        try:
            for plist in ET.parse(deck).getroot().iter("ParameterList"):
                if plist.get("name") == "Problem":
                    for p in plist.findall("Parameter"):
                        if p.get("name") == "units":
                            return p.get("value")
        except (OSError, ET.ParseError):
            return None
        return "SI"

    def is_vector(self, field):
        """More than one value per point or cell (a vector or tensor: drawn by its magnitude)."""
        d = self.h5[self.steps[-1]].get(field)
        return d is not None and d.ndim > 1 and d.shape[1] > 1

    def legend(self, field):
        u = UNITS.get(self.units or "", {}).get(DIMENSION.get(field, "?"))
        title = TITLES.get(field, field) + (" magnitude" if self.is_vector(field) else "")
        return title + (" [%s]" % u if u else "")

    def field_range(self, field, steps, body):
        """min, max of the field (its magnitude for vectors and tensors) over steps and body."""
        lo, hi = math.inf, -math.inf
        for k in steps:
            if field not in self.h5[self.steps[k]]:
                continue
            v = np.asarray(self.h5[self.steps[k]][field], dtype=float)
            v = v.reshape(v.shape[0], -1)
            v = v[:, 0] if v.shape[1] == 1 else np.linalg.norm(v, axis=1)
            if body is not None and self.center.get(field) == "Cell" and self.cell_block is not None:
                v = v[self.cell_block == self.bodies[body]]
            if v.size:
                lo, hi = min(lo, float(v.min())), max(hi, float(v.max()))
        if not math.isfinite(lo):
            fail("field '%s' has no values at the times asked for" % field)
        if hi - lo <= 1e-14 * max(1.0, abs(hi)):
            hi = lo + max(1.0, abs(lo)) * 1e-6
        return lo, hi


    def bounds(self, steps, body, warp):
        """The bounding box of the drawn shape x + warp u over steps (of one body)."""
        x = np.asarray(self.h5["mesh/coordinates"], dtype=float)
        x = np.pad(x, ((0, 0), (0, 3 - x.shape[1])))
        nodes = slice(None)
        top = np.asarray(self.h5["mesh/topology"])
        if body is not None and self.cell_block is not None and top.ndim == 2:  # (a "Mixed" list: all nodes)
            nodes = np.unique(top[self.cell_block == self.bodies[body]])
            nodes = nodes[nodes >= 0]
        lo, hi = np.full(3, math.inf), np.full(3, -math.inf)
        for k in steps:
            y = x.copy()
            if warp != 0.0 and "displacement" in self.h5[self.steps[k]]:
                u = np.asarray(self.h5[self.steps[k]]["displacement"], dtype=float)
                y[:, : u.shape[1]] += warp * u
            lo, hi = np.minimum(lo, y[nodes].min(axis=0)), np.maximum(hi, y[nodes].max(axis=0))
        return [v for pair in zip(lo, hi) for v in pair]


def chosen_steps(res, when):
    if when == "last":
        return [len(res.steps) - 1]
    if when == "all":
        return list(range(len(res.steps)))
    try:
        t = float(when)
    except ValueError:
        fail("--time %s: expected last, all or a time" % when)
    return [int(np.argmin([abs(s - t) for s in res.times]))]


def pipeline(res, a):
    reader = pv.Xdmf3ReaderS(FileName=[res.xdmf])
    src = reader
    if a.body is not None:
        src = pv.Threshold(Input=src, Scalars=["CELLS", "cell_block"])
        src.LowerThreshold = src.UpperThreshold = res.bodies[a.body]
        src.ThresholdMethod = "Between"
    if a.warp != 0.0 and "displacement" in res.center:
        src = pv.WarpByVector(Input=src, Vectors=["POINTS", "displacement"], ScaleFactor=a.warp)
    return src


def render(res, a, out):
    w, _, h = a.size.partition("x")
    try:
        size = [int(w), int(h)]
    except ValueError:
        fail("--size %s: expected WIDTHxHEIGHT in pixels, e.g. 1200x900" % a.size)
    steps = chosen_steps(res, a.time)
    lo, hi = res.field_range(a.field, steps, a.body)
    view = pv.CreateView("RenderView")
    view.ViewSize = size
    view.OrientationAxesVisibility = 0
    if hasattr(view, "UseColorPaletteForBackground"):
        view.UseColorPaletteForBackground = 0
    view.Background = [1.0, 1.0, 1.0]
    shown = pv.Show(pipeline(res, a), view)
    center = "POINTS" if res.center[a.field] == "Node" else "CELLS"
    pv.ColorBy(shown, (center, a.field, "Magnitude") if res.is_vector(a.field) else (center, a.field))
    lut = pv.GetColorTransferFunction(a.field)
    lut.ApplyPreset("Rainbow Uniform", True)
    lut.RescaleTransferFunction(lo, hi)
    lut.AutomaticRescaleRangeMode = "Never"
    shown.SetScalarBarVisibility(view, True)
    bar = pv.GetScalarBar(lut, view)
    bar.Title, bar.ComponentTitle = res.legend(a.field), ""
    bar.TitleColor = bar.LabelColor = [0.0, 0.0, 0.0]
    bar.TitleFontSize, bar.LabelFontSize = 18, 16
    bar.AutomaticLabelFormat = 0
    bar.LabelFormat = bar.RangeLabelFormat = "%.3g"
    obstacles = os.path.join(os.path.dirname(res.xdmf), res.base + "_obstacles.xdmf")
    if not a.no_obstacles and os.path.isfile(obstacles):
        ob = pv.Show(pv.Xdmf3ReaderS(FileName=[obstacles]), view)
        pv.ColorBy(ob, None)
        ob.AmbientColor = ob.DiffuseColor = [0.6, 0.6, 0.6]
        ob.Opacity = 0.5 if res.planar else 0.15  # in 3D the bodies seen through it
    label = pv.Text()
    tl = pv.Show(label, view)
    tl.Color, tl.FontSize, tl.WindowLocation = [0.0, 0.0, 0.0], 18, "Upper Left Corner"
    if res.planar:  # flat cells face either way: colours unshaded
        shown.Ambient, shown.Diffuse = 1.0, 0.0
    # The camera frames the bodies drawn over all the times drawn (not the obstacles).
    box = res.bounds(steps, a.body, a.warp)
    fp = [0.5 * (box[2 * i] + box[2 * i + 1]) for i in range(3)]
    view.CameraFocalPoint = fp
    if res.planar:
        view.CameraPosition, view.CameraViewUp = [fp[0], fp[1], fp[2] + 1.0], [0.0, 1.0, 0.0]
        view.CameraParallelProjection = 1
    else:
        view.CameraPosition = [p + d for p, d in zip(fp, [1.0, 0.8, 1.2])]
        view.CameraViewUp = [0.0, 1.0, 0.0]
    view.ResetCamera(*box)
    if res.planar:  # the bodies in the left 80 % of the picture, clear of the legend
        cam = view.GetActiveCamera()
        scale = 1.05 * max(0.5 * (box[3] - box[2]), 0.5 * (box[1] - box[0]) / 0.8 * size[1] / size[0])
        f, p = cam.GetFocalPoint(), cam.GetPosition()
        shift = 0.2 * scale * size[0] / size[1]
        cam.SetParallelScale(scale)
        cam.SetFocalPoint(f[0] + shift, f[1], f[2])
        cam.SetPosition(p[0] + shift, p[1], p[2])
    written = []
    for k in steps:
        name = "%s_%s%s.png" % (res.base, a.field, "_%d" % k if a.time == "all" else "")
        path = os.path.join(out, name)
        if os.path.exists(path) and not a.overwrite:
            fail("%s exists (give --overwrite to replace it)" % path)
        view.ViewTime = res.times[k]
        label.Text = "%s%s   t = %.6g" % (res.base, "  (" + a.body + ")" if a.body else "", res.times[k])
        pv.SaveScreenshot(path, view, ImageResolution=size, TransparentBackground=0)
        written.append((path, res.times[k]))
    # The view goes before the interpreter's exit: torn down after it, its GL context
    # crashes pvbatch (SIGSEGV) once the pictures are written.
    pv.Delete(view)
    return written, (lo, hi)


def main():
    a = parse()
    res = Result(a.xdmf)
    if a.list:
        print("fields: " + ", ".join("%s (%s)" % (f, "point" if c == "Node" else "cell")
                                     for f, c in sorted(res.center.items())))
        print("bodies: " + ", ".join(sorted(res.bodies, key=res.bodies.get)))
        print("times: %d outputs, t = %.6g ... %.6g" % (len(res.times), res.times[0], res.times[-1]))
        return 0
    if a.field not in res.center:
        fail("--field %s: %s has no such field; it has %s" % (a.field, a.xdmf, ", ".join(sorted(res.center))))
    if a.body is not None and a.body not in res.bodies:
        fail("--body %s: %s has no such body; it has %s" % (a.body, a.xdmf, ", ".join(sorted(res.bodies))))
    out = a.out or os.path.dirname(res.xdmf).rstrip(os.sep) + "_pictures"
    os.makedirs(out, exist_ok=True)
    written, (lo, hi) = render(res, a, out)
    for path, t in written:
        print("%s  (t = %.6g)" % (path, t))
    print("%d picture%s of %s, colour range %.6g ... %.6g" % (len(written), "" if len(written) == 1 else "s",
                                                            res.legend(a.field), lo, hi))
    return 0


if __name__ == "__main__":
    sys.exit(main())
