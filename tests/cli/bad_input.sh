#!/usr/bin/env bash
# The CLI turns bad input into one line naming file:line:column, exit status
# 2, and leaves no output directory behind.  Usage: bad_input.sh SPALL SRC
# SPALL_LAUNCH (environment) prefixes every run, e.g. "mpirun -q -np 2"
# (tests/cli/mpi_errors.sh: the same cases on two MPI ranks).
set -u
spall="$1"
src="$2"
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
cd "$tmp"
fail=0
pass=0
check() { # name deck-text expected-substring
    local name="$1" text="$2" expect="$3"
    printf '%s' "$text" > deck.yaml
    rm -rf out
    ${SPALL_LAUNCH:-} "$spall" run deck.yaml -o out >stdout.txt 2>stderr.txt
    local rc=$?
    local lines
    lines=$(wc -l < stderr.txt)
    if [ "$rc" -ne 2 ]; then echo "FAIL $name: exit $rc, expected 2"; cat stderr.txt; fail=$((fail+1)); return; fi
    if [ -e out ]; then echo "FAIL $name: output directory was created"; fail=$((fail+1)); return; fi
    if [ "$lines" -ne 1 ]; then echo "FAIL $name: $lines lines on stderr, expected 1"; cat stderr.txt; fail=$((fail+1)); return; fi
    if ! grep -Eq "deck\.yaml:[0-9]+:[0-9]+: " stderr.txt; then echo "FAIL $name: no file:line:column"; cat stderr.txt; fail=$((fail+1)); return; fi
    if ! grep -q -- "$expect" stderr.txt; then echo "FAIL $name: message lacks '$expect'"; cat stderr.txt; fail=$((fail+1)); return; fi
    pass=$((pass+1))
}
base='model: {type: lattice}
materials:
  m: {density: 1000, youngs_modulus: 1.0e9, poisson_ratio: 0.3333333333333333, failure_strain: 0.05}
lattice: {type: triangular, spacing: 0.001}
geometry:
  plate: {box: {min: [0, 0], max: [0.01, 0.01]}}
body: {geometry: plate, material: m}
'
check "syntax" "${base}run: {steps: [10}
" "syntax"
check "unknown key" "${base}run: {steps: 10, stpes: 3}
" "unknown key 'stpes'"
check "wrong type" "${base}run: {steps: many}
" "steps"
check "dt above limit" "${base}run: {steps: 10, dt: 1.0}
" "stability limit"
check "empty geometry" "$(echo "$base" | sed 's/max: \[0.01, 0.01\]/max: [0.0001, 0.0001]/; s/min: \[0, 0\]/min: [0.00002, 0.00002]/')
run: {steps: 10}
" "no lattice site"

# Found by scripts/fuzz_decks.py (docs/decks.md, "Deck fuzzing"):
# a spacing typo asking for ~1.2e8 particles is refused before allocating
check "huge particle count" "$(echo "$base" | sed 's/spacing: 0.001/spacing: 1.0e-6/')
run: {steps: 10}
" "more than the limit of 1e+07 (run.max_particles)"
check "run.max_particles" "${base}run: {steps: 10, max_particles: 50}
" "more than the limit of 50 (run.max_particles)"
check "run.max_particles range" "${base}run: {steps: 10, max_particles: 1e10}
" "max_particles"
# a far-away circle intersected with the plate: empty bounding box (was a hang)
check "empty intersection" "$(echo "$base" | sed 's/plate: {box: {min: \[0, 0\], max: \[0.01, 0.01\]}}/plate: {intersection: [{circle: {center: [1.0e300, 0], radius: 0.005}}, {box: {min: [0, 0], max: [0.01, 0.01]}}]}/')
run: {steps: 10}
" "bounding box is empty"
# a region 1e300 m from the lattice origin (undefined (long) conversion before)
check "far from origin" "$(echo "$base" | sed 's/spacing: 0.001}/spacing: 0.001, origin: [1.0e300, 0]}/')
run: {steps: 10}
" "lattice steps from the lattice origin"
check "faster than light" "${base}initial_velocity: [{group: all, value: [1.0e300, 0]}]
run: {steps: 10}
" "not below the speed of light"
sph='model: {type: sph, kernel: cubic_spline, plane: strain, clamp: {group: clamp, point: [0, 0], normal: [1, 0]}}
materials:
  r: {density: 1000, youngs_modulus: 2.0e6, poisson_ratio: 0.3975}
lattice: {type: square, spacing: 2.0e-3, origin: [0.001, 0.001], thickness: 1.0}
body: {geometry: {box: {min: [-0.01, -0.01], max: [0.04, 0.01]}}, material: r}
groups:
  clamp: {box: {min: [-1, -1], max: [0.0, 1]}}
run: {steps: 2}
'
# a model's set-up refusal ("model.clamp: ...") points at that key (no position before)
check "sph clamp without fixed bc" "$sph" "model.clamp: group 'clamp' needs a fixed boundary"
# a refusal of the model's set-up without a key of its own points at 'model'
check "sph no stable step" "$(echo "$sph" | sed 's/density: 1000,/density: 1000, eos: mie_gruneisen, sound_speed: 1.0e300, hugoniot_slope: 1.5, gruneisen: 2,/')
boundary_conditions: [{group: clamp, type: fixed}]
" "no finite stable time step"
# an unknown output field: positioned, cut short, and refused before the
# output directory exists (was: no position, after creating the directory)
check "unknown output field" "${base}run: {steps: 10}
output: {fields: [velocity, $(printf 'x%.0s' $(seq 300))]}
" "unknown output field 'xxxx"
# a 3000-character unknown name is quoted cut short (was: a 1 kB line)
check "long unknown name" "$(echo "$base" | sed "s/body: {geometry: plate/body: {geometry: $(printf 'x%.0s' $(seq 3000))/")
run: {steps: 10}
" "unknown geometry 'xxxx"
if [ "$(wc -c < stderr.txt)" -gt 300 ]; then echo "FAIL long unknown name: $(wc -c < stderr.txt) bytes"; fail=$((fail+1)); fi

# a missing deck file: one line, exit 2
${SPALL_LAUNCH:-} "$spall" run missing.yaml -o out2 2>stderr.txt; rc=$?
if [ $rc -ne 2 ] || [ -e out2 ]; then echo "FAIL missing deck: exit $rc"; fail=$((fail+1)); else pass=$((pass+1)); fi

# existing results are never overwritten without --overwrite
printf '%s' "${base}run: {steps: 3}
" > good.yaml
if ! ${SPALL_LAUNCH:-} "$spall" run good.yaml -o res --no-progress >/dev/null 2>err.txt; then echo "FAIL good deck did not run"; cat err.txt; fail=$((fail+1)); fi
before=$(stat -c %Y res/history.csv 2>/dev/null || echo none)
${SPALL_LAUNCH:-} "$spall" run good.yaml -o res >/dev/null 2>err.txt; rc=$?
if [ $rc -ne 2 ] || ! grep -q -- "--overwrite" err.txt; then echo "FAIL overwrite refused: exit $rc"; cat err.txt; fail=$((fail+1)); else pass=$((pass+1)); fi
if ! ${SPALL_LAUNCH:-} "$spall" run good.yaml -o res --overwrite >/dev/null 2>err.txt; then echo "FAIL --overwrite"; cat err.txt; fail=$((fail+1)); else pass=$((pass+1)); fi
[ "$before" != none ] && pass=$((pass+1))

echo "$pass passed, $fail failed"
[ $fail -eq 0 ]
