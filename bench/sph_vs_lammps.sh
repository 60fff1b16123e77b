#!/bin/sh
# SPH race (issue 6 item 8), run by hand:  sh bench/sph_vs_lammps.sh [build-dir]
#
# The problem: copper Taylor bar L0 = 32.4 mm, R0 = 3.2 mm, 227 m/s onto a
# rigid wall, E = 117 GPa, nu = 0.35, rho = 8930 kg/m^3, sigma_y = 0.4 GPa
# + 0.1 GPa eps_p (linear hardening), simple-cubic particles dx = 0.4 mm
# (16 848 particles; --scale 0.3: dx = 0.598 mm, 4 752 particles).
#
# Matched neighbour count: LAMMPS MACHDYN's TLSPH examples set the kernel
# radius (the atom "diameter") to 2.01 dx
# (/usr/share/lammps/examples/PACKAGES/machdyn/aluminum_strip_pull/in.*,
# rubber_strip_pull, funnel_flow; Debian lammps-examples 20220106), and
# pair smd/tlsph takes h = radius_i + radius_j as the support of its spiky
# kernel (src/MACHDYN/pair_smd_tlsph.cpp): 32 neighbours inside a cubic
# lattice, 27.3 on average over this bar.  spall's Wendland kernel with
# h = 1.005 dx has the same support 2.01 dx (bench case sph_taylor_cu_tl).
# Other MACHDYN settings of those examples: hourglass coefficient 10, Q1 =
# 0.56 (metal) / 1.0, Q2 = 0, time step 0.1 x kernel radius / wave speed
# (fix smd/adjust_dt 0.1).  The hourglass and viscosity terms are not the
# same formulas as spall's (kappa = 0.1 on the pair mismatch; Monaghan AV
# [1, 1]): matched are the problem, the kernel support and the neighbour
# count, not the stabilisation.
#
# 1. spall on 1 and 2 threads, both sizes (wall clock of the time loop).
# 2. LAMMPS MACHDYN on the same bar, if `lmp` has the package.  Debian's
#    lammps 20220106 does NOT include MACHDYN (checked 2026-11-23:
#    `lmp -h | grep -ci smd` prints 0), so on this machine only step 1 runs;
#    the input below is written for a LAMMPS built with -D PKG_MACHDYN=on
#    (needs Eigen3) and has not been run.
set -eu
BUILD=${1:-build}
echo "== spall: copper Taylor bar, 200 steps"
for s in 1 0.3; do
    for t in 1 2; do
        OMP_WAIT_POLICY=passive "$BUILD/spall" bench sph_taylor_cu_tl sph_taylor_cu \
            --threads "$t" --scale "$s" || true
    done
done
if ! command -v lmp >/dev/null 2>&1 || [ "$(lmp -h 2>&1 | grep -ci 'smd/tlsph')" = 0 ]; then
    echo "== LAMMPS: no lmp with the MACHDYN package (smd/tlsph) here; skipped"
    exit 0
fi
dir=$(mktemp -d)
for dx in 0.4e-3 0.598e-3; do
cat > "$dir/in.taylor" <<LMP
# copper Taylor bar, TLSPH (MACHDYN), SI units, dx = $dx m
units          si
dimension      3
boundary       sm sm sm
atom_style     smd
comm_modify    vel yes
newton         off
atom_modify    map array
variable       dx equal $dx
variable       h  equal 2.01*\${dx}     # kernel diameter = support radius (MACHDYN examples)
neighbor       \${h} bin
neigh_modify   every 10 delay 0 check yes
lattice        sc \${dx} origin 0.5 0.5 0.5
region         bar cylinder z 0 0 3.2e-3 0 32.4e-3 units box
region         box block -8e-3 8e-3 -8e-3 8e-3 -1e-3 34e-3 units box
create_box     1 box
create_atoms   1 region bar
group          tlsph type 1
set            group all volume \$(v_dx^3)
set            group all smd/mass/density 8930
set            group all diameter \${h}
set            group all smd/contact/radius \${dx}
velocity       all set 0 0 -227 units box
# *COMMON rho0 E nu Q1 Q2 hg Cp
pair_style     smd/tlsph
pair_coeff     1 1 *COMMON 8930 117e9 0.35 1.0 1.0 10.0 1.0 &
               *STRENGTH_LINEAR_PLASTIC 0.4e9 0.1e9 &
               *EOS_LINEAR &
               *END
fix            wall all wall/reflect zlo 0.0 units box
fix            dtfix tlsph smd/adjust_dt 0.1
fix            integ tlsph smd/integrate_tlsph
compute        nn all smd/tlsph/num/neighs
compute        nnave all reduce ave c_nn
thermo         50
thermo_style   custom step time f_dtfix c_nnave
run            200
LMP
for t in 1 2; do
    echo "== LAMMPS MACHDYN, dx = $dx, $t thread(s) (MPI ranks)"
    (cd "$dir" && mpirun -np "$t" lmp -in in.taylor > log.$t 2>&1 || lmp -in in.taylor > log.$t 2>&1)
    atoms=$(grep -m1 "Created .* atoms" "$dir/log.$t" | awk '{print $2}')
    loop=$(grep -m1 "^Loop time" "$dir/log.$t" | awk '{print $4}')
    grep -E "average # of neighbors|^ +200 " "$dir/log.$t" || true
    awk -v n="$atoms" -v s="$loop" 'BEGIN {printf "   %d atoms, 200 steps in %.3f s: %.4g particle-steps/s\n", n, s, n * 200 / s}'
done
done
