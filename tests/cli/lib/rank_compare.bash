# Shared by the MPI rank tests tests/cli/mpi_*.sh (sourced, not a test):
# the MPI environment of the suite's rank tests, a scratch directory, and
# the comparison of a distributed run's output (and checkpoints) with the
# serial reference, the launch on N ranks, decks taken from other scripts.
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
mpi() { # ranks args...: spall on that many ranks, quiet
    local n="$1"
    shift
    OMP_NUM_THREADS=1 timeout 120 "$mpiexec" --allow-run-as-root --oversubscribe -q -np "$n" \
        "$spall" "$@" --quiet --no-progress
}
checkpoints_same() { # ref out what [h5diff options]: every checkpoint OUT holds, under h5diff
    local f
    for f in "$2"/checkpoint_*.h5; do
        [ -e "$f" ] || { echo "FAIL $3: no checkpoint"; fail=1; return; }
        # shellcheck disable=SC2086 # the options are words
        h5diff -q ${4:-} "$1/$(basename "$f")" "$f" ||
            { echo "FAIL $3: $(basename "$f") differs"; fail=1; }
    done
}
deck_from() { # script deck checkpoint-every: DECK.yaml of the heredoc `cat > DECK.yaml`
    # in tests/cli/SCRIPT, with a checkpoint every N steps added to its output map
    sed -n "/^cat > $2.yaml/,/^YAML\$/p" "$1" | sed '1d;$d' |
        sed "s/^output: {\(.*\)\$/output: {checkpoint: {every_steps: $3, keep: 5}, \1/" > "$2.yaml"
    grep -q "checkpoint: {every_steps: $3" "$2.yaml" ||
        { echo "FAIL: cannot take deck $2 of $1"; exit 1; }
}
written_on_2() { # deck: DECK on 2 ranks into DECK2, outputs and checkpoints as DECK_serial's
    mpi 2 run "$1.yaml" -o "${1}2" || { echo "FAIL $1 on 2 ranks: exit $?"; exit 1; }
    same_as_serial "$1_serial" "${1}2" "$1, 2 ranks"
    checkpoints_same "$1_serial" "${1}2" "$1, 2 ranks (checkpoints in the serial layout)"
}
continued() { # deck checkpoint n [h5diff options]: DECK continued from CHECKPOINT on n
    # ranks (1: without mpirun) into DECK_contN; outputs and later checkpoints as DECK_serial's
    local out="$1_cont$3" what="$1 continued from $2 on $3 ranks"
    if [ "$3" -eq 1 ]; then
        OMP_NUM_THREADS=1 timeout 120 "$spall" run "$1.yaml" --restart "$2" -o "$out" --quiet \
            --no-progress
    else
        mpi "$3" run "$1.yaml" --restart "$2" -o "$out"
    fi || { echo "FAIL $what: exit $?"; fail=1; return; }
    same_as_serial "${1%_rb}_serial" "$out" "$what"
    checkpoints_same "${1%_rb}_serial" "$out" "$what" "${4:-}"
    grep -q "^restart_from: .*$(basename "$2")\$" "$out/run.log" ||
        { echo "FAIL $what: run.log: no restart"; fail=1; }
}
refused_restart() { # what dir deck expected-substring: a restart from dir on 2 ranks is
    # refused in one line, exit 2, dir untouched (byte for byte, times included)
    local before after rc
    before=$(cd "$2" && ls -l --time-style=+%s.%N && md5sum -- *)
    mpi 2 run "$3" --restart "$2" 2> refused.err
    rc=$?
    after=$(cd "$2" && ls -l --time-style=+%s.%N && md5sum -- *)
    [ $rc -eq 2 ] || { echo "FAIL $1: exit $rc, expected 2"; fail=1; }
    if [ "$(wc -l < refused.err)" -ne 1 ] || ! grep -q -- "$4" refused.err; then
        echo "FAIL $1: message"; cat refused.err; fail=1
    fi
    [ "$before" = "$after" ] || { echo "FAIL $1: $2 changed"; fail=1; }
}
