#!/usr/bin/env bash
# Rank-count independence of fragments and rigid impactors (issue 22 item 3):
#  - a lattice plate shattered by a fast sphere (penalty contact with
#    friction): many fragments that cross rank boundaries, the `fragment_id`
#    field in every frame;
#  - a reduced Kalthoff-Winkler plate (peridynamics, PMB) struck by a free
#    flat-ended cylinder (penalty contact);
#  - a lattice beam under a falling round-nose tup (no-slip contact, gravity)
#    on two rollers (penalty, prescribed).
# Each runs without mpirun and on 2 and 3 ranks (the shattered plate also on
# 4): history.csv (impactor force, position, velocity, absorbed energy,
# contacts; the fragment columns), fragments.csv and fields.xdmf identical
# byte for byte, every frame identical under h5diff.
# Usage: mpi_impact.sh SPALL SRC MPIEXEC
set -u
spall="$1"
mpiexec="$3"
# shellcheck source=lib/rank_compare.bash
source "$2/tests/cli/lib/rank_compare.bash"
cp "$2/tests/cli/decks/mpi_shatter.yaml" shatter.yaml
cat > kw.yaml <<'YAML'
title: reduced Kalthoff-Winkler plate struck by a cylinder, rank-count independence
model: {type: peridynamics}
materials:
  steel: {density: 8000, youngs_modulus: 190.0e9, fracture_energy: 2.2e4}
lattice: {type: square, spacing: 1.0e-3, thickness: 1.0e-3}
geometry:
  plate: {box: {min: [-1.0e-5, -0.02001], max: [0.04001, 0.02001]}}
body: {geometry: plate, material: steel}
precracks:
  - {from: [-0.001, 0.0105], to: [0.0155, 0.0105]}
  - {from: [-0.001, -0.0105], to: [0.0155, -0.0105]}
impactors:
  - {name: striker, shape: cylinder, position: [-0.0015, 0], radius: 0.01, edge_radius: 0.001,
     length: 0.05, axis: [1, 0], mass: 0.5, velocity: [60.0, 0], contact: penalty}
run: {steps: 300}
output: {field_every: 150, history_every: 10, fields: [position, velocity, damage]}
YAML
cp "$2/tests/cli/decks/mpi_tup.yaml" tup.yaml
for deck in shatter kw tup; do
    serial $deck
done
# the references must fracture and touch, else the test proves little
frags=$(col shatter_serial/history.csv "fragments [1]")
awk -v f="$frags" 'BEGIN {exit !(f >= 50)}' || { echo "FAIL shatter made $frags fragments"; fail=1; }
kw_broken=$(col kw_serial/history.csv bonds_broken)
awk -v b="$kw_broken" 'BEGIN {exit !(b > 50)}' || { echo "FAIL kw broke $kw_broken bonds"; fail=1; }
for c in "ball_contacts" "striker_contacts" "tup_contacts"; do
    f=shatter_serial; [ $c = striker_contacts ] && f=kw_serial; [ $c = tup_contacts ] && f=tup_serial
    awk -F, -v n="$c" 'NR == 1 {for (k = 1; k <= NF; k++) if ($k == n) c = k; next}
                       $c > 0 {hit = 1} END {exit !hit}' $f/history.csv ||
        { echo "FAIL $c: the impactor never touched the body"; fail=1; }
done
counts="${SPALL_MPI_RANK_COUNTS:-2 3 4}"
for n in $counts; do
    for deck in shatter kw tup; do
        [ "$n" = 4 ] && [ $deck != shatter ] && continue
        ranks $deck "$n"
    done
done
# impactors with migrating particles (contact rows keyed by gid, regrown)
rebalanced kw 3
[ $fail -eq 0 ] && echo "mpi_impact: identical on $counts ranks ($frags fragments," \
    "$kw_broken pd bonds broken)"
[ $fail -eq 0 ]
