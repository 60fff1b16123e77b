#!/usr/bin/env bash
# Distributed checkpoints of a macro-particle run (issue 21 item 4, issue 22
# item 2): the rod of mpi_macro.sh (pairwise Langevin forces, pair
# plasticity, neighbour lists rebuilt during the run) with a checkpoint
# every 200 steps.
#  - written on 2 ranks, every checkpoint is the serial run's under h5diff
#    (the pair lists with their plastic state by global id);
#  - restarted from the 2-rank checkpoint of step 200 without mpirun and on
#    3 and 4 ranks: history.csv and fields.xdmf byte for byte, every frame
#    and later checkpoint under h5diff, as the uninterrupted serial run;
#  - a truncated checkpoint and another deck (another temperature) are
#    refused on 2 ranks with one line, exit 2, the run directory untouched.
# Usage: mpi_restart_macro.sh SPALL SRC MPIEXEC
set -u
spall="$1"
mpiexec="$3"
# shellcheck source=lib/rank_compare.bash
source "$2/tests/cli/lib/rank_compare.bash"
deck_from "$2/tests/cli/mpi_macro.sh" rod 200
grep -q "temperature: 300" rod.yaml || { echo "FAIL: the rod deck's temperature changed"; exit 1; }
serial rod
ls rod_serial/checkpoint_0000000200.h5 rod_serial/checkpoint_0000000400.h5 > /dev/null ||
    { echo "FAIL: the serial run wrote no checkpoints"; exit 1; }
written_on_2 rod
for n in 1 ${SPALL_MPI_RANK_COUNTS:-3 4}; do
    continued rod rod2/checkpoint_0000000200.h5 "$n"
done
# the state after step 200 must matter: more plastic pairs and a list rebuild
awk -F, 'NR == 1 {for (k = 1; k <= NF; k++) {if ($k == "plastic_pairs") p = k
                                             if ($k == "neighbor_builds") b = k}; next}
         $1 == 200 {p0 = $p; b0 = $b} END {exit !($p > p0 && p0 > 100 && $b > b0)}' \
    rod_serial/history.csv || { echo "FAIL rod: no plasticity or rebuild after step 200"; fail=1; }
# refusals on 2 ranks: one line, exit 2, the run directory untouched
mkdir cut
cp rod2/history.csv rod2/fields_000000.h5 rod2/fields.xdmf cut/
head -c 20000 rod2/checkpoint_0000000400.h5 > cut/checkpoint_0000000400.h5
refused_restart "truncated checkpoint" cut rod.yaml "not a readable HDF5 file"
sed 's/temperature: 300/temperature: 310/' rod.yaml > rod_warm.yaml
refused_restart "another deck" rod2 rod_warm.yaml "deck key 'model.temperature' differs"
[ $fail -eq 0 ] && echo "mpi_restart_macro: 2-rank checkpoints as serial; restarts on 1" \
    "${SPALL_MPI_RANK_COUNTS:-3 4} ranks exact; refusals"
[ $fail -eq 0 ]
