#!/usr/bin/python3
"""The XDMF/HDF5 results as a user opens them: meshio's TimeSeriesReader and h5py.

usage: xdmf_readers.py STENTOR WORKDIR DECK [ORDER]
       xdmf_readers.py --results DIR BASENAME
Runs DECK (a copy with Mesh->order set to ORDER when given; fields at every step) and
checks, for every output step: meshio reads the points (= /mesh/coordinates), the cells (types, counts, node order
= meshio's/VTK's: in the undeformed mesh of a flat-sided body every mid-edge node of a
tetra10/triangle6 is the midpoint of meshio's edge, tetrahedra and hexahedra have positive
volume in VTK's vertex order), the time (= the history CSV's time column, = the HDF5 step
group's "time" attribute), the node and cell fields with the right shapes, and the
displacement equal to h5py's /step_<k>/displacement; with rigid obstacles in the deck, their
<base>_obstacles.xdmf the same way (io/Obstacles.hpp): the field file's times, line
segments (2D) or quadrilaterals (3D), cell_block naming the rigid pairs in deck order, each
step's displacement = its /step_<k>/coordinates - the first step's, non-zero at the end
when the deck moves or inflates an obstacle; without rigid obstacles no such file. With --results, the same checks of
the results folder DIR as it is, e.g. a run's <out>.partial after `kill -9` (restart.sh):
each XDMF step's time is 0 or a history row's, in order (fields are written after the
row). Needs Debian's python3-meshio, python3-h5py and python3-numpy (ci/setup.sh
installs them); exit 77 (skipped) without.
"""
import csv
import os
import xml.etree.ElementTree as ET
import re
import shutil
import subprocess
import sys

try:
    import h5py
    import meshio
    import numpy as np
except ImportError as e:  # pragma: no cover
    print("SKIP: %s (install python3-meshio python3-h5py python3-numpy)" % e)
    sys.exit(77)


# meshio cell type -> (nodes, VTK edges of the mid-edge nodes, in meshio's order)
EDGES = {
    "triangle6": [(0, 1), (1, 2), (2, 0)],
    "tetra10": [(0, 1), (1, 2), (2, 0), (0, 3), (1, 3), (2, 3)],
}
failures = []


def check(cond, what):
    if not cond:
        failures.append(what)
        print("FAIL: " + what)


def tet_volumes(p, c):
    a, b, d, e = (p[c[:, i]] for i in range(4))
    return np.einsum("ij,ij->i", np.cross(b - a, d - a), e - a) / 6.0


def hex_volumes(p, c):
    # VTK hexahedron: 0-1-2-3 a face, counter-clockwise seen from the opposite face 4-5-6-7
    # (node 4 + i above node i); its 5-tetrahedra split has 5 positive volumes.
    tets = [(0, 1, 3, 4), (1, 2, 3, 6), (1, 4, 5, 6), (3, 4, 6, 7), (1, 3, 4, 6)]
    return [tet_volumes(p, c[:, list(t)]) for t in tets]


def rigid_pairs(deck_text):
    """Names of the deck's contact pairs with an `obstacle`, in deck order."""
    root = ET.fromstring(deck_text)
    names = []
    for lst in root.iter("ParameterList"):
        if lst.get("name") == "Contact":
            for pair in lst.findall("ParameterList"):
                if any(p.get("name") == "obstacle" for p in pair.findall("Parameter")):
                    names.append(pair.get("name"))
    return names


