#!/usr/bin/env bash
# Distributed checkpoints of a run with particle contact (issue 21 item 4,
# issue 22 item 3): the reduced flyer-plate spall of mpi_macro.sh (a lattice
# flyer striking a lattice target, contact between the bodies and between
# fragments) with a checkpoint every 100 steps.
#  - written on 2 ranks, every checkpoint is the serial run's under h5diff
#    (the candidate lists by global id, the positions they were built at);
#  - restarted from the 2-rank checkpoint of step 100 without mpirun and on
#    3 ranks: history.csv, fragments.csv, fields.xdmf byte for byte, every
#    frame and later checkpoint under h5diff, as the uninterrupted serial run;
#  - with a repartition every 20 steps (contact lists follow the migrating
#    particles) on 3 ranks, and that run's checkpoint continued on 2 ranks,
#    still rebalancing: the same bytes (the checkpoints differ from the
#    serial ones only in the deck's `parallel` key).
# Usage: mpi_restart_contact.sh SPALL SRC MPIEXEC
set -u
spall="$1"
mpiexec="$3"
# shellcheck source=lib/rank_compare.bash
source "$2/tests/cli/lib/rank_compare.bash"
deck_from "$2/tests/cli/mpi_macro.sh" spall 100
grep -q "^contact:" spall.yaml || { echo "FAIL: the spall deck has no contact"; exit 1; }
{ cat spall.yaml; echo "parallel: {rebalance_every: 20, imbalance_threshold: 1.0}"; } > spall_rb.yaml
serial spall
written_on_2 spall
for n in 1 3; do
    continued spall spall2/checkpoint_0000000100.h5 "$n"
done
# rebalanced: the deck differs by its parallel key (/deck and so /checksum)
skip="--exclude-path /deck --exclude-path /checksum"
mpi 3 run spall_rb.yaml -o spall_rb3 || { echo "FAIL rebalanced on 3: exit $?"; fail=1; }
same_as_serial spall_serial spall_rb3 "contact rebalanced, 3 ranks"
checkpoints_same spall_serial spall_rb3 "contact rebalanced, 3 ranks" "$skip"
continued spall_rb spall_rb3/checkpoint_0000000100.h5 2 "$skip"
moved=$(sed -n 's/^rebalances: [0-9]* (\([0-9]*\) particles migrated).*/\1/p' spall_rb3/run.log)
[ "${moved:-0}" -gt 0 ] || { echo "FAIL contact rebalanced: nothing migrated"; fail=1; }
# contacts and fracture must go on after the checkpoint
awk -F, 'NR == 1 {for (k = 1; k <= NF; k++) if ($k == "bonds_broken") b = k; next}
         $1 == 100 {b0 = $b} END {exit !($b > b0 + 100)}' spall_serial/history.csv ||
    { echo "FAIL contact: fewer than 100 bonds broken after step 100"; fail=1; }
[ $fail -eq 0 ] && echo "mpi_restart_contact: 2-rank checkpoints as serial; restarts on 1 and 3" \
    "ranks exact; rebalanced on 3 ($moved particles migrated) and continued on 2 exact"
[ $fail -eq 0 ]
