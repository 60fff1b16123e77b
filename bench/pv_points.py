"""Open a run's fields.xdmf in ParaView as a user would and print, for the
first and last frame, the number of points and cells ParaView reads and the
bounds of the points; exits 1 when a frame has no points or fewer cells than
points (ParaView's default Surface view draws cells).  Run by pvbatch under a
virtual X server (tests/client/pvbatch.sh, or xvfb-run -a pvbatch), e.g. by
bench/impact_block_3d.sh:

    pvbatch pv_points.py RUN/fields.xdmf
"""
import sys

from paraview import simple as pv

src = pv.OpenDataFile(sys.argv[1])
times = list(src.TimestepValues) if src.TimestepValues else [0.0]
ok = True
for t in (times[0], times[-1]):
    src.UpdatePipeline(t)
    info = src.GetDataInformation()
    n_pts, n_cells = info.GetNumberOfPoints(), info.GetNumberOfCells()
    b = info.GetBounds()
    print(f"pv_points: t = {t:.6g} s: {n_pts} points, {n_cells} cells, "
          f"bounds x [{b[0]:.6g}, {b[1]:.6g}] y [{b[2]:.6g}, {b[3]:.6g}] z [{b[4]:.6g}, {b[5]:.6g}]")
    ok = ok and n_pts > 0 and n_cells >= n_pts
print("pv_check: " + ("ok" if ok else "FAILED"))
sys.exit(0 if ok else 1)
