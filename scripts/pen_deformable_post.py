#!/usr/bin/env python3
"""Projectile measures of an axisymmetric deformable-projectile run
(examples/pen_sph_deformable): for each field frame, the projectile's
(material index MAT, default 1 = silica) ring-mass-weighted mean axial
displacement and velocity, its tip depth, height and radius (deformation),
and its peak pressure and von Mises stress.

    scripts/pen_deformable_post.py RUN_DIR [MAT] [DX] [GAP]

DX: the projectile's lattice spacing (default 0.5e-6 m); GAP: initial
distance of the sphere's surface above the target (default 0.25e-6 m), so
that P = -mean(u_z) - GAP is the rigid sphere's P(t) convention (tip depth
below the initial surface for an undeformed sphere).  Needs h5dump (the
hdf5-tools package), no Python modules beyond the standard library.
"""
import glob
import math
import subprocess
import sys


def dataset(path, name):
    """Values of one dataset, flat, as floats (h5dump text output)."""
    out = subprocess.run(["h5dump", "-y", "-w", "0", "-d", name, path],
                         capture_output=True, text=True, check=True).stdout
    body = out[out.index("DATA {") + 6:out.rindex("}")]
    body = body[:body.rindex("}")] if body.count("}") else body
    vals = []
    for tok in body.replace("\n", ",").split(","):
        tok = tok.strip()
        if tok:
            try:
                vals.append(float(tok))
            except ValueError:
                pass
    return vals


def frame(path, mat, dx, gap):
    t = dataset(path, "/time")[0]
    n = len(dataset(path, "/mass"))
    x = dataset(path, "/position")
    u = dataset(path, "/displacement")
    v = dataset(path, "/velocity")
    m = dataset(path, "/mass")
    mt = dataset(path, "/material")
    p = dataset(path, "/pressure")
    s = dataset(path, "/deviatoric_stress")
    nc = len(s) // n
    M = uz = vz = 0.0
    zmin, zmax, rmax, pmax, vmmax = math.inf, -math.inf, 0.0, -math.inf, 0.0
    for i in range(n):
        if int(mt[i]) != mat:
            continue
        M += m[i]
        uz += m[i] * u[2 * i + 1]
        vz += m[i] * v[2 * i + 1]
        z, r = x[3 * i + 1], x[3 * i]
        zmin, zmax, rmax = min(zmin, z), max(zmax, z), max(rmax, r)
        pmax = max(pmax, p[i])
        sx, sy, sz, sxy = (s[nc * i + k] for k in range(4))
        vmmax = max(vmmax, math.sqrt(1.5 * (sx * sx + sy * sy + sz * sz + 2 * sxy * sxy)))
    uz /= M
    vz /= M
    return dict(t=t, M=M, P=-uz - gap, V=vz, tip=-(zmin - 0.5 * dx), H=zmax - zmin + dx,
                R=rmax + 0.5 * dx, pmax=pmax, vm=vmmax)


def main():
    run = sys.argv[1]
    mat = int(sys.argv[2]) if len(sys.argv) > 2 else 1
    dx = float(sys.argv[3]) if len(sys.argv) > 3 else 0.5e-6
    gap = float(sys.argv[4]) if len(sys.argv) > 4 else 0.25e-6
    print("t_ns  P_um  V_m/s  tip_um  height_um  radius_um  pmax_GPa  vm_max_GPa  mass_kg")
    for f in sorted(glob.glob(run + "/fields_*.h5")):
        r = frame(f, mat, dx, gap)
        print(f"{r['t']*1e9:6.1f} {r['P']*1e6:7.3f} {r['V']:8.1f} {r['tip']*1e6:7.3f} "
              f"{r['H']*1e6:7.3f} {r['R']*1e6:7.3f} {r['pmax']/1e9:8.3f} {r['vm']/1e9:8.3f} "
              f"{r['M']:.5e}")


if __name__ == "__main__":
    main()
