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
sed -n '/^cat > rod.yaml/,/^YAML$/p' "$2/tests/cli/mpi_macro.sh" | sed '1d;$d' |
    sed 's/^output: {\(.*\)$/output: {checkpoint: {every_steps: 200, keep: 5}, \1/' > rod.yaml
grep -q "checkpoint: {every_steps: 200" rod.yaml && grep -q "temperature: 300" rod.yaml ||
    { echo "FAIL: cannot take the rod deck of tests/cli/mpi_macro.sh"; exit 1; }
mpi() { # ranks args...
    local n="$1"
    shift
    OMP_NUM_THREADS=1 timeout 120 "$mpiexec" --allow-run-as-root --oversubscribe -q -np "$n" \
        "$spall" "$@" --quiet --no-progress
}
checkpoints_same() { # ref out what: every checkpoint OUT holds, under h5diff
    local f
    for f in "$2"/checkpoint_*.h5; do
        [ -e "$f" ] || { echo "FAIL $3: no checkpoint"; fail=1; return; }
        h5diff -q "$1/$(basename "$f")" "$f" || { echo "FAIL $3: $(basename "$f") differs"; fail=1; }
    done
}
serial rod
ls rod_serial/checkpoint_0000000200.h5 rod_serial/checkpoint_0000000400.h5 > /dev/null ||
    { echo "FAIL: the serial run wrote no checkpoints"; exit 1; }
mpi 2 run rod.yaml -o rod2 || { echo "FAIL rod on 2 ranks: exit $?"; exit 1; }
same_as_serial rod_serial rod2 "rod, 2 ranks"
checkpoints_same rod_serial rod2 "rod, 2 ranks (checkpoints in the serial layout)"
ck=rod2/checkpoint_0000000200.h5
OMP_NUM_THREADS=1 timeout 120 "$spall" run rod.yaml --restart $ck -o rod_cont1 --quiet \
    --no-progress || { echo "FAIL rod restarted without mpirun: exit $?"; fail=1; }
same_as_serial rod_serial rod_cont1 "rod, written by 2 ranks, restarted on 1"
checkpoints_same rod_serial rod_cont1 "rod, restarted on 1"
for n in ${SPALL_MPI_RANK_COUNTS:-3 4}; do
    mpi "$n" run rod.yaml --restart $ck -o rod_cont"$n" ||
        { echo "FAIL rod restarted on $n ranks: exit $?"; fail=1; continue; }
    same_as_serial rod_serial rod_cont"$n" "rod, written by 2 ranks, restarted on $n"
    checkpoints_same rod_serial rod_cont"$n" "rod, restarted on $n"
    grep -q '^restart_step: 200$' rod_cont"$n"/run.log ||
        { echo "FAIL rod on $n ranks: run.log: no restart"; fail=1; }
done
# the state after step 200 must matter: more plastic pairs and a list rebuild
awk -F, 'NR == 1 {for (k = 1; k <= NF; k++) {if ($k == "plastic_pairs") p = k
                                             if ($k == "neighbor_builds") b = k}; next}
         $1 == 200 {p0 = $p; b0 = $b} END {exit !($p > p0 && p0 > 100 && $b > b0)}' \
    rod_serial/history.csv || { echo "FAIL rod: no plasticity or rebuild after step 200"; fail=1; }
# refusals on 2 ranks: one line, exit 2, the run directory untouched
refused() { # what dir deck expected-substring
    local before after rc
    before=$(cd "$2" && ls -l --time-style=+%s.%N && md5sum -- *)
    mpi 2 run "$3" --restart "$2" 2> refused.err
    rc=$?
    after=$(cd "$2" && ls -l --time-style=+%s.%N && md5sum -- *)
    [ $rc -eq 2 ] || { echo "FAIL $1: exit $rc, expected 2"; fail=1; }
    [ "$(wc -l < refused.err)" -eq 1 ] && grep -q -- "$4" refused.err ||
        { echo "FAIL $1: message"; cat refused.err; fail=1; }
    [ "$before" = "$after" ] || { echo "FAIL $1: $2 changed"; fail=1; }
}
mkdir cut
cp rod2/history.csv rod2/fields_000000.h5 rod2/fields.xdmf cut/
head -c 20000 rod2/checkpoint_0000000400.h5 > cut/checkpoint_0000000400.h5
refused "truncated checkpoint" cut rod.yaml "not a readable HDF5 file"
sed 's/temperature: 300/temperature: 310/' rod.yaml > rod_warm.yaml
refused "another deck" rod2 rod_warm.yaml "deck key 'model.temperature' differs"
[ $fail -eq 0 ] && echo "mpi_restart_macro: 2-rank checkpoints as serial; restarts on 1" \
    "${SPALL_MPI_RANK_COUNTS:-3 4} ranks exact; refusals"
[ $fail -eq 0 ]
