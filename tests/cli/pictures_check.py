# Reads PNGs back with VTK (pvpython) and checks each is W x H with the bodies drawn:
# in the picture without the legend (the right fifth) and the time label (the top
# tenth), more than 1 % of the pixels are not background, in MIN_COLOURS or more
# distinct colours (a varying field coloured, not one flat colour).
# usage: pvpython pictures_check.py W H MIN_COLOURS FILE.png...
import sys

import numpy as np
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkIOImage import vtkPNGReader

w, h, min_colours, files = int(sys.argv[1]), int(sys.argv[2]), int(sys.argv[3]), sys.argv[4:]
bad = 0
for f in files:
    r = vtkPNGReader()
    r.SetFileName(f)
    r.Update()
    img = r.GetOutput()
    nx, ny, _ = img.GetDimensions()
    rgb = vtk_to_numpy(img.GetPointData().GetScalars())[:, :3].reshape(ny, nx, 3)  # row 0 at the bottom
    rgb = rgb[: int(0.9 * ny), : int(0.8 * nx)].reshape(-1, 3)
    drawn = rgb[np.any(rgb < 250, axis=1)]
    colours = len({tuple(p) for p in drawn[:: max(1, len(drawn) // 20000)]})
    share = len(drawn) / float(len(rgb))
    print("%s: %d x %d, %.1f %% drawn, %d colours" % (f, nx, ny, 100 * share, colours))
    if (nx, ny) != (w, h) or share < 0.01 or colours < min_colours:
        print("FAIL: %s" % f)
        bad += 1
sys.exit(1 if bad else 0)
