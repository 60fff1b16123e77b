#!/usr/bin/env bash
# Rank-count independence (issue 20): a small lattice fracture deck (pre-crack,
# velocity and force BCs, damping, a probe, bonds breaking, fragments) run
# without mpirun and on 1, 2, 3, 4 ranks and 2 ranks x 2 threads gives the
# same bytes: h5diff of every frame, cmp of history.csv, fragments.csv and
# fields.xdmf; a peridynamic (PMB) fracture deck the same on 2, 3, 4 ranks.
# run.log records ranks x threads and the decomposition.
# Usage: mpi_ranks.sh SPALL SRC MPIEXEC
set -u
spall="$1"
mpiexec="$3"
# shellcheck source=lib/mpi_env.bash
source "$2/tests/cli/lib/mpi_env.bash"
# the lattice and PMB decks shared by the MPI tests
cp "$2/tests/cli/decks/mpi_frac.yaml" frac.yaml
cp "$2/tests/cli/decks/mpi_pd.yaml" pd.yaml
fail=0
OMP_NUM_THREADS=1 timeout 120 "$spall" run frac.yaml -o serial --quiet --no-progress ||
    { echo "FAIL serial run"; exit 1; }
OMP_NUM_THREADS=1 timeout 120 "$spall" run pd.yaml -o pd_serial --quiet --no-progress ||
    { echo "FAIL serial pd run"; exit 1; }
# the reference must have broken bonds, else the test proves little
broken=$(awk -F, 'NR == 1 {for (k = 1; k <= NF; k++) if ($k == "bonds_broken") c = k}
                   END {print $c}' serial/history.csv)
if ! awk -v b="$broken" 'BEGIN {exit !(b > 50)}'; then
    echo "FAIL reference broke too few bonds ($broken)"; fail=1
fi
compare() { # name out-dir [reference-dir]
    local f ref="${3:-serial}"
    for f in history.csv fragments.csv fields.xdmf; do
        [ -e "$ref/$f" ] || continue
        cmp -s "$ref/$f" "$2/$f" || { echo "FAIL $1: $f differs"; fail=1; }
    done
    for f in "$ref"/fields_*.h5; do
        h5diff -q "$f" "$2/$(basename "$f")" || { echo "FAIL $1: $(basename "$f") differs"; fail=1; }
    done
}
# SPALL_MPI_RANK_COUNTS: the rank counts to compare (the ASan build runs 3
# only: every path of the halo, the reductions and the collective frames, at
# a third of the cost; CMakeLists.txt)
counts="${SPALL_MPI_RANK_COUNTS:-1 2 3 4}"
for n in $counts; do
    OMP_NUM_THREADS=1 timeout 120 "$mpiexec" --allow-run-as-root --oversubscribe -q -np "$n" \
        "$spall" run frac.yaml -o "r$n" --quiet --no-progress || { echo "FAIL $n ranks: exit $?"; fail=1; continue; }
    compare "$n ranks" "r$n"
    [ "$n" = 1 ] && continue
    OMP_NUM_THREADS=1 timeout 120 "$mpiexec" --allow-run-as-root --oversubscribe -q -np "$n" \
        "$spall" run pd.yaml -o "pd$n" --quiet --no-progress || { echo "FAIL pd $n ranks: exit $?"; fail=1; continue; }
    compare "pd, $n ranks" "pd$n" pd_serial
done
if [ -z "${SPALL_MPI_RANK_COUNTS:-}" ]; then
    OMP_NUM_THREADS=2 timeout 120 "$mpiexec" --allow-run-as-root --oversubscribe -q -np 2 \
        "$spall" run frac.yaml -o r2t2 --quiet --no-progress || { echo "FAIL 2x2: exit $?"; fail=1; }
    compare "2 ranks x 2 threads" r2t2
    grep -q "^ranks_x_threads: 2 x 2$" r2t2/run.log || { echo "FAIL run.log: ranks x threads"; fail=1; }
fi
[ "$(grep -c '^  rank [0-9]*: [0-9]* owned, [0-9]* ghosts' r3/run.log)" -eq 3 ] ||
    { echo "FAIL run.log: decomposition per rank"; fail=1; }
pd_broken=$(awk -F, 'NR == 1 {for (k = 1; k <= NF; k++) if ($k == "bonds_broken") c = k}
                      END {print $c}' pd_serial/history.csv)
if ! awk -v b="$pd_broken" 'BEGIN {exit !(b > 50)}'; then
    echo "FAIL pd reference broke too few bonds ($pd_broken)"; fail=1
fi
[ $fail -eq 0 ] && echo "mpi_ranks: identical on 1-4 ranks and 2x2 ($broken lattice bonds," \
    "$pd_broken pd bonds broken)"
[ $fail -eq 0 ]
