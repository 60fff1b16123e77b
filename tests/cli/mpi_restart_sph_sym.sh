#!/usr/bin/env bash
# Distributed checkpoints of SPH with symmetry planes, the mirrored clamp
# and a variable h (issue 21 item 4, issue 22 item 1; docs/restart.md,
# "Distributed runs"):
# the reduced quarter Taylor bar of mpi_sph_sym.sh (planes x = 0 and y = 0,
# tests/cli/decks/mpi_sym.yaml: fused loop, artificial stress, XSPH, the
# wall, the predictor-corrector) and the reduced clamped plate
# (mpi_clamp.yaml: the clamp with CSPM, the leapfrog, a probe, the clamp's
# reaction force) and the rubber strip pulled apart with a variable h
# (mpi_vh.yaml: the partition of a restart keeps the list radius of the
# checkpointed build, not that of h_max at the checkpoint), a checkpoint
# every 40 steps; and two strips behind the interface with a variable h
# (mpi_vh_if.yaml), a checkpoint every 3 steps (below).  A symmetry run
# saves no list, only the whole body's
# count of mirror images as a check: a restart on several ranks finds the
# images and the list of the checkpointed build after the partition
# (sph_symmetry_list), on one rank before its first force call
# (sph_symmetry_restore).
#  - written on 2 ranks, every checkpoint equals the serial run's (h5diff);
#  - continued from the 2-rank checkpoint of step 40 without mpirun and on
#    2 and 3 ranks, and the bar from the serial one on 2 ranks: history.csv,
#    fields.xdmf (bodies.xdmf) byte for byte, every frame and later
#    checkpoint under h5diff, as the uninterrupted serial run;
#  - the lists are rebuilt after the checkpoint, and the restart's own
#    list is not counted as a build (the engine's ghost rebuilds on 3
#    ranks are the serial builds after step 40).
# SPALL_TEST_LIGHT=1 (the sanitizer build, CMakeLists.txt) runs the same
# restarts at a quarter of the steps: a checkpoint every 20 steps, the bar
# and the plate to 1.5 us and 1.5 ms (48 and 56 steps; their lists rebuilt
# 7 and 6 times after step 20), continued from step 20; the strip alone is
# left out (its restart is the two strips'); the two strips behind the
# interface to 95 us (42 steps, a checkpoint every 4: 10 writes instead of
# 20; the builds at steps 30 and 40 checked as before); the bar from the
# serial checkpoint is left out (the 2-rank checkpoints equal the serial
# ones).
# Usage: mpi_restart_sph_sym.sh SPALL SRC MPIEXEC
set -u
spall="$1"
mpiexec="$3"
# shellcheck source=lib/rank_compare.bash
source "$2/tests/cli/lib/rank_compare.bash"
counts=${SPALL_MPI_RANK_COUNTS:-2 3}
light=${SPALL_TEST_LIGHT:-0}
ck=40
[ "$light" = 1 ] && ck=20
ckf=$(printf "checkpoint_%010d.h5" "$ck")
decks="sym clamp vh"
# (light: the strip's restart, the list radius of the checkpointed build,
# is the two strips' below, which also take its h_max)
[ "$light" = 1 ] && decks="sym clamp"
for d in $decks; do
    sed "s/^output: {\(.*\)\$/output: {checkpoint: {every_steps: $ck, keep: 5}, \1/" \
        "$2/tests/cli/decks/mpi_$d.yaml" > "$d.yaml"
    grep -q "checkpoint: {every_steps: $ck" "$d.yaml" || { echo "FAIL: cannot make $d.yaml"; exit 1; }
    if [ "$light" = 1 ]; then
        case $d in sym) end=1.5e-6 ;; clamp) end=1.5e-3 ;; esac
        sed -i "s/^run: {end_time: [0-9.e-]*}\$/run: {end_time: $end}/" "$d.yaml"
        grep -q "^run: {end_time: $end}\$" "$d.yaml" || { echo "FAIL: cannot shorten $d.yaml"; exit 1; }
    fi
    serial "$d"
    written_on_2 "$d"
    for n in 1 $counts; do
        continued "$d" "${d}2/$ckf" "$n"
    done
    # the lists must be rebuilt after the checkpoint, or the test shows little
    b0=$(awk -F, -v s="$ck" 'NR == 1 {for (k = 1; k <= NF; k++) if ($k == "neighbor_builds") b = k
                                      next}
                             $1 == s {print $b}' "${d}_serial/history.csv")
    nb=$(col "${d}_serial/history.csv" neighbor_builds)
    [ "$nb" -gt "${b0:-$nb}" ] || { echo "FAIL $d: no list rebuild after step $ck"; fail=1; }
    for n in $counts; do
        rb=$(sed -n 's/^spatial_ghost_rebuilds: \([0-9]*\) in.*/\1/p' "${d}_cont$n/run.log")
        [ "${rb:-0}" -eq $((nb - b0)) ] ||
            { echo "FAIL $d continued on $n ranks: ${rb:-no} ghost rebuilds, serial" \
                "$((nb - b0)) builds after step $ck"; fail=1; }
    done
