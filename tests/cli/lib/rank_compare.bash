# Shared by tests/cli/mpi_impact.sh and mpi_models.sh (sourced, not a test):
# the MPI environment of the suite's rank tests, a scratch directory, and
# the comparison of a distributed run's output with the serial reference.
# Expects $spall and $mpiexec; sets $fail (0) and changes into the scratch
# directory.
# shellcheck source=mpi_env.bash
source "$(dirname "${BASH_SOURCE[0]}")/mpi_env.bash"
fail=0
col() { # file column-name: the last row's value
    awk -F, -v n="$2" 'NR == 1 {for (k = 1; k <= NF; k++) if ($k == n) c = k} END {print $c}' "$1"
}
serial() { # deck: its reference run, without mpirun, into DECK_serial
    OMP_NUM_THREADS=1 timeout 120 "$spall" run "$1.yaml" -o "$1_serial" --quiet --no-progress ||
        { echo "FAIL serial $1 run"; exit 1; }
}
same_as_serial() { # ref out what: the outputs byte for byte, every frame under h5diff
    local f
    for f in history.csv fragments.csv fields.xdmf bodies.xdmf; do
        [ -e "$1/$f" ] || continue
        cmp -s "$1/$f" "$2/$f" || { echo "FAIL $3: $f differs"; fail=1; }
    done
    for f in "$1"/fields_*.h5; do
        h5diff -q "$f" "$2/$(basename "$f")" || { echo "FAIL $3: $(basename "$f") differs"; fail=1; }
    done
}
rebalanced() { # deck n: ranks() with rebalancing forced every 20 steps (deck
    # DECK_rb.yaml, output DECK_rbN compared with DECK_serial); particles must move
    { cat "$1.yaml"; echo "parallel: {rebalance_every: 20, imbalance_threshold: 1.0}"; } > "$1_rb.yaml"
    OMP_NUM_THREADS=1 timeout 120 "$mpiexec" --allow-run-as-root --oversubscribe -q -np "$2" \
        "$spall" run "$1_rb.yaml" -o "$1_rb$2" --quiet --no-progress ||
        { echo "FAIL $1 rebalanced on $2 ranks: exit $?"; fail=1; return; }
    local out="$1_rb$2" moved
    same_as_serial "$1_serial" "$out" "$1 rebalanced, $2 ranks"
    moved=$(sed -n 's/^rebalances: [0-9]* (\([0-9]*\) particles migrated).*/\1/p' "$out/run.log")
    [ "${moved:-0}" -gt 0 ] || { echo "FAIL $1 rebalanced, $2 ranks: nothing migrated"; fail=1; }
}
ranks() { # deck n: run on n ranks into DECKn and compare with DECK_serial
    OMP_NUM_THREADS=1 timeout 120 "$mpiexec" --allow-run-as-root --oversubscribe -q -np "$2" \
        "$spall" run "$1.yaml" -o "$1$2" --quiet --no-progress ||
        { echo "FAIL $1 on $2 ranks: exit $?"; fail=1; return; }
    same_as_serial "$1_serial" "$1$2" "$1, $2 ranks"
}
refused() { # name deck expected-substring: 2 ranks refuse the deck in one line, exit 2,
    # no output directory
    rm -rf out
    timeout 120 "$mpiexec" --allow-run-as-root --oversubscribe -q -np 2 "$spall" run "$2" -o out \
        >stdout.txt 2>stderr.txt
    local rc=$?
    if [ $rc -ne 2 ] || [ -e out ] || [ "$(wc -l < stderr.txt)" -ne 1 ] ||
        ! grep -q -- "$3" stderr.txt; then
        echo "FAIL $1: exit $rc (expected 2)"; cat stderr.txt; fail=1
    fi
}
