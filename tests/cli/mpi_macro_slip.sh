#!/usr/bin/env bash
# The macro-particles' slip_vector and slip_normal output fields on a
# distributed run (issue 22): a macro-particle cylinder whose halves are
# thrown apart sideways, so that neighbours across the middle slip past each
# other by more than the 0.25 r0 threshold; without mpirun and on 2 and 3
# ranks: every frame (slip fields included) under h5diff and history.csv
# byte for byte.  The reference neighbours of each owned particle come from
# a ghost set built on the reference positions (macro_slip_par).
# Usage: mpi_macro_slip.sh SPALL SRC MPIEXEC
set -u
spall="$1"
mpiexec="$3"
# shellcheck source=lib/rank_compare.bash
source "$2/tests/cli/lib/rank_compare.bash"
cat > shear.yaml <<'YAML'
title: macro-particle cylinder sheared apart, slip fields on any rank count
model: {type: macroparticle, skin: 0.03}
materials:
  al: {density: 2700, atomic_mass_u: 26.98, cohesive_energy_ev: 3.39, exponents: [4, 9],
       debye_temperature: 428}
lattice: {type: fcc, spacing: 1.2374368670764582e-3}
geometry:
  rod: {cylinder: {base: [0, 0, -1.0e-9], top: [0, 0, 0.010000001], radius: 0.004000001}}
body: {geometry: rod, material: al}
groups:
  upper: {box: {min: [-1, -1, 0.005], max: [1, 1, 1]}}
  lower: {box: {min: [-1, -1, -1], max: [1, 1, 0.005]}}
initial_velocity: [{group: upper, value: [150, 0, 0]}, {group: lower, value: [-150, 0, 0]}]
run: {steps: 600}
output: {field_every: 300, history_every: 20, fields: [slip_vector, slip_normal, position, id]}
YAML
serial shear
# the reference must have slipped particles, else the test proves little
slipped=$(h5dump -y -d /slip_vector shear_serial/fields_000002.h5 |
    sed -n '/DATA {/,/}/p' | tr -s ' ,' '\n' | grep -E '^-?[0-9]' | paste - - - |
    awk '$1 != 0 || $2 != 0 || $3 != 0' | wc -l)
[ "$slipped" -gt 100 ] || { echo "FAIL: $slipped particles slipped in the serial run"; fail=1; }
for n in ${SPALL_MPI_RANK_COUNTS:-2 3}; do
    ranks shear "$n"
done
[ $fail -eq 0 ] && echo "mpi_macro_slip: slip fields of $slipped slipped particles identical on" \
    "${SPALL_MPI_RANK_COUNTS:-2 3} ranks"
[ $fail -eq 0 ]
