#!/usr/bin/env python3
"""Richardson extrapolation over three meshes, h = 1/NR (issue 6 item 8).

Usage: python3 richardson.py NR1 f1 NR2 f2 NR3 f3   (NR1 < NR2 < NR3)
Solves f(h) = f_inf + C h^p through the three points (p by bisection on
the ratio of differences, which allows a non-constant refinement ratio),
and gives Roache's grid convergence index of the finest mesh,
GCI = Fs |f3 - f2| / (r^p - 1), r = NR3 / NR2, Fs = 1.25 (three meshes).
If the differences change sign (oscillatory convergence) no order exists:
it prints the range of the three values instead.
"""
import math
import sys

n = [float(a) for a in sys.argv[1::2]]
f = [float(a) for a in sys.argv[2::2]]
h = [1 / v for v in n]
d1, d2 = f[1] - f[0], f[2] - f[1]
if d1 * d2 <= 0:
    print(f"oscillatory or flat: differences {d1:+.4f}, {d2:+.4f}; "
          f"range {min(f):.4f} .. {max(f):.4f}")
    sys.exit(0)


def g(p):                                  # model ratio minus measured ratio
    return (h[0] ** p - h[1] ** p) / (h[1] ** p - h[2] ** p) - d1 / d2


lo, hi = 0.05, 12.0
if g(lo) * g(hi) > 0:
    print(f"no order in [{lo}, {hi}]: ratio of differences {d1 / d2:.3f}")
    sys.exit(0)
for _ in range(100):
    mid = 0.5 * (lo + hi)
    lo, hi = (mid, hi) if g(lo) * g(mid) > 0 else (lo, mid)
p = 0.5 * (lo + hi)
r = n[2] / n[1]
finf = f[2] + d2 / (r ** p - 1)
gci = 1.25 * abs(d2) / (r ** p - 1)
print(f"order p = {p:.2f}; limit f_inf = {finf:.4f}; GCI (finest) = "
      f"{gci:.4f} ({100 * gci / abs(f[2]):.2f} %)")
