#!/usr/bin/env bash
# Distributed checkpoints and restart at any rank count (issue 21, item 4):
# - a lattice fracture deck and a peridynamic (PMB) deck run to the end on 2
#   ranks with checkpoints; each checkpoint holds what the serial run's
#   checkpoint of the same step holds (h5diff), so it does not depend on the
#   rank count that wrote it;
# - restarts from the 2-rank (and 3-rank, 1-rank) checkpoints on 1, 2 and 3
#   ranks give history.csv, fragments.csv and fields.xdmf identical byte for
#   byte and every frame and later checkpoint identical under h5diff;
# - the same with particles migrating (a repartition every 20 steps);
# - SIGUSR1 sent to one rank only stops both ranks after the same step with
#   one checkpoint, one message and exit status 75; the run continues from it
#   on 3 ranks exactly;
# - a truncated checkpoint and one of another deck are refused under mpirun
#   with one line, exit 2, and no output directory.
# Usage: mpi_restart.sh SPALL SRC MPIEXEC
set -u
spall="$1"
mpiexec="$3"
export OMP_NUM_THREADS=1
# shellcheck source=lib/mpi_env.bash
source "$2/tests/cli/lib/mpi_env.bash"
# the decks of mpi_ranks.sh (tests/cli/decks), with checkpoints
sed 's/^output: {\(.*\)}$/output: {\1, checkpoint: {every_steps: 100, keep: 5}}/' \
    "$2/tests/cli/decks/mpi_frac.yaml" > frac.yaml
sed 's/^output: {\(.*\)}$/output: {\1, checkpoint: {every_steps: 150, keep: 5}}/' \
    "$2/tests/cli/decks/mpi_pd.yaml" > pd.yaml
grep -q "checkpoint: {every_steps: 100" frac.yaml && grep -q "checkpoint: {every_steps: 150" pd.yaml ||
    { echo "FAIL: the decks' output lines changed; cannot add checkpoints"; exit 1; }
fail=0
mpi() { # ranks args...
    local n="$1"
    shift
    timeout 120 "$mpiexec" --allow-run-as-root --oversubscribe -q -np "$n" "$spall" "$@"
}
# compare NAME REF OUT: the text files byte for byte, every frame and
# checkpoint OUT holds under h5diff (a restart does not rewrite the
# checkpoint it started from)
compare() {
    local f
    for f in history.csv fragments.csv fields.xdmf; do
        [ -e "$2/$f" ] || continue
        cmp -s "$2/$f" "$3/$f" || { echo "FAIL $1: $f differs"; fail=1; }
    done
    for f in "$2"/fields_*.h5; do
        h5diff -q "$f" "$3/$(basename "$f")" || { echo "FAIL $1: $(basename "$f") differs"; fail=1; }
    done
    for f in "$3"/checkpoint_*.h5; do
        h5diff -q "$2/$(basename "$f")" "$f" ||
            { echo "FAIL $1: $(basename "$f") differs"; fail=1; }
    done
}
run_ok() { # name command...
    local name="$1"
    shift
    "$@" --quiet --no-progress || { echo "FAIL $name: exit $?"; fail=1; }
}
# SPALL_MPI_RANK_COUNTS: the restart rank counts (ASan: 3 only, CMakeLists.txt)
counts="${SPALL_MPI_RANK_COUNTS:-1 2 3}"
full=$([ -z "${SPALL_MPI_RANK_COUNTS:-}" ] && echo 1 || echo 0)

# ---- the uninterrupted runs: serial and on 2 ranks ------------------------
run_ok "serial" "$spall" run frac.yaml -o serial
run_ok "2 ranks" mpi 2 run frac.yaml -o r2
[ -e r2/checkpoint_0000000100.h5 ] || { echo "FAIL 2 ranks wrote no checkpoint"; exit 1; }
compare "2 ranks vs serial (checkpoints in the serial layout)" serial r2
if [ "$full" = 1 ]; then
    run_ok "3 ranks" mpi 3 run frac.yaml -o r3
    compare "3 ranks vs serial" serial r3
