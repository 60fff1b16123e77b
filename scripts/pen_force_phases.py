#!/usr/bin/env python3
"""Where the rigid sphere's energy goes in an axisymmetric SPH penetration
run (history.csv of examples/pen_sph_gelatin or a scripts/pen_decks.sh
variant), against the Poncelet law of [Meng2021] (Eq. 4.1, C_d = 0.375,
R = 21 MPa, silica 7.38 um into 10 wt% gelatin).

    scripts/pen_force_phases.py HISTORY.csv V0 [GAP]

Prints, for stretches of the tip depth P (P = -sphere_uy - GAP, GAP the
initial distance of the tip above the surface, default 0.25e-6 m): the
entry and exit speeds, the mean retarding stress of the SPH run
F/(pi d^2/4) with F = -(M/2) d(V^2)/dP over the stretch (work-energy:
smooth, where the sampled contact force is noisy), Poncelet's
(R + rho_t C_d V^2/2) at the stretch's mean V^2, and the SPH's
"quasi-static" resistance R_eff = F/A - rho_t C_d <V^2>/2 (the SPH stress
less Poncelet's drag term).  Then the Poncelet P_max at V0 in three
conventions for the first d/2 of the tip's travel: (a) Eq. 4.6 + d/2
(Eq. 4.7, the validation reference: that d/2 costs nothing), (b) the full
frontal area from first contact (tip depth = Eq. 4.6), (c) the sphere's
geometric section at the surface, pi (d P - P^2), while P < d/2.
Standard library only.
"""
import csv
import math
import sys

D, RHO_P, RHO_T, CD, R = 7.38e-6, 1850.0, 1030.0, 0.375, 21.0e6
M = RHO_P * math.pi * D**3 / 6.0
AF = math.pi * D * D / 4.0
C = R * AF
B = RHO_T * math.pi * D * D * CD / 8.0


def poncelet(v0, area):
    """Tip depth at rest of M dV/dt = -(area(P)/AF)(B V^2 + C) (RK4)."""
    p, v, dt = 0.0, v0, 1e-12
    acc = lambda p, v: -area(p) / AF * (C + B * v * v) / M
    while v > 0.0:
        k1p, k1v = v, acc(p, v)
        k2p, k2v = v + 0.5 * dt * k1v, acc(p + 0.5 * dt * k1p, v + 0.5 * dt * k1v)
        k3p, k3v = v + 0.5 * dt * k2v, acc(p + 0.5 * dt * k2p, v + 0.5 * dt * k2v)
        k4p, k4v = v + dt * k3v, acc(p + dt * k3p, v + dt * k3v)
        p += dt * (k1p + 2 * k2p + 2 * k3p + k4p) / 6.0
        v += dt * (k1v + 2 * k2v + 2 * k3v + k4v) / 6.0
    return p


def main():
    if len(sys.argv) < 3:
        sys.exit(__doc__)
    path, v0 = sys.argv[1], float(sys.argv[2])
    gap = float(sys.argv[3]) if len(sys.argv) > 3 else 0.25e-6
    rows = list(csv.DictReader(open(path)))
    pts = [(-float(r["sphere_uy [m]"]) - gap, -float(r["sphere_vy [m/s]"])) for r in rows]
    kmax = max(range(len(pts)), key=lambda k: pts[k][0])
    pts = pts[:kmax + 1]  # the way down only
    pmax = pts[-1][0]

    def v_at(pq):
        for (p0, u0), (p1, u1) in zip(pts, pts[1:]):
            if p0 <= pq <= p1 and p1 > p0:
                return u0 + (pq - p0) / (p1 - p0) * (u1 - u0)
        return 0.0

    edges = [0.0, D / 4, D / 2, 0.75 * D, D]
    edges += [D * k / 2 for k in range(3, 60) if D * k / 2 < pmax]
    edges = [e for e in edges if e < pmax] + [pmax]
    print("P_max %.3f um (%.3f d); entry (tip 0..d/2) absorbs %.1f %% of the kinetic energy"
          % (pmax * 1e6, pmax / D, 100.0 * (1.0 - v_at(D / 2) ** 2 / v0**2)))
    print("P/d range    V in -> out [m/s]  SPH F/A [MPa]  Poncelet [MPa]  SPH R_eff [MPa]")
    for a, b in zip(edges, edges[1:]):
        va, vb = v_at(a), (v_at(b) if b < pmax else 0.0)
        f = 0.5 * M * (va * va - vb * vb) / (b - a)
        v2 = 0.5 * (va * va + vb * vb)
        print("%5.2f-%5.2f  %7.1f -> %7.1f  %9.2f  %12.2f  %12.2f"
              % (a / D, b / D, va, vb, f / AF * 1e-6, (C + B * v2) / AF * 1e-6,
                 (f - B * v2) / AF * 1e-6))
    pa = 2 * RHO_P * D / (3 * RHO_T * CD) * math.log(1 + RHO_T * CD * v0 * v0 / (2 * R)) + D / 2
    pb = poncelet(v0, lambda p: AF)
    pc = poncelet(v0, lambda p: math.pi * (D * p - p * p) if p < D / 2 else AF)
    for name, ref in (("(a) Eq. 4.6 + d/2", pa), ("(b) full area", pb), ("(c) geometric entry", pc)):
        print("Poncelet %-20s %8.3f um  SPH %+6.1f %%" % (name, ref * 1e6, 100 * (pmax / ref - 1)))


if __name__ == "__main__":
    main()
