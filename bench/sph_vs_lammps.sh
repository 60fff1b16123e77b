#!/bin/sh
# SPH race (issue 6 item 8), run by hand:  sh bench/sph_vs_lammps.sh [build-dir]
# 1. spall: the copper Taylor bar of bench/bench_sph.c (L0 = 32.4 mm,
#    R0 = 3.2 mm, 227 m/s, E = 117 GPa, nu = 0.35, rho = 8930 kg/m^3,
#    sigma_y = 0.4 GPa + 0.1 GPa eps_p, dx = 0.4 mm) on 1 and 2 threads.
# 2. LAMMPS MACHDYN (pair smd/tlsph) on the same bar, if `lmp` has the
#    package.  Debian's lammps 20220106 does NOT include MACHDYN (checked:
#    `lmp -h | grep -ci smd` prints 0), so on this machine only step 1 runs;
#    the input below is written for a LAMMPS built with -DPKG_MACHDYN=on.
set -eu
BUILD=${1:-build}
echo "== spall (copper Taylor bar, 200 steps)"
for t in 1 2; do
    "$BUILD/spall" bench sph_taylor_cu --threads "$t" || true
done
if ! command -v lmp >/dev/null 2>&1 || [ "$(lmp -h 2>&1 | grep -ci 'smd/tlsph')" = 0 ]; then
    echo "== LAMMPS: no lmp with the MACHDYN package (smd/tlsph) here; skipped"
    exit 0
fi
dir=$(mktemp -d)
cat > "$dir/in.taylor" <<'LMP'
# copper Taylor bar, TLSPH (MACHDYN), SI units
units          si
dimension      3
boundary       sm sm sm
atom_style     smd
comm_modify    vel yes
newton         off
atom_modify    map array
variable       dx equal 0.4e-3
variable       h  equal 3.0*${dx}   # kernel support radius = 2 h_spall, h_spall = 1.5 dx
lattice        sc ${dx}
region         bar cylinder z 0 0 3.2e-3 0 32.4e-3 units box
region         box block -8e-3 8e-3 -8e-3 8e-3 -1e-3 34e-3 units box
create_box     1 box
create_atoms   1 region bar
set            group all smd/contact/radius ${dx}
set            group all diameter ${h}
set            group all volume $(v_dx^3)
set            group all smd/mass/density 8930
velocity       all set 0 0 -227 units box
pair_style     smd/tlsph
pair_coeff     1 1 *COMMON 8930 117e9 0.35 1.0 10.0 &
               *STRENGTH_LINEAR_PLASTIC 0.4e9 0.1e9 &
               *EOS_LINEAR &
               *END
fix            wall all wall/reflect zlo 0
fix            integ all smd/integrate_tlsph
compute        nn all smd/tlsph/num/neighs
timestep       2.0e-8
thermo         50
run            200
LMP
echo "== LAMMPS MACHDYN"
(cd "$dir" && lmp -in in.taylor | tail -25)
