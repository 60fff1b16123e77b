#!/usr/bin/env python3
"""Write a CalculiX deck for the copper Taylor bar (issue 6 item 8).

Usage: python3 gen_taylor.py NR [wedge|quarter] [ELTYPE] [key=value ...]
  NR      elements across R0 (even for quarter); axial layers 10.125 NR
  wedge   (default) one element thick sector (5 degrees unless angle=):
          an axisymmetric model built from 3D bricks, every node off the
          plane y = 0 held in its own radial plane by *EQUATION (the axis
          column is degenerate unless hole=)
  quarter 3D quarter bar, O-grid cross-section (square core 0.45 R0)
  ELTYPE  C3D8I (default; incompatible modes), C3D8R, C3D8, or the 20-node
          C3D20R / C3D20 (midside nodes; in the wedge the theta midside
          nodes lie on the arc)
  options: see the comment at opt below (hole, angle, tend, dtmax,
          explicit, energy)

The reference (README.md): C3D20R, 20-degree wedge, implicit -- no
inverted element, volume and energy kept, final length flat over NR = 2-6.
C3D8I wedges invert face-centre elements at NR = 8 (5 and 20 degrees) and
at NR >= 4 (5 degrees); CAX4R/CAX4 are expanded by CalculiX 2.20 into a
2-degree C3D8R/C3D8 layer (initial velocity lost, CAX4R stalls at 45 us,
CAX4 locks); C3D8R implicit stalls at 40-47 us.

SI units, axis z.  Impact face z = 0: u_z = 0, in-plane free -- a
frictionless rigid wall while the face keeps pushing on it (check RF_z of
set WALL stays >= 0, see post_taylor.py).  Material: E = 117 GPa,
nu = 0.35, rho = 8930 kg/m^3, sigma_y = 0.4 GPa + 0.1 GPa * eps_p (two-point
*PLASTIC table, isotropic), no rate/temperature effect.
v0 = -227 m/s along z; implicit HHT dynamics (alpha = -0.05) to 80 us
(tend=), or central differences with explicit=N.
"""
import math
import sys

L0, R0, V0, T_END = 32.4e-3, 3.2e-3, 227.0, 80e-6
WEDGE_DEG, CORE = 5.0, 0.45
nr = int(sys.argv[1])
geom = sys.argv[2] if len(sys.argv) > 2 else "wedge"
eltype = sys.argv[3] if len(sys.argv) > 3 else "C3D8I"
# key=value options after the positional ones:
#   hole=F   wedge only: axial pinhole of radius F * R0 (free surface), so
#            that no brick on the axis is degenerate (where does the
#            inversion come from?)
#   angle=A  wedge only: sector angle in degrees (default 5)
#   tend=T   end time [s] (default 80e-6; run past the rest point)
#   dtmax=D  largest implicit increment [s] (default 2e-7)
opt = dict(a.split("=", 1) for a in sys.argv[4:])
# another bar (the copper bar's values are the defaults, and its decks stay
# byte-identical when none of these is given):
#   L0=, R0= [m], v0= [m/s], E= [Pa], nu=, rho= [kg/m^3], sy= yield stress
#   [Pa], hard= linear hardening modulus [Pa] (0: perfectly plastic),
#   pb=, pn= power-law hardening sy + pb eps_p^pn instead (a 20-point
#   *PLASTIC table to eps_p = 10; pb= 0: off),
#   name= heading text; peeq=1 prints the equivalent plastic strain of
#   every integration point (post_taylor.py: the undeformed length X).  The bar's data go into the deck as "** BAR" so
#   that post_taylor.py reads them.
MAT = None
if any(k in opt for k in ("L0", "R0", "v0", "E", "nu", "rho", "sy", "hard",
                          "pb", "pn")):
    L0 = float(opt.get("L0", L0))
    R0 = float(opt.get("R0", R0))
    V0 = float(opt.get("v0", V0))
    MAT = (float(opt.get("E", 117e9)), float(opt.get("nu", 0.35)),
           float(opt.get("rho", 8930.0)), float(opt.get("sy", 0.4e9)),
           float(opt.get("hard", 0.1e9)), float(opt.get("pb", 0.0)),
           float(opt.get("pn", 1.0)))
hole = float(opt.get("hole", 0.0))
WEDGE_DEG = float(opt.get("angle", WEDGE_DEG))
T_END = float(opt.get("tend", T_END))
DT_MAX = opt.get("dtmax", "2e-7")         # kept as text: same deck as before
nz = int(nr * L0 / R0 + 0.5)              # 10.125 NR, rounded half up

# --- 2D cross-section: nodes merged by coordinates, quads CCW about +z ---
xy, key2id, quads = [], {}, []


