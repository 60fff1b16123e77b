#!/usr/bin/env bash
# Rank-count independence of total-Lagrangian SPH (issue 22 item 1): a
# reduced 3D copper Taylor bar (tests/cli/decks/mpi_tl.yaml: leapfrog,
# Balsara's switch, hourglass control, the rigid wall; plastic flow at the
# impact face) without mpirun and on 2 and 4 ranks, and the same bar with
# the predictor-corrector, the adaptive step as a global minimum and a
# probe on 3 ranks: history.csv, fields.xdmf and bodies.xdmf byte for byte,
# every frame under h5diff; the bar with a Zoltan repartition every 20
# steps on 3 ranks (particles migrate with their reference rows); its
# checkpoints (written by 2 ranks: the serial ones under h5diff) restarted on
# 3 ranks and on one without mpirun, with the same bytes; the bar with a
# re-reference every 20 steps (h grown where the neighbourhood went flat) on
# 2 and 3 ranks and rebalanced on 3, its 2-rank checkpoint restarted on 3;
# two TLSPH blocks behind the penalty interface re-referenced every 5 steps
# on 2 ranks (more of that in tests/cli/mpi_sph_tl_reref.sh).
# Axisymmetric TLSPH, which one rank refuses, is refused in one line, exit
# 2 (the updated form distributes: tests/cli/mpi_sph_ul.sh; TLSPH bodies
# behind an interface: tests/cli/mpi_sph_tl_ifc.sh).
# Usage: mpi_sph.sh SPALL SRC MPIEXEC
set -u
spall="$1"
mpiexec="$3"
# shellcheck source=lib/rank_compare.bash
source "$2/tests/cli/lib/rank_compare.bash"
sed 's/^output: {\(.*\)}$/output: {\1, checkpoint: {every_steps: 50, keep: 5}}/' \
    "$2/tests/cli/decks/mpi_tl.yaml" > tl.yaml
grep -q "checkpoint: {every_steps: 50" tl.yaml || { echo "FAIL: cannot add checkpoints"; exit 1; }
# the predictor-corrector (the model's default) without Balsara's switch
sed '/time_integration: leapfrog/d; /viscosity_switch: balsara/d' tl.yaml > pc.yaml
printf "probes: [{name: tip, position: [0.0004, 0.0004, 0.0092]}]\n" >> pc.yaml
grep -q "time_integration" pc.yaml && { echo "FAIL: cannot make pc.yaml"; exit 1; }
counts="${SPALL_MPI_RANK_COUNTS:-2 4}"
tl_checkpoints_same() { # out what: every checkpoint of out is tl_serial's, under h5diff
    local f
    for f in "$1"/checkpoint_*.h5; do
        h5diff -q "tl_serial/$(basename "$f")" "$f" ||
            { echo "FAIL $2: $(basename "$f") differs"; fail=1; }
    done
}
serial tl
[ -e tl_serial/checkpoint_0000000050.h5 ] || { echo "FAIL: no checkpoint at step 50"; exit 1; }
for n in $counts; do
    ranks tl "$n"
done
w="${counts%% *}" # the checkpoints of the first rank count (2; 3 under ASan)
tl_checkpoints_same "tl$w" "checkpoints written by $w ranks"
rebalanced tl 3
for n in 3 1; do # restarts from that run's checkpoint of step 50, on another count
    [ "$n" = "$w" ] && continue
    launch=(timeout 120 "$mpiexec" --allow-run-as-root --oversubscribe -q -np "$n")
    [ "$n" = 1 ] && launch=(timeout 120)
    OMP_NUM_THREADS=1 "${launch[@]}" "$spall" run tl.yaml --restart "tl$w/checkpoint_0000000050.h5" \
        -o "restart$n" --quiet --no-progress || { echo "FAIL restart on $n: exit $?"; fail=1; }
    same_as_serial tl_serial "restart$n" "written by $w ranks, restarted on $n"
    tl_checkpoints_same "restart$n" "restarted on $n"
done
# the bar must deform plastically, or the test shows little
ep=$(col tl_serial/history.csv max_plastic_strain)
awk -v e="$ep" 'BEGIN {exit !(e > 0.1)}' || { echo "FAIL: max plastic strain $ep <= 0.1"; fail=1; }
serial pc
ranks pc 3
# re-references every 20 steps, h grown where the neighbourhood went flat
# (isotropy 0.9: 160 particles by step 100): each regathers the ghosts
# around the current positions (sph_tlsph_reref.c); its checkpoints written
# by 2 ranks after two re-references continue on 3 across three more
sed 's/^  hourglass: 1.0$/  hourglass: 1.0\n  reference_update: {every: 20, isotropy: 0.9}/' \
    tl.yaml > reref.yaml
grep -q reference_update reref.yaml || { echo "FAIL: cannot make reref.yaml"; exit 1; }
serial reref
nr=$(col reref_serial/history.csv reference_updates)
[ "${nr:-0}" -ge 5 ] || { echo "FAIL: reref: ${nr:-0} reference updates"; fail=1; }
written_on_2 reref
ranks reref 3
rebalanced reref 3
continued reref reref2/checkpoint_0000000050.h5 3
# (TLSPH bodies behind the penalty interface distribute: mpi_sph_tl_ifc.sh)
cp "$2/tests/cli/decks/mpi_tl_ifc.yaml" ifc.yaml
# and so do their reference updates (the regather keeps the spatial
# ghosts, the current list is found again: mpi_sph_tl_reref.sh)
sed 's/, interface: bodies}$/, interface: bodies, reference_update: {every: 5}}/' ifc.yaml > ifcrr.yaml
grep -q "reference_update: {every: 5}}" ifcrr.yaml || { echo "FAIL: cannot make ifcrr.yaml"; exit 1; }
serial ifcrr
nr=$(col ifcrr_serial/history.csv reference_updates)
[ "${nr:-0}" -ge 4 ] || { echo "FAIL: ifcrr: ${nr:-0} reference updates"; fail=1; }
ranks ifcrr 2
# axisymmetric TLSPH does not exist on one rank either (sph_options.c): the
# deck is refused on several ranks by the same one line
sed 's/^model: {type: tlsph, plane: strain,/model: {type: tlsph, plane: axisymmetric,/;
     s/, interface: bodies}$/}/' ifc.yaml > axi.yaml
grep -q "plane: axisymmetric, kernel: wendland, h_factor: 1.3}" axi.yaml ||
    { echo "FAIL: cannot make axi.yaml"; exit 1; }
refused "axisymmetric TLSPH" axi.yaml "takes no artificial_stress, summation density or total"
[ $fail -eq 0 ] && echo "mpi_sph: OK"
exit $fail
