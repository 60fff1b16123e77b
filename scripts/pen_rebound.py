#!/usr/bin/env python3
"""Penetration, maximum depth and rebound of the rigid sphere of an
axisymmetric SPH penetration run (history.csv of examples/pen_sph_gelatin,
pen_sph_rate, pen_sph_skin or a scripts/pen_decks.sh variant).

    scripts/pen_rebound.py HISTORY.csv [GAP]

P = tip depth below the initial surface = -sphere_uy - GAP (GAP the initial
distance of the tip above the surface, default 0.25e-6 m, the decks'),
V = sphere_vy (< 0 going in, > 0 on the way back).  Times are from the
start of the run (first contact: the first row with sphere_contacts > 0,
printed).  Prints:
  - P at 20, 50, 100, 150, 200 ns (linear interpolation between rows);
  - P_max and its time (largest sampled P; rows every history_every steps);
  - the rebound: the time V turns upward (first 0-crossing of V after
    P_max, interpolated), the peak upward speed after it and its time
    (flagged when it is the last row: still accelerating), the energy it
    carries (M V^2 / 2, % of the sphere's initial kinetic energy E0), and
    the tip's recovery P_max - P(end) (um and % of P_max) at the last row;
  - the energy balance (energy_balance / E0; E0 = the kinetic energy of
    row 0, the sphere's, the target being at rest): at P_max, at the end,
    and the largest |.| over the run.
The sphere's mass for the rebound energy is taken from E0 and V(0):
M = 2 E0 / V(0)^2.  Standard library only.
"""
import csv
import sys


def column(rows, header, name):
    """Values of the first column whose header starts with @p name."""
    for k, h in enumerate(header):
        if h.split(" ")[0] == name:
            return [float(r[k]) for r in rows]
    sys.exit(f"pen_rebound.py: no column '{name}' in the history")


def interp(ts, ys, tq):
    """y at tq by linear interpolation; None outside the samples."""
    for k in range(1, len(ts)):
        if ts[k - 1] <= tq <= ts[k]:
            w = (tq - ts[k - 1]) / (ts[k] - ts[k - 1]) if ts[k] > ts[k - 1] else 0.0
            return ys[k - 1] + w * (ys[k] - ys[k - 1])
    return None


def main():
    if len(sys.argv) < 2 or sys.argv[1] in ("-h", "--help"):
        print(__doc__)
        return 0 if len(sys.argv) >= 2 else 2
    gap = float(sys.argv[2]) if len(sys.argv) > 2 else 0.25e-6
    with open(sys.argv[1], newline="") as f:
        rd = csv.reader(f)
        header = next(rd)
        rows = [r for r in rd if r and not r[0].startswith("#")]
    if len(rows) < 3:
        sys.exit("pen_rebound.py: fewer than 3 rows in the history")
    t = column(rows, header, "time")
    uy = column(rows, header, "sphere_uy")
    vy = column(rows, header, "sphere_vy")
    kin = column(rows, header, "kinetic")
    bal = column(rows, header, "energy_balance")
    contacts = column(rows, header, "sphere_contacts")
    P = [-u - gap for u in uy]
    e0 = kin[0]
    mass = 2.0 * e0 / (vy[0] * vy[0]) if vy[0] != 0.0 else float("nan")
    t_contact = next((t[k] for k in range(len(t)) if contacts[k] > 0), float("nan"))
    print(f"rows {len(t)}, end {t[-1] * 1e9:.1f} ns, first contact at {t_contact * 1e9:.2f} ns "
          f"(row time), E0 = {e0:.4e} J, M = {mass:.4e} kg")
    marks = [20e-9, 50e-9, 100e-9, 150e-9, 200e-9]
    ps = [interp(t, P, m) for m in marks]
    print("P at 20/50/100/150/200 ns [um]: "
          + " / ".join("—" if p is None else f"{p * 1e6:.2f}" for p in ps))
    kmax = max(range(len(P)), key=lambda k: P[k])
    print(f"P_max {P[kmax] * 1e6:.2f} um at {t[kmax] * 1e9:.1f} ns"
          + (" (the last row: not reached)" if kmax == len(P) - 1 else ""))
    print(f"energy balance / E0: at P_max {bal[kmax] / e0 * 100:+.2f} %, at the end "
          f"{bal[-1] / e0 * 100:+.2f} %, max |.| {max(abs(b) for b in bal) / e0 * 100:.2f} %")
    # reversal: first row after P_max's neighbourhood where V > 0
    krev = next((k for k in range(max(kmax - 1, 1), len(vy)) if vy[k] > 0.0 >= vy[k - 1]), None)
    if krev is None:
        print("rebound: V has not turned upward by the end "
              f"(V(end) = {vy[-1]:.1f} m/s)")
        return 0
    w = -vy[krev - 1] / (vy[krev] - vy[krev - 1])
    t_rev = t[krev - 1] + w * (t[krev] - t[krev - 1])
    kpk = max(range(krev, len(vy)), key=lambda k: vy[k])
    v0 = abs(vy[0])
    e_pk = 0.5 * mass * vy[kpk] ** 2
    rec = P[kmax] - P[-1]
    print(f"rebound: V turns upward at {t_rev * 1e9:.1f} ns; peak upward speed "
          f"{vy[kpk]:.1f} m/s ({vy[kpk] / v0 * 100:.2f} % of v0, "
          f"{e_pk / e0 * 100:.3f} % of E0) at {t[kpk] * 1e9:.1f} ns"
          + (" (the last row: still accelerating)" if kpk == len(vy) - 1 else ""))
    print(f"rebound: V(end) = {vy[-1]:.1f} m/s; tip recovery at the end "
          f"P_max - P = {rec * 1e6:.2f} um ({rec / P[kmax] * 100:.1f} % of P_max), "
          f"P(end) = {P[-1] * 1e6:.2f} um")
    return 0


if __name__ == "__main__":
    sys.exit(main())
