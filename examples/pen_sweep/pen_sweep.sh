#!/usr/bin/env bash
# Issue 7 item 7: P_max/d vs v0 tables and plots, velocity x diameter, from
# the analytical models with the thesis' coefficients:
#   gelatin.csv  silica into 10 wt% gelatin, Poncelet C_d = 0.375, R = 21 MPa
#                ([Meng2021] Fig. 4.14), d = 5, 7.38, 10 um, v0 = 100-1500 m/s
#   sebs.csv     steel into 40 vol% SEBS, Modified-CG eta = 4.5e-2 Pa s,
#                R = 25 MPa (fit (b), Fig. 4.5), d = 11-22 um, v0 = 50-900 m/s
#   sebs_poncelet.csv  the same grid with Poncelet fit (b), C_d = 0.8, R = 33.7 MPa
# Each NAME.csv (long form, one row per (d, v0); columns d, v0, T_f, P_max,
# P_max_nose, P_max_over_d (, Re), SI units) comes with
#   NAME.png        P_max/d against v0, one line per d (`spall penetrate
#                   sweep`, cairo, src/io/plot.c; docs/pictures.md)
#   NAME_table.csv  the same P_max/d as a table: one row per v0, one column
#                   per d (P_max/d without the nose; add 0.5 for the tip
#                   convention of Eq. 4.7)
# Poncelet's P_max/d depends on v0 only (Eq. 4.6: P_max is proportional to
# d at fixed v0), so the three gelatin lines coincide; the diameter matters
# with Modified-CG (Re = rho_t V d / eta) and Liu (strain rate V/d).
# The SPH side (axisymmetric SPH, one d): validation case
# pen-sph-gelatin-sweep, decks from scripts/pen_decks.sh DIR.
# Usage: examples/pen_sweep/pen_sweep.sh [spall] [outdir]
#   defaults: the build/spall of this checkout, ./pen_sweep_out
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
spall="${1:-$here/../../build/spall}"
out="${2:-pen_sweep_out}"
if [ ! -f "$spall" ] || [ ! -x "$spall" ]; then
    echo "pen_sweep.sh: no spall executable at '$spall' (build first, or pass its path)" >&2
    exit 2
fi
if [ -d "$out" ] && [ -n "$(ls -A "$out")" ]; then # as spall run: never replace results
    echo "pen_sweep.sh: '$out' exists and is not empty; name another output directory" >&2
    exit 2
fi
mkdir -p "$out"

# NAME.csv (long form) -> NAME_table.csv: v0, then P_max/d per diameter
# (diameters in um in the header, in the order of the sweep)
pivot() {
    awk -F, '
        /^#/ || $1 == "d" { next }
        {
            if (!($1 in seen_d)) { seen_d[$1] = 1; dl[++nd] = $1 }
            if (!($2 in seen_v)) { seen_v[$2] = 1; vl[++nv] = $2 }
            val[$1, $2] = $6
        }
        END {
            printf "# P_max/d (no nose) vs v0 [m/s]; columns: d [um]\nv0"
            for (i = 1; i <= nd; i++) printf ",d=%g", dl[i] * 1e6
            printf "\n"
            for (j = 1; j <= nv; j++) {
                printf "%g", vl[j]
                for (i = 1; i <= nd; i++) printf ",%.6g", val[dl[i], vl[j]]
                printf "\n"
            }
        }' "$1" > "${1%.csv}_table.csv"
    echo "wrote ${1%.csv}_table.csv"
}

"$spall" penetrate sweep --model poncelet --projectile silica --target gelatin \
    --Cd 0.375 --R 21e6 --diameter 5e-6,7.38e-6,10e-6 --v0 100:1500:50 --csv "$out/gelatin.csv"
"$spall" penetrate sweep --model mcg --projectile steel --target sebs \
    --eta 4.5e-2 --R 25e6 --diameter 11e-6,13e-6,16e-6,20e-6,22e-6 --v0 50:900:25 --csv "$out/sebs.csv"
"$spall" penetrate sweep --model poncelet --projectile steel --target sebs \
    --Cd 0.8 --R 33.7e6 --diameter 11e-6,13e-6,16e-6,20e-6,22e-6 --v0 50:900:25 \
    --csv "$out/sebs_poncelet.csv"
for f in gelatin sebs sebs_poncelet; do
    pivot "$out/$f.csv"
done
