"""Open a spall run's fields.xdmf in ParaView as a user would, and check it.

Run by pvbatch under a virtual X server (tests/client/pvbatch.sh):

    pvbatch pv_check.py --xdmf RUN/fields.xdmf --reader default|legacy --png OUT.png

--reader default: paraview.simple.OpenDataFile, i.e. the reader ParaView picks
for the file name (5.11: Xdmf3ReaderS); legacy: the older "XDMF Reader"
(XDMFReader).  On the last time step it checks
  - one cell per particle (ParaView's default Surface representation draws
    cells only: with 0 cells the view is empty, issue 23);
  - the point coordinates' bounds equal the HDF5 /position data's, and every
    point array's per-component range equals the HDF5 dataset's (read with
    h5py from the frame the XDMF's last grid names), and the component counts
    agree;
  - with the default reader, the components of every vector and tensor carry
    spall's names (x y z; xx yy zz xy yz xz), as ParaView labels them;
  - the default representation, coloured by each point array in turn, renders
    particle pixels: at least --min-fill of the image differs from the same
    view with the data hidden (ParaView's own background and axes).  --png
    keeps the picture coloured by --color (default: the first array).
Prints one line per finding and exits 1 on any failure.
"""
import argparse
import os
import sys
import xml.etree.ElementTree as ET

import h5py
import numpy as np
from paraview import simple as pv
from paraview.vtk.vtkIOImage import vtkPNGReader
from vtkmodules.util.numpy_support import vtk_to_numpy

def last_frame(xdmf):
    """The last temporal entry of the index: the HDF5 file its particle grid
    reads, and the inline points and triangle count of its rigid bodies."""
    root = ET.parse(xdmf).getroot()
    temporal = [g for g in root.iter("Grid") if g.get("CollectionType") == "Temporal"][0]
    frames = [g for g in temporal if g.tag == "Grid"]
    last = frames[-1]
    grids = [last] if last.get("GridType") == "Uniform" else [g for g in last if g.tag == "Grid"]
    h5path, body_pts, body_cells = None, [], 0
    for g in grids:
        item = g.find("Geometry/DataItem")
        if item.get("Format") == "HDF":
            h5name = item.text.strip().split(":")[0]
            h5path = os.path.join(os.path.dirname(os.path.abspath(xdmf)), h5name)
        else:
            body_pts.append(np.array(item.text.split(), dtype=float).reshape(-1, 3))
            body_cells += int(g.find("Topology").get("NumberOfElements"))
    pts = np.concatenate(body_pts) if body_pts else np.zeros((0, 3))
    return h5path, len(frames), pts, body_cells


def component_names(xdmf):
    """{array: [component names]} from the <Information Name="components">
    of the last frame's attributes (spall's names, e.g. xx yy zz xy yz xz)."""
    root = ET.parse(xdmf).getroot()
    temporal = [g for g in root.iter("Grid") if g.get("CollectionType") == "Temporal"][0]
    last = [g for g in temporal if g.tag == "Grid"][-1]
    names = {}
    for attr in last.iter("Attribute"):
        for info in attr.findall("Information"):
            if info.get("Name") == "components":
                names[attr.get("Name")] = info.get("Value").split()
    return names


# The legacy XDMF reader expands a Tensor6 to a row-major 3x3 tensor reading
# the six columns in the XDMF specification's order (xx xy xz yy yz zz), not
# spall's (xx yy zz xy yz xz, VTK's, whose labels Xdmf3ReaderS shows): the
# HDF5 column behind each of its 9 components (measured, ParaView 5.11).
TENSOR6_AS_9 = [0, 1, 2, 1, 3, 4, 2, 4, 5]


def open_reader(xdmf, which):
    if which == "default":
        return pv.OpenDataFile(xdmf)
    return pv.XDMFReader(FileNames=[xdmf])


def read_png(png):
    r = vtkPNGReader()
    r.SetFileName(png)
    r.Update()
    return vtk_to_numpy(r.GetOutput().GetPointData().GetScalars())[:, :3]


