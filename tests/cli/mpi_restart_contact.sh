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
sed -n '/^cat > spall.yaml/,/^YAML$/p' "$2/tests/cli/mpi_macro.sh" | sed '1d;$d' |
    sed 's/^output: {\(.*\)$/output: {checkpoint: {every_steps: 100, keep: 5}, \1/' > spall.yaml
grep -q "checkpoint: {every_steps: 100" spall.yaml && grep -q "^contact:" spall.yaml ||
    { echo "FAIL: cannot take the contact deck of tests/cli/mpi_macro.sh"; exit 1; }
{ cat spall.yaml; echo "parallel: {rebalance_every: 20, imbalance_threshold: 1.0}"; } > spall_rb.yaml
mpi() { # ranks args...
    local n="$1"
    shift
    OMP_NUM_THREADS=1 timeout 120 "$mpiexec" --allow-run-as-root --oversubscribe -q -np "$n" \
        "$spall" "$@" --quiet --no-progress
}
checkpoints_same() { # ref out what [h5diff options]: every checkpoint OUT holds
    local f
    for f in "$2"/checkpoint_*.h5; do
        [ -e "$f" ] || { echo "FAIL $3: no checkpoint"; fail=1; return; }
        h5diff -q ${4:-} "$1/$(basename "$f")" "$f" ||
            { echo "FAIL $3: $(basename "$f") differs"; fail=1; }
    done
}
serial spall
mpi 2 run spall.yaml -o spall2 || { echo "FAIL contact on 2 ranks: exit $?"; exit 1; }
same_as_serial spall_serial spall2 "contact, 2 ranks"
checkpoints_same spall_serial spall2 "contact, 2 ranks (checkpoints in the serial layout)"
ck=spall2/checkpoint_0000000100.h5
OMP_NUM_THREADS=1 timeout 120 "$spall" run spall.yaml --restart $ck -o spall_cont1 --quiet \
    --no-progress || { echo "FAIL contact restarted without mpirun: exit $?"; fail=1; }
same_as_serial spall_serial spall_cont1 "contact, written by 2 ranks, restarted on 1"
checkpoints_same spall_serial spall_cont1 "contact, restarted on 1"
mpi 3 run spall.yaml --restart $ck -o spall_cont3 || { echo "FAIL restart on 3: exit $?"; fail=1; }
same_as_serial spall_serial spall_cont3 "contact, written by 2 ranks, restarted on 3"
checkpoints_same spall_serial spall_cont3 "contact, restarted on 3"
# rebalanced: the deck differs by its parallel key (/deck and so /checksum)
skip="--exclude-path /deck --exclude-path /checksum"
mpi 3 run spall_rb.yaml -o spall_rb3 || { echo "FAIL rebalanced on 3: exit $?"; fail=1; }
same_as_serial spall_serial spall_rb3 "contact rebalanced, 3 ranks"
checkpoints_same spall_serial spall_rb3 "contact rebalanced, 3 ranks" "$skip"
mpi 2 run spall_rb.yaml --restart spall_rb3/checkpoint_0000000100.h5 -o spall_rb_cont2 ||
    { echo "FAIL rebalanced restart on 2: exit $?"; fail=1; }
same_as_serial spall_serial spall_rb_cont2 "contact rebalanced on 3, restarted on 2"
checkpoints_same spall_serial spall_rb_cont2 "contact rebalanced, restarted on 2" "$skip"
moved=$(sed -n 's/^rebalances: [0-9]* (\([0-9]*\) particles migrated).*/\1/p' spall_rb3/run.log)
[ "${moved:-0}" -gt 0 ] || { echo "FAIL contact rebalanced: nothing migrated"; fail=1; }
# contacts and fracture must go on after the checkpoint
awk -F, 'NR == 1 {for (k = 1; k <= NF; k++) if ($k == "bonds_broken") b = k; next}
         $1 == 100 {b0 = $b} END {exit !($b > b0 + 100)}' spall_serial/history.csv ||
    { echo "FAIL contact: fewer than 100 bonds broken after step 100"; fail=1; }
[ $fail -eq 0 ] && echo "mpi_restart_contact: 2-rank checkpoints as serial; restarts on 1 and 3" \
    "ranks exact; rebalanced on 3 ($moved particles migrated) and continued on 2 exact"
[ $fail -eq 0 ]
