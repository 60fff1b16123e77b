#!/usr/bin/env bash
# Rank-count independence of models lifted from the issue-20 refusals:
#  - peridynamics `formulation: lps` (state-based: each force call sends the
#    owners' dilatations to their ghosts, a second halo after the positions)
#    on a pre-cracked plate under traction (and with partial_volume_rule
#    cell on 2 ranks);
#  - the thermal lattice (conduction over bonds to ghosts, one halo of the
#    temperatures per conduction sub-step; heating, expansion, melting; a
#    fixed-temperature group) with two materials, and with one material and
#    an E(T) table built by the distributed set-up;
#  - the same LPS plate with `surface_correction: position_aware`
#    (pd_lps_pals.c: influences of both halves per half-bond, fixed by the
#    distributed set-up's windows; theta and P of the owners to the ghosts
#    each force call), also restarted on 2 ranks from a serial checkpoint,
#    and the 3D pre-cracked block of mpi_setup.sh in it (the coordinate-
#    strain constraint set of 3D);
# Each runs without mpirun and on 2 and 3 ranks, and on 3 ranks rebalanced
# every 20 steps: history.csv, fragments.csv and fields.xdmf identical byte
# for byte, every frame under h5diff.
# Usage: mpi_models.sh SPALL SRC MPIEXEC
set -u
spall="$1"
mpiexec="$3"
# shellcheck source=lib/rank_compare.bash
source "$2/tests/cli/lib/rank_compare.bash"
# the PMB deck of mpi_ranks.sh (tests/cli/decks) in the LPS formulation, nu = 0.22
sed 's/^model: {type: peridynamics}$/model: {type: peridynamics, formulation: lps}/;
     s/youngs_modulus: 72.0e9, fracture_energy/youngs_modulus: 72.0e9, poisson_ratio: 0.22, fracture_energy/' \
    "$2/tests/cli/decks/mpi_pd.yaml" > lps.yaml
grep -q "formulation: lps" lps.yaml && grep -q "poisson_ratio: 0.22" lps.yaml ||
    { echo "FAIL: cannot make lps.yaml from tests/cli/decks/mpi_pd.yaml"; exit 1; }
# the same with partial_volume_rule cell: families and halos reach delta + the
# cell's circumradius (pd_cellvol.c)
sed 's/formulation: lps}/formulation: lps, partial_volume_rule: cell}/' lps.yaml > lpscell.yaml
grep -q "partial_volume_rule: cell" lpscell.yaml ||
    { echo "FAIL: cannot make lpscell.yaml"; exit 1; }
# the position-aware LPS (pd_lps_pals.c), with checkpoints for the restart below
sed 's/formulation: lps}/formulation: lps, surface_correction: position_aware}/;
     s/^output: {\(.*\)$/output: {checkpoint: {every_steps: 100, keep: 5}, \1/' lps.yaml > lpspa.yaml
grep -q "surface_correction: position_aware" lpspa.yaml && grep -q "every_steps: 100" lpspa.yaml ||
    { echo "FAIL: cannot make lpspa.yaml"; exit 1; }
# 3D position_aware: the pre-cracked sc block of mpi_setup.sh in LPS
sed 's/^model: {type: peridynamics}$/model: {type: peridynamics, formulation: lps, surface_correction: position_aware}/;
     s/youngs_modulus: 72.0e9, fracture_energy/youngs_modulus: 72.0e9, poisson_ratio: 0.22, fracture_energy/' \
    "$2/tests/cli/decks/mpi_setup_pd3.yaml" > lpspa3.yaml
grep -q "surface_correction: position_aware" lpspa3.yaml && grep -q "poisson_ratio: 0.22" lpspa3.yaml ||
    { echo "FAIL: cannot make lpspa3.yaml"; exit 1; }
cp "$2/tests/cli/decks/mpi_thermal.yaml" thermal.yaml
for deck in lps lpscell lpspa lpspa3 thermal; do
    serial $deck
done
ranks lpscell 2
# the references must break and melt bonds, else the test proves little
lps_broken=$(col lps_serial/history.csv bonds_broken)
awk -v b="$lps_broken" 'BEGIN {exit !(b > 50)}' || { echo "FAIL lps broke $lps_broken bonds"; fail=1; }
pa_broken=$(col lpspa_serial/history.csv bonds_broken)
awk -v b="$pa_broken" 'BEGIN {exit !(b > 50)}' || { echo "FAIL lpspa broke $pa_broken bonds"; fail=1; }
melted=$(col thermal_serial/history.csv bonds_melted)
awk -v b="$melted" 'BEGIN {exit !(b > 10)}' || { echo "FAIL thermal melted $melted bonds"; fail=1; }
counts="${SPALL_MPI_RANK_COUNTS:-2 3}"
for n in $counts; do
    for deck in lps lpspa lpspa3 thermal; do
        ranks $deck "$n"
    done
done
# LPS state (weighted volume, dilatation, coefficients, influence) travels
# with migrating particles: forced rebalancing, still bitwise
rebalanced lps 3
rebalanced lpspa 3
# position_aware restarted on 2 ranks from the serial run's first checkpoint:
# the influences are rebuilt from the deck, the history is the serial one
OMP_NUM_THREADS=1 timeout 120 "$mpiexec" --allow-run-as-root --oversubscribe -q -np 2 \
    "$spall" run lpspa.yaml --restart lpspa_serial/checkpoint_0000000100.h5 -o lpspa_rs2 \
    --quiet --no-progress || { echo "FAIL lpspa restart on 2 ranks: exit $?"; fail=1; }
cmp -s lpspa_serial/history.csv lpspa_rs2/history.csv ||
    { echo "FAIL lpspa restart on 2 ranks: history.csv differs"; fail=1; }
# the thermal lattice's state (heating, heat capacity, conductances,
# reference rest lengths) travels with migrating particles: bitwise
rebalanced thermal 3
# one body (no inclusions): the distributed set-up builds each rank's window
# (run.log says so), with an E(T) table (its per-bond factors migrate too)
grep -v "^inclusions:\|material: pyrite, count" thermal.yaml |
    sed 's/^body: {geometry: plate, material: calcite}$/body: {geometry: plate, material: pyrite}/;
         s/melting_temperature: 800,/melting_temperature: 800, youngs_modulus_table: [[293, 290.0e9], [700, 150.0e9]],/' \
    > thermal1.yaml
grep -q "material: pyrite}" thermal1.yaml && grep -q "youngs_modulus_table" thermal1.yaml &&
    ! grep -q "inclusions" thermal1.yaml || { echo "FAIL: cannot make thermal1.yaml"; exit 1; }
serial thermal1
ranks thermal1 2
grep -q "^setup: distributed" thermal12/run.log ||
    { echo "FAIL thermal1 on 2 ranks: not the distributed set-up"; fail=1; }
rebalanced thermal1 3
melted1=$(col thermal1_serial/history.csv bonds_melted)
awk -v b="$melted1" 'BEGIN {exit !(b > 10)}' || { echo "FAIL thermal1 melted $melted1 bonds"; fail=1; }
[ $fail -eq 0 ] && echo "mpi_models: identical on $counts ranks ($lps_broken lps bonds broken," \
    "$pa_broken position_aware, restarted on 2," \
    "$melted and $melted1 bonds melted; rebalanced on 3)"
[ $fail -eq 0 ]