fi
# bonds must break after the first checkpoint (step 100, row 12), else the
# restarts prove little
broken=$(awk -F, 'NR == 1 {for (k = 1; k <= NF; k++) if ($k == "bonds_broken") c = k}
                   NR == 12 {b = $c} END {print $c - b}' serial/history.csv)
if ! awk -v b="$broken" 'BEGIN {exit !(b > 50)}'; then
    echo "FAIL reference broke too few bonds after step 100 ($broken)"; fail=1
fi
ls -a r2 | grep -q '\.tmp$' && { echo "FAIL 2 ranks left a temporary checkpoint"; fail=1; }

# ---- restart on M ranks from checkpoints written by N ranks ---------------
for m in $counts; do
    run_ok "2 -> $m ranks" mpi "$m" run frac.yaml --restart r2/checkpoint_0000000100.h5 -o "from2_$m"
    compare "written by 2, restarted on $m ranks" serial "from2_$m"
done
if [ "$full" = 1 ]; then
    run_ok "1 -> 2 ranks" mpi 2 run frac.yaml --restart serial/checkpoint_0000000200.h5 -o from1_2
    compare "written by 1, restarted on 2 ranks" serial from1_2
    run_ok "3 -> 2 ranks" mpi 2 run frac.yaml --restart r3/checkpoint_0000000100.h5 -o from3_2
    compare "written by 3, restarted on 2 ranks" serial from3_2
    # continuing in the run's own directory (history.csv cut back, frames rewritten)
    cp -r r2 same && rm same/checkpoint_0000000200.h5 same/checkpoint_0000000300.h5
    run_ok "same directory, 3 ranks" mpi 3 run frac.yaml --restart same
    compare "same directory, 3 ranks" serial same
    grep -q '^restart_step: 100$' same/run.log || { echo "FAIL run.log: no restart section"; fail=1; }
fi

# ---- with migration: a Zoltan repartition every 20 steps ------------------
if [ "$full" = 1 ]; then
    { cat frac.yaml; echo "parallel: {rebalance_every: 20, imbalance_threshold: 1.0}"; } > mig.yaml
    run_ok "migrating, serial" "$spall" run mig.yaml -o mig_serial
    run_ok "migrating, 2 ranks" mpi 2 run mig.yaml -o mig2
    grep -q '^rebalances: [1-9][0-9]* ([1-9][0-9]* particles migrated)' mig2/run.log ||
        { echo "FAIL migrating: no particle migrated"; fail=1; }
    compare "migrating on 2 ranks vs serial" mig_serial mig2
    run_ok "migrating, 2 -> 3 ranks" mpi 3 run mig.yaml --restart mig2/checkpoint_0000000100.h5 -o mig3
    compare "migrating, written by 2, restarted on 3 ranks" mig_serial mig3
fi

# ---- peridynamics ---------------------------------------------------------
run_ok "pd serial" "$spall" run pd.yaml -o pd_serial
run_ok "pd 2 ranks" mpi 2 run pd.yaml -o pd2
compare "pd: 2 ranks vs serial" pd_serial pd2
for m in $counts; do
    [ "$m" = 2 ] && [ "$full" = 1 ] && continue # 1 and 3 cover both directions
    run_ok "pd 2 -> $m ranks" mpi "$m" run pd.yaml --restart pd2/checkpoint_0000000150.h5 -o "pd_from2_$m"
    compare "pd: written by 2, restarted on $m ranks" pd_serial "pd_from2_$m"
done

# ---- a signal to one rank: both stop after the same step ------------------
sed 's/steps: 300/steps: 200000/' frac.yaml > long.yaml
"$mpiexec" --allow-run-as-root --oversubscribe -q -np 2 "$spall" run long.yaml -o sig --quiet \
    --no-progress > sig.out 2>&1 &
launcher=$!
for _ in $(seq 600); do # until it is well under way (rows past step 150)
    [ -f sig/history.csv ] && [ "$(wc -l < sig/history.csv)" -gt 16 ] && break
    sleep 0.1
done
one=$(pgrep -P "$launcher" | tail -n 1)
if [ -z "$one" ]; then
    echo "FAIL signal: no rank process found"; fail=1
else
    kill -USR1 "$one"
fi
timeout 120 tail --pid="$launcher" -f /dev/null
wait "$launcher"
st=$?
[ "$st" = 75 ] || { echo "FAIL signal: exit $st, expected 75"; cat sig.out; fail=1; }
[ "$(grep -c 'stopped by signal 10' sig.out)" = 1 ] ||
    { echo "FAIL signal: not one message"; cat sig.out; fail=1; }
stop=$(sed -n 's/^status: interrupted by signal 10 at step \([0-9]*\),.*/\1/p' sig/run.log)
if [ -z "$stop" ] || [ ! -e "sig/checkpoint_$(printf %010d "$stop").h5" ]; then
    echo "FAIL signal: no checkpoint of the step it stopped at ('$stop')"; fail=1
else
    end=$((stop + 120))
    sed "s/steps: 300/steps: $end/" frac.yaml > cont.yaml
    run_ok "signal reference" mpi 2 run cont.yaml -o sig_ref
    run_ok "signal restart" mpi 3 run cont.yaml --restart sig -o sig_cont
    compare "continued on 3 ranks after a signal at step $stop" sig_ref sig_cont
fi

# ---- bad checkpoints under mpirun: one line, exit 2, nothing written ------
refused() { # name expected-text deck checkpoint
    local out st
    out=$(mpi 2 run "$3" --restart "$4" -o refused --quiet --no-progress 2>&1)
    st=$?
    [ "$st" = 2 ] || { echo "FAIL $1: exit $st, expected 2"; fail=1; }
    [ "$(printf '%s\n' "$out" | wc -l)" = 1 ] || { echo "FAIL $1: not one line: $out"; fail=1; }
    printf '%s' "$out" | grep -q -- "$2" || { echo "FAIL $1: message '$out'"; fail=1; }
    [ -e refused ] && { echo "FAIL $1: output directory created"; fail=1; rm -rf refused; }
}
good=r2/checkpoint_0000000200.h5
head -c $(($(stat -c %s $good) / 2)) $good > truncated.h5
refused "truncated" "not a readable HDF5 file" frac.yaml truncated.h5
sed 's/youngs_modulus: 1.0e9/youngs_modulus: 2.0e9/' frac.yaml > other.yaml
refused "other deck" "deck key 'materials.m.youngs_modulus' differs" other.yaml r2
[ $fail -eq 0 ] && echo "mpi_restart: checkpoints of 1, 2, 3 ranks identical; restarts on" \
    "$counts ranks, after a signal at step $stop, exact ($broken bonds broken after step 100)"
[ $fail -eq 0 ]
