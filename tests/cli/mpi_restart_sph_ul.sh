#!/usr/bin/env bash
# Distributed checkpoints of updated-Lagrangian SPH (issue 21 item 4, issue
# 22 item 1; docs/restart.md, "Distributed runs"): the neighbour list (and
# the interface list) saved as bond lists of the owned rows, partners by
# global id, so that a checkpoint written on any rank count is the serial
# one.  The reduced decks of mpi_sph_ul.sh and mpi_sph_axi.sh: the rubber
# rings (fused loop, artificial stress, predictor-corrector), the copper bar
# in the updated form with the two-pass loops (leapfrog, CSPM, Balsara,
# XSPH, the artificial stress smoothed between the passes, the wall) and the
# axisymmetric gelatin penetration (axis weights, rigid sphere, cavity), and
# the same with the sphere as an SPH body behind the penalty interface
# (the interface list: written on 2 ranks, continued on 3).
#  - written on 2 ranks, every checkpoint equals the serial run's (h5diff);
#  - continued from the 2-rank checkpoint without mpirun and on 3 and 4
#    ranks (the rings also on 2 ranks x 2 threads): history.csv and
#    fields.xdmf byte for byte, every frame and later checkpoint under
#    h5diff, as the uninterrupted serial run; the lists are rebuilt after
#    the checkpoint;
#  - the rings with a Zoltan repartition every 20 steps written on 3 ranks
#    and continued on 4, still rebalancing (the checkpoints differ from the
#    serial ones only in the deck's `parallel` key);
#  - a truncated checkpoint and another deck refused on 2 ranks with one
#    line, exit 2, the run directory untouched.
# Usage: mpi_restart_sph_ul.sh SPALL SRC MPIEXEC
set -u
spall="$1"
mpiexec="$3"
# shellcheck source=lib/rank_compare.bash
source "$2/tests/cli/lib/rank_compare.bash"
with_checkpoints() { # deck every: a checkpoint every N steps added to the output map
    sed -i "s/^output: {\(.*\)\$/output: {checkpoint: {every_steps: $2, keep: 5}, \1/" "$1.yaml"
    grep -q "checkpoint: {every_steps: $2" "$1.yaml" ||
        { echo "FAIL: cannot make $1.yaml"; exit 1; }
}
cp "$2/tests/cli/decks/mpi_ul.yaml" rings.yaml
# the bar in the updated form, as mpi_sph_ul.sh makes it
sed 's/^  type: tlsph$/  type: sph\n  cspm: true\n  xsph: 0.5/; /hourglass/d' \
    "$2/tests/cli/decks/mpi_tl.yaml" > bar.yaml
sed -i 's/^  xsph: 0.5$/  xsph: 0.5\n  artificial_stress: 0.3\n  artificial_stress_smoothing: true/' \
    bar.yaml
grep -q "artificial_stress_smoothing" bar.yaml || { echo "FAIL: cannot make bar.yaml"; exit 1; }
cp "$2/tests/cli/decks/mpi_ul_gel.yaml" gel.yaml
# (the first half: ~400 steps, the sphere in contact throughout)
sed 's/^run: {end_time: 1.0e-08}$/run: {end_time: 5.0e-09}/' \
    "$2/tests/cli/decks/mpi_ul_def.yaml" > def.yaml
grep -q "end_time: 5.0e-09" def.yaml || { echo "FAIL: cannot make def.yaml"; exit 1; }
declare -A every=([rings]=60 [bar]=60 [gel]=100 [def]=200)
counts=${SPALL_MPI_RANK_COUNTS:-3 4}
for d in rings bar gel def; do
    ck=${every[$d]}
    with_checkpoints "$d" "$ck"
    serial "$d"
    written_on_2 "$d"
    ckf=$(printf "checkpoint_%010d.h5" "$ck")
    cont="1 $counts"
    [ "$d" = def ] && cont=3 # (the interface list; one restart suffices)
    for n in $cont; do
        continued "$d" "${d}2/$ckf" "$n"
    done
    # the lists must be rebuilt after the checkpoint, or the test shows little
    awk -F, -v s="$ck" 'NR == 1 {for (k = 1; k <= NF; k++) if ($k == "neighbor_builds") b = k
                                 next}
                        $1 == s {b0 = $b} END {exit !($b > b0 && b0 > 1)}' \
        "${d}_serial/history.csv" || { echo "FAIL $d: no list rebuild after step $ck"; fail=1; }
done
# the deformable sphere's interface pairs must be in contact after the checkpoint
awk -F, 'NR == 1 {for (k = 1; k <= NF; k++) if ($k == "interface_pairs") c = k; next}
         $1 > 200 && $c > 0 {n++} END {exit !(n > 3)}' def_serial/history.csv ||
    { echo "FAIL def: no interface pairs after step 200"; fail=1; }
# 2 ranks x 2 threads
OMP_NUM_THREADS=2 timeout 120 "$mpiexec" --allow-run-as-root --oversubscribe -q -np 2 "$spall" \
    run rings.yaml --restart rings2/checkpoint_0000000060.h5 -o rings_t2 --quiet --no-progress ||
    { echo "FAIL rings continued on 2 ranks x 2 threads: exit $?"; fail=1; }
same_as_serial rings_serial rings_t2 "rings continued on 2 ranks x 2 threads"
checkpoints_same rings_serial rings_t2 "rings continued on 2 ranks x 2 threads"
grep -q "^ranks_x_threads: 2 x 2" rings_t2/run.log ||
    { echo "FAIL rings on 2 ranks x 2 threads: run.log"; fail=1; }
# rebalanced: the deck differs by its parallel key (/deck and so /checksum)
{ cat rings.yaml; echo "parallel: {rebalance_every: 20, imbalance_threshold: 1.0}"; } \
    > rings_rb.yaml
skip="--exclude-path /deck --exclude-path /checksum"
mpi 3 run rings_rb.yaml -o rings_rb3 || { echo "FAIL rings rebalanced on 3: exit $?"; fail=1; }
same_as_serial rings_serial rings_rb3 "rings rebalanced, 3 ranks"
checkpoints_same rings_serial rings_rb3 "rings rebalanced, 3 ranks" "$skip"
continued rings_rb rings_rb3/checkpoint_0000000060.h5 4 "$skip"
for r in rings_rb3 rings_rb_cont4; do
    moved=$(sed -n 's/^rebalances: [0-9]* (\([0-9]*\) particles migrated).*/\1/p' "$r/run.log")
    [ "${moved:-0}" -gt 0 ] || { echo "FAIL $r: nothing migrated"; fail=1; }
done
# refusals on 2 ranks: one line, exit 2, the run directory untouched
mkdir cut
cp rings2/history.csv rings2/fields_000000.h5 rings2/fields.xdmf cut/
head -c 20000 rings2/checkpoint_0000000120.h5 > cut/checkpoint_0000000120.h5
refused_restart "truncated checkpoint" cut rings.yaml "not a readable HDF5 file"
sed 's/youngs_modulus: 1.0e7/youngs_modulus: 1.1e7/' rings.yaml > rings_stiff.yaml
refused_restart "another deck" rings2 rings_stiff.yaml \
    "deck key 'materials.rubber.youngs_modulus' differs"
[ $fail -eq 0 ] && echo "mpi_restart_sph_ul: 2-rank checkpoints as serial; restarts on 1" \
    "$counts ranks and 2 x 2 threads exact; rebalanced on 3 and continued on 4 exact; refusals"
[ $fail -eq 0 ]
