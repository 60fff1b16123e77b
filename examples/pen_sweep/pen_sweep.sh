#!/usr/bin/env bash
# Issue 7 item 7: P_max/d vs v0 tables, velocity x diameter, from the
# analytical models with the thesis' coefficients (runnable now):
#   gelatin.csv  silica into 10 wt% gelatin, Poncelet C_d = 0.375, R = 21 MPa
#                (seed 004 Fig. 4.14), d = 5, 7.38, 10 um, v0 = 100-1500 m/s
#   sebs.csv     steel into 40 vol% SEBS, Modified-CG eta = 4.5e-2 Pa s,
#                R = 25 MPa (fit (b), Fig. 4.5), d = 11-22 um, v0 = 50-900 m/s
#   sebs_poncelet.csv  the same grid with Poncelet fit (b), C_d = 0.8, R = 33.7 MPa
# Columns: d, v0, T_f, P_max, P_max_nose, P_max_over_d (, Re).
# The SPH side (axisymmetric SPH): scripts/pen_decks.sh DIR writes the
# gelatin velocity and modulus decks.  Plot: each --csv also gets a PNG of
# P_max/d against v0 (one line per d) beside it.
# Usage: examples/pen_sweep/pen_sweep.sh [spall] [outdir]
set -euo pipefail
spall="${1:-build/spall}"
out="${2:-pen_sweep_out}"
mkdir -p "$out"
"$spall" penetrate sweep --model poncelet --projectile silica --target gelatin \
    --cd 0.375 --R 21e6 --d 5e-6,7.38e-6,10e-6 --v0 100:1500:50 --csv "$out/gelatin.csv"
"$spall" penetrate sweep --model mcg --projectile steel --target sebs \
    --eta 4.5e-2 --R 25e6 --d 11e-6,13e-6,16e-6,20e-6,22e-6 --v0 50:900:25 --csv "$out/sebs.csv"
"$spall" penetrate sweep --model poncelet --projectile steel --target sebs \
    --cd 0.8 --R 33.7e6 --d 11e-6,13e-6,16e-6,20e-6,22e-6 --v0 50:900:25 \
    --csv "$out/sebs_poncelet.csv"