def node2(x, y):
    k = (round(x * 1e10), round(y * 1e10))  # 0.1 nm merge tolerance
    if k not in key2id:
        key2id[k] = len(xy)
        xy.append((x, y))
    return key2id[k]


quadratic = eltype.startswith("C3D20")   # 20-node bricks: midside nodes


def block(pt, ns, nt):                    # mapped grid pt(s, t), ns x nt
    if not quadratic:
        g = [[node2(*pt(s, t)) for t in range(nt + 1)] for s in range(ns + 1)]
        for s in range(ns):
            for t in range(nt):
                quads.append([g[s][t], g[s + 1][t], g[s + 1][t + 1],
                              g[s][t + 1]])
        return
    # 8-node quads: corners then midsides 01, 12, 23, 30 (grid at half step)
    g = [[node2(*pt(s / 2, t / 2)) for t in range(2 * nt + 1)]
         for s in range(2 * ns + 1)]
    for s in range(0, 2 * ns, 2):
        for t in range(0, 2 * nt, 2):
            quads.append([g[s][t], g[s + 2][t], g[s + 2][t + 2], g[s][t + 2],
                          g[s + 1][t], g[s + 2][t + 1], g[s + 1][t + 2],
                          g[s][t + 1]])


if geom == "wedge":                        # r along x, one sector element
    al = math.radians(WEDGE_DEG)
    r_in = hole * R0

    def rad(s):
        return r_in + (R0 - r_in) * s / nr
    block(lambda s, t: (rad(s) * math.cos(al * t),
                        rad(s) * math.sin(al * t)), nr, 1)
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


def flip(q):                               # reverse the orientation
    return ([q[0], q[3], q[2], q[1], q[7], q[6], q[5], q[4]] if quadratic
            else q[::-1])


quads = [q if area(q[:4]) > 0 else flip(q) for q in quads]
n2 = len(xy)
corner2 = sorted({i for q in quads for i in q[:4]})
used2 = sorted({i for q in quads for i in q})  # not the 8-node face centres
# 3D nodes: level k = 0 .. nlev at z = L0 k / nlev; with 20-node bricks the
# odd levels carry only the corner positions (vertical midside nodes)
nlev = nz * (2 if quadratic else 1)
ids = {}
for k in range(nlev + 1):
    for i2 in (corner2 if quadratic and k % 2 else used2):
        ids[(i2, k)] = len(ids) + 1       # = 1 + i2 + n2 k for linear bricks


def nid(i2, k):                            # 3D node id: 2D node i2, level k
    return ids[(i2, k)]


out = ["*HEADING", f"{opt.get('name', 'Copper')} Taylor bar, {geom} {eltype}, "
       f"NR={nr}, NZ={nz}", f"** RF_SCALE={scale}"]
if MAT:
    out.append(f"** BAR L0={L0!r} R0={R0!r} V0={V0!r} RHO={MAT[2]!r}")
out.append("*NODE, NSET=NALL")
for (i2, k), n in ids.items():
    x, y = xy[i2]
    out.append(f"{n}, {x:.10e}, {y:.10e}, {L0 * k / nlev:.10e}")
out.append(f"*ELEMENT, TYPE={eltype}, ELSET=EALL")
for k in range(nz):
    for e, q in enumerate(quads):          # degenerate on the axis (wedge)
        if quadratic:                      # CalculiX C3D20 node order
            a, b, c = 2 * k, 2 * k + 1, 2 * k + 2
            n = ([nid(i, a) for i in q[:4]] + [nid(i, c) for i in q[:4]]
                 + [nid(i, a) for i in q[4:]] + [nid(i, c) for i in q[4:]]
                 + [nid(i, b) for i in q[:4]])
            out.append(f"{1 + e + len(quads) * k}, "
                       + ", ".join(map(str, n[:15])) + ",")
            out.append(", ".join(map(str, n[15:])))
        else:
            out.append(f"{1 + e + len(quads) * k}, "
                       + ", ".join(str(nid(i, k)) for i in q) + ", "
                       + ", ".join(str(nid(i, k + 1)) for i in q))


def nset(name, nodes):
    out.append(f"*NSET, NSET={name}")
    nodes = list(nodes)
    for j in range(0, len(nodes), 10):
        out.append(", ".join(map(str, nodes[j:j + 10])) + ",")


def layers(pred):                          # all 3D nodes over a 2D predicate
    return [n for (i, k), n in ids.items() if pred(*xy[i])]


tol = 1e-12
nset("YSYM", layers(lambda x, y: abs(y) < tol))           # plane y = 0
if geom == "wedge":                        # tilted plane, axis excluded
    if hole == 0.0:
        nset("AXIS", layers(lambda x, y: abs(x) < tol and abs(y) < tol))
    # off the plane y = 0: the plane theta = alpha and, with 20-node
    # bricks, the midside nodes at alpha / 2 (each held in its own plane)
    tilt = [(n, math.atan2(xy[i][1], xy[i][0])) for (i, k), n in ids.items()
            if abs(xy[i][1]) > tol]
