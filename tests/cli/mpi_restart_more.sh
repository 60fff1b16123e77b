#!/usr/bin/env bash
# Distributed checkpoint/restart of what tests/cli/mpi_restart.sh leaves out
# (issue 21): the thermal lattice (temperatures, heat, conductances and the
# melted count, checkpointed by global ids) and rigid impactors with penalty
# contact (a sphere with friction shattering a plate) and with no-slip
# contact (a falling tup on two penalty rollers, gravity).  Each deck runs
# without mpirun (the reference) and on 2 ranks with checkpoints (each
# checkpoint identical to the serial one under h5diff), then continues on 3
# ranks from the 2-rank checkpoint: history.csv, fragments.csv, fields.xdmf
# and bodies.xdmf byte for byte, every frame and later checkpoint under h5diff.
# Usage: mpi_restart_more.sh SPALL SRC MPIEXEC
set -u
spall="$1"
mpiexec="$3"
# shellcheck source=lib/rank_compare.bash
source "$2/tests/cli/lib/rank_compare.bash"
# the decks of mpi_models.sh and mpi_impact.sh (tests/cli/decks), with checkpoints
for d in thermal:thermal penalty:shatter noslip:tup; do
    sed 's/^output: {\(.*\)}$/output: {\1, checkpoint: {every_steps: 100, keep: 5}}/' \
        "$2/tests/cli/decks/mpi_${d#*:}.yaml" > "${d%%:*}.yaml"
    grep -q "checkpoint: {every_steps: 100" "${d%%:*}.yaml" ||
        { echo "FAIL: cannot add checkpoints to tests/cli/decks/mpi_${d#*:}.yaml"; exit 1; }
done
for d in thermal penalty noslip; do
    serial $d
    mpi 2 run $d.yaml -o ${d}2 || { echo "FAIL $d on 2 ranks: exit $?"; fail=1; continue; }
    same_as_serial ${d}_serial ${d}2 "$d, 2 ranks"
    checkpoints_same ${d}_serial ${d}2 "$d, 2 ranks (checkpoints in the serial layout)"
    mpi 3 run $d.yaml --restart ${d}2/checkpoint_0000000200.h5 -o ${d}_cont3 ||
        { echo "FAIL $d restarted on 3 ranks: exit $?"; fail=1; continue; }
    same_as_serial ${d}_serial ${d}_cont3 "$d, written by 2 ranks, restarted on 3"
    checkpoints_same ${d}_serial ${d}_cont3 "$d, restarted on 3"
    grep -q '^restart_step: 200$' ${d}_cont3/run.log || { echo "FAIL $d: run.log: no restart"; fail=1; }
done
# what happens after the restart must matter: melting, and contacts
melted=$(col thermal_serial/history.csv bonds_melted)
melted200=$(awk -F, 'NR == 1 {for (k = 1; k <= NF; k++) if ($k == "bonds_melted") c = k}
                     $1 == 200 {print $c}' thermal_serial/history.csv)
awk -v a="$melted200" -v b="$melted" 'BEGIN {exit !(b > a + 10)}' ||
    { echo "FAIL thermal: melted $melted200 bonds by step 200, $melted at the end"; fail=1; }
for c in penalty:ball_contacts noslip:tup_contacts; do
    awk -F, -v n="${c#*:}" 'NR == 1 {for (k = 1; k <= NF; k++) if ($k == n) c = k; next}
                            $1 > 200 && $c > 0 {hit = 1} END {exit !hit}' "${c%%:*}_serial/history.csv" ||
        { echo "FAIL ${c%%:*}: no contact after the restart step"; fail=1; }
done
[ $fail -eq 0 ] && echo "mpi_restart_more: thermal ($melted200 -> $melted bonds melted), penalty" \
    "and no-slip impactors: 2-rank checkpoints as serial, restarts on 3 ranks exact"
[ $fail -eq 0 ]