def image_fill(png, empty_png):
    """Fraction of the pixels of @png that differ from the empty view's, and
    the fraction of those that are coloured (max - min channel > 40 of 255:
    not the grey of an uncoloured surface, shaded or not)."""
    px, bg = read_png(png), read_png(empty_png)
    changed = np.any(px != bg, axis=1)
    if not changed.any():
        return 0.0, 0.0
    c = px[changed].astype(int)
    sat = c.max(axis=1) - c.min(axis=1) > 40
    return float(np.count_nonzero(changed)) / px.shape[0], float(np.mean(sat))


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--xdmf", required=True)
    ap.add_argument("--reader", choices=["default", "legacy"], default="default")
    ap.add_argument("--png", required=True)
    ap.add_argument("--color", default=None)
    ap.add_argument("--min-fill", type=float, default=0.01)
    ap.add_argument("--min-colour", type=float, default=0.01)
    a = ap.parse_args()
    failures = []

    src = open_reader(a.xdmf, a.reader)
    print("reader: %s (%s)" % (src.GetXMLName(), a.reader))
    times = list(src.TimestepValues) if src.TimestepValues else [0.0]
    t = times[-1]
    src.UpdatePipeline(t)
    info = src.GetDataInformation()
    npts, ncells = info.GetNumberOfPoints(), info.GetNumberOfCells()
    print("time steps: %d, last t = %.9g s: %d points, %d cells" % (len(times), t, npts, ncells))

    h5path, nframes, body_pts, body_cells = last_frame(a.xdmf)
    comps = component_names(a.xdmf)
    if len(times) != nframes:
        failures.append("%d time steps, the index has %d frames" % (len(times), nframes))
    if body_cells:
        print("rigid bodies: %d points, %d triangles" % (body_pts.shape[0], body_cells))
    with h5py.File(h5path, "r") as f:
        pos = f["position"][()]
        n = pos.shape[0]
        want_pts, want_cells = n + body_pts.shape[0], n + body_cells
        if ncells != want_cells or npts != want_pts:
            failures.append("%d points and %d cells, expected %d and %d (one vertex cell per "
                            "particle, the bodies' triangles)" % (npts, ncells, want_pts, want_cells))
        allpts = np.concatenate([pos, body_pts])
        b = info.GetBounds()
        for c in range(3):
            lo, hi = allpts[:, c].min(), allpts[:, c].max()
            if (b[2 * c], b[2 * c + 1]) != (lo, hi):
                failures.append("bounds[%d] = (%r, %r), HDF5 /position and the bodies have (%r, %r)"
                                % (c, b[2 * c], b[2 * c + 1], lo, hi))
        arrays = list(src.PointData.keys())
        print("point arrays: %s" % ", ".join(arrays))
        for name in f.keys():
            ds = f[name]
            if name in ("position", "connectivity") or ds.ndim == 0:
                continue
            if name not in arrays:
                failures.append("HDF5 dataset /%s is not a point array" % name)
        for name in arrays:
            if name not in f:
                failures.append("point array %s has no HDF5 dataset" % name)
                continue
            data = f[name][()]
            data = data.reshape(data.shape[0], -1)
            arr = src.PointData[name]
            nc = arr.GetNumberOfComponents()
            cols = list(range(data.shape[1]))
            if a.reader == "legacy" and nc == 9 and data.shape[1] == 6:
                cols = TENSOR6_AS_9
            if nc != len(cols):
                failures.append("%s: %d components, HDF5 has %d" % (name, nc, data.shape[1]))
                continue
            for c in range(nc):
                got = tuple(arr.GetRange(c))
                want = (data[:, cols[c]].min(), data[:, cols[c]].max())
                if got != want:
                    failures.append("%s[%d]: range %r, HDF5 %r" % (name, c, got, want))
            labels = [arr.GetComponentName(c) for c in range(nc)] if nc > 1 else []
            # ParaView's labels are its own (X, Y, Z; XX .. XZ for a Tensor6):
            # with the default reader they must be spall's names, upper case
            want_labels = [s.upper() for s in comps.get(name, [])]
            if a.reader == "default" and nc > 1 and labels != want_labels:
                failures.append("%s: ParaView names the components %s, spall's are %s"
                                % (name, " ".join(labels), " ".join(want_labels) or "none"))
            print("  %s: %d component(s)%s, ranges equal to HDF5"
                  % (name, nc, " (" + " ".join(labels) + ")" if labels else ""))

    # rigid impactors and walls: their own index beside fields.xdmf
    bodies = None
    bpath = os.path.join(os.path.dirname(os.path.abspath(a.xdmf)), "bodies.xdmf")
    if os.path.exists(bpath):
        bodies = open_reader(bpath, a.reader)
        btimes = list(bodies.TimestepValues) if bodies.TimestepValues else [0.0]
        bodies.UpdatePipeline(t)
        binfo = bodies.GetDataInformation()
        _, bframes, bpts, bcells = last_frame(bpath)
        print("bodies.xdmf: %d time steps, %d points, %d triangles at t = %.9g s"
              % (len(btimes), binfo.GetNumberOfPoints(), binfo.GetNumberOfCells(), t))
        if btimes != times:
            failures.append("bodies.xdmf's times differ from fields.xdmf's")
        if (binfo.GetNumberOfCells(), binfo.GetNumberOfPoints()) != (bcells, bpts.shape[0]):
            failures.append("bodies.xdmf: %d triangles and %d points, the index has %d and %d"
                            % (binfo.GetNumberOfCells(), binfo.GetNumberOfPoints(), bcells,
                               bpts.shape[0]))

    view = pv.GetActiveViewOrCreate("RenderView")
    view.ViewSize = [480, 360]
    view.ViewTime = t
    disp = pv.Show(src, view)
    print("default representation: %s" % disp.Representation)
    if bodies is not None:  # in the camera's frame, out of the colour count
        pv.Show(bodies, view)
    view.ResetCamera()
    if b[5] - b[4] > 0:  # 3D: look from an oblique direction, z up
        cam = view.GetActiveCamera()
        cam.SetFocalPoint(0, 0, 0)
        cam.SetPosition(1.0, -1.6, 0.8)
        cam.SetViewUp(0, 0, 1)
        view.ResetCamera()
    if bodies is not None:
        pv.Hide(bodies, view)
    # The background as the user sees it (ParaView's palette, orientation
    # axes): the same view with the data hidden.
    pv.Hide(src, view)
    empty = a.png[:-4] + "_empty.png"
    pv.SaveScreenshot(empty, view, ImageResolution=[480, 360])
    pv.Show(src, view)
    color = a.color or (arrays[0] if arrays else None)
    for name in arrays + [color]:  # every array, then the screenshot's
        if name is not None:
            pv.ColorBy(disp, ("POINTS", name))
            disp.RescaleTransferFunctionToDataRange(False, True)
        pv.SaveScreenshot(a.png, view, ImageResolution=[480, 360])
        fill, sat = image_fill(a.png, empty)
        print("coloured by %s: %.1f %% of the image is particles, %.1f %% of them in colour"
              % (name, 100 * fill, 100 * sat))
        if name is not None:
            lo, hi = src.PointData[name].GetRange(-1)
            if hi > lo and sat < a.min_colour:
                failures.append("coloured by %s (range %g..%g): %.2f %% of the particle pixels in "
                                "colour (< %.2f %%): the particles are not coloured"
                                % (name, lo, hi, 100 * sat, 100 * a.min_colour))
        if fill < a.min_fill:
            failures.append("coloured by %s: only %.2f %% particle pixels (< %.2f %%): the "
                            "default representation shows nothing"
                            % (name, 100 * fill, 100 * a.min_fill))
    if bodies is not None:
        pv.Show(bodies, view)
        pv.SaveScreenshot(a.png, view, ImageResolution=[480, 360])
    os.remove(empty)

    for msg in failures:
        print("FAIL: " + msg)
    print("pv_check: %s" % ("FAILED" if failures else "ok"))
    return 1 if failures else 0


if __name__ == "__main__":
    if main() != 0:
        sys.exit(1)