done
# two strips behind the interface with a variable h (mpi_vh_if.yaml, to
# 150 us): the partition of a restart splits the rebuilt list with the
# h_max of the checkpointed build (sph.list_hmax); a checkpoint every 3
# steps, continued from step 36 (built at 33, h has grown since), whose
# next checkpoint (39) comes before the next build (41) and holds the
# interface list of the restart's split
sed "s/^output: {\(.*\)\$/output: {checkpoint: {every_steps: 3, keep: 30}, \1/;
     s/^run: {end_time: 4.0e-4}\$/run: {end_time: 1.5e-4}/" \
    "$2/tests/cli/decks/mpi_vh_if.yaml" > vhif.yaml
grep -q "checkpoint: {every_steps: 3" vhif.yaml && grep -q "end_time: 1.5e-4" vhif.yaml ||
    { echo "FAIL: cannot make vhif.yaml"; exit 1; }
if [ "$light" = 1 ]; then # (a checkpoint every 4 steps: 36 and 40 as 36 and 39 above)
    sed -i 's/^run: {end_time: 1.5e-4}$/run: {end_time: 9.5e-5}/;
            s/checkpoint: {every_steps: 3, keep: 30}/checkpoint: {every_steps: 4, keep: 30}/' vhif.yaml
    grep -q "end_time: 9.5e-5" vhif.yaml && grep -q "every_steps: 4" vhif.yaml ||
        { echo "FAIL: cannot shorten vhif.yaml"; exit 1; }
fi
serial vhif
written_on_2 vhif
for n in 1 3; do
    continued vhif vhif2/checkpoint_0000000036.h5 "$n"
done
b=$(awk -F, 'NR == 1 {for (k = 1; k <= NF; k++) if ($k == "neighbor_builds") c = k; next}
             $1 == 30 || $1 == 40 {printf "%s ", $c}' vhif_serial/history.csv)
[ "$b" = "5 6 " ] || { echo "FAIL vhif: list builds at steps 30, 40: $b (expected 5 6)"; fail=1; }
if [ "$light" != 1 ]; then # the serial checkpoint continued on 2 ranks
    out=sym_from_serial
    mpi 2 run sym.yaml --restart "sym_serial/$ckf" -o "$out" ||
        { echo "FAIL sym: serial checkpoint continued on 2 ranks: exit $?"; fail=1; }
    same_as_serial sym_serial "$out" "sym: serial checkpoint continued on 2 ranks"
    checkpoints_same sym_serial "$out" "sym: serial checkpoint continued on 2 ranks"
fi
[ $fail -eq 0 ] && echo "mpi_restart_sph_sym: 2-rank checkpoints as serial; restarts on 1" \
    "$counts ranks (vhif: 1 and 3)$([ "$light" = 1 ] || echo " and from the serial checkpoint on 2") exact"
[ $fail -eq 0 ]
