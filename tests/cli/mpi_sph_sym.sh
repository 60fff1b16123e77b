#!/usr/bin/env bash
# Rank-count independence of SPH's symmetry planes and mirrored clamp
# (issue 22 item 1; docs/parallel.md, "Updated-Lagrangian SPH on spatial
# ghosts"): the reduced quarter Taylor bar with the planes x = 0 and y = 0
# (tests/cli/decks/mpi_sym.yaml: the fused loop with artificial stress,
# XSPH, the wall, the predictor-corrector; the list over real and mirrored
# particles is rebuilt ~30 times) without mpirun, on 2, 3 and 4 ranks and
# with a Zoltan repartition every 20 steps on 3 ranks; the same bar without
# artificial stress (the fused loop's vector rows) on 2 ranks; the reduced
# clamped plate (mpi_clamp.yaml: the mirrored clamp with the two-pass
# loops, CSPM, the leapfrog, a probe and the clamp's reaction force;
# clamp particles and their images on different ranks from 3 ranks on)
# on 2, 3 and 4 ranks and rebalanced on 3: history.csv, fields.xdmf and
# bodies.xdmf byte for byte, every frame under h5diff.  (Both features
# belong to the updated form: a total-Lagrangian deck with either is
# refused on one rank already, sph_options.c.)
# Usage: mpi_sph_sym.sh SPALL SRC MPIEXEC
set -u
spall="$1"
mpiexec="$3"
# shellcheck source=lib/rank_compare.bash
source "$2/tests/cli/lib/rank_compare.bash"
cp "$2/tests/cli/decks/mpi_sym.yaml" sym.yaml
cp "$2/tests/cli/decks/mpi_clamp.yaml" clamp.yaml
sed '/artificial_stress/d' sym.yaml > symv.yaml
grep -q "artificial_stress" symv.yaml && { echo "FAIL: cannot make symv.yaml"; exit 1; }
serial sym
for n in 2 3 4; do
    ranks sym "$n"
done
rebalanced sym 3
# the lists must be rebuilt across ranks, or the test shows little: the
# serial run builds at set-up and (with the images) at its first force
# call, both before the partition; every later build is a ghost rebuild
nb=$(col sym_serial/history.csv neighbor_builds)
[ "${nb:-0}" -ge 10 ] || { echo "FAIL: sym: $nb neighbour builds (expected >= 10)"; fail=1; }
rb=$(sed -n 's/^spatial_ghost_rebuilds: \([0-9]*\) in.*/\1/p' sym4/run.log)
[ "${rb:-0}" -eq $((nb - 2)) ] ||
    { echo "FAIL: sym on 4 ranks: ${rb:-no} ghost rebuilds, serial $nb builds"; fail=1; }
serial symv
ranks symv 2
serial clamp
for n in 2 3 4; do
    ranks clamp "$n"
done
rebalanced clamp 3
nb=$(col clamp_serial/history.csv neighbor_builds)
[ "${nb:-0}" -ge 10 ] || { echo "FAIL: clamp: $nb neighbour builds (expected >= 10)"; fail=1; }
[ $fail -eq 0 ] && echo "mpi_sph_sym: OK"
exit $fail
