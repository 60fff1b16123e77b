#!/usr/bin/env bash
# Migration and rebalancing (issue 20 item 2, issue 22 item 4): the lattice
# fracture deck and the peridynamic (PMB) deck of mpi_ranks.sh with a forced
# Zoltan repartition every 20 steps (imbalance_threshold 1.0) on 2 and 3
# ranks give the bytes of one rank: history.csv, fragments.csv, fields.xdmf
# cmp-equal and every frame h5diff-equal, while run.log shows particles
# migrated (more than zero) and balance.csv one imbalance row per history
# row.  A bad `parallel:` key is refused with file:line:column, exit 2.
# Usage: mpi_migrate.sh SPALL SRC MPIEXEC
set -u
spall="$1"
src="$2"
mpiexec="$3"
# shellcheck source=lib/rank_compare.bash
source "$src/tests/cli/lib/rank_compare.bash"
# the decks of mpi_ranks.sh (tests/cli/decks), with forced rebalancing
for d in frac pd; do
    { cat "$src/tests/cli/decks/mpi_$d.yaml"
      echo "parallel: {rebalance_every: 20, imbalance_threshold: 1.0}"; } > "$d.yaml"
done
fail=0
for d in frac pd; do
    OMP_NUM_THREADS=1 timeout 120 "$spall" run "$d.yaml" -o "${d}_1" --quiet --no-progress ||
        { echo "FAIL one-rank $d run"; exit 1; }
done
compare() { # name out-dir reference-dir (tests/cli/lib/rank_compare.bash)
    same_as_serial "$3" "$2" "$1"
}
# SPALL_MPI_RANK_COUNTS: the ASan build runs 3 ranks only (CMakeLists.txt)
counts="${SPALL_MPI_RANK_COUNTS:-2 3}"
summary=""
for n in $counts; do
    for d in frac pd; do
        out="${d}_$n"
        OMP_NUM_THREADS=1 timeout 180 "$mpiexec" --allow-run-as-root --oversubscribe -q -np "$n" \
            "$spall" run "$d.yaml" -o "$out" --quiet --no-progress ||
            { echo "FAIL $d on $n ranks: exit $?"; fail=1; continue; }
        compare "$d, $n ranks" "$out" "${d}_1"
        moved=$(sed -n 's/^rebalances: \([0-9]*\) (\([0-9]*\) particles migrated).*/\2/p' "$out/run.log")
        nreb=$(sed -n 's/^rebalances: \([0-9]*\) .*/\1/p' "$out/run.log")
        if [ -z "$moved" ] || [ "$moved" -eq 0 ]; then
            echo "FAIL $d, $n ranks: no particle migrated (run.log: '${moved}')"; fail=1
        fi
        [ "$nreb" = 15 ] || { echo "FAIL $d, $n ranks: $nreb rebalances, expected 15 (every 20 of 300 steps)"; fail=1; }
        [ "$(grep -c '^rebalance: step [0-9]*, ' "$out/run.log")" = 15 ] ||
            { echo "FAIL $d, $n ranks: run.log lists $(grep -c '^rebalance: ' "$out/run.log") rebalances"; fail=1; }
        # one imbalance row per history row, each >= 1
        rows=$(($(wc -l < "$out/history.csv") - 1))
        brows=$(($(wc -l < "$out/balance.csv") - 1))
        [ "$rows" = "$brows" ] || { echo "FAIL $d, $n ranks: $brows balance rows, $rows history rows"; fail=1; }
        awk -F, 'NR > 1 && !($3 >= 1.0) {bad = 1} END {exit bad}' "$out/balance.csv" ||
            { echo "FAIL $d, $n ranks: imbalance below 1 in balance.csv"; fail=1; }
        summary="$summary $d/$n:$moved"
    done
done
# the reference must break bonds, else equality proves little about the
# broken-bond state that migrates
for d in frac pd; do
    b=$(awk -F, 'NR == 1 {for (k = 1; k <= NF; k++) if ($k == "bonds_broken") c = k} END {print $c}' \
        "${d}_1/history.csv")
    awk -v b="$b" 'BEGIN {exit !(b > 50)}' || { echo "FAIL $d reference broke too few bonds ($b)"; fail=1; }
done
# deck errors: a bad key and a bad value under parallel:
sed 's/^parallel: .*/parallel: {rebalance_every: 20, imbalance_treshold: 1.0}/' frac.yaml > bad1.yaml
sed 's/^parallel: .*/parallel: {rebalance_every: 20, imbalance_threshold: 0.5}/' frac.yaml > bad2.yaml
for b in bad1 bad2; do
    "$spall" run "$b.yaml" -o "$b" --quiet --no-progress > "$b.out" 2>&1
    rc=$?
    [ "$rc" = 2 ] || { echo "FAIL $b: exit $rc, expected 2"; fail=1; }
    grep -q "$b.yaml:[0-9]*:[0-9]*" "$b.out" || { echo "FAIL $b: no file:line:column: $(cat "$b.out")"; fail=1; }
    [ ! -e "$b" ] || { echo "FAIL $b: output directory created"; fail=1; }
done
[ $fail -eq 0 ] && echo "mpi_migrate: forced rebalancing bitwise equal to one rank (deck/ranks:migrated$summary)"
[ $fail -eq 0 ]
