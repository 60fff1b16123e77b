#!/usr/bin/env bash
# Rank-count independence of the models on spatial ghosts (issue 22,
# docs/parallel.md "Spatial ghosts in the step"):
#  - a macro-particle rod pulled at both ends, with pairwise Langevin forces
#    (random stream keyed by global ids) and pair plasticity, a small skin
#    so that the neighbour lists (and the ghosts) are rebuilt during the run;
#    on 2 and 4 ranks, and with a forced repartition every 20 steps (particles
#    migrate with their pair state) on 2 and 3 ranks;
#  - particle contact between bodies and between the fragments of a lattice
#    (a reduced flyer-plate spall: the flyer strikes the target, bonds break)
#    on 2 and 3 ranks, and with a forced repartition every 20 steps on 3;
# each against the run without mpirun: history.csv, fragments.csv and
# fields.xdmf identical byte for byte, every frame under h5diff.
# Usage: mpi_macro.sh SPALL SRC MPIEXEC
set -u
spall="$1"
mpiexec="$3"
# shellcheck source=lib/rank_compare.bash
source "$2/tests/cli/lib/rank_compare.bash"
cat > rod.yaml <<'YAML'
title: macro rod, Langevin forces and plasticity, rank-count independence
model: {type: macroparticle, skin: 0.03, damping: pairwise, mu: 1.0e-3, temperature: 300,
        eta_cg: 30}
materials:
  al: {density: 2700, atomic_mass_u: 26.98, cohesive_energy_ev: 3.39, exponents: [4, 9],
       debye_temperature: 428, yield_strain: 0.0015, hardening: 0.1}
lattice: {type: fcc, spacing: 1.2374368670764582e-3}
geometry:
  rod: {cylinder: {base: [0, 0, -1.0e-9], top: [0, 0, 0.014000001], radius: 0.004000001}}
body: {geometry: rod, material: al}
groups:
  bottom: {box: {min: [-1, -1, -1], max: [1, 1, 3.0e-4]}}
  top: {box: {min: [-1, -1, 0.0137], max: [1, 1, 1]}}
boundary_conditions:
  - {group: bottom, type: velocity, components: [z], value: -10}
  - {group: top, type: velocity, components: [z], value: 10}
run: {steps: 500}
output: {field_every: 250, history_every: 20,
         fields: [position, velocity, stress, plastic_slip, strain_energy, centro_symmetry, id]}
YAML
cat > spall.yaml <<'YAML'
title: flyer-plate spall with particle contact, rank-count independence
model: {type: lattice, law: linear}
materials:
  metal: {density: 8900, youngs_modulus: 163.24e9,
          poisson_ratio: 0.3333333333333333, failure_strain: 0.02}
lattice: {type: triangular, spacing: 0.0002}
geometry:
  target: {box: {min: [-1.0e-5, -1.0e-5], max: [0.01601, 0.0030]}}
  flyer: {box: {min: [0.00399, 0.0030], max: [0.01201, 0.0040]}}
bodies:
  - {geometry: target, material: metal}
  - {geometry: flyer, material: metal}
contact: {distance: 0.0002, stiffness: 32648000}
groups: {flyer: flyer}
initial_velocity: [{group: flyer, value: [0, -260.0]}]
run: {end_time: 4.0e-6}
output: {field_interval: 2.0e-6, history_every: 20,
         fields: [position, velocity, displacement, fracture_density, fragment_id, id]}
YAML
serial rod
serial spall
# the reference must yield and rebuild its lists, else the test proves little
pairs=$(col rod_serial/history.csv plastic_pairs)
builds=$(col rod_serial/history.csv neighbor_builds)
awk -v p="$pairs" -v b="$builds" 'BEGIN {exit !(p > 100 && b >= 3)}' ||
    { echo "FAIL rod: $pairs plastic pairs, $builds list builds"; fail=1; }
broken=$(col spall_serial/history.csv bonds_broken)
awk -v b="$broken" 'BEGIN {exit !(b > 100)}' || { echo "FAIL spall broke $broken bonds"; fail=1; }
counts="${SPALL_MPI_RANK_COUNTS:-2 4}"
for n in $counts; do
    ranks rod "$n"
done
for n in ${SPALL_MPI_RANK_COUNTS:-2 3}; do
    ranks spall "$n"
done
rebalanced rod 2
rebalanced rod 3
# contact lists follow a repartition (rebuilt from the build positions
# that travel with the particles: the serial lists)
rebalanced spall 3
[ $fail -eq 0 ] && echo "mpi_macro: identical on $counts ranks and rebalanced (rod: $pairs plastic" \
    "pairs, $builds list builds; spall: $broken bonds broken)"
[ $fail -eq 0 ]
