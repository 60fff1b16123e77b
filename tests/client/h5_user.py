"""Read a spall frame with h5py the way a user's script would (docs/postprocessing.md).

    python3 h5_user.py RUN_DIR

Takes the newest fields_NNNNNN.h5 of RUN_DIR, prints its time, particle count,
each dataset's shape and unit, and checks what the docs promise: /time in s,
/position n x 3 in m, /connectivity = 0..n-1, every field n rows with a unit
attribute, finite values, and the same time as fields.xdmf's last grid.
Exits 1 naming the first broken promise.
"""
import glob
import os
import sys
import xml.etree.ElementTree as ET

import h5py
import numpy as np


def main(run_dir):
    frames = sorted(glob.glob(os.path.join(run_dir, "fields_*.h5")))
    if not frames:
        sys.exit("no fields_*.h5 in %s" % run_dir)
    path = frames[-1]
    with h5py.File(path, "r") as f:
        t = float(f["time"][()])
        step = int(f["step"][()])
        pos = f["position"][()]
        n = pos.shape[0]
        print("%s: t = %.6g s (step %d), %d particles" % (os.path.basename(path), t, step, n))
        if f["time"].attrs["unit"].decode() != "s":
            sys.exit("/time unit is not s")
        if pos.shape != (n, 3) or f["position"].attrs["unit"].decode() != "m":
            sys.exit("/position is %r in %s, expected (n, 3) in m"
                     % (pos.shape, f["position"].attrs["unit"]))
        if not np.array_equal(f["connectivity"][()], np.arange(n)):
            sys.exit("/connectivity is not 0..n-1")
        for name, ds in f.items():
            if name in ("time", "step", "connectivity") or not isinstance(ds, h5py.Dataset):
                continue
            data = ds[()]
            unit = ds.attrs.get("unit")
            if unit is None:
                sys.exit("/%s has no unit attribute" % name)
            if data.shape[0] != n:
                sys.exit("/%s has %d rows for %d particles" % (name, data.shape[0], n))
            if not np.all(np.isfinite(data)):
                sys.exit("/%s has non-finite values" % name)
            comps = ds.attrs.get("components")
            print("  %-20s %-12s [%s]%s" % (name, str(data.shape), unit.decode(),
                                            "" if comps is None else
                                            " components " + comps.decode()))
    # the XDMF index's last grid is this frame at this time
    # (with rigid bodies each frame is a spatial collection holding the
    # particles' grid and one grid per body; the Time is the frame's)
    root = ET.parse(os.path.join(run_dir, "fields.xdmf")).getroot()
    temporal = [g for g in root.iter("Grid") if g.get("CollectionType") == "Temporal"][0]
    frames = [g for g in temporal if g.tag == "Grid"]
    if float(frames[-1].find("Time").get("Value")) != t:
        sys.exit("fields.xdmf's last grid is not at t = %r" % t)
    print("h5_user: ok")


if __name__ == "__main__":
    main(sys.argv[1])
