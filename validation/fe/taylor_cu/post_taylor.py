#!/usr/bin/env python3
"""Final length/radius and wall-force history from a gen_taylor.py run.

Usage: python3 post_taylor.py JOB      (reads JOB.inp and JOB.dat)
length = max over rear-face nodes of z + u_z minus min over impact-face
nodes of z + u_z (the face is held at u_z = 0, so the min is 0);
radius = max over impact-face nodes of |(x + u_x, y + u_y)|.
"""
import math
import re
import sys

job = sys.argv[1]
xyz, sec = {}, None
for line in open(job + ".inp"):
    if line.startswith("*"):
        sec = line.upper().startswith("*NODE,")
        continue
    if sec:
        f = line.split(",")
        xyz[int(f[0])] = tuple(map(float, f[1:4])) + (0.0,) * (4 - len(f))
ax = 2 if any(p[2] != 0.0 for p in xyz.values()) else 1   # 3D: z, CAX: y

blocks = []                                # (kind, set, time, rows)
cur = None
for line in open(job + ".dat"):
    h = re.match(r"\s*(displacements|velocities|total force)\s.*for set (\S+)"
                 r" and time\s+(\S+)", line)
    if h:
        cur = (h.group(1), h.group(2), float(h.group(3)), [])
        blocks.append(cur)
    elif cur and line.strip():
        cur[3].append([float(v) for v in line.split()])


def last(kind, name):
    return [b for b in blocks if b[0] == kind and b[1] == name][-1]


wall, top = last("displacements", "WALL"), last("displacements", "TOP")
zmin = min(xyz[int(r[0])][ax] + r[1 + ax] for r in wall[3])
zmax = max(xyz[int(r[0])][ax] + r[1 + ax] for r in top[3])
rad = max(math.hypot(xyz[int(r[0])][0] + r[1],
                     (xyz[int(r[0])][1] + r[2]) if ax == 2 else 0.0)
          for r in wall[3])
print(f"t = {wall[2]:.4e} s  length = {1e3 * (zmax - zmin):.4f} mm  "
      f"radius = {1e3 * rad:.4f} mm")
# RF along the axis (quarter 3D model: x4; CAX: per radian, x 2 pi);
# > 0 = the wall pushes on the bar
rf = [(b[2], (4 if ax == 2 else 2 * math.pi) * b[3][0][ax]) for b in blocks
      if b[0] == "total force" and b[1] == "WALL"]
neg = [(t, f) for t, f in rf if f < 0]
print(f"wall force samples {len(rf)}, peak {max(f for _, f in rf):.4e} N, "
      f"first tensile sample: "
      + (f"t = {neg[0][0]:.3e} s, F = {neg[0][1]:.3e} N" if neg else "none"))
tip = [(b[2], b[3][0][1 + ax]) for b in blocks
       if b[0] == "velocities" and b[1] == "TIP"]
for t, v in tip[:: max(1, len(tip) // 12)] + tip[-1:]:
    print(f"  t = {1e6 * t:7.2f} us  rear-axis v_z = {v:9.3f} m/s  "
          f"wall force = {dict(rf).get(t, float('nan')):.3e} N")
