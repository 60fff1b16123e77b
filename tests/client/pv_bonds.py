"""Open a run's bonds.xdmf (output.fields lists `bonds`) in ParaView as a
user would, and check it (ctest client_pv_bonds_*; run by pvbatch.sh):

    pvbatch pv_bonds.py --dir RUN --reader default|legacy --png OUT.png

On the last time step: one line cell per bond of the HDF5 frame
(bonds_NNNNNN.h5:/connectivity), the points those of the field frame's
/position, the cell array `broken` with the HDF5 data's range and as many
broken bonds; the default representation coloured by `broken` draws the
bonds (>= 1 % of the image differs from the empty view, some of it in
colour).  Prints its findings and "pv_check: ok|FAILED".
"""
import argparse
import glob
import os
import sys

import h5py
import numpy as np
from paraview import simple as pv
from paraview import servermanager as sm
from vtkmodules.util.numpy_support import vtk_to_numpy

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from pv_check import image_fill  # noqa: E402  (beside this script)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--dir", required=True)
    ap.add_argument("--reader", choices=["default", "legacy"], default="default")
    ap.add_argument("--png", required=True)
    a = ap.parse_args()
    failures = []
    xdmf = os.path.join(a.dir, "bonds.xdmf")
    src = pv.OpenDataFile(xdmf) if a.reader == "default" else pv.XDMFReader(FileNames=[xdmf])
    print("reader: %s (%s)" % (src.GetXMLName(), a.reader))
    times = list(src.TimestepValues) if src.TimestepValues else [0.0]
    frames = sorted(glob.glob(os.path.join(a.dir, "bonds_*.h5")))
    if len(times) != len(frames):
        failures.append("%d time steps, %d bond frames" % (len(times), len(frames)))
    t = times[-1]
    src.UpdatePipeline(t)
    data = sm.Fetch(src)
    if data.IsA("vtkMultiBlockDataSet"):
        data = data.GetBlock(0)
    last = frames[-1]
    with h5py.File(last, "r") as f:
        ij = f["connectivity"][()]
        broken = f["broken"][()]
        ht = f["time"][()]
    with h5py.File(last.replace("bonds_", "fields_"), "r") as f:
        npos = f["position"].shape[0]
    m = ij.shape[0]
    ncell, npt = data.GetNumberOfCells(), data.GetNumberOfPoints()
    print("last t = %.9g s (HDF5 %.9g): %d points, %d cells; HDF5: %d bonds, %d broken"
          % (t, ht, npt, ncell, m, int(broken.sum())))
    if ht != t:
        failures.append("last time %r, the bond frame's %r" % (t, ht))
    if (ncell, npt) != (m, npos):
        failures.append("%d cells and %d points, expected %d bonds and %d particles"
                        % (ncell, npt, m, npos))
    # both readers make 2-point polylines (VTK 4; measured, 5.11); lines (3) would do
    types = {data.GetCellType(c) for c in range(0, ncell, max(1, ncell // 97))}
    sizes = {data.GetCell(c).GetNumberOfPoints() for c in range(0, ncell, max(1, ncell // 97))}
    if not types <= {3, 4} or sizes != {2}:
        failures.append("cell types %s of %s points, expected 2-point lines"
                        % (sorted(types), sorted(sizes)))
    print("cell types %s, %s points each" % (sorted(types), sorted(sizes)))
    arr = data.GetCellData().GetArray("broken")
    if arr is None:
        failures.append("no cell array 'broken'")
    else:
        vals = vtk_to_numpy(arr)
        if not np.array_equal(vals, broken):
            failures.append("'broken' differs from the HDF5 data (%d vs %d broken)"
                            % (int(vals.sum()), int(broken.sum())))
        # each line joins the particles the HDF5 row names
        pts = vtk_to_numpy(data.GetPoints().GetData())
        for c in range(0, ncell, max(1, ncell // 50)):
            ids = data.GetCell(c).GetPointIds()
            got = sorted(ids.GetId(k) for k in range(ids.GetNumberOfIds()))
            if got != sorted(ij[c]):
                failures.append("cell %d joins %s, HDF5 row %s" % (c, got, list(ij[c])))
                break
        if broken.sum() == 0:
            failures.append("no broken bond in the last frame: the test run must break some")

    view = pv.GetActiveViewOrCreate("RenderView")
    view.ViewSize = [480, 360]
    view.ViewTime = t
    disp = pv.Show(src, view)
    print("default representation: %s" % disp.Representation)
    view.ResetCamera()
    pv.Hide(src, view)
    empty = a.png[:-4] + "_empty.png"
    pv.SaveScreenshot(empty, view, ImageResolution=[480, 360])
    pv.Show(src, view)
    pv.ColorBy(disp, ("CELLS", "broken"))
    disp.RescaleTransferFunctionToDataRange(False, True)
    pv.SaveScreenshot(a.png, view, ImageResolution=[480, 360])
    fill, sat = image_fill(a.png, empty)
    print("coloured by broken: %.1f %% of the image is bonds, %.1f %% of them in colour"
          % (100 * fill, 100 * sat))
    if fill < 0.01 or sat < 0.01:
        failures.append("the default representation shows no coloured bonds")
    os.remove(empty)
    for msg in failures:
        print("FAIL: " + msg)
    print("pv_check: %s" % ("FAILED" if failures else "ok"))
    return 1 if failures else 0


if __name__ == "__main__":
    if main() != 0:
        sys.exit(1)
