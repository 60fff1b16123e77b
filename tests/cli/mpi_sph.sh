#!/usr/bin/env bash
# Rank-count independence of total-Lagrangian SPH (issue 22 item 1): a
# reduced 3D copper Taylor bar (tests/cli/decks/mpi_tl.yaml: leapfrog,
# Balsara's switch, hourglass control, the rigid wall; plastic flow at the
# impact face) without mpirun and on 2 and 4 ranks, and the same bar with
# the predictor-corrector, the adaptive step as a global minimum and a
# probe on 3 ranks: history.csv, fields.xdmf and bodies.xdmf byte for byte,
# every frame under h5diff.  What SPH cannot do distributed yet (the
# updated-Lagrangian form, reference updates) is refused in one line, exit 2.
# Usage: mpi_sph.sh SPALL SRC MPIEXEC
set -u
spall="$1"
mpiexec="$3"
# shellcheck source=lib/rank_compare.bash
source "$2/tests/cli/lib/rank_compare.bash"
cp "$2/tests/cli/decks/mpi_tl.yaml" tl.yaml
# the predictor-corrector (the model's default) without Balsara's switch
sed '/time_integration: leapfrog/d; /viscosity_switch: balsara/d' tl.yaml > pc.yaml
printf "probes: [{name: tip, position: [0.0004, 0.0004, 0.0092]}]\n" >> pc.yaml
grep -q "time_integration" pc.yaml && { echo "FAIL: cannot make pc.yaml"; exit 1; }
counts="${SPALL_MPI_RANK_COUNTS:-2 4}"
serial tl
for n in $counts; do
    ranks tl "$n"
done
# the bar must deform plastically, or the test shows little
ep=$(col tl_serial/history.csv max_plastic_strain)
awk -v e="$ep" 'BEGIN {exit !(e > 0.1)}' || { echo "FAIL: max plastic strain $ep <= 0.1"; fail=1; }
serial pc
ranks pc 3
refused() { # name deck expected-substring
    rm -rf out
    timeout 120 "$mpiexec" --allow-run-as-root --oversubscribe -q -np 2 "$spall" run "$2" -o out \
        >stdout.txt 2>stderr.txt
    local rc=$?
    if [ $rc -ne 2 ] || [ -e out ] || [ "$(wc -l < stderr.txt)" -ne 1 ] ||
        ! grep -q -- "$3" stderr.txt; then
        echo "FAIL $1: exit $rc (expected 2)"; cat stderr.txt; fail=1
    fi
}
sed 's/formulation: total/formulation: updated/' tl.yaml > ul.yaml
refused "updated Lagrangian" ul.yaml "updated-Lagrangian formulation"
sed 's/^  hourglass: 1.0$/  hourglass: 1.0\n  reference_update: {distortion: 1.2}/' tl.yaml > reref.yaml
grep -q reference_update reref.yaml || { echo "FAIL: cannot make reref.yaml"; exit 1; }
refused "reference update" reref.yaml "reference updates"
[ $fail -eq 0 ] && echo "mpi_sph: OK"
exit $fail
