#!/bin/sh
# SPH race (issue 6 item 8), side by side with LAMMPS MACHDYN, run by hand:
#
#   LMP=$(sh bench/lammps_machdyn_build.sh) sh bench/sph_vs_lammps.sh [build-dir] [--rest]
#
# The problem: copper Taylor bar L0 = 32.4 mm, R0 = 3.2 mm, 227 m/s onto a
# rigid wall, E = 117 GPa, nu = 0.35, rho = 8930 kg/m^3, sigma_y = 0.4 GPa
# + 0.1 GPa eps_p (linear hardening), simple-cubic particles dx = 0.4 mm
# (16 848 particles; --scale 0.3: dx = 0.598 mm, 4 752 particles).
#
# Matched neighbour count: LAMMPS MACHDYN's TLSPH examples set the kernel
# radius (the atom "diameter") to 2.01 dx (examples/PACKAGES/machdyn/
# aluminum_strip_pull, rubber_strip_pull, funnel_flow), and pair smd/tlsph
# takes h = radius_i + radius_j as the support of its spiky kernel: 32
# neighbours inside a cubic lattice, 27.3 on average over this bar.
# spall's Wendland kernel with h = 1.005 dx has the same support 2.01 dx
# (bench case sph-taylor-cu-tl).  Same AV (Monaghan [1, 1] in both; MACHDYN
# Q1 = Q2 = 1).  Not matched (different formulas): the hourglass control
# (MACHDYN 10 on its own pair-error measure; spall kappa = 0.1 default, 1 in
# the rest case) and the time step (MACHDYN 0.1 x radius / c; spall 0.3 h /
# (c + |v|) with the leapfrog).  Throughput is per particle-step, so the time
# step does not enter it; it enters the cost per simulated microsecond.
#
# OMP_WAIT_POLICY (default passive, for a shared machine) is passed to spall;
# on an idle machine OMP_WAIT_POLICY=active lets the two threads of the
# pipelined sweep meet at its barriers without sleeping (docs/performance.md).
#
# 1. throughput, 200 steps, one core each: spall (1 and 2 threads) and
#    LAMMPS (serial build: one core) on both sizes;
# 2. with --rest: the accuracy half, both codes run to 80 us and report the
#    final length (axial extent + dx) and mushroom radius (largest radius of
#    a particle + dx/2), spall with the leapfrog and hourglass 1
#    (sph-taylor-cu-rest-lf), LAMMPS with the settings above.
#
# LMP defaults to `lmp` on PATH; Debian's lammps 20220106 binary has no
# MACHDYN (`lmp -h | grep -c smd/tlsph` prints 0), its source package does:
# bench/lammps_machdyn_build.sh builds one.
set -eu
BUILD=${1:-build}
REST=${2:-}
LMP=${LMP:-lmp}
echo "== spall: copper Taylor bar, 200 steps"
for s in 1 0.3; do
    for t in 1 2; do
        OMP_WAIT_POLICY=${OMP_WAIT_POLICY:-passive} "$BUILD/spall" bench sph-taylor-cu-tl --threads "$t" \
            --scale "$s" || true
    done
done
if [ "$REST" = "--rest" ]; then
    for s in 0.125 0.3 1; do
        OMP_NUM_THREADS=1 "$BUILD/spall" bench sph-taylor-cu-rest-lf --threads 1 --scale "$s" \
            || true
    done
fi
if ! command -v "$LMP" >/dev/null 2>&1 || [ "$("$LMP" -h 2>&1 | grep -c 'smd/tlsph')" = 0 ]; then
    echo "== LAMMPS: no lmp with the MACHDYN package (smd/tlsph) at '$LMP'; skipped"
    echo "   (LMP=\$(sh bench/lammps_machdyn_build.sh) builds one from Debian's source)"
    exit 0
fi
dir=$(mktemp -d)
machdyn_input() { # $1 = dx [m], $2 = run length: steps or "rest"
    cat <<LMP
# copper Taylor bar, TLSPH (MACHDYN), SI units, dx = $1 m
units          si
dimension      3
boundary       sm sm sm
atom_style     smd
comm_modify    vel yes
newton         off
atom_modify    map array
variable       dx equal $1
variable       h  equal 2.01*\${dx}     # kernel diameter = support radius (MACHDYN examples)
neighbor       \${h} bin
neigh_modify   every 10 delay 0 check yes
lattice        sc \${dx} origin 0.5 0.5 0.5
region         bar cylinder z 0 0 3.2e-3 0 32.4e-3 units box
region         box block -12e-3 12e-3 -12e-3 12e-3 -1e-3 34e-3 units box
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
variable       r atom sqrt(x*x+y*y)
compute        rmax all reduce max v_r
variable       zlo equal bound(all,zmin)
variable       zhi equal bound(all,zmax)
variable       len equal v_zhi-v_zlo+\${dx}
variable       rad equal c_rmax+0.5*\${dx}
thermo         500
thermo_style   custom step time f_dtfix c_nnave v_len v_rad
thermo_modify  norm no
LMP
    if [ "$2" = rest ]; then
        # fix smd/adjust_dt sets the step; run in chunks of 100 steps until 80 us
        cat <<LMP
run            200
variable       tnow equal time
label          more
if "\${tnow} >= 80e-6" then "jump SELF done"
run            100 post no
jump           SELF more
label          done
print          "RESULT time \${tnow} length \$(v_len) radius \$(v_rad) steps \$(step)"
LMP
    else
        echo "run            $2"
    fi
}
for dx in 0.4e-3 0.598e-3; do
    machdyn_input "$dx" 200 > "$dir/in.taylor"
    echo "== LAMMPS MACHDYN, dx = $dx, 1 core (serial), 200 steps"
    (cd "$dir" && "$LMP" -in in.taylor > log.200 2>&1)
    atoms=$(grep -m1 "Created .* atoms" "$dir/log.200" | awk '{print $2}')
    loop=$(grep -m1 "^Loop time" "$dir/log.200" | awk '{print $4}')
    cpu=$(grep -m1 "% CPU use" "$dir/log.200" | awk '{sub("%", "", $1); print $1}')
    grep -E "^ +200 " "$dir/log.200" || true
    # LAMMPS' loop time is wall clock; "% CPU use" turns it into CPU
    # seconds, comparable with spall's "loop CPU" on a shared machine
    awk -v n="$atoms" -v s="$loop" -v c="$cpu" 'BEGIN {printf "   %d atoms, 200 steps in %.3f s wall (%.1f %% CPU): %.4g particle-steps/s, %.4g per CPU-second\n", n, s, c, n * 200 / s, n * 200 / (s * c / 100)}'
done
if [ "$REST" = "--rest" ]; then
    for dx in 0.8e-3 0.598e-3 0.4e-3; do
        machdyn_input "$dx" rest > "$dir/in.rest"
        echo "== LAMMPS MACHDYN to 80 us, dx = $dx"
        start=$(date +%s)
        (cd "$dir" && "$LMP" -in in.rest > log.rest 2>&1) || tail -5 "$dir/log.rest"
        end=$(date +%s)
        grep -E "^RESULT|ERROR|WARNING.*deleted" "$dir/log.rest" | head -5 || true
        echo "   wall $((end - start)) s"
    done
fi
rm -rf "$dir"
