#!/usr/bin/env python3
"""Write a CalculiX deck for the copper Taylor bar (issue 6 item 8).

Usage: python3 gen_taylor.py NR > taylor_NR.inp    (NR even: elements across R0)

3D quarter bar (x >= 0, y >= 0), axis along z, C3D8R bricks, SI units.
Cross-section: O-grid (square core of side A*R0, two curved outer blocks),
NR elements along each symmetry line from the axis to the rim; the axial
count is round(NR * L0 / R0) = 10.125 NR layers of equal height.
Why 3D: CalculiX 2.20 expands CAX elements into a 2-degree wedge tied by
MPCs; its explicit solver then picks a 5.8e-10 s step and the bar did not
move (README.md).  Symmetry planes x = 0, y = 0: u_x = 0, u_y = 0.
Impact face z = 0: u_z = 0, in-plane free -- a frictionless rigid wall while
the face keeps pushing on it (check RF_z of set WALL stays >= 0).
Material: E = 117 GPa, nu = 0.35, rho = 8930 kg/m^3, isotropic hardening
sigma_y = 0.4 GPa + 0.1 GPa * eps_p (two-point *PLASTIC table, linear in
between), no rate/temperature effect.  v0 = -227 m/s along z, t_end = 80 us.
"""
import math
import sys

L0, R0, V0, T_END, A = 32.4e-3, 3.2e-3, 227.0, 80e-6, 0.45
nr = int(sys.argv[1])
m = nr // 2                                # core and outer blocks: m x m
nz = int(nr * L0 / R0 + 0.5)             # 10.125 NR, half up

# --- 2D cross-section: nodes merged by coordinates, quads CCW about +z ---
xy, key2id, quads = [], {}, []


def node2(x, y):
    k = (round(x * 1e9), round(y * 1e9))   # 1 nm merge tolerance
    if k not in key2id:
        key2id[k] = len(xy)
        xy.append((x, y))
    return key2id[k]


def block(pt):                             # pt(s, t): mapped grid, m x m
    g = [[node2(*pt(s, t)) for t in range(m + 1)] for s in range(m + 1)]
    for s in range(m):
        for t in range(m):
            quads.append([g[s][t], g[s + 1][t], g[s + 1][t + 1], g[s][t + 1]])


a = A * R0
block(lambda s, t: (a * s / m, a * t / m))                 # core square


def outer(edge):                           # edge(s) -> (square pt, angle)
    def pt(s, t):
        (x0, y0), th = edge(s)
        f = t / m
        return ((1 - f) * x0 + f * R0 * math.cos(th),
                (1 - f) * y0 + f * R0 * math.sin(th))
    return pt


# right block: square edge x = a -> arc 0..45 deg (s radial-outward first
# index so the quad stays CCW: t runs along the edge, s outward)
block(lambda s, t: outer(lambda q: ((a, a * q / m),
                                    math.pi / 4 * q / m))(t, s))
# top block: square edge y = a -> arc 90..45 deg
block(lambda s, t: outer(lambda q: ((a * q / m, a),
                                    math.pi / 2 - math.pi / 4 * q / m))(s, t))


def area(q):                               # signed area, must be > 0
    p = [xy[i] for i in q]
    return 0.5 * sum(p[i][0] * p[(i + 1) % 4][1] - p[(i + 1) % 4][0] * p[i][1]
                     for i in range(4))


quads = [q if area(q) > 0 else q[::-1] for q in quads]
n2 = len(xy)


def nid(i2, k):                            # 3D node id: 2D node i2, layer k
    return 1 + i2 + n2 * k


out = ["*HEADING", f"Copper Taylor bar, quarter C3D8R, NR={nr}, NZ={nz}",
       "*NODE, NSET=NALL"]
for k in range(nz + 1):
    for i2, (x, y) in enumerate(xy):
        out.append(f"{nid(i2, k)}, {x:.9e}, {y:.9e}, {L0 * k / nz:.9e}")
out.append("*ELEMENT, TYPE=C3D8R, ELSET=EALL")
e = 0
for k in range(nz):
    for q in quads:
        e += 1
        out.append(f"{e}, " + ", ".join(str(nid(i, k)) for i in q) + ", "
                   + ", ".join(str(nid(i, k + 1)) for i in q))


def nset(name, ids):
    out.append(f"*NSET, NSET={name}")
    ids = list(ids)
    for j in range(0, len(ids), 10):
        out.append(", ".join(map(str, ids[j:j + 10])) + ",")


tol = 1e-12
nset("XSYM", [nid(i, k) for k in range(nz + 1)
              for i, p in enumerate(xy) if abs(p[0]) < tol])
nset("YSYM", [nid(i, k) for k in range(nz + 1)
              for i, p in enumerate(xy) if abs(p[1]) < tol])
nset("WALL", [nid(i, 0) for i in range(n2)])            # impact face
nset("TOP", [nid(i, nz) for i in range(n2)])            # rear face
nset("TIP", [nid(key2id[(0, 0)], nz)])                  # rear face on axis
out += [
    "*MATERIAL, NAME=CU",
    "*ELASTIC", "117e9, 0.35",
    "*DENSITY", "8930.",
    "*PLASTIC", "0.4e9, 0.", "1.4e9, 10.",
    "*SOLID SECTION, ELSET=EALL, MATERIAL=CU",
    "*BOUNDARY", "XSYM, 1, 1", "YSYM, 2, 2", "WALL, 3, 3",
    "*INITIAL CONDITIONS, TYPE=VELOCITY", f"NALL, 3, {-V0}",
]
# NSTEP explicit steps: CalculiX 2.20 printed explicit results at every
# increment or only at the end of the step (FREQUENCY=100, TIME POINTS gave
# nothing in between), and each step re-estimates the stable increment on
# the current geometry (one 80 us step with the initial increment -> NaN)
NSTEP = 80
for s in range(NSTEP):
    out += ["*STEP, NLGEOM, INC=10000000",
            "*DYNAMIC, EXPLICIT",          # increment: CalculiX's estimate
            f"1.e-9, {T_END / NSTEP:.6e}",
            # FREQUENCY: no per-increment output, only the end of the step
            "*NODE PRINT, NSET=WALL, TOTALS=ONLY, FREQUENCY=99999999", "RF",
            "*NODE PRINT, NSET=TIP, FREQUENCY=99999999", "U, V",
            "*NODE PRINT, NSET=WALL, FREQUENCY=99999999", "U",
            "*NODE PRINT, NSET=TOP, FREQUENCY=99999999", "U",
            "*END STEP"]
print("\n".join(out))
