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
xyz, els, sec, scale = {}, [], None, 1.0
BAR = dict(L0=32.4e-3, R0=3.2e-3, V0=227.0, RHO=8930.0)   # copper default
npe, buf = 8, []                           # nodes per element, pending row
for line in open(job + ".inp"):
    if line.startswith("** RF_SCALE="):  # model part -> whole bar
        scale = float(line.split("=")[1])
    if line.startswith("** BAR "):        # another bar (gen_taylor.py L0= ...)
        BAR.update((k, float(v)) for k, v in
                   (f.split("=") for f in line.split()[2:]))
    if line.startswith("*"):
        sec = line.upper().split(",")[0]
        if sec == "*ELEMENT":
            npe = 20 if "C3D20" in line.upper() else 8
        continue
    f = line.split(",")
    if sec == "*NODE":
        xyz[int(f[0])] = tuple(map(float, f[1:4]))
    elif sec == "*ELEMENT":               # rows may continue on a 2nd line
        buf += [int(v) for v in f if v.strip()]
        if len(buf) == 1 + npe:
            els.append(buf[1:9])          # corners only (volume, centroid)
            buf = []

blocks = []                                # (kind, set, time, rows)
cur = None
for line in open(job + ".dat"):
    h = re.match(r"\s*(displacements|velocities|total force)\s.*for set (\S+)"
                 r" and time\s+(\S+)", line)
    if h:
        cur = (h.group(1), h.group(2), float(h.group(3)), [])
        blocks.append(cur)
    elif " for set " in line:              # another kind of block
        cur = None
    elif cur and line.strip():
        cur[3].append([float(v) for v in line.split()])


def shape(wall, top):                      # (length, radius) of one state
    zmin = min(xyz[int(r[0])][2] + r[3] for r in wall[3])
    zmax = max(xyz[int(r[0])][2] + r[3] for r in top[3])
    rad = max(math.hypot(xyz[int(r[0])][0] + r[1], xyz[int(r[0])][1] + r[2])
              for r in wall[3])
    return zmax - zmin, rad


walls = [b for b in blocks if b[0] == "displacements" and b[1] == "WALL"]
tops = [b for b in blocks if b[0] == "displacements" and b[1] == "TOP"]
hist = {w[2]: shape(w, t) for w, t in zip(walls, tops)}
t_end = walls[-1][2]
print(f"t = {t_end:.4e} s  length = {1e3 * hist[t_end][0]:.4f} mm  "
      f"radius = {1e3 * hist[t_end][1]:.4f} mm")

def tet(a, b, c, d):                       # signed volume of a tetrahedron
    u, v, w = ([q[k] - a[k] for k in range(3)] for q in (b, c, d))
    return (u[0] * (v[1] * w[2] - v[2] * w[1])
            - u[1] * (v[0] * w[2] - v[2] * w[0])
            + u[2] * (v[0] * w[1] - v[1] * w[0])) / 6


def volume(blk):                           # (V / V0 whole bar, # elements < 0)
    p = {int(r[0]): [xyz[int(r[0])][k] + r[1 + k] for k in range(3)]
         for r in blk[3]}
    vols = []
    for e in els:                          # 6 tets around diagonal 1-7
        n = [p[i] for i in e]
        vols.append(sum(tet(n[0], n[a], n[b], n[6]) for a, b in
                        ((1, 2), (2, 3), (3, 7), (7, 4), (4, 5), (5, 1))))
    v0 = math.pi * BAR["R0"] ** 2 * BAR["L0"]
    return (scale * sum(vols) / v0, sum(v < 0 for v in vols),
            [k for k, v in enumerate(vols) if v < 0])


def where(k):                              # initial centroid (r, z) [mm]
    c = [sum(xyz[i][d] for i in els[k]) / 8 for d in range(3)]
    return f"({1e3 * math.hypot(c[0], c[1]):.2f}, {1e3 * c[2]:.2f})"


