#!/usr/bin/env bash
# `spall calibrate` (issue 24 item 5): the deck form prints exactly the
# summary that run.log of the same deck starts with (so its time step is the
# run's); the SPH form's time step equals a run's of the same material and
# spacing; the PD form takes --rho and --plane and its time step is a run's;
# every model has a form and a --help; unknown options and models are named.
# Usage: calibrate.sh SPALL SRC
set -u
spall="$1"
src="$2"
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
cd "$tmp"
fail=0
bad() { echo "FAIL $*"; fail=1; }
summary() { # the lines from "model:" to the end of model_constants
    awk '/^model: /{on=1} /^deck_echo:/{on=0} on' "$1"
}

# 1. deck form == run.log header, for a PD and an SPH example
for deck in pd_kalthoff/pd_kalthoff.yaml sph_plate/sph_plate.yaml; do
    name=$(basename "$deck" .yaml)
    "$spall" calibrate "$src/examples/$deck" > cal_$name.txt 2> err.txt || bad "$name: calibrate exit $?"
    "$spall" run "$src/examples/$deck" -o run_$name --quiet > /dev/null 2>&1 &
    pid=$!
    for _ in $(seq 1 100); do # run.log is written before step 1: wait for it, then stop
        [ -s run_$name/run.log ] && grep -q '^deck_echo:' run_$name/run.log && break
        sleep 0.1
    done
    kill "$pid" 2> /dev/null
    wait "$pid" 2> /dev/null
    summary cal_$name.txt > a.txt
    summary run_$name/run.log > b.txt
    [ -s a.txt ] || bad "$name: calibrate printed no summary"
    grep -q '^dt: ' a.txt || bad "$name: no dt line"
    cmp -s a.txt b.txt || { bad "$name: calibrate summary differs from run.log"; diff a.txt b.txt | head; }
    [ -e "$src/examples/${deck%/*}/run.log" ] && bad "$name: calibrate wrote into the example"
done
grep -q 'material rubber: E = 2e+06 Pa' cal_sph_plate.txt || bad "sph: materials not named in constants"

# 2. SPH form: time step equals that of a run of the same block
"$spall" calibrate sph --E 2e6 --nu 0.3975 --rho 1000 --spacing 2e-3 --kernel cubic_spline \
    > sph_form.txt || bad "sph form exit $?"
cat > block.yaml <<'YAML'
title: block
model: {type: sph, kernel: cubic_spline, h_factor: 1.5, plane: strain}
materials: {rubber: {density: 1000, youngs_modulus: 2.0e6, poisson_ratio: 0.3975}}
lattice: {type: square, spacing: 2.0e-3, origin: [0.001, 0.001]}
body: {geometry: {box: {min: [0, 0], max: [0.04, 0.04]}}, material: rubber}
run: {steps: 3}
YAML
"$spall" run block.yaml -o block --quiet > /dev/null 2>&1 || bad "block run exit $?"
dt_form=$(grep '^dt: ' sph_form.txt | awk '{print $2}')
dt_run=$(grep '^dt: ' block/run.log | awk '{print $2}')
[ -n "$dt_form" ] && [ "$dt_form" = "$dt_run" ] || bad "sph form dt '$dt_form' != run dt '$dt_run'"
grep -q 'c0 = 64.855 m/s' sph_form.txt || bad "sph form: c0"
grep -q '^energy_balance_final: .*(no energy put in)' block/run.log || bad "run.log: balance at rest"
"$spall" run "$src/examples/wave_1d_velocity/wave_1d_velocity.yaml" -o wave --quiet > /dev/null 2>&1 ||
    bad "wave run exit $?"
grep -Eq '^energy_balance_final: .* J \(input .* J; [0-9.e+-]+ % of the input\)' wave/run.log ||
    bad "run.log: energy balance as a fraction of the input"

# 3. PD form: --rho and --plane reach the built plate; dt is a run's
"$spall" calibrate peridynamics --E 1.9e11 --rho 8000 --plane strain > pd_form.txt || bad "pd form exit $?"
grep -q 'density 8000 kg/m^3' pd_form.txt || bad "pd form: density not used"
grep -q 'plane strain' pd_form.txt || bad "pd form: plane strain not used"
cat > pdblock.yaml <<'YAML'
model: {type: peridynamics, variant: pmb, horizon_factor: 3.015, plane: plane_strain}
materials: {m: {density: 8000, youngs_modulus: 1.9e11}}
lattice: {type: square, spacing: 0.001, thickness: 0.001}
geometry: {p: {box: {min: [0, 0], max: [0.0205, 0.0205]}}}
body: {geometry: p, material: m}
run: {steps: 1}
YAML
"$spall" run pdblock.yaml -o pdblock --quiet > /dev/null 2>&1 || bad "pd block run exit $?"
dt_form=$(grep '^dt: ' pd_form.txt | awk '{print $2}')
dt_run=$(grep '^dt: ' pdblock/run.log | awk '{print $2}')
[ -n "$dt_form" ] && [ "$dt_form" = "$dt_run" ] || bad "pd form dt '$dt_form' != run dt '$dt_run'"

# 4. help and errors
"$spall" calibrate --help > help.txt || bad "calibrate --help exit $?"
for m in lattice peridynamics macroparticle sph DECK.yaml; do
    grep -q "spall calibrate $m" help.txt || bad "--help does not list $m"
    [ "$m" = DECK.yaml ] && continue
    "$spall" calibrate $m --help > h_$m.txt 2>&1 || bad "$m --help exit $?"
    grep -q "usage: spall calibrate $m" h_$m.txt || bad "$m --help is not its own usage"
done
expect() { # name expected-exit pattern cmd...
    local name=$1 code=$2 pat=$3
    shift 3
    "$@" > out.txt 2> err.txt
    local rc=$?
    [ $rc -eq "$code" ] || bad "$name: exit $rc, expected $code"
    grep -q -- "$pat" err.txt || { bad "$name: message"; cat err.txt; }
}
expect pd_unknown 2 "unknown option '--bogus'" "$spall" calibrate peridynamics --E 1e9 --bogus 1
expect pd_plane 2 "--plane must be stress or strain" "$spall" calibrate peridynamics --E 1e9 --plane x
expect sph_unknown 2 "unknown option '--bogus'" "$spall" calibrate sph --bogus 1
expect sph_missing 2 "--E, --nu, --rho and --spacing are required" "$spall" calibrate sph --E 1e9
expect sph_units 2 "density = 1.1 kg/m^3 is outside" \
    "$spall" calibrate sph --E 2e6 --nu 0.3 --rho 1.1 --spacing 1e-3
expect sph_kernel 2 "kernel" "$spall" calibrate sph --E 2e6 --nu 0.3 --rho 1000 --spacing 1e-3 --kernel foo
expect model 2 "unknown model 'solid'" "$spall" calibrate solid
printf 'model: {type: lattice}\nmaterials: {m: {density: 1000, youngs_modulus: 1e9, poisson_ratio: 0.3333333333333333, failure_strain: 0.01}}\nlattice: {type: triangular, spacing: 0.001}\nbody: {geometry: {box: {min: [0, 0], max: [0.01, 0.01]}}, material: m}\nrun: {end_tme: 1e-6}\n' > typo.yaml
expect deck_typo 2 "typo.yaml:5:7" "$spall" calibrate typo.yaml
expect deck_missing 2 "no_such.yaml" "$spall" calibrate no_such.yaml
exit $fail