else:
    nset("XSYM", layers(lambda x, y: abs(x) < tol))       # plane x = 0
nset("WALL", [nid(i, 0) for i in used2])                 # impact face
nset("TOP", [nid(i, nlev) for i in used2])               # rear face
tip = min(range(n2), key=lambda i: math.hypot(*xy[i]))    # axis (or hole)
nset("TIP", [nid(tip, nlev)])                             # rear, on axis
if MAT and MAT[5] > 0.0:                   # power law sy + pb eps_p^pn
    mat = ["*ELASTIC", f"{MAT[0]!r}, {MAT[1]!r}", "*DENSITY", f"{MAT[2]!r}",
           "*PLASTIC"] + [f"{MAT[3] + MAT[5] * e ** MAT[6]!r}, {e!r}" for e in
                          (0.0, 1e-3, 2e-3, 5e-3, 0.01, 0.02, 0.03, 0.05, 0.075,
                           0.1, 0.15, 0.2, 0.3, 0.5, 0.75, 1.0, 1.5, 2.0, 5.0,
                           10.0)]
elif MAT:                                  # sigma_y + hard * eps_p to 10
    mat = ["*ELASTIC", f"{MAT[0]!r}, {MAT[1]!r}", "*DENSITY", f"{MAT[2]!r}",
           "*PLASTIC", f"{MAT[3]!r}, 0.", f"{MAT[3] + 10 * MAT[4]!r}, 10."]
else:
    mat = ["*ELASTIC", "117e9, 0.35", "*DENSITY", "8930.", "*PLASTIC",
           "0.4e9, 0.", "1.4e9, 10."]
out += ["*MATERIAL, NAME=CU"] + mat + [
        "*SOLID SECTION, ELSET=EALL, MATERIAL=CU",
        "*BOUNDARY", "YSYM, 2, 2", "WALL, 3, 3"]
if geom == "wedge":
    if hole == 0.0:
        out += ["AXIS, 1, 2"]
    # axisymmetry: a node at angle th moves in its radial plane (on the
    # sector face th = alpha: zero normal velocity), cos(th) u_y -
    # sin(th) u_x = 0 (u_y dependent)
    for n, th in tilt:
        c, s = math.cos(th), math.sin(th)
        out += ["*EQUATION", "2", f"{n}, 2, {c:.12f}, {n}, 1, {-s:.12f}"]
else:
    out += ["XSYM, 1, 1"]
out += ["*INITIAL CONDITIONS, TYPE=VELOCITY", f"NALL, 3, {-V0}"]
# explicit=N: central differences (*DYNAMIC, EXPLICIT; stable increment set
# by CalculiX) in N equal steps, because explicit steps print only at their
# end in CalculiX 2.20 (FREQUENCY / *TIME POINTS gave nothing in between)
nexp = int(opt.get("explicit", 0))
for st in range(max(nexp, 1)):
    if nexp:
        out += ["*STEP, NLGEOM, INC=10000000", "*DYNAMIC, EXPLICIT",
                f"1e-9, {T_END / nexp:.6e}"]
        freq = 10000000                   # step end only
    else:
        out += ["*STEP, NLGEOM, INC=100000",
                "*DYNAMIC, ALPHA=-0.05",   # dt0, period, dt_min, dt_max
                f"{'1e-7' if float(DT_MAX) >= 1e-7 else DT_MAX}, {T_END}, "
                f"1e-12, {DT_MAX}"]
        freq = 10                          # every 10 increments + the end
    for name, var in (("WALL", "RF"), ("TIP", "U, V"), ("WALL", "U"),
                      ("TOP", "U")):
        tot = ", TOTALS=ONLY" if var == "RF" else ""
        out += [f"*NODE PRINT, NSET={name}{tot}, FREQUENCY={freq}", var]
    # all nodes: lets post_taylor.py check whether side nodes cross the
    # wall plane z = 0 (only the face nodes are held there).  FREQUENCY is
    # one value for all *NODE PRINT requests of a step in CalculiX (the
    # last one wins).
    out += [f"*NODE PRINT, NSET=NALL, FREQUENCY={freq}", "U"]
    if opt.get("energy"):                 # energy=1: internal (elastic +
        out += [f"*EL PRINT, ELSET=EALL, TOTALS=ONLY, FREQUENCY={freq}",
                "ELSE, ELKE"]             # plastic) and kinetic, sector
    if opt.get("peeq"):                   # peeq=1: equivalent plastic strain
        out += [f"*EL PRINT, ELSET=EALL, FREQUENCY={freq}", "PEEQ"]  # per point
    out += ["*END STEP"]
print("\n".join(out))