def check_obstacles(out, base, times, pairs, moving):
    """<out>/<base>_obstacles.xdmf/.h5 as meshio and h5py read them (see the module doc)."""
    xdmf = os.path.join(out, base + "_obstacles.xdmf")
    if not pairs:
        check(not os.path.exists(xdmf), "no rigid obstacle: no %s" % xdmf)
        return
    check(os.path.exists(xdmf), "rigid obstacles %s: %s exists" % (pairs, xdmf))
    if not os.path.exists(xdmf):
        return
    legend = ET.parse(xdmf).getroot().find("Domain/Information[@Name='cell_block']").get("Value")
    check(legend == "; ".join("%d: %s" % (i, n) for i, n in enumerate(pairs)), "obstacles named %r" % legend)
    h5 = h5py.File(os.path.join(out, base + "_obstacles.h5"), "r")
    with meshio.xdmf.TimeSeriesReader(xdmf) as reader:
        points, cells = reader.read_points_cells()
        X0 = h5["step_0/coordinates"][()]
        check(np.array_equal(points, X0), "obstacles: points = /step_0/coordinates")
        check(len(cells) == 1 and cells[0].type in ("line", "quad"), "obstacles: one block of lines or quads")
        check(np.array_equal(cells[0].data, h5["mesh/topology"][()]), "obstacles: cells = /mesh/topology")
        check(reader.num_steps == len(times), "obstacles: %d steps, the field file's %d" % (reader.num_steps, len(times)))
        u = None
        for k in range(min(reader.num_steps, len(times))):
            t, point_data, cell_data = reader.read_data(k)
            check(t == times[k], "obstacles step %d: time %r = the field file's %r" % (k, t, times[k]))
            u = point_data.get("displacement")
            x = h5["step_%d/coordinates" % k][()]
            check(u is not None and np.array_equal(u, x - X0), "obstacles step %d: displacement = coordinates - first" % k)
            check(np.array_equal(cell_data["cell_block"][0], h5["mesh/cell_block"][()]), "obstacles step %d: cell_block" % k)
        if moving and u is not None:
            check(np.max(np.abs(u)) > 0, "obstacles: moved or inflated by the end")
        print("obstacles: %s, %d points, %d %s cells, %d steps, last max |u| %g" %
              (pairs, len(points), len(cells[0].data), cells[0].type, reader.num_steps, np.max(np.abs(u)) if u is not None else -1))
    h5.close()


def run_deck(stentor, work, deck, order):
    """Runs a copy of DECK with fields at every step; returns (results folder, basename)."""
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    deck_dir = os.path.dirname(os.path.abspath(deck))
    text = open(deck).read()
    # the mesh path made absolute, so that the copy still finds it
    text = re.sub(r'(name="file" type="string" value=")([^/"][^"]*)"',
                  lambda m: m.group(1) + os.path.join(deck_dir, m.group(2)) + '"', text)
    if order is not None:
        text, n = re.subn(r'(name="order" type="int" value=")\d+"', r'\g<1>%s"' % order, text)
        if n == 0:
            text = text.replace('<ParameterList name="Mesh">',
                                '<ParameterList name="Mesh">\n    <Parameter name="order" type="int" value="%s"/>' % order, 1)
    # fields on, at every step
    text = re.sub(r'name="fields" type="bool" value="[a-z]+"', 'name="fields" type="bool" value="true"', text)
    text = re.sub(r'name="every" type="int" value="\d+"', 'name="every" type="int" value="1"', text)
    copy = os.path.join(work, "deck.xml")
    open(copy, "w").write(text)
    out = os.path.join(work, "results")
    r = subprocess.run([stentor, "--output", out, copy], stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                       universal_newlines=True, env=dict(os.environ, OMP_NUM_THREADS="1"))
    if r.returncode != 0:
        print(r.stdout)
        print("FAIL: stentor exit status %d" % r.returncode)
        sys.exit(1)
    m = re.search(r'name="basename" type="string" value="([^"]+)"', text)
    base = m.group(1) if m else "stentor"
    return out, base, text


