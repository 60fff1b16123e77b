#!/usr/bin/env bash
# MPI scaling of `spall run` (issue 20): a 289 k-particle lattice plate (the
# `spall bench` lattice2d deck at 538 x 538 sites) and a peridynamic
# Kalthoff-Winkler plate (80 k particles, dx = 0.5 mm), each on 1 rank
# (no mpirun), 2 ranks x 1 thread and 1 rank x 2 threads.  Prints
# particle-steps/s of the time-step loop (run.log), the ratio to one rank,
# the halo seconds of rank 0 and whether history.csv is identical to the
# one-rank run.  Run it on an otherwise idle machine: on a loaded one the
# ratios measure the load, not spall.
#
#   bench/mpi_scaling.sh [SPALL] [MPIRUN]     (defaults: build/spall, mpirun)
#   STEPS=300 DAMPING=50 bench/mpi_scaling.sh  (more steps; damping on, so
#                                               that every step sums over all
#                                               particles)
set -euo pipefail
SPALL=${1:-build/spall}
MPIRUN=${2:-mpirun}
STEPS=${STEPS:-200}
DAMPING=${DAMPING:-0}
WORK=$(mktemp -d "${TMPDIR:-/tmp}/spall_mpi_scaling.XXXXXX")
trap 'rm -rf "$WORK"' EXIT
[ -x "$SPALL" ] || { echo "mpi_scaling.sh: no spall binary at $SPALL" >&2; exit 2; }

# lattice2d of bench/bench_lattice.c with n_side = 538: 289 444 sites
r0=1e-3
n=538
w=$(awk -v n=$n -v r=$r0 'BEGIN{printf "%.17g", (n - 0.5) * r}')
h=$(awk -v n=$n -v r=$r0 'BEGIN{printf "%.17g", ((n - 1) * sqrt(3) / 2 + 0.25) * r}')
cat > "$WORK/lattice.yaml" <<EOF
model: {type: lattice, law: linear}
materials:
  pmma: {density: 1140, youngs_modulus: 3.0e9, poisson_ratio: 0.3333333333333333,
         failure_strain: 0.02}
lattice: {type: triangular, spacing: $r0}
geometry:
  plate: {box: {min: [-0.00025, -0.00025], max: [$w, $h]}}
body: {geometry: plate, material: pmma}
groups:
  left: {box: {min: [-1, -1], max: [0.0005, 1]}}
boundary_conditions:
  - {group: left, type: velocity, components: [x], value: -1.0}
damping: $DAMPING
run: {steps: $STEPS, max_particles: 1e9}
output: {field_interval: 1.0, history_every: 50}
EOF

# examples/pd_kalthoff at dx = 0.5 mm: 401 x 201 sites
cat > "$WORK/pd.yaml" <<EOF
model: {type: peridynamics}
materials:
  steel: {density: 8000, youngs_modulus: 190.0e9, fracture_energy: 2.2e4}
lattice: {type: square, spacing: 0.5e-3, thickness: 1.0e-3}
geometry:
  plate: {box: {min: [-1.0e-5, -0.05001], max: [0.20001, 0.05001]}}
body: {geometry: plate, material: steel}
precracks:
  - {from: [-0.001, 0.0255], to: [0.0505, 0.0255]}
  - {from: [-0.001, -0.0255], to: [0.0505, -0.0255]}
groups:
  impact: {box: {min: [-1, -0.025], max: [0.0025, 0.025]}}
boundary_conditions:
  - {group: impact, type: velocity, components: [x], value: 32.0}
damping: $DAMPING
run: {steps: $STEPS}
output: {field_interval: 1.0, history_every: 50}
EOF

# value of a "key: value" line of run.log
logval() { awk -v k="$1:" '$1 == k {print $2; exit}' "$2"; }
halo() { awk '$1 == "halo_exchanges:" {gsub(/[(:]/, " "); print $5; exit}' "$1"; }

printf '%-8s %-12s %10s %6s %14s %7s %9s %s\n' case ranks_x_thr particles steps \
    particle_st/s ratio halo_s history
for c in lattice pd; do
    base=""
    for cfg in 1x1 2x1 1x2; do
        ranks=${cfg%x*} threads=${cfg#*x} out="$WORK/${c}_$cfg"
        if [ "$ranks" = 1 ]; then
            OMP_NUM_THREADS=$threads "$SPALL" run "$WORK/$c.yaml" -o "$out" --no-progress \
                > "$out.txt" 2>&1
        else
            OMP_NUM_THREADS=$threads "$MPIRUN" --allow-run-as-root --oversubscribe -np "$ranks" "$SPALL" run \
                "$WORK/$c.yaml" -o "$out" --no-progress > "$out.txt" 2>&1
        fi || { echo "mpi_scaling.sh: $c on $cfg failed:" >&2; cat "$out.txt" >&2; exit 1; }
        log="$out/run.log"
        ps=$(logval particle_steps_per_s "$log")
        [ -z "$base" ] && base=$ps
        ratio=$(awk -v a="$ps" -v b="$base" 'BEGIN{printf "%.3f", a / b}')
        same=$(cmp -s "$out/history.csv" "$WORK/${c}_1x1/history.csv" && echo identical \
               || echo DIFFERS)
        printf '%-8s %-12s %10s %6s %14s %7s %9s %s\n' "$c" "$ranks x $threads" \
            "$(logval particles "$log")" "$(logval steps_done "$log")" "$ps" "$ratio" \
            "$(halo "$log")" "$same"
    done
done
echo "(ratio: particle-steps/s against 1 x 1 of the same case; halo_s: rank 0's wall"
echo " seconds in the ghost exchange; history: history.csv against the 1 x 1 run)"
