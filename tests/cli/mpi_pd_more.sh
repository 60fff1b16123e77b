#!/usr/bin/env bash
# Rank-count independence of the bond models lifted from the issue-20
# refusals after the first increments (docs/parallel.md):
#  - peridynamics `formulation: eps` (elastic-plastic state-based: each force
#    call sends the scalar force state t_ji of every half-bond whose partner
#    is a ghost on another rank, the per-bond halo core/parallel/bhalo.h);
#    yield stress below the applied traction, so many particles flow;
#  - adaptive dynamic relaxation (`quasi_static: adr`: its damping
#    coefficient is a ratio of two exact sums over all ranks);
# both on the pre-cracked plate of tests/cli/decks/mpi_pd.yaml;
#  - the lattice's angular springs (`angular: on`, nu = 0.25: the forces of
#    angles centred on a ghost come from its owner through the per-bond halo
#    core/parallel/bhalo.h) on the pre-cracked plate of
#    tests/cli/decks/mpi_frac.yaml;
#  - an orthotropic PDLM lamina (fibers at 30 deg) with mixed-mode matrix
#    failure (a ghost's factor on the matrix critical stretch comes with the
#    halo) pulled apart across a pre-crack;
#  - the same lamina with `matrix_crack: fiber_plane` (a stretch-broken
#    matrix bond breaks its zigzag twins, named by gid through the halo when
#    the twin's other end is another rank's; pd_plane.c);
# each without mpirun and on 2 ranks, and on 3 with particles migrating (a
# repartition every 20 steps):
# history.csv, fields.xdmf byte for byte, every frame under h5diff.
# Usage: mpi_pd_more.sh SPALL SRC MPIEXEC
set -u
spall="$1"
mpiexec="$3"
# shellcheck source=lib/rank_compare.bash
source "$2/tests/cli/lib/rank_compare.bash"
deck="$2/tests/cli/decks/mpi_pd.yaml"
sed 's/^model: {type: peridynamics}$/model: {type: peridynamics, formulation: eps}/;
     s/youngs_modulus: 72.0e9, fracture_energy/youngs_modulus: 72.0e9, poisson_ratio: 0.22, yield_stress: 12.0e6, fracture_energy/;
     s/^output: {field_every: 150, history_every: 10}$/output: {field_every: 150, history_every: 10, fields: [position, damage, plastic_strain]}/' \
    "$deck" > eps.yaml
sed 's/^model: {type: peridynamics}$/model: {type: peridynamics, quasi_static: adr}/' "$deck" > adr.yaml
sed 's/^model: {type: lattice, law: linear}$/model: {type: lattice, law: linear, angular: on}/;
     s/poisson_ratio: 0.3333333333333333/poisson_ratio: 0.25/' "$2/tests/cli/decks/mpi_frac.yaml" > ang.yaml
grep -q "formulation: eps" eps.yaml && grep -q "yield_stress: 12.0e6" eps.yaml &&
    grep -q "plastic_strain" eps.yaml && grep -q "quasi_static: adr" adr.yaml &&
    grep -q "angular: on" ang.yaml && grep -q "poisson_ratio: 0.25" ang.yaml ||
    { echo "FAIL: cannot make eps.yaml, adr.yaml, ang.yaml from tests/cli/decks"; exit 1; }
cat > lam.yaml <<'YAML'
title: PDLM lamina, mixed-mode matrix failure
model: {type: peridynamics, variant: pdlm}
materials:
  t700: {density: 1550, fiber_modulus: 130.0e9, transverse_modulus: 8.5e9, shear_modulus: 4.5e9,
         major_poisson_ratio: 0.3, matrix_fracture_energy: 300, mode2_fracture_energy: 800,
         fiber_fracture_energy: 60.0e3, fiber_angle: 30}
lattice: {type: triangular, spacing: 1.0e-3, thickness: 1.0e-4, angle: 30}
geometry:
  plate: {box: {min: [-1.0e-5, -1.0e-5], max: [0.04001, 0.02001]}}
