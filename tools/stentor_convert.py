#!/usr/bin/python3
"""Convert Stentor results (an XDMF time series + HDF5) to files that open anywhere.

usage: stentor_convert.py RESULT.xdmf [--step K | --last | --all] [--out DIR] [--ext vtu]
                          [--overwrite]

Stentor writes each run as one XDMF time series (<basename>.xdmf + .h5; rigid obstacles
in <basename>_obstacles.xdmf). ParaView opens it directly, but `meshio.read` does not
(it reads single-grid files only). This tool writes one mesh file per output step, in any
format meshio writes, chosen by --ext (vtu, the default; vtk, xdmf, msh, ...):
  --step K   the output step K (0 = the initial state; negative counts from the end)
  --last     the last output step (the default)
  --all      every step, and with vtu a ParaView collection <basename>.pvd with the times
Files go to --out (default: a folder beside the result's, <result folder>_<ext>, so
that a later run into the result folder does not meet them) as <basename>_<K>.<ext>. Existing files
are not overwritten unless --overwrite is given. Every point field (displacement,
velocity, ...) and cell field (stress, von_mises, cell_block, ...) is kept; the times are in the .pvd
and printed.
Exit status: 0 done, 2 bad arguments or input (the message names it), 77 meshio missing.
"""
import argparse
import os
import sys
import xml.sax.saxutils as su

try:
    import meshio
except ImportError as e:  # pragma: no cover
    print("stentor_convert: %s (install python3-meshio)" % e, file=sys.stderr)
    sys.exit(77)


def fail(msg):
    print("stentor_convert: " + msg, file=sys.stderr)
    sys.exit(2)


def parse():
    p = argparse.ArgumentParser(description="Convert a Stentor XDMF time series to one mesh file per step.")
    p.add_argument("xdmf")
    g = p.add_mutually_exclusive_group()
    g.add_argument("--step", type=int)
    g.add_argument("--last", action="store_true")
    g.add_argument("--all", action="store_true")
    p.add_argument("--out")
    p.add_argument("--ext", default="vtu")
    p.add_argument("--overwrite", action="store_true")
    return p.parse_args()


def main():
    a = parse()
    if not os.path.isfile(a.xdmf):
        fail("no such result file: %s" % a.xdmf)
    base = os.path.splitext(os.path.basename(a.xdmf))[0]
    ext = a.ext.lstrip(".")
    out = a.out or os.path.dirname(os.path.abspath(a.xdmf)).rstrip(os.sep) + "_" + ext
    try:
        reader = meshio.xdmf.TimeSeriesReader(a.xdmf)
        reader.__enter__()
        points, cells = reader.read_points_cells()
    except Exception as e:  # meshio raises many kinds on a file that is not a time series
        fail("%s is not a readable Stentor XDMF time series: %s" % (a.xdmf, e))
    n = reader.num_steps
    if a.all:
        steps = list(range(n))
    elif a.step is not None:
        k = a.step + n if a.step < 0 else a.step
        if not 0 <= k < n:
            fail("--step %d: the file has output steps 0 .. %d" % (a.step, n - 1))
        steps = [k]
    else:
        steps = [n - 1]
    names = [os.path.join(out, "%s_%d.%s" % (base, k, ext)) for k in steps]
    pvd = os.path.join(out, base + ".pvd") if a.all and ext == "vtu" else None
    clash = [f for f in names + ([pvd] if pvd else []) if os.path.exists(f)]
    if clash and not a.overwrite:
        fail("%s exists (and %d more); nothing written: use --overwrite or another --out" % (clash[0], len(clash) - 1))
    os.makedirs(out, exist_ok=True)
    times = []
    for k, name in zip(steps, names):
        t, point_data, cell_data = reader.read_data(k)
        mesh = meshio.Mesh(points, cells, point_data=point_data, cell_data=cell_data)
        try:
            mesh.write(name)
        except Exception as e:
            fail("cannot write %s as .%s: %s" % (name, ext, e))
        times.append(t)
    reader.__exit__(None, None, None)
    if pvd:
        with open(pvd, "w") as f:
            f.write('<?xml version="1.0"?>\n<VTKFile type="Collection" version="0.1">\n<Collection>\n')
            for t, name in zip(times, names):
                f.write('<DataSet timestep="%.17g" file=%s/>\n' % (t, su.quoteattr(os.path.basename(name))))
            f.write("</Collection>\n</VTKFile>\n")
    shown = ", ".join("%d (t = %g)" % (k, t) for k, t in zip(steps, times)) if len(steps) <= 4 else "0 .. %d" % (n - 1)
    print("wrote %d file%s to %s: step%s %s%s" % (len(names), "" if len(names) == 1 else "s", out, "" if len(names) == 1 else "s",
                                                  shown, "; collection " + os.path.basename(pvd) if pvd else ""))


if __name__ == "__main__":
    main()
