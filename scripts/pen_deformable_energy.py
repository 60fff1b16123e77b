#!/usr/bin/env python3
"""Energy partition of an axisymmetric deformable-projectile run
(examples/pen_sph_deformable), per field frame, as fractions of the
projectile's initial kinetic energy E0 (first frame's total kinetic):

  sph_cm    projectile kinetic energy of its centre of mass, M V_cm^2 / 2
  sph_vib   projectile kinetic energy relative to its centre of mass
  sph_el    projectile elastic energy, sum V (p^2 / 2K + s:s / 4G)
  sph_heat  projectile internal energy minus sph_el (AV heating)
  gel_kin   target kinetic energy
  gel_el    target elastic energy, the same estimate as sph_el
  gel_heat  target internal energy minus gel_el (AV and plastic heating)
  iface     interface penalty energy (history.csv, nearest row)
  balance   energy_balance of history.csv (nearest row)

The elastic estimate uses the linear moduli (K = rho0 c0^2 for the gel's
Mie-Grueneisen EOS, K = E / 3(1 - 2 nu) for the silica; G = E / 2(1 + nu))
and V = m / rho; the frames need the fields internal_energy, density,
velocity, mass, material, pressure and deviatoric_stress.

    scripts/pen_deformable_energy.py RUN_DIR [MAT]

MAT: the projectile's material index (default 1 = silica; the target is
every other material).  Needs h5dump (hdf5-tools).
"""
import csv
import glob
import sys

from pen_deformable_post import dataset

# Moduli of examples/pen_sph_deformable: index 0 gelatin, 1 silica.
K_MOD = {0: 1030.0 * 1520.0 ** 2, 1: 7.2e10 / (3.0 * (1.0 - 2.0 * 0.17))}
G_MOD = {0: 2.0e7 / (2.0 * 1.499), 1: 7.2e10 / (2.0 * 1.17)}


def frame(path, mat):
    t = dataset(path, "/time")[0]
    m = dataset(path, "/mass")
    n = len(m)
    v = dataset(path, "/velocity")
    mt = [int(x) for x in dataset(path, "/material")]
    e = dataset(path, "/internal_energy")
    rho = dataset(path, "/density")
    p = dataset(path, "/pressure")
    s = dataset(path, "/deviatoric_stress")
    nc = len(s) // n
    out = dict(t=t, M=0.0, Pz=0.0, ke_s=0.0, ie_s=0.0, el_s=0.0,
               ke_g=0.0, ie_g=0.0, el_g=0.0)
    for i in range(n):
        k = mt[i]
        ke = 0.5 * m[i] * (v[2 * i] ** 2 + v[2 * i + 1] ** 2)
        ss = sum(s[nc * i + c] ** 2 for c in range(3)) + 2.0 * s[nc * i + 3] ** 2
        vol = m[i] / rho[i]
        el = vol * (p[i] ** 2 / (2.0 * K_MOD[k]) + ss / (4.0 * G_MOD[k]))
        tag = "s" if k == mat else "g"
        if k == mat:
            out["M"] += m[i]
            out["Pz"] += m[i] * v[2 * i + 1]
        out["ke_" + tag] += ke
        out["ie_" + tag] += m[i] * e[i]
        out["el_" + tag] += el
    return out


def history(run):
    with open(run + "/history.csv") as f:
        rows = list(csv.reader(f))
    head = rows[0]
    ti, bi = head.index("time [s]"), head.index("energy_balance [J]")
    ii = head.index("interface_energy [J]")
    return [(float(r[ti]), float(r[ii]), float(r[bi])) for r in rows[1:]]


def main():
    run = sys.argv[1]
    mat = int(sys.argv[2]) if len(sys.argv) > 2 else 1
    hist = history(run)
    e0 = None
    print("t_ns  sph_cm sph_vib sph_el sph_heat gel_kin gel_el gel_heat iface balance  [% of E0]")
    for f in sorted(glob.glob(run + "/fields_*.h5")):
        r = frame(f, mat)
        if e0 is None:
            e0 = r["ke_s"]
        cm = 0.5 * r["Pz"] ** 2 / r["M"]
        h = min(hist, key=lambda row: abs(row[0] - r["t"]))
        vals = (cm, r["ke_s"] - cm, r["el_s"], r["ie_s"] - r["el_s"], r["ke_g"],
                r["el_g"], r["ie_g"] - r["el_g"], h[1], h[2])
        print(f"{r['t'] * 1e9:6.1f} " + " ".join(f"{100.0 * x / e0:7.3f}" for x in vals))


if __name__ == "__main__":
    main()
