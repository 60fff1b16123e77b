#!/usr/bin/env bash
# Race and cross-check: the same 3D PMB problem in spall and in LAMMPS
# (PERI package, pair_style peri/pmb).  Run by hand, not part of the suite:
#     bench/pd_vs_lammps.sh [path/to/spall] [NX NY NZ STEPS]
# Installs lammps (Debian package) if `lmp` is missing (bench/lammps_setup.sh).
#
# Problem (identical in both codes):
#   simple-cubic lattice, spacing dx = 1 mm, NX x NY x NZ sites (default
#   36 x 24 x 24 = 20736), horizon delta = 3.015 dx; family = sites closer
#   than delta, partial volume beta = (delta + dx/2 - xi)/dx for xi within
#   dx/2 of delta (PDLAMMPS's vfrac_scale; spall partial_volume_rule: lammps);
#   E = 72 GPa, nu = 1/4 -> K = 48 GPa, c = 18 K / (pi delta^4) (Parks et al.
#   convention: force density c s V_j beta, particle volume dx^3 = LAMMPS
#   vfrac, density 2440 kg/m^3 = LAMMPS rmass of atom_style peri);
#   critical stretch s0 = 0.002 constant (LAMMPS alpha = 0);
#   the two end slabs (2 layers) pulled apart at -/+ 5 m/s in x (LAMMPS:
#   setforce 0 + velocity set), dt = 5e-8 s, STEPS steps (default 200).
# Compared: sum over particles of the damage (LAMMPS compute damage/atom),
# the x displacement of a probe particle, loop wall time -> bond-steps/s on
# 1 and 2 threads (spall: OpenMP threads; LAMMPS: MPI ranks, the Debian
# build has no OPENMP package), and the peak resident memory per particle.
# SPALL_RANKS=1: spall's 2-core run is 2 MPI ranks x 1 thread as well (rank
# for rank with LAMMPS; memory = the sum of the ranks' peaks).
# Differences to keep in mind: LAMMPS's PMB also runs its short-range
# contact loop every step (inactive here: the block is pulled); it applies a
# bond's force in the step it breaks, which spall does with break_order:
# next_step (its default, immediate, drops the bond at once).
set -euo pipefail
SPALL=${1:-build/spall}
NX=${2:-36}; NY=${3:-24}; NZ=${4:-24}; STEPS=${5:-200}
NAME=pd_vs_lammps CHECK=0
. "$(dirname "$0")/lammps_setup.sh"
DX=1.0e-3
DELTA=$(python3 -c "print(3.015*$DX)")
C=$(python3 -c "import math; print(repr(18*48e9/(math.pi*(3.015*$DX)**4)))")
PX=$(python3 -c "print(($NX*3//4)*$DX)"); PY=$(python3 -c "print(($NY//2)*$DX)"); PZ=$(python3 -c "print(($NZ//2)*$DX)")
# ---- LAMMPS --------------------------------------------------------------
cat > "$W/in.pmb" <<LMP
units si
dimension 3
boundary s s s
atom_style peri
atom_modify map array
lattice sc $DX
region box block -0.5 $(($NX))-0.5 -0.5 $(($NY))-0.5 -0.5 $(($NZ))-0.5
create_box 1 box
create_atoms 1 region box
pair_style peri/pmb
pair_coeff * * $C $DELTA 0.002 0.0
set group all density 2440
set group all volume $(python3 -c "print($DX**3)")
region left block INF 1.5 INF INF INF INF
region right block $(($NX-2))-0.5 INF INF INF INF INF
region pr block $(($NX*3/4))-0.5 $(($NX*3/4))+0.5 $(($NY/2))-0.5 $(($NY/2))+0.5 $(($NZ/2))-0.5 $(($NZ/2))+0.5
group left region left
group right region right
group probe region pr
velocity all set 0 0 0
velocity left set -5 NULL NULL units box
velocity right set 5 NULL NULL units box
fix 1 all nve
fix 2 left setforce 0.0 NULL NULL
fix 3 right setforce 0.0 NULL NULL
compute dmg all damage/atom
compute dsum all reduce sum c_dmg
compute dsp probe displace/atom
compute pux probe reduce sum c_dsp[1]
thermo_style custom step c_dsum c_pux
thermo $STEPS
timestep 5e-8
run $STEPS
LMP
sed -i -E 's/([0-9]+)-0\.5/\1 - 0.5/g' "$W/in.pmb"
python3 - "$W/in.pmb" <<'PY'
import re,sys
p=sys.argv[1]; s=open(p).read()
def ev(m): return repr(eval(m.group(0)))
s=re.sub(r'\$\(\(([^)]*)\)\)',lambda m: m.group(1),s)
s=re.sub(r'(?<![\w.])(\d+(?:\*\d+)?(?:/\d+)?)\s*([-+])\s*0\.5', lambda m: repr(eval(m.group(1).replace('/','//'))+(0.5 if m.group(2)=='+' else -0.5)), s)
open(p,'w').write(s)
PY
# ---- spall ---------------------------------------------------------------
cat > "$W/pmb.yaml" <<YML
title: PMB race vs LAMMPS peri/pmb
model: {type: peridynamics, horizon_factor: 3.015, partial_volume_rule: lammps, break_order: next_step}
materials:
  glass: {density: 2440, bulk_modulus: 48.0e9, critical_stretch: 0.002}