def profile(blk, z0):                      # outer radius at height z0
    """Largest radius where the deformed outer surface (the nodes that
    start on r = R0, in order of their initial z) crosses the height z0;
    linear between nodes.  The same measure as spall's profile_radius
    (src/core/profile.h) up to its band interpolation."""
    u = {int(r[0]): r[1:4] for r in blk[3]}
    side = sorted((xyz[n][2], n) for n in u
                  if math.hypot(xyz[n][0], xyz[n][1]) > BAR["R0"] * (1 - 1e-9))
    pts, seen = [], set()
    for z, n in side:                      # one node per initial height
        if round(z * 1e10) in seen:
            continue
        seen.add(round(z * 1e10))
        p = [xyz[n][k] + u[n][k] for k in range(3)]
        pts.append((math.hypot(p[0], p[1]), p[2]))
    best = math.nan
    for (ra, za), (rb, zb) in zip(pts, pts[1:]):
        if (za - z0) * (zb - z0) <= 0 and za != zb:
            r = ra + (rb - ra) * (z0 - za) / (zb - za)
            best = r if not best >= r else best
    return best


ts = sorted(hist)                          # L, R before the tangling
for tq in (10e-6, 20e-6, 80e-6):
    k = next((i for i, t in enumerate(ts) if t >= tq), None)
    if k:
        f = (tq - ts[k - 1]) / (ts[k] - ts[k - 1])
        Lq, Rq = (hist[ts[k - 1]][i] + f * (hist[ts[k]][i]
                                             - hist[ts[k - 1]][i])
                  for i in (0, 1))
        print(f"t = {1e6 * tq:.0f} us (interpolated): length = "
              f"{1e3 * Lq:.4f} mm  radius = {1e3 * Rq:.4f} mm")
alln = [b for b in blocks if b[0] == "displacements" and b[1] == "NALL"]
if alln:                                   # side nodes crossing z = 0?
    def low(b):                            # (min z, its radius) over nodes
        return min((xyz[int(r[0])][2] + r[3],
                    math.hypot(xyz[int(r[0])][0] + r[1],
                               xyz[int(r[0])][1] + r[2])) for r in b[3])
    below = [b[2] for b in alln if low(b)[0] < -1e-6]
    z, r = low(alln[-1])
    vol = {b[2]: volume(b) for b in alln}
    print(f"deformed volume / initial = {vol[alln[-1][2]][0]:.5f}; "
          f"elements with negative volume: "
          f"{vol[alln[-1][2]][1]} of {len(els)}")
    bad = [b[2] for b in alln if vol[b[2]][1]]
    if bad:                                # where the inversion starts
        first = vol[bad[0]][2]
        print(f"first inverted elements at t = {bad[0]:.3e} s, initial "
              f"centroids (r, z) [mm]: "
              + " ".join(where(k) for k in first[:8]))
        print("inverted at the end, initial (r, z) [mm]: "
              + " ".join(where(k) for k in vol[alln[-1][2]][2][:40]))
    print("side nodes below the wall plane (z < -1 um) from t = "
          + (f"{below[0]:.3e} s" if below else "never")
          + f"; at t = {alln[-1][2]:.4e} s the lowest node is at z = "
          f"{1e3 * z:.4f} mm, r = {1e3 * r:.4f} mm")
# axial RF of the wall, scaled to the whole bar; > 0 = the wall pushes
rf = [(b[2], scale * b[3][0][2]) for b in blocks
      if b[0] == "total force" and b[1] == "WALL"]
neg = [(t, f) for t, f in rf if f < 0]
print(f"wall force samples {len(rf)}, peak {max(f for _, f in rf):.4e} N, "
      f"first tensile sample: "
      + (f"t = {neg[0][0]:.3e} s, F = {neg[0][1]:.3e} N" if neg else "none"))
tip = [(b[2], b[3][0][3]) for b in blocks
       if b[0] == "velocities" and b[1] == "TIP"]
# rest point: the rear-axis velocity first turns from < 0 to >= 0; L and R
# interpolated linearly there (printed states are <= 2 us apart)
up = next((k for k in range(1, len(tip))
           if tip[k - 1][1] < 0 <= tip[k][1]), None)
if up is not None:
    (t0, v0_), (t1, v1) = tip[up - 1], tip[up]
    f = -v0_ / (v1 - v0_)
    Lr, Rr = (hist[t0][i] + f * (hist[t1][i] - hist[t0][i]) for i in (0, 1))
    print(f"at rest (rear-axis v_z = 0) t = {1e6 * (t0 + f * (t1 - t0)):.2f}"
          f" us: length = {1e3 * Lr:.4f} mm  radius = {1e3 * Rr:.4f} mm")
    nall = {b[2]: b for b in alln}
    if t0 in nall and t1 in nall:          # mushroom radius above the wall
        print("  outer radius at rest, " + ", ".join(
            f"z = {1e3 * z0:.2f} mm: "
            f"{1e3 * ((1 - f) * profile(nall[t0], z0) + f * profile(nall[t1], z0)):.4f} mm"
            for z0 in (0.5e-3, 1e-3)))
