#!/usr/bin/env python3
"""Write a CalculiX deck for the copper Taylor bar (issue 6 item 8).

Usage: python3 gen_taylor.py NR [wedge|quarter] [ELTYPE] > JOB.inp
  NR      elements across R0 (even for quarter); axial layers 10.125 NR
  wedge   (default) one element thick 5-degree sector: an axisymmetric
          model built from 3D bricks (the axis column is degenerate)
  quarter 3D quarter bar, O-grid cross-section (square core 0.45 R0)
  ELTYPE  C3D8I (default; incompatible modes) or C3D8R / C3D8

Why not CAX4R/CAX4 and why implicit (README.md has the runs): CalculiX 2.20
expands CAX elements into a 2-degree C3D8R/C3D8 layer tied by MPCs; there the
initial velocity was not applied (bar never moved), CAX4R (C3D8R) stopped
converging at 45 us and CAX4 (C3D8) locks; explicit steps collapsed to
4e-10 s as the face-centre elements flatten.  C3D8I, implicit, reaches
80 us, but only by inverting face-centre elements from 12-22 us on
(post_taylor.py reports V/V0 and the inverted count).

SI units, axis z.  Impact face z = 0: u_z = 0, in-plane free -- a
frictionless rigid wall while the face keeps pushing on it (check RF_z of
set WALL stays >= 0, see post_taylor.py).  Material: E = 117 GPa,
nu = 0.35, rho = 8930 kg/m^3, sigma_y = 0.4 GPa + 0.1 GPa * eps_p (two-point
*PLASTIC table, isotropic), no rate/temperature effect.
v0 = -227 m/s along z; implicit HHT dynamics (alpha = -0.05) to 80 us.
"""
import math
import sys

L0, R0, V0, T_END = 32.4e-3, 3.2e-3, 227.0, 80e-6
WEDGE_DEG, CORE = 5.0, 0.45
nr = int(sys.argv[1])
geom = sys.argv[2] if len(sys.argv) > 2 else "wedge"
eltype = sys.argv[3] if len(sys.argv) > 3 else "C3D8I"
nz = int(nr * L0 / R0 + 0.5)              # 10.125 NR, rounded half up

# --- 2D cross-section: nodes merged by coordinates, quads CCW about +z ---
xy, key2id, quads = [], {}, []


def node2(x, y):
    k = (round(x * 1e10), round(y * 1e10))  # 0.1 nm merge tolerance
    if k not in key2id:
        key2id[k] = len(xy)
        xy.append((x, y))
    return key2id[k]


def block(pt, ns, nt):                    # mapped grid pt(s, t), ns x nt
    g = [[node2(*pt(s, t)) for t in range(nt + 1)] for s in range(ns + 1)]
    for s in range(ns):
        for t in range(nt):
            quads.append([g[s][t], g[s + 1][t], g[s + 1][t + 1], g[s][t + 1]])


if geom == "wedge":                        # r along x, one sector element
    al = math.radians(WEDGE_DEG)
    block(lambda s, t: (R0 * s / nr * math.cos(al * t),
                        R0 * s / nr * math.sin(al * t)), nr, 1)
    scale = 360.0 / WEDGE_DEG              # RF of the sector -> whole bar
else:
    m, a = nr // 2, CORE * R0
    block(lambda s, t: (a * s / m, a * t / m), m, m)      # core square

    def outer(x0, y0, th, f):              # square edge -> arc, fraction f
        return ((1 - f) * x0 + f * R0 * math.cos(th),
                (1 - f) * y0 + f * R0 * math.sin(th))
    block(lambda s, t: outer(a, a * t / m, math.pi / 4 * t / m, s / m), m, m)
    block(lambda s, t: outer(a * s / m, a, math.pi / 2 - math.pi / 4 * s / m,
                             t / m), m, m)
    scale = 4.0


def area(q):                               # signed area of a 2D quad
    p = [xy[i] for i in q]
    return 0.5 * sum(p[i][0] * p[(i + 1) % 4][1] - p[(i + 1) % 4][0] * p[i][1]
                     for i in range(4))


