#!/usr/bin/env bash
# Rank-count independence of axisymmetric updated-Lagrangian SPH on spatial
# ghosts (issue 22 item 1; docs/parallel.md, "Updated-Lagrangian SPH on
# spatial ghosts"): the reduced gelatin penetration
# (tests/cli/decks/mpi_ul_gel.yaml: graded layers, the axis images and
# weights, XSPH, the rigid sphere's penalty contact, the cavity columns)
# without mpirun, on 2 ranks, and with a Zoltan repartition every 20 steps
# on 3 ranks (particles migrate); the same with the sphere as an SPH body
# behind the penalty interface between materials
# (tests/cli/decks/mpi_ul_def.yaml): history.csv, fields.xdmf and
# bodies.xdmf byte for byte, every frame under h5diff.
# Usage: mpi_sph_axi.sh SPALL SRC MPIEXEC
set -u
spall="$1"
mpiexec="$3"
# shellcheck source=lib/rank_compare.bash
source "$2/tests/cli/lib/rank_compare.bash"
cp "$2/tests/cli/decks/mpi_ul_gel.yaml" gel.yaml
serial gel
ranks gel 2
rebalanced gel 3
# the deformable sphere: an SPH body behind the penalty interface
cp "$2/tests/cli/decks/mpi_ul_def.yaml" def.yaml
serial def
ranks def 2
rebalanced def 3
np=$(awk -F, 'NR == 1 {for (k = 1; k <= NF; k++) if ($k == "interface_pairs") c = k}
              NR > 1 && $c > 0 {n++} END {print n + 0}' def_serial/history.csv)
[ "$np" -gt 5 ] || { echo "FAIL: def: interface pairs in $np history rows"; fail=1; }
# the sphere must open a cavity, or the test shows little
d1=$(col gel_serial/history.csv "cavity_D1 [m]")
awk -v d="$d1" 'BEGIN {exit !(d > 1e-6)}' || { echo "FAIL: gel: no cavity (D1 = $d1)"; fail=1; }
[ $fail -eq 0 ] && echo "mpi_sph_axi: OK"
exit $fail
