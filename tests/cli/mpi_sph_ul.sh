#!/usr/bin/env bash
# Rank-count independence of updated-Lagrangian SPH on spatial ghosts
# (issue 22 item 1; docs/parallel.md, "Updated-Lagrangian SPH on spatial
# ghosts"): the reduced rubber rings (tests/cli/decks/mpi_ul.yaml: cubic
# spline, AV, artificial stress, the fused loop, the predictor-corrector;
# the rings collide and the neighbour list is rebuilt ~10 times) without
# mpirun and on 2 and 4 ranks, and with a Zoltan repartition every 20 steps
# on 3 ranks (particles migrate); the reduced copper bar of mpi_tl.yaml in
# the updated form with the two-pass loops (leapfrog, CSPM, Balsara's
# switch, XSPH, the artificial stress smoothed between the passes, the
# rigid wall) on 3 ranks, with summation density,
# the adaptive step and a probe (predictor-corrector) on 3 ranks, and the
# vector rows of the fused loop (Wendland, no artificial stress) on 2, and
# a rubber strip pulled apart with a variable h (mpi_vh.yaml: h_max and
# with it the list radius and the ghosts' range grow) on 2 and 3 ranks
# and rebalanced on 3 (a migration keeps the last build's radius), and
# two such strips pressed together and pulled behind the interface between
# bodies (mpi_vh_if.yaml) on 2 and 3 ranks and rebalanced on 3, with their
# checkpoints (axisymmetric runs: mpi_sph_axi.sh):
# history.csv, fields.xdmf and bodies.xdmf byte for byte, every frame and
# checkpoint under h5diff.
# SPALL_TEST_LIGHT=1 (the sanitizer build, CMakeLists.txt) runs every path
# above with 4 launches of mpirun instead of 10 and fewer steps: the strip
# and the two strips rebalanced on 3 ranks only (their 3-rank runs up to
# the first repartition, and the ghost rebuilds counted there: a migration
# rebuilds no list), the strip to 120 us (47 steps, 23 list builds), the
# two strips to 175 us (76 steps, the interface pairs up and gone again);
# the bar's summation and vector-row variants on 3 ranks to 3 us (61
# steps: its list is built once, the wall and the yield act from the
# start); the rings and the bar itself are left to cli_mpi_restart_sph_ul.
# Usage: mpi_sph_ul.sh SPALL SRC MPIEXEC
set -u
spall="$1"
mpiexec="$3"
# shellcheck source=lib/rank_compare.bash
source "$2/tests/cli/lib/rank_compare.bash"
light=${SPALL_TEST_LIGHT:-0}
# shorten DECK.yaml's run to END (light plan)
shorten() { # deck end
    sed -i "s/^run: {end_time: [0-9.e-]*}\$/run: {end_time: $2}/" "$1.yaml"
    grep -q "^run: {end_time: $2}\$" "$1.yaml" || { echo "FAIL: cannot shorten $1.yaml"; exit 1; }
}
cp "$2/tests/cli/decks/mpi_ul.yaml" rings.yaml
# the bar in the updated form: the split loops with every partner value
sed 's/^  type: tlsph$/  type: sph\n  cspm: true\n  xsph: 0.5/; /hourglass/d' \
    "$2/tests/cli/decks/mpi_tl.yaml" > bar.yaml
grep -q "cspm: true" bar.yaml || { echo "FAIL: cannot make bar.yaml"; exit 1; }
# ... with the artificial stress, smoothed between the passes
sed -i 's/^  xsph: 0.5$/  xsph: 0.5\n  artificial_stress: 0.3\n  artificial_stress_smoothing: true/' \
    bar.yaml
grep -q "artificial_stress_smoothing" bar.yaml || { echo "FAIL: cannot make bar.yaml"; exit 1; }
[ "$light" = 1 ] && shorten bar 3.0e-6
sed '/time_integration: leapfrog/d; /viscosity_switch: balsara/d; /artificial_stress/d;
     s/^  cspm: true$/  density: summation\n  adaptive_dt: true/' bar.yaml > barpc.yaml
