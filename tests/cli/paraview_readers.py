# ParaView 5.11's three XDMF readers (XDMFReader = Xdmf2, Xdmf3ReaderS, Xdmf3ReaderT) on
# a Stentor result: every reader sees every output time, all points and cells with the
# expected VTK cell type (quadratic types for P2), the fields, and the displacement of
# the last step equal to the HDF5 dataset (read with h5py).
# Usage (tests/cli/paraview_readers.sh runs it): pvbatch paraview_readers.py FILE.xdmf VTK_TYPE
import sys

import h5py
import numpy as np
from paraview import servermanager as sm
from paraview import simple as pv

xdmf, vtk_type = sys.argv[1], int(sys.argv[2])
h5 = h5py.File(xdmf[: -len(".xdmf")] + ".h5", "r")
steps = sorted((k for k in h5 if k.startswith("step_")), key=lambda k: int(k[5:]))
times = [float(h5[k].attrs["time"]) for k in steps]
u_last = np.asarray(h5[steps[-1]]["displacement"])
fail = []
for name in ["XDMFReader", "Xdmf3ReaderS", "Xdmf3ReaderT"]:
    ctor = getattr(pv, name)
    r = ctor(FileNames=[xdmf]) if name == "XDMFReader" else ctor(FileName=[xdmf])
    ts = list(r.TimestepValues or [])
    r.UpdatePipeline(ts[-1] if ts else 0.0)
    d = sm.Fetch(r)
    if d.IsA("vtkMultiBlockDataSet"):
        fail.append(f"{name}: a multiblock, expected one grid")
        continue
    types = {d.GetCellType(i) for i in range(d.GetNumberOfCells())}
    u = d.GetPointData().GetArray("displacement")
    du = None
    if u is not None:
        ua = np.array([u.GetTuple(i) for i in range(u.GetNumberOfTuples())])
        du = float(np.max(np.abs(ua - u_last[:, : ua.shape[1]])))
    print(f"[paraview] {name}: {len(ts)} times, {d.GetNumberOfPoints()} points, {d.GetNumberOfCells()} cells, "
          f"VTK types {sorted(types)}, max |u - u_h5| = {du}")
    if not np.allclose(ts, times, rtol=0, atol=1e-12):
        fail.append(f"{name}: times {ts} != {times}")
    if d.GetNumberOfPoints() != h5["mesh/coordinates"].shape[0]:
        fail.append(f"{name}: {d.GetNumberOfPoints()} points")
    if d.GetNumberOfCells() != h5["mesh/topology"].shape[0] and types != {vtk_type}:
        fail.append(f"{name}: cells")
    if types != {vtk_type}:
        fail.append(f"{name}: VTK cell types {sorted(types)}, expected {vtk_type}")
    for a in ["cell_block", "von_mises", "J"]:
        if d.GetCellData().GetArray(a) is None:
            fail.append(f"{name}: no cell field {a}")
    if du is None or du > 1e-12 * max(1.0, float(np.max(np.abs(u_last)))):
        fail.append(f"{name}: displacement differs from the HDF5 ({du})")
    pv.Delete(r)
for f in fail:
    print("FAIL:", f)
sys.exit(1 if fail else 0)
