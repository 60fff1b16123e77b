#!/usr/bin/env bash
# Set-up peak memory of the PD race problem of bench/pd_vs_lammps.sh (3D PMB
# block, SC lattice, delta = 3.015 dx, ends pulled), run by hand, not part of
# the suite:
#     bench/setup_mem.sh [--lattice2d] SPALL [SPALL ...] [-- NX NY NZ STEPS]
# (--lattice2d: the `spall bench lattice2d` plate instead, NX x NX sites,
# default 1000; 36 x 24 x 24 is the race, 48 x 32 x 32 `pd3d`)
# For each binary: peak RSS of the whole process (/usr/bin/time %M) per
# particle, the same for a 4 x 4 x 4 block of the same deck (what the process
# takes whatever the problem: code, libraries, MPI/HDF5 start-up), the
# difference per particle (what the problem itself costs at its peak), and
# the model's own arrays after set-up (run.log `model arrays`, pd_model_bytes).
# Memory does not depend on the machine's load.  docs/performance.md "Set-up
# peak memory" records the numbers.
set -euo pipefail
BINS=(); CASE=pd
[ "${1:-}" = "--lattice2d" ] && { CASE=lattice2d; shift; }
while [ $# -gt 0 ] && [ "$1" != "--" ]; do BINS+=("$(realpath "$1")"); shift; done
[ "${1:-}" = "--" ] && shift
if [ $CASE = pd ]; then NX=${1:-36}; NY=${2:-24}; NZ=${3:-24}; else NX=${1:-1000}; NY=$NX; NZ=1; fi
STEPS=${4:-20}
[ ${#BINS[@]} -gt 0 ] || { echo "usage: $0 SPALL [SPALL ...] [-- NX NY NZ STEPS]" >&2; exit 2; }
W=$(mktemp -d /tmp/setup_mem.XXXX)
deck() { # nx ny nz steps -> yaml on stdout
  python3 - $CASE "$@" <<'PY'
import sys, math
case = sys.argv[1]
nx, ny, nz, steps = (int(a) for a in sys.argv[2:6])
dx = 1.0e-3
if case == "lattice2d": # bench/bench_lattice.c's plate
    w, h = (nx - 0.5) * dx, ((nx - 1) * math.sqrt(3.0) / 2.0 + 0.25) * dx
    print(f"""title: lattice2d plate (spall bench), set-up memory
model: {{type: lattice, law: linear}}
materials:
  pmma: {{density: 1140, youngs_modulus: 3.0e9, poisson_ratio: 0.3333333333333333,
         failure_strain: 0.02}}
lattice: {{type: triangular, spacing: {dx!r}}}
geometry:
  plate: {{box: {{min: [{-0.25*dx!r}, {-0.25*dx!r}], max: [{w!r}, {h!r}]}}}}
body: {{geometry: plate, material: pmma}}
groups:
  left: {{box: {{min: [-1, -1], max: [{0.5*dx!r}, 1]}}}}
boundary_conditions:
  - {{group: left, type: velocity, components: [x], value: -1.0}}
run: {{steps: {steps}, max_particles: 1e9, threads: 1}}
output: {{history_every: {steps}, field_interval: 1.0}}""")
    sys.exit(0)
print(f"""title: PMB race problem (bench/pd_vs_lammps.sh), set-up memory
model: {{type: peridynamics, horizon_factor: 3.015, partial_volume_rule: lammps, break_order: next_step}}
materials:
  glass: {{density: 2440, bulk_modulus: 48.0e9, critical_stretch: 0.002}}
lattice: {{type: sc, spacing: {dx}}}
geometry:
  block: {{box: {{min: [-0.0005, -0.0005, -0.0005], max: [{(nx-0.5)*dx}, {(ny-0.5)*dx}, {(nz-0.5)*dx}]}}}}
body: {{geometry: block, material: glass}}
groups:
  left: {{box: {{min: [-1, -1, -1], max: [0.0015, 1, 1]}}}}
  right: {{box: {{min: [{(nx-2.5)*dx}, -1, -1], max: [1, 1, 1]}}}}
boundary_conditions:
  - {{group: left, type: velocity, components: [x], value: -5.0}}
  - {{group: right, type: velocity, components: [x], value: 5.0}}
run: {{dt: 5.0e-8, dt_override: true, steps: {steps}, threads: 1}}
output: {{history_every: {steps}, field_interval: 1.0}}""")
PY
}
deck "$NX" "$NY" "$NZ" "$STEPS" > "$W/race.yaml"
if [ $CASE = pd ]; then deck 4 4 4 "$STEPS" > "$W/tiny.yaml"; else deck 10 10 1 "$STEPS" > "$W/tiny.yaml"; fi
echo "work dir: $W; $CASE $NX x $NY x $NZ, $STEPS steps"
printf "%-40s %14s %14s %16s %18s\n" binary peak_B/part floor_MB peak-floor_B/part model_arrays_B/part
k=0
for B in "${BINS[@]}"; do
  k=$((k + 1))
  ( cd "$W" && /usr/bin/time -f "%M" -o "race_$k.mem" "$B" run race.yaml -o "race_$k" > "race_$k.out" 2>&1 )
  ( cd "$W" && /usr/bin/time -f "%M" -o "tiny_$k.mem" "$B" run tiny.yaml -o "tiny_$k" > "tiny_$k.out" 2>&1 )
  python3 - "$W" "$k" "$B" <<'PY'
import sys, re
W, k, b = sys.argv[1], sys.argv[2], sys.argv[3]
peak = float(open(f"{W}/race_{k}.mem").read().split()[-1]) * 1024
floor = float(open(f"{W}/tiny_{k}.mem").read().split()[-1]) * 1024
log = open(f"{W}/race_{k}/run.log").read()
n = int(re.search(r"particles: (\d+)", log).group(1))
ma = re.search(r"(?:model arrays|bonds): (\d+) B, (\d+) B/particle", log)
print(f"{b[-40:]:<40} {peak/n:14.0f} {floor/2**20:14.1f} {(peak-floor)/n:16.0f} {ma.group(2) if ma else '?':>18}")
PY
done
