#!/usr/bin/env bash
# Rank-count independence of models lifted from the issue-20 refusals:
#  - peridynamics `formulation: lps` (state-based: each force call sends the
#    owners' dilatations to their ghosts, a second halo after the positions)
#    on a pre-cracked plate under traction;
#  - the thermal lattice (conduction over bonds to ghosts, one halo of the
#    temperatures per conduction sub-step; heating, expansion, melting; a
#    fixed-temperature group) with two materials.
# Each runs without mpirun and on 2 and 3 ranks: history.csv, fragments.csv
# and fields.xdmf identical byte for byte, every frame under h5diff.
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
cp "$2/tests/cli/decks/mpi_thermal.yaml" thermal.yaml
for deck in lps thermal; do
    serial $deck
done
# the references must break and melt bonds, else the test proves little
lps_broken=$(col lps_serial/history.csv bonds_broken)
awk -v b="$lps_broken" 'BEGIN {exit !(b > 50)}' || { echo "FAIL lps broke $lps_broken bonds"; fail=1; }
melted=$(col thermal_serial/history.csv bonds_melted)
awk -v b="$melted" 'BEGIN {exit !(b > 10)}' || { echo "FAIL thermal melted $melted bonds"; fail=1; }
counts="${SPALL_MPI_RANK_COUNTS:-2 3}"
for n in $counts; do
    for deck in lps thermal; do
        ranks $deck "$n"
    done
done
# LPS state (weighted volume, dilatation, coefficients, influence) travels
# with migrating particles: forced rebalancing, still bitwise
rebalanced lps 3
# the thermal lattice cannot migrate yet: refused before any output
{ cat thermal.yaml; echo "parallel: {rebalance_every: 20}"; } > thermal_rb.yaml
OMP_NUM_THREADS=1 timeout 120 "$mpiexec" --allow-run-as-root --oversubscribe -q -np 2 \
    "$spall" run thermal_rb.yaml -o thermal_rb --quiet --no-progress 2> thermal_rb.err
rc=$?
[ $rc -eq 2 ] || { echo "FAIL thermal rebalanced: exit $rc, expected 2"; fail=1; }
[ "$(grep -c "thermal_rb.yaml:[0-9]*:[0-9]*: .*thermal lattice cannot migrate" thermal_rb.err)" -eq 1 ] ||
    { echo "FAIL thermal rebalanced: message"; cat thermal_rb.err; fail=1; }
[ ! -e thermal_rb ] || { echo "FAIL thermal rebalanced: output written"; fail=1; }
[ $fail -eq 0 ] && echo "mpi_models: identical on $counts ranks ($lps_broken lps bonds broken," \
    "$melted bonds melted)"
[ $fail -eq 0 ]
