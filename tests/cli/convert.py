#!/usr/bin/python3
"""tools/stentor_convert.py on a real run: the converted files open with meshio.read.

usage: convert.py STENTOR CONVERT WORKDIR DECK
Runs DECK (fields at every step), converts every output step to VTU (+ .pvd) and the last
one to legacy VTK, and checks each file read back with meshio.read against the HDF5 read
with h5py: the points (= /mesh/coordinates), the cell count, every point and cell field of
the step (displacement, J, von_mises, ...) bit for bit, the times of the .pvd.
Then the refusals: existing files (exit 2, nothing changed), a step out of range, a file
that is not a result. Exit 77 (skipped) without python3-meshio/h5py/numpy.
"""
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

stentor, convert, work, deck = sys.argv[1:5]
shutil.rmtree(work, ignore_errors=True)
os.makedirs(work)
fails = []


def check(cond, what):
    if not cond:
        fails.append(what)
        print("FAIL: " + what)


text = open(deck).read()
text = re.sub(r'value="([^"/]+\.geo)"', lambda m: 'value="%s"' % os.path.join(os.path.dirname(os.path.abspath(deck)), m.group(1)), text)
run_deck = os.path.join(work, "deck.xml")
open(run_deck, "w").write(text)
r = subprocess.run([stentor, "--output", os.path.join(work, "res"), run_deck], capture_output=True, text=True)
check(r.returncode == 0, "the run: exit %d\n%s" % (r.returncode, r.stdout[-2000:] + r.stderr[-2000:]))
base = re.search(r'name="basename" type="string" value="([^"]+)"', text)
base = base.group(1) if base else os.path.splitext(os.path.basename(deck))[0]
xdmf = os.path.join(work, "res", base + ".xdmf")
h5 = h5py.File(os.path.join(work, "res", base + ".h5"), "r")
nsteps = len([k for k in h5.keys() if k.startswith("step_")])
check(nsteps >= 3, "at least 3 output steps (got %d)" % nsteps)

r = subprocess.run([convert, xdmf, "--all"], capture_output=True, text=True)
check(r.returncode == 0, "--all: exit %d: %s" % (r.returncode, r.stderr))
out = os.path.join(work, "res_vtu")
coords = h5["mesh/coordinates"][()]
for k in range(nsteps):
    m = meshio.read(os.path.join(out, "%s_%d.vtu" % (base, k)))
    g = h5["step_%d" % k]
    check(np.array_equal(m.points[:, : coords.shape[1]], coords), "step %d: points" % k)
    ncells = sum(len(c.data) for c in m.cells)
    for name in g.keys():
        v = g[name][()]
        if name in m.point_data:
            check(np.array_equal(np.asarray(m.point_data[name]).reshape(v.shape), v, equal_nan=True), "step %d: point field %s" % (k, name))
        elif name in m.cell_data:
            check(np.array_equal(np.concatenate(m.cell_data[name]).reshape(v.shape), v, equal_nan=True), "step %d: cell field %s" % (k, name))
            check(len(v) == ncells, "step %d: %s has one value per cell" % (k, name))
        else:
            check(False, "step %d: field %s missing from the VTU" % (k, name))
pvd = open(os.path.join(out, base + ".pvd")).read()
times = [float(t) for t in re.findall(r'timestep="([^"]+)"', pvd)]
check(times == [float(h5["step_%d" % k].attrs["time"]) for k in range(nsteps)], "the .pvd times")

r = subprocess.run([convert, xdmf, "--last", "--ext", "vtk", "--out", os.path.join(work, "vtk")], capture_output=True, text=True)
check(r.returncode == 0, "--last --ext vtk: exit %d: %s" % (r.returncode, r.stderr))
m = meshio.read(os.path.join(work, "vtk", "%s_%d.vtk" % (base, nsteps - 1)))
last = h5["step_%d" % (nsteps - 1)]
check(np.array_equal(np.asarray(m.point_data["displacement"]).reshape(last["displacement"].shape), last["displacement"][()]),
      "legacy VTK: the last displacement")

before = {f: os.path.getmtime(os.path.join(out, f)) for f in os.listdir(out)}
r = subprocess.run([convert, xdmf, "--all"], capture_output=True, text=True)
check(r.returncode == 2 and "exists" in r.stderr and "nothing written" in r.stderr, "refuses existing files: %d %s" % (r.returncode, r.stderr))
check(before == {f: os.path.getmtime(os.path.join(out, f)) for f in os.listdir(out)}, "nothing changed by the refused run")
r = subprocess.run([convert, xdmf, "--step", str(nsteps)], capture_output=True, text=True)
check(r.returncode == 2 and "--step %d: the file has output steps 0 .. %d" % (nsteps, nsteps - 1) in r.stderr, "step out of range: %s" % r.stderr)
r = subprocess.run([convert, run_deck, "--out", os.path.join(work, "bad")], capture_output=True, text=True)
check(r.returncode == 2 and "is not a readable Stentor XDMF time series" in r.stderr and not os.path.exists(os.path.join(work, "bad")),
      "a file that is not a result: %d %s" % (r.returncode, r.stderr))
print("converted %d steps of %s; %d failures" % (nsteps, base, len(fails)))
sys.exit(1 if fails else 0)
