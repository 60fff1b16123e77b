#!/usr/bin/env bash
# Errors under MPI (issue 20): on two ranks every deck error case of
# bad_input.sh still gives one line with file:line:column, exit status 2 and
# no output directory; what is not distributed yet is refused the same way;
# a run that goes unstable stops both ranks with one message, exit 3.  Every
# launch runs under `timeout`, so a hang fails instead of blocking the suite.
# Usage: mpi_errors.sh SPALL SRC MPIEXEC
set -u
spall="$1"
src="$2"
mpiexec="$3"
export OMP_NUM_THREADS=1 OMP_WAIT_POLICY=passive
# shellcheck source=lib/asan_mpi.bash
source "$src/tests/cli/lib/asan_mpi.bash"
launch="timeout 120 $mpiexec --allow-run-as-root --oversubscribe -q -np 2"
fail=0
# the deck error cases of the suite, on two ranks
if ! SPALL_LAUNCH="$launch" bash "$src/tests/cli/bad_input.sh" "$spall" "$src"; then
    echo "FAIL bad_input.sh on 2 ranks"; fail=1
fi
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
cd "$tmp"
base='materials:
  m: {density: 1000, youngs_modulus: 1.0e9, poisson_ratio: 0.3333333333333333, failure_strain: 0.05}
lattice: {type: triangular, spacing: 0.001}
geometry:
  plate: {box: {min: [0, 0], max: [0.01, 0.01]}}
body: {geometry: plate, material: m}
run: {steps: 5}
'
refused() { # name deck-text expected-substring
    printf '%s' "$2" > deck.yaml
    rm -rf out
    $launch "$spall" run deck.yaml -o out >stdout.txt 2>stderr.txt
    local rc=$?
    if [ $rc -ne 2 ] || [ -e out ] || [ "$(wc -l < stderr.txt)" -ne 1 ] ||
        ! grep -q -- "$3" stderr.txt; then
        echo "FAIL $1: exit $rc (expected 2), out $( [ -e out ] && echo exists || echo absent)"
        cat stderr.txt; fail=1
    fi
}
$launch "$spall" penetrate --help >stdout.txt 2>stderr.txt; rc=$?
if [ $rc -ne 2 ] || [ "$(wc -l < stderr.txt)" -ne 1 ] || ! grep -q "does not run distributed" stderr.txt; then
    echo "FAIL penetrate on 2 ranks: exit $rc"; cat stderr.txt; fail=1
fi
# one rank's instability stops both: one message, exit 3, output kept
cat > unstable.yaml <<'YAML'
model: {type: lattice}
materials:
  m: {density: 1000, youngs_modulus: 1.0e9, poisson_ratio: 0.3333333333333333, failure_strain: 10}
lattice: {type: triangular, spacing: 0.001}
geometry:
  plate: {box: {min: [0, 0], max: [0.02, 0.02]}}
body: {geometry: plate, material: m}
groups:
  left: {box: {min: [-1, -1], max: [0.0006, 1]}}
boundary_conditions:
  - {group: left, type: velocity, components: [x], value: 1.0}
run: {steps: 400, dt: 2.0e-6, dt_override: true}
output: {field_every: 1, history_every: 1}
YAML
"$spall" run unstable.yaml -o serial --quiet >/dev/null 2>serial_err.txt
$launch "$spall" run unstable.yaml -o ranks >stdout.txt 2>stderr.txt; rc=$?
if [ $rc -ne 3 ] || [ "$(grep -c '^spall: error' stderr.txt)" -ne 1 ] ||
    ! grep -q "unstable at step [0-9]*, t = .* particle [0-9]* (id [0-9]*)" stderr.txt; then
    echo "FAIL unstable on 2 ranks: exit $rc"; cat stderr.txt; fail=1
fi
# the same step, time and particle as one rank
if ! diff <(grep '^spall: error' serial_err.txt) <(grep '^spall: error' stderr.txt); then
    echo "FAIL unstable: message differs from one rank"; fail=1
fi
if ! cmp -s serial/history.csv ranks/history.csv; then echo "FAIL unstable: history differs"; fail=1; fi
if ! grep -q "status: FAILED" ranks/run.log; then echo "FAIL unstable: run.log lacks the failure"; fail=1; fi
[ $fail -eq 0 ] && echo "mpi_errors: all passed"
[ $fail -eq 0 ]
