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
export OMP_WAIT_POLICY=passive
# ASan builds (make asan): full stacks and loaded MCA components, so that
# tests/lsan.supp can name Open MPI's own run-time state
export OMPI_MCA_mca_base_component_disable_dlclose=1
[ -n "${ASAN_OPTIONS:-}" ] && export ASAN_OPTIONS="$ASAN_OPTIONS:fast_unwind_on_malloc=0"
[ -n "${LSAN_OPTIONS:-}" ] && export LSAN_OPTIONS="$LSAN_OPTIONS:print_suppressions=0"
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
cd "$tmp"
cat > frac.yaml <<'YAML'
title: lattice fracture, rank-count independence
model: {type: lattice, law: linear}
materials:
  m: {density: 1000, youngs_modulus: 1.0e9, poisson_ratio: 0.3333333333333333, failure_strain: 0.004}
lattice: {type: triangular, spacing: 0.001}
geometry:
  plate: {box: {min: [0, 0], max: [0.04, 0.03]}}
body: {geometry: plate, material: m}
precracks:
  - {from: [-0.001, 0.015], to: [0.012, 0.015]}
groups:
  bottom: {box: {min: [-1, -1], max: [1, 0.0006]}}
  top: {box: {min: [-1, 0.0285], max: [1, 1]}}
  right: {box: {min: [0.0395, -1], max: [1, 1]}}
boundary_conditions:
  - {group: bottom, type: velocity, components: [y], value: -2.0}
  - {group: top, type: velocity, components: [y], value: 2.0}
  - {group: right, type: force, components: [x], value: 5.0}
probes:
  - {name: tip, position: [0.012, 0.015]}
damping: 50.0
run: {steps: 300}
output: {field_every: 100, history_every: 10}
YAML
# peridynamics (PMB): a pre-cracked plate pulled by tractions
cat > pd.yaml <<'YAML'
title: peridynamic fracture, rank-count independence
model: {type: peridynamics}
materials:
  glass: {density: 2440, youngs_modulus: 72.0e9, fracture_energy: 3.8}
lattice: {type: square, spacing: 1.0e-3, thickness: 1.0e-3}
geometry:
  plate: {box: {min: [-1.0e-5, -1.0e-5], max: [0.04001, 0.02001]}}
body: {geometry: plate, material: glass}
precracks:
  - {from: [-0.001, 0.0105], to: [0.015, 0.0105]}
groups:
  top: {box: {min: [-1, 0.0175], max: [1, 1]}}
  bottom: {box: {min: [-1, -1], max: [1, 0.0025]}}
probes:
  - {name: tip, position: [0.015, 0.0105]}
boundary_conditions:
  - {group: top, type: traction, components: [y], value: 15.0e6, area: 4.0e-5}
  - {group: bottom, type: traction, components: [y], value: -15.0e6, area: 4.0e-5}
run: {steps: 300}
output: {field_every: 150, history_every: 10}
YAML
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