body: {geometry: plate, material: t700}
precracks:
  - {from: [-0.001, 0.0105], to: [0.015, 0.0105]}
groups:
  top: {box: {min: [-1, 0.0185], max: [1, 1]}}
  bottom: {box: {min: [-1, -1], max: [1, 0.0015]}}
boundary_conditions:
  - {group: top, type: velocity, components: [y], value: 6.0}
  - {group: bottom, type: velocity, components: [y], value: -6.0}
run: {steps: 400}
output: {field_every: 200, history_every: 10}
YAML
sed 's/^model: {type: peridynamics, variant: pdlm}$/model: {type: peridynamics, variant: pdlm, matrix_crack: fiber_plane}/' \
    lam.yaml > lamfp.yaml
grep -q "matrix_crack: fiber_plane" lamfp.yaml || { echo "FAIL: cannot make lamfp.yaml"; exit 1; }
for d in eps adr ang lam lamfp; do
    serial $d
done
# the references must break bonds, flow plastically and damp, else the test proves little
eps_broken=$(col eps_serial/history.csv bonds_broken)
awk -v b="$eps_broken" 'BEGIN {exit !(b > 50)}' || { echo "FAIL eps broke $eps_broken bonds"; fail=1; }
h5dump -y -w 0 -d /plastic_strain -o eps_plastic.txt eps_serial/fields_000002.h5 > /dev/null
yielded=$(tr ', ' '\n\n' < eps_plastic.txt | awk 'NF && $1 > 0 {n++} END {print n + 0}')
[ "$yielded" -gt 20 ] || { echo "FAIL eps: $yielded particles yielded"; fail=1; }
adr_c=$(col adr_serial/history.csv adr_damping)
awk -v c="$adr_c" 'BEGIN {exit !(c > 0)}' || { echo "FAIL adr: damping $adr_c"; fail=1; }
ang_broken=$(col ang_serial/history.csv bonds_broken)
awk -v b="$ang_broken" 'BEGIN {exit !(b > 50)}' || { echo "FAIL ang broke $ang_broken bonds"; fail=1; }
lam_broken=$(col lam_serial/history.csv bonds_broken)
awk -v b="$lam_broken" 'BEGIN {exit !(b > 50)}' || { echo "FAIL lam broke $lam_broken bonds"; fail=1; }
# the twins break too: more bonds than the plain stretch rule (195 against 118)
fp_broken=$(col lamfp_serial/history.csv bonds_broken)
awk -v b="$fp_broken" -v l="$lam_broken" 'BEGIN {exit !(b > l + 30)}' ||
    { echo "FAIL lamfp broke $fp_broken bonds (plain rule: $lam_broken)"; fail=1; }
counts="${SPALL_MPI_RANK_COUNTS:-2}"
for n in $counts; do
    for d in eps adr ang lam lamfp; do
        ranks $d "$n"
    done
done
# ADR builds each rank's window only (the distributed set-up)
grep -q "^setup: distributed" adr2/run.log 2>/dev/null || [ ! -d adr2 ] ||
    { echo "FAIL adr on 2 ranks: not the distributed set-up"; grep "^setup" adr2/run.log; fail=1; }
# the plastic extension and force states per half-bond, ADR's last two
# forces per particle, the angles per half-bond, the mode-mix factors and
# the twin slots travel with migrating particles: still bitwise
for d in eps adr ang lam lamfp; do
    rebalanced $d 3
done
[ $fail -eq 0 ] && echo "mpi_pd_more: identical on $counts ranks (eps: $eps_broken bonds broken," \
    "$yielded particles yielded; adr: final damping $adr_c 1/s; angular: $ang_broken," \
    "lamina: $lam_broken bonds broken, $fp_broken with fiber_plane; rebalanced on 3)"
[ $fail -eq 0 ]
