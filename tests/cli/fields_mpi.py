#!/usr/bin/python3
"""Output->field list = all on 1 and 2 MPI ranks.

usage: fields_mpi.py STENTOR WORKDIR DECK MPIEXEC NPFLAG
DECK is the uniaxial block (inputs/block3d.xml; run as a copy with P1 cells of size 0.5,
`field list` = all and `times` = {0.3}). Checks: both runs write the same steps (times
0, 0.25, 0.3, 0.5, 0.75, 1: 0.3 is reached by a shortened step), every dataset of every
step agrees between the ranks to 1e-8 of its largest value (mpi_rank aside: it differs),
the mesh datasets and their attributes are bitwise equal and so is the .xdmf text (the
2-rank file is written in parallel, each rank its rows: io/XdmfWriter.hpp),
the sum of reaction_force over each face's nodes equals the history's reaction of that
face's set, and meshio's TimeSeriesReader reads every field with the right shape.
Needs Debian's python3-meshio, python3-h5py, python3-numpy; exit 77 (skipped) without.
"""
import csv
import os
import re
import shutil
import subprocess
import sys

try:
    import h5py
    import meshio
    import numpy as np
except ImportError as e:  # pragma: no cover
    print("SKIP: %s" % e)
    sys.exit(77)

stentor, work, deck, mpiexec, npflag = sys.argv[1:6]
failures = []


def check(cond, what):
    if not cond:
        failures.append(what)
        print("FAIL: " + what)


shutil.rmtree(work, ignore_errors=True)
os.makedirs(work)
text = open(deck).read()
text = re.sub(r'(name="file" type="string" value=")([^"/][^"]*)"',
              lambda m: m.group(1) + os.path.join(os.path.dirname(os.path.abspath(deck)), m.group(2)) + '"', text)
text = text.replace('name="order" type="int" value="2"', 'name="order" type="int" value="1"')
text = text.replace('name="size" type="double" value="0.25"', 'name="size" type="double" value="0.5"')
text = text.replace('<ParameterList name="Output">', '<ParameterList name="Output">\n'
                    '    <Parameter name="field list" type="string" value="all"/>\n'
                    '    <Parameter name="times" type="Array(double)" value="{0.3}"/>', 1)
copy = os.path.join(work, "deck.xml")
open(copy, "w").write(text)
flags = ["--oversubscribe"] if "Open MPI" in subprocess.run([mpiexec, "--version"], capture_output=True, text=True).stdout else []
outs = {}
for np_ in (1, 2):
    out = os.path.join(work, "out%d" % np_)
    r = subprocess.run([mpiexec, npflag, str(np_)] + flags + [stentor, "--output", out, copy], capture_output=True, text=True)
    print("\n".join(l for l in r.stdout.splitlines() if "step " in l or "Summary" in l))
    if r.returncode != 0:
        print(r.stdout, r.stderr)
        sys.exit("FAIL: %d rank(s): exit %d" % (np_, r.returncode))
    outs[np_] = out
base = "block3d"
h = [h5py.File(os.path.join(outs[n], base + ".h5"), "r") for n in (1, 2)]
steps = sorted((k for k in h[0] if k.startswith("step_")), key=lambda k: int(k[5:]))
times = [float(h[0][k].attrs["time"]) for k in steps]
print("output times:", times)
check(np.allclose(times, [0, 0.25, 0.3, 0.55, 0.8, 1.0], rtol=0, atol=1e-14), "output times %s" % times)
expected = {"displacement", "reaction_force", "cauchy_stress_nodal", "von_mises_nodal", "cauchy_stress", "von_mises",
            "principal_stress", "green_lagrange_strain", "log_strain", "J", "mpi_rank"}
worst = 0.0
for k in steps:
    check(set(h[0][k]) == expected, "%s: datasets %s" % (k, sorted(h[0][k])))
    check(set(h[1][k]) == set(h[0][k]), "%s: 2 ranks wrote other datasets" % k)
    for f in h[0][k]:
        if f == "mpi_rank" or f not in h[1][k]:
            continue
        a, b = h[0][k][f][()], h[1][k][f][()]
        scale = max(np.abs(a).max(), 1e-300)
        d = np.abs(a - b).max() / scale
        worst = max(worst, d)
        check(d < 1e-8, "%s/%s: 1 vs 2 ranks differ by %.2e of its largest value" % (k, f, d))
print("largest relative difference 1 vs 2 ranks: %.2e" % worst)
# The mesh (written by both ranks, each its rows) bitwise, its attributes, the XDMF text.
mesh_items = []
h[0]["mesh"].visititems(lambda name, obj: mesh_items.append(name))
for name in mesh_items:
    a, b = h[0]["mesh"][name], h[1]["mesh"].get(name)
    check(b is not None, "mesh/%s: absent in the 2-rank file" % name)
    if b is None:
        continue
    check(dict(a.attrs) == dict(b.attrs), "mesh/%s: attributes differ" % name)
    if isinstance(a, h5py.Dataset):
        check(a.dtype == b.dtype and a.shape == b.shape and np.array_equal(a[()], b[()]), "mesh/%s: 1 vs 2 ranks differ" % name)
print("mesh datasets and attributes bitwise equal:", len(mesh_items))
for k in steps:
    check(h[0][k].attrs["time"] == h[1][k].attrs["time"], "%s: time attribute differs" % k)
x1, x2 = (open(os.path.join(outs[n], base + ".xdmf")).read() for n in (1, 2))
check(x1 == x2, "the .xdmf text differs between 1 and 2 ranks")
check(h[1][steps[-1]]["mpi_rank"][()].max() == 1, "2 ranks: mpi_rank does not reach 1")
# reaction_force per face = the history's reaction of its set (2-rank run, every step).
rows = list(csv.DictReader(open(os.path.join(outs[2], base + "_history.csv"))))
X = h[1]["mesh/coordinates"][()]
for i, k in enumerate(steps[1:]):
    R = h[1][k]["reaction_force"][()]
    for col, axis, at in (("reaction_left_x", 0, 0.0), ("reaction_pull_x", 0, 1.0), ("reaction_front_y", 1, 0.0),
                          ("reaction_bottom_z", 2, 0.0)):
        s = R[X[:, axis] == at, axis].sum()
        ref = float(rows[i][col])
        check(abs(s - ref) <= 1e-10 * abs(float(rows[i]["reaction_pull_x"])), "%s %s: sum %.12g, history %.12g" % (k, col, s, ref))
# meshio reads the new fields (tensors as 9 components per row, as HDF5 stores them).
with meshio.xdmf.TimeSeriesReader(os.path.join(outs[2], base + ".xdmf")) as r:
    points, cells = r.read_points_cells()
    t, pd, cd = r.read_data(r.num_steps - 1)
    nc = sum(len(c.data) for c in cells)
    for f, shape in (("reaction_force", (len(points), 3)), ("cauchy_stress_nodal", (len(points), 9)),
                     ("von_mises_nodal", (len(points),)), ("displacement", (len(points), 3))):
        check(f in pd and pd[f].shape == shape, "meshio point field %s: %s" % (f, pd[f].shape if f in pd else "absent"))
    for f, shape in (("principal_stress", (nc, 3)), ("green_lagrange_strain", (nc, 9)), ("log_strain", (nc, 9))):
        got = np.concatenate(cd[f]) if f in cd else None
        check(got is not None and got.shape == shape, "meshio cell field %s: %s" % (f, None if got is None else got.shape))
if failures:
    sys.exit("%d failure(s)" % len(failures))
print("OK")