lattice: {type: sc, spacing: $DX}
geometry:
  block: {box: {min: [-0.0005, -0.0005, -0.0005], max: [$(python3 -c "print(($NX-0.5)*$DX)"), $(python3 -c "print(($NY-0.5)*$DX)"), $(python3 -c "print(($NZ-0.5)*$DX)")]}}
body: {geometry: block, material: glass}
groups:
  left: {box: {min: [-1, -1, -1], max: [0.0015, 1, 1]}}
  right: {box: {min: [$(python3 -c "print(($NX-2.5)*$DX)"), -1, -1], max: [1, 1, 1]}}
boundary_conditions:
  - {group: left, type: velocity, components: [x], value: -5.0}
  - {group: right, type: velocity, components: [x], value: 5.0}
probes:
  - {name: p, position: [$PX, $PY, $PZ]}
run: {dt: 5.0e-8, dt_override: true, steps: $STEPS, threads: THREADS}
output: {history_every: $STEPS, field_interval: 1.0}
YML
printf "%-8s %-8s %12s %14s %14s %14s %12s\n" code threads wall_s bond_steps/s damage_sum probe_ux_m rss_B/part
for T in 1 2; do
  if [ "${SPALL_RANKS:-0}" = 1 ] && [ "$T" -gt 1 ]; then
    sed "s/THREADS/1/" "$W/pmb.yaml" > "$W/pmb_$T.yaml"
    ( cd "$W" && OMP_NUM_THREADS=1 mpirun --allow-run-as-root --oversubscribe -np "$T" \
        /usr/bin/time -f "%M" -a -o "spall_$T.mem" "$SPALL" run "pmb_$T.yaml" \
        > "spall_$T.out" 2>&1 )
  else
    sed "s/THREADS/$T/" "$W/pmb.yaml" > "$W/pmb_$T.yaml"
    ( cd "$W" && /usr/bin/time -f "%M" -o "spall_$T.mem" "$SPALL" run "pmb_$T.yaml" > "spall_$T.out" 2>&1 )
  fi
  ( cd "$W" && OMP_NUM_THREADS=1 /usr/bin/time -f "%M" -o "lmp_$T.mem" mpirun --allow-run-as-root --oversubscribe -np $T lmp -in in.pmb -log "lmp_$T.log" > "lmp_$T.out" 2>&1 )
done
python3 - "$W" "$NX" "$NY" "$NZ" "$STEPS" <<'PY'
import sys, csv, re, glob
W, nx, ny, nz, steps = sys.argv[1], int(sys.argv[2]), int(sys.argv[3]), int(sys.argv[4]), int(sys.argv[5])
n = nx*ny*nz
res = {}
for T in (1, 2):
    out = open(f"{W}/spall_{T}.out").read()
    log = open(f"{W}/pmb_{T}/run.log").read() if glob.glob(f"{W}/pmb_{T}/run.log") else ""
    bonds = int(re.search(r"interactions: (\d+)", log).group(1))
    wall = float(re.search(r"([0-9.eE+-]+) s wall", out).group(1))
    rows = list(csv.DictReader(open(f"{W}/pmb_{T}/history.csv")))
    last = rows[-1]
    ux = float([v for k, v in last.items() if k.startswith("p_ux")][0])
    ds = float(last["damage_sum"])
    # one peak per process (ranks append theirs): the run's memory is their sum
    mem = sum(float(v) for v in open(f"{W}/spall_{T}.mem").read().split()) * 1024
    res[("spall", T)] = (wall, bonds * steps / wall, ds, ux, mem / n)
    ma = re.search(r"model arrays: (\d+) B, (\d+) B/particle \((\w+) families", log)
    if ma and T == 1:  # the model's own allocations (pd_model_bytes), not the process' RSS
        print(f"spall model arrays: {ma.group(2)} B/particle ({ma.group(3)} families)")
    lg = open(f"{W}/lmp_{T}.log").read()
    lw = float(re.search(r"Loop time of ([0-9.eE+-]+)", lg).group(1))
    th = re.findall(r"^\s*(\d+)\s+([-0-9.eE+]+)\s+([-0-9.eE+]+)\s*$", lg, re.M)
    st, lds, lux = th[-1]
    lmem = float(open(f"{W}/lmp_{T}.mem").read().split()[-1]) * 1024
    res[("lammps", T)] = (lw, bonds * steps / lw, float(lds), float(lux), lmem / n * T)
for k, v in res.items():
    print(f"{k[0]:<8} {k[1]:<8} {v[0]:12.3f} {v[1]:14.4g} {v[2]:14.6g} {v[3]:14.6g} {v[4]:12.0f}")
s1, l1 = res[("spall", 1)], res[("lammps", 1)]
print(f"damage_sum rel. diff {abs(s1[2]-l1[2])/max(abs(l1[2]),1e-30):.3%}, probe ux rel. diff {abs(s1[3]-l1[3])/max(abs(l1[3]),1e-30):.3%}")
for T in (1, 2):
    print(f"{T} thread(s): spall / lammps throughput = {res[('spall',T)][1]/res[('lammps',T)][1]:.2f}x")
PY