else:
    print("at rest: not reached (rear-axis v_z < 0 at every printed state)")
for t, v in tip[:: max(1, len(tip) // 12)] + tip[-1:]:
    L, R = hist.get(t, (math.nan, math.nan))
    vr, nneg = vol.get(t, (math.nan, 0))[:2] if alln else (math.nan, 0)
    print(f"  t = {1e6 * t:6.2f} us  rear-axis v_z = {v:8.2f} m/s  wall "
          f"force = {dict(rf).get(t, math.nan):9.3e} N  L = {1e3 * L:.3f} mm"
          f"  R = {1e3 * R:.3f} mm  V/V0 = {vr:.4f} ({nneg} inverted)")
# undeformed length X (gen_taylor.py peeq=1), the measure of the SPH case
# sph-taylor-2d: from the height where the equivalent plastic strain on the
# axis first falls below 0.2 % (elements of the axis column, mean over their
# integration points, placed at their deformed centroid; linear between
# them) to the rear face; at the last printed state
pe, cur_t = {}, None
for line in open(job + ".dat"):
    h = re.match(r"\s*equivalent plastic strain .*time\s+(\S+)", line)
    if h:
        cur_t = float(h.group(1))
        pe[cur_t] = {}
    elif " for set " in line:              # another kind of block
        cur_t = None
    elif cur_t is not None and line.strip():
        f = line.split()
        if len(f) == 3:
            pe[cur_t].setdefault(int(f[0]), []).append(float(f[2]))
if pe and alln:
    tl = max(pe)
    blk = {b[2]: b for b in alln}.get(tl)
    if blk:
        u = {int(r[0]): r[1:4] for r in blk[3]}
        col = []                            # (deformed centroid z, mean PEEQ)
        for k, e in enumerate(els):
            c0 = [sum(xyz[i][d] for i in e) / 8 for d in range(3)]
            zc = sum(xyz[i][2] + u[i][2] for i in e) / 8
            rc0 = math.hypot(c0[0], c0[1])
            col.append((rc0, zc, sum(pe[tl][k + 1]) / len(pe[tl][k + 1])))
        rmin = min(c[0] for c in col)
        axis = sorted((z, p) for r, z, p in col if r < rmin * 1.5)
        top = max(xyz[int(r[0])][2] + r[3] for r in blk[3])
        zx = None
        for (za, pa), (zb, pb) in zip(axis, axis[1:]):
            if pa >= 2e-3 > pb:
                zx = za + (zb - za) * (pa - 2e-3) / (pa - pb)
                break
        print(f"undeformed length X at t = {1e6 * tl:.2f} us: "
              + (f"{1e3 * (top - zx):.3f} mm (PEEQ on the axis falls below "
                 f"0.2 % at z = {1e3 * zx:.3f} mm)" if zx is not None
                 else "not found (PEEQ on the axis never falls below 0.2 %)"))
        print("  axis PEEQ (z [mm], mean): " + " ".join(
            f"{1e3 * z:.2f}:{p:.4f}" for z, p in axis))
# energies (gen_taylor.py energy=1), scaled to the whole bar: internal
# (elastic + plastic work) + kinetic against the initial kinetic energy
en = {}
kind = None
for line in open(job + ".dat"):
    h = re.match(r"\s*total (internal|kinetic) energy for set \S+ and time"
                 r"\s+(\S+)", line)
    if h:
        kind, t = h.group(1), float(h.group(2))
    elif kind and line.strip():
        en.setdefault(t, {})[kind] = scale * float(line.split()[0])
        kind = None
if en:
    m0 = BAR["RHO"] * math.pi * BAR["R0"] ** 2 * BAR["L0"]
    ek0 = 0.5 * m0 * BAR["V0"] ** 2
    for t in sorted(en)[:: max(1, len(en) // 8)] + [max(en)]:
        e = en[t]
        print(f"  t = {1e6 * t:6.2f} us  internal {e.get('internal', 0):7.2f}"
              f" J  kinetic {e.get('kinetic', 0):7.2f} J  sum / "
              f"(1/2 m v0^2 = {ek0:.1f} J) = "
              f"{(e.get('internal', 0) + e.get('kinetic', 0)) / ek0:.4f}")
