#!/usr/bin/env bash
# Rank-count independence of TLSPH bodies behind the penalty interface
# (issue 22 item 1; docs/parallel.md, "TLSPH bodies behind an interface"):
# a rank holds the spatial ghosts of the current list (the interface pairs)
# and the reference partners of its TLSPH rows in one ghost set.  Two TLSPH
# blocks pressed together (tests/cli/decks/mpi_tl_ifc.yaml, type: tlsph,
# interface: bodies) without mpirun, on 2, 3 and 4 ranks and rebalanced
# every 20 steps on 3: history.csv, fields.xdmf byte for byte, every frame
# under h5diff; a TLSPH strip pulled apart on an updated-form block
# (tests/cli/decks/mpi_tl_bf.yaml, model.body_formulation: some reference
# partners lie beyond range + skin, ghosts for them alone) on 2 and 3 ranks
# and rebalanced on 3, its checkpoints written by 2 ranks (the serial ones
# under h5diff) restarted on 1 (without mpirun) and on 3 ranks.
# SPALL_TEST_LIGHT=1 (the sanitizer build, CMakeLists.txt) runs every path
# above at a third of the launches: the blocks rebalanced on 3 ranks only
# (the 3-rank run up to its repartition at step 20); the strip to 200 us
# (348 steps, interface pairs in 24 rows) rebalanced on 3 ranks, which
# writes the checkpoints (the serial ones under h5diff, deck and checksum
# aside), continued from step 222 on 1 (without mpirun) and on 2 ranks.
# Usage: mpi_sph_tl_ifc.sh SPALL SRC MPIEXEC
set -u
spall="$1"
mpiexec="$3"
# shellcheck source=lib/rank_compare.bash
source "$2/tests/cli/lib/rank_compare.bash"
cp "$2/tests/cli/decks/mpi_tl_ifc.yaml" ifc.yaml
serial ifc
np=$(awk -F, 'NR == 1 {for (k = 1; k <= NF; k++) if ($k == "interface_pairs") c = k}
              NR > 1 && $c > 0 {n++} END {print n + 0}' ifc_serial/history.csv)
[ "$np" -gt 5 ] || { echo "FAIL: ifc: interface pairs in $np history rows"; fail=1; }
light=${SPALL_TEST_LIGHT:-0}
if [ "$light" != 1 ]; then
    # (the ASan build sets SPALL_MPI_RANK_COUNTS=3: 3 ranks only, CMakeLists.txt)
    for n in ${SPALL_MPI_RANK_COUNTS:-2 3 4}; do
        ranks ifc "$n"
    done
fi
rebalanced ifc 3
sed 's/^output: {\(.*\)}$/output: {\1, checkpoint: {every_steps: 100, keep: 5}}/' \
    "$2/tests/cli/decks/mpi_tl_bf.yaml" > bf.yaml
grep -q "checkpoint: {every_steps: 100" bf.yaml || { echo "FAIL: cannot add checkpoints"; exit 1; }
if [ "$light" = 1 ]; then
    # a checkpoint every 111 steps, none at a rebalance (every 20 steps):
    # there a run mixing the formulations saves as sph.pairs the current
    # list's pairs alone, not with the reference list's (the serial count
    # returns at the next force call, so the restart is exact)
    sed -i 's/^run: {end_time: 4.0e-4}$/run: {end_time: 2.0e-4}/;
            s/checkpoint: {every_steps: 100, keep: 5}/checkpoint: {every_steps: 111, keep: 5}/' bf.yaml
    grep -q "end_time: 2.0e-4" bf.yaml && grep -q "every_steps: 111" bf.yaml ||
        { echo "FAIL: cannot shorten bf.yaml"; exit 1; }
fi
serial bf
np=$(awk -F, 'NR == 1 {for (k = 1; k <= NF; k++) if ($k == "interface_pairs") c = k}
              NR > 1 && $c > 0 {n++} END {print n + 0}' bf_serial/history.csv)
[ "$np" -gt 20 ] || { echo "FAIL: bf: interface pairs in $np history rows"; fail=1; }
if [ "$light" = 1 ]; then
    # the rebalanced run writes the checkpoints (its deck has a line more:
    # deck and checksum differ from the serial run's) and is continued
    rebalanced bf 3
    ex="--exclude-path /checksum --exclude-path /deck"
    checkpoints_same bf_serial bf_rb3 "bf rebalanced, 3 ranks" "$ex"
    continued bf_rb bf_rb3/checkpoint_0000000222.h5 1 "$ex"
    continued bf_rb bf_rb3/checkpoint_0000000222.h5 2 "$ex"
else
    written_on_2 bf
    [ -z "${SPALL_MPI_RANK_COUNTS:-}" ] && ranks bf 3
    rebalanced bf 3
    continued bf bf2/checkpoint_0000000300.h5 1
    continued bf bf2/checkpoint_0000000300.h5 3
fi
[ $fail -eq 0 ] && echo "mpi_sph_tl_ifc: OK"
exit $fail