quads = [q if area(q) > 0 else q[::-1] for q in quads]
n2 = len(xy)


def nid(i2, k):                            # 3D node id: 2D node i2, layer k
    return 1 + i2 + n2 * k


out = ["*HEADING", f"Copper Taylor bar, {geom} {eltype}, NR={nr}, NZ={nz}",
       f"** RF_SCALE={scale}", "*NODE, NSET=NALL"]
for k in range(nz + 1):
    for i2, (x, y) in enumerate(xy):
        out.append(f"{nid(i2, k)}, {x:.10e}, {y:.10e}, {L0 * k / nz:.10e}")
out.append(f"*ELEMENT, TYPE={eltype}, ELSET=EALL")
for k in range(nz):
    for e, q in enumerate(quads):          # degenerate on the axis (wedge)
        out.append(f"{1 + e + len(quads) * k}, "
                   + ", ".join(str(nid(i, k)) for i in q) + ", "
                   + ", ".join(str(nid(i, k + 1)) for i in q))


def nset(name, ids):
    out.append(f"*NSET, NSET={name}")
    ids = list(ids)
    for j in range(0, len(ids), 10):
        out.append(", ".join(map(str, ids[j:j + 10])) + ",")


def layers(pred):                          # all 3D nodes over a 2D predicate
    return [nid(i, k) for k in range(nz + 1)
            for i, p in enumerate(xy) if pred(*p)]


tol = 1e-12
nset("YSYM", layers(lambda x, y: abs(y) < tol))           # plane y = 0
if geom == "wedge":                        # tilted plane, axis excluded
    nset("AXIS", layers(lambda x, y: abs(x) < tol and abs(y) < tol))
    tilt = layers(lambda x, y: abs(y) > tol)
else:
    nset("XSYM", layers(lambda x, y: abs(x) < tol))       # plane x = 0
nset("WALL", [nid(i, 0) for i in range(n2)])              # impact face
nset("TOP", [nid(i, nz) for i in range(n2)])              # rear face
nset("TIP", [nid(key2id[(0, 0)], nz)])                    # rear, on axis
out += ["*MATERIAL, NAME=CU", "*ELASTIC", "117e9, 0.35",
        "*DENSITY", "8930.", "*PLASTIC", "0.4e9, 0.", "1.4e9, 10.",
        "*SOLID SECTION, ELSET=EALL, MATERIAL=CU",
        "*BOUNDARY", "YSYM, 2, 2", "WALL, 3, 3"]
if geom == "wedge":
    out += ["AXIS, 1, 2"]
    # sector face theta = alpha: velocity normal to it is zero,
    # cos(a) u_y - sin(a) u_x = 0 (u_y dependent)
    c, s = math.cos(al), math.sin(al)
    for n in tilt:
        out += ["*EQUATION", "2", f"{n}, 2, {c:.12f}, {n}, 1, {-s:.12f}"]
else:
    out += ["XSYM, 1, 1"]
out += ["*INITIAL CONDITIONS, TYPE=VELOCITY", f"NALL, 3, {-V0}",
        "*STEP, NLGEOM, INC=100000",
        "*DYNAMIC, ALPHA=-0.05",           # dt0, period, dt_min, dt_max
        f"1e-7, {T_END}, 1e-12, 2e-7"]
for name, var in (("WALL", "RF"), ("TIP", "U, V"), ("WALL", "U"),
                  ("TOP", "U")):           # every 10 increments + the end
    tot = ", TOTALS=ONLY" if var == "RF" else ""
    out += [f"*NODE PRINT, NSET={name}{tot}, FREQUENCY=10", var]
# all nodes: lets post_taylor.py check whether side nodes cross the wall
# plane z = 0 (only the face nodes are held there).  FREQUENCY is one value
# for all *NODE PRINT requests of a step in CalculiX (the last one wins).
out += ["*NODE PRINT, NSET=NALL, FREQUENCY=10", "U", "*END STEP"]
print("\n".join(out))