def check_results(out, base, every_step, deck_text=None):
    """meshio and h5py read <out>/<base>.xdmf/.h5 alike, step by step. every_step: the XDMF
    steps are the initial state and one per history row; else each step's time is 0 or a
    history row's time, in increasing order (a folder a killed run left)."""
    xdmf = os.path.join(out, base + ".xdmf")
    h5 = h5py.File(os.path.join(out, base + ".h5"), "r")
    with open(os.path.join(out, base + "_history.csv")) as f:
        rows = list(csv.DictReader(f))
    # The output times: the initial state, then the steps (all of them with Output->every = 1).
    csv_times = [0.0] + [float(row["time"]) for row in rows]

    with meshio.xdmf.TimeSeriesReader(xdmf) as reader:
        points, cells = reader.read_points_cells()
        X = h5["mesh/coordinates"][()]
        check(points.shape == X.shape and np.array_equal(points, X), "points = /mesh/coordinates")
        nn = X.shape[0]
        # Cells: the same as /mesh/topology, blocks in order.
        topo = h5["mesh/topology"][()]
        ncells = sum(len(c.data) for c in cells)
        check(ncells == len(h5["mesh/cell_block"]), "cell count = len(/mesh/cell_block)")
        if topo.ndim == 2:
            check(len(cells) == 1 and np.array_equal(cells[0].data, topo), "cells = /mesh/topology")
        nblocks = len([k for k in h5["mesh"] if k.startswith("block_")])
        expected = np.concatenate([h5["mesh/block_%d/connectivity" % b][()].reshape(-1)
                                   for b in range(nblocks)])
        check(np.array_equal(np.concatenate([c.data.reshape(-1) for c in cells]), expected),
              "cells = the blocks' connectivities in order")
        types = sorted({c.type for c in cells})
        print("mesh: %d nodes, cells %s" % (nn, ", ".join("%d %s" % (len(c.data), c.type) for c in cells)))
        for c in cells:
            conn = c.data
            h = np.max(np.ptp(X, axis=0))
            if c.type in EDGES:
                for k, (a, b) in enumerate(EDGES[c.type]):
                    nv = 3 if c.type == "triangle6" else 4  # vertices
                    mid = 0.5 * (X[conn[:, a]] + X[conn[:, b]])
                    err = np.max(np.abs(X[conn[:, nv + k]] - mid))
                    check(err < 1e-12 * h, "%s node %d is the midpoint of edge %s (off by %g)" % (c.type, nv + k, (a, b), err))
            if c.type in ("tetra", "tetra10"):
                v = tet_volumes(X, conn)
                check(np.all(v > 0), "%s: positive volume in VTK order (min %g)" % (c.type, v.min()))
            if c.type == "hexahedron":
                for v in hex_volumes(X, conn):
                    check(np.all(v > 0), "hexahedron: positive sub-volumes in VTK order (min %g)" % v.min())

        if every_step:
            check(reader.num_steps == len(csv_times),
                  "XDMF steps: the initial state and one per history row (%d, 1 + %d)" % (reader.num_steps, len(rows)))
        else:
            check(reader.num_steps >= 2, "XDMF steps: the initial state and at least one more (%d)" % reader.num_steps)
        last = -1.0
        for k in range(reader.num_steps):
            t, point_data, cell_data = reader.read_data(k)
            g = h5["step_%d" % k]
            check(t == float(g.attrs["time"]), "step %d: XDMF time %r = HDF5 time %r" % (k, t, g.attrs["time"]))
            if every_step and k < len(csv_times):
                check(abs(t - csv_times[k]) <= 1e-12 * max(1.0, abs(t)), "step %d: time %r = CSV time %r" % (k, t, csv_times[k]))
            if not every_step:
                check(t > last and any(abs(t - c) <= 1e-12 * max(1.0, abs(t)) for c in csv_times),
                      "step %d: time %r after the step before (%r) and a history row's time" % (k, t, last))
            last = t
            u = point_data.get("displacement")
            check(u is not None and u.shape == (nn, 3), "step %d: displacement %d x 3" % (k, nn))
            if u is not None:
                check(np.array_equal(u, g["displacement"][()]), "step %d: displacement = h5py's" % k)
                if k == reader.num_steps - 1:
                    check(np.max(np.abs(u)) > 0, "last step: a non-zero displacement")
            for name, ncomp in (("cauchy_stress", 9), ("von_mises", None), ("J", None), ("mpi_rank", None),
                                ("cell_block", None)):
                d = cell_data.get(name)
                check(d is not None and len(d) == len(cells), "step %d: cell field %s per cell block" % (k, name))
                if d is None:
                    continue
                for blk, c in zip(d, cells):
                    shape = (len(c.data), ncomp) if ncomp else (len(c.data),)
                    check(blk.shape == shape, "step %d: %s of shape %s, got %s" % (k, name, shape, blk.shape))
                check(np.array_equal(np.concatenate(d), g[name][()] if name != "cell_block" else h5["mesh/cell_block"][()]),
                      "step %d: %s = h5py's" % (k, name))
            J = np.concatenate(cell_data["J"])
            check(np.all(J > 0), "step %d: J > 0" % k)
            for name, d in point_data.items():
                check(d.shape[0] == nn, "step %d: node field %s has %d rows" % (k, name, nn))
        print("%d steps, times %s" % (reader.num_steps, [reader.read_data(k)[0] for k in range(reader.num_steps)]))
        print("node fields: %s; cell fields: %s" % (sorted(point_data), sorted(cell_data)))
        times = [reader.read_data(k)[0] for k in range(reader.num_steps)]
    h5.close()
    if deck_text is not None:
        moving = re.search(r'name="(translation|radius change)"', deck_text) is not None
        check_obstacles(out, base, times, rigid_pairs(deck_text), moving)


if len(sys.argv) == 4 and sys.argv[1] == "--results":
    check_results(sys.argv[2], sys.argv[3], False)
else:
    stentor, work, deck = sys.argv[1:4]
    order = sys.argv[4] if len(sys.argv) > 4 else None
    out, base, text = run_deck(stentor, work, deck, order)
    check_results(out, base, True, text)
if failures:
    print("%d check(s) failed" % len(failures))
    sys.exit(1)
print("OK")
