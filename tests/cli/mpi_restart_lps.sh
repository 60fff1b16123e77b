#!/usr/bin/env bash
# Bitwise restart of peridynamics `formulation: lps` and `eps` (default
# surface correction) when bonds break in the first force call after the
# restart: with break_order immediate such a half-bond's energy t e / 2 is
# booked at the dilatation of the last force call, which the checkpoint
# holds (pd.lps_theta, src/models/peridynamics/pd_restart.c; before it the
# restart priced it at theta = 0 and history.csv differed from line 13).
# The pre-cracked plate of mpi_models.sh (lps) and mpi_pd_more.sh (eps),
# history every step, checkpoints every 100 steps; bonds break in step 101.
# Each deck: the serial reference; restarted serially and on 2 ranks from
# its step-100 checkpoint; run on 2 ranks (outputs and checkpoints as the
# serial ones) and continued on 3 ranks from that run's step-100
# checkpoint: history.csv, fragments.csv and fields.xdmf byte for byte,
# every frame and later checkpoint under h5diff.  A checkpoint without
# pd.lps_theta (one written before it was saved) is refused in one line
# naming it.
# Usage: mpi_restart_lps.sh SPALL SRC MPIEXEC
set -u
spall="$1"
mpiexec="$3"
# shellcheck source=lib/rank_compare.bash
source "$2/tests/cli/lib/rank_compare.bash"
deck="$2/tests/cli/decks/mpi_pd.yaml"
for f in lps eps; do
    [ $f = eps ] && ys="yield_stress: 12.0e6, " || ys=""
    sed "s/^model: {type: peridynamics}\$/model: {type: peridynamics, formulation: $f}/;
         s/youngs_modulus: 72.0e9, fracture_energy/youngs_modulus: 72.0e9, poisson_ratio: 0.22, ${ys}fracture_energy/;
         s/^output: {field_every: 150, history_every: 10}\$/output: {field_every: 150, history_every: 1, checkpoint: {every_steps: 100, keep: 5}}/" \
        "$deck" > $f.yaml
    grep -q "formulation: $f}" $f.yaml && grep -q "poisson_ratio: 0.22, ${ys}fracture" $f.yaml &&
        grep -q "history_every: 1, checkpoint: {every_steps: 100" $f.yaml ||
        { echo "FAIL: cannot make $f.yaml from tests/cli/decks/mpi_pd.yaml"; exit 1; }
done
broken() { # file step: bonds_broken of that step's row
    awk -F, -v s="$2" 'NR == 1 {for (k = 1; k <= NF; k++) if ($k == "bonds_broken") c = k}
                       $1 == s {print $c}' "$1"
}
for f in lps eps; do
    serial $f
    # the restart must meet bonds breaking in its first force call
    b100=$(broken ${f}_serial/history.csv 100)
    b101=$(broken ${f}_serial/history.csv 101)
    awk -v a="$b100" -v b="$b101" 'BEGIN {exit !(b > a && a > 0)}' ||
        { echo "FAIL $f: bonds broken $b100 at step 100, $b101 at 101"; fail=1; }
    OMP_NUM_THREADS=1 timeout 120 "$spall" run $f.yaml --restart ${f}_serial/checkpoint_0000000100.h5 \
        -o ${f}_rs1 --quiet --no-progress || { echo "FAIL $f restarted serially: exit $?"; fail=1; }
    same_as_serial ${f}_serial ${f}_rs1 "$f, restarted serially at step 100"
    checkpoints_same ${f}_serial ${f}_rs1 "$f, restarted serially"
    mpi 2 run $f.yaml --restart ${f}_serial/checkpoint_0000000100.h5 -o ${f}_rs2 ||
        { echo "FAIL $f restarted on 2 ranks: exit $?"; fail=1; }
    same_as_serial ${f}_serial ${f}_rs2 "$f, serial checkpoint restarted on 2 ranks"
    checkpoints_same ${f}_serial ${f}_rs2 "$f, restarted on 2 ranks"
    written_on_2 $f
    mpi 3 run $f.yaml --restart ${f}2/checkpoint_0000000100.h5 -o ${f}_cont3 ||
        { echo "FAIL $f restarted on 3 ranks: exit $?"; fail=1; }
    same_as_serial ${f}_serial ${f}_cont3 "$f, written by 2 ranks, restarted on 3"
    checkpoints_same ${f}_serial ${f}_cont3 "$f, restarted on 3"
    grep -q '^restart_step: 100$' ${f}_cont3/run.log || { echo "FAIL $f: run.log: no restart"; fail=1; }
done
# a checkpoint without the dilatation (as written before it was saved): the
# step-100 one copied without /state/pd.lps_theta
old=lps_old.h5
rm -f $old
h5ls -r lps_serial/checkpoint_0000000100.h5 | awk '$2 == "Dataset" {print $1}' |
    while read -r ds; do
        [ "$ds" = /state/pd.lps_theta ] && continue
        h5copy -p -i lps_serial/checkpoint_0000000100.h5 -o $old -s "$ds" -d "$ds" ||
            echo "FAIL: h5copy $ds"
    done
h5ls -r $old | grep -q "^/state/pd.bond_state " && ! h5ls -r $old | grep -q "pd.lps_theta" ||
    { echo "FAIL: cannot make a checkpoint without pd.lps_theta"; exit 1; }
rm -rf lps_old
"$spall" run lps.yaml --restart $old -o lps_old --quiet --no-progress >stdout.txt 2>stderr.txt
rc=$?
if [ $rc -ne 2 ] || [ -e lps_old ] || [ "$(wc -l < stderr.txt)" -ne 1 ] ||
    ! grep -q "state 'pd.lps_theta' is missing: .*rerun from the start" stderr.txt; then
    echo "FAIL old checkpoint: exit $rc (expected 2)"; cat stderr.txt; fail=1
fi
[ $fail -eq 0 ] && echo "mpi_restart_lps: lps and eps restarted at step 100 (bonds broken" \
    "$(broken lps_serial/history.csv 100) -> $(broken lps_serial/history.csv 101)," \
    "$(broken eps_serial/history.csv 100) -> $(broken eps_serial/history.csv 101))" \
    "serially, on 2 ranks and on 3 from 2: identical; a checkpoint without pd.lps_theta refused"
[ $fail -eq 0 ]