printf "probes: [{name: tip, position: [0.0004, 0.0004, 0.0092]}]\n" >> barpc.yaml
grep -q "density: summation" barpc.yaml || { echo "FAIL: cannot make barpc.yaml"; exit 1; }
sed '/time_integration: leapfrog/d; /viscosity_switch: balsara/d; /artificial_stress/d; /cspm: true/d' bar.yaml > barfv.yaml
grep -q "cspm\|leapfrog\|balsara" barfv.yaml && { echo "FAIL: cannot make barfv.yaml"; exit 1; }
# (light: the rings rebalanced on 3 and the bar on 2 and continued on 3 are
# runs of cli_mpi_restart_sph_ul, under the sanitizers too, with these very
# decks; the ghost rebuilds are counted on the strip below)
if [ "$light" != 1 ]; then
    serial rings
    for n in 2 4; do
        ranks rings "$n"
    done
    rebalanced rings 3
    # the runs must rebuild their lists across ranks, or the test shows little
    nb=$(col rings_serial/history.csv neighbor_builds)
    [ "${nb:-0}" -ge 5 ] || { echo "FAIL: rings: $nb neighbour builds (expected >= 5)"; fail=1; }
    rb=$(sed -n 's/^spatial_ghost_rebuilds: \([0-9]*\) in.*/\1/p' rings4/run.log)
    [ "${rb:-0}" -eq $((nb - 1)) ] ||
        { echo "FAIL: rings on 4 ranks: ${rb:-no} ghost rebuilds, serial $nb builds"; fail=1; }
    serial bar
    ranks bar 3
fi
serial barpc
ranks barpc 3
serial barfv
ranks barfv "${SPALL_MPI_RANK_COUNTS:-2}"
# a variable h: the list radius and the ghosts' range grow with h_max
cp "$2/tests/cli/decks/mpi_vh.yaml" vh.yaml
[ "$light" = 1 ] && shorten vh 1.2e-4
serial vh
# (the ASan build sets SPALL_MPI_RANK_COUNTS=3: 3 ranks only, CMakeLists.txt)
[ -z "${SPALL_MPI_RANK_COUNTS:-}" ] && ranks vh 2
[ "$light" = 1 ] || ranks vh 3
rebalanced vh 3
rr=vh3
[ "$light" = 1 ] && rr=vh_rb3
nb=$(col vh_serial/history.csv neighbor_builds)
rb=$(sed -n 's/^spatial_ghost_rebuilds: \([0-9]*\) in.*/\1/p' "$rr/run.log")
[ "${rb:-0}" -eq $((nb - 1)) ] && [ "$nb" -ge 20 ] ||
    { echo "FAIL: vh ($rr): ${rb:-no} ghost rebuilds, serial $nb builds"; fail=1; }
# ... and with an interface between two strips pressed and pulled
# (mpi_vh_if.yaml): the split of a partition or migration between builds
# takes the last build's h_max; it shows in the interface list, which the
# checkpoints hold (with the h_max of the moment the rebalanced run's
# checkpoint of step 20 differed; without the interface values migrating,
# those of steps 40 and 60)
sed "s/^output: {\(.*\)\$/output: {checkpoint: {every_steps: 10, keep: 20}, \1/" \
    "$2/tests/cli/decks/mpi_vh_if.yaml" > vhif.yaml
grep -q "checkpoint: {every_steps: 10" vhif.yaml || { echo "FAIL: cannot make vhif.yaml"; exit 1; }
[ "$light" = 1 ] && shorten vhif 1.75e-4
serial vhif
[ -z "${SPALL_MPI_RANK_COUNTS:-}" ] && ranks vhif 2
[ "$light" = 1 ] || ranks vhif 3
rebalanced vhif 3
# (the rebalanced deck has a line more: its deck and checksum differ)
checkpoints_same vhif_serial vhif_rb3 "vhif rebalanced, 3 ranks" \
    "--exclude-path /checksum --exclude-path /deck"
[ "$light" = 1 ] || checkpoints_same vhif_serial vhif3 "vhif, 3 ranks"
np=$(awk -F, 'NR == 1 {for (k = 1; k <= NF; k++) if ($k == "interface_pairs") c = k; next}
              $c > m {m = $c} END {print m + 0}' vhif_serial/history.csv)
[ "$np" -ge 10 ] || { echo "FAIL: vhif: at most $np interface pairs in contact"; fail=1; }
[ $fail -eq 0 ] && echo "mpi_sph_ul: OK"
exit $fail
