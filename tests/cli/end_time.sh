#!/usr/bin/env bash
# Runs end where asked (issue 24 item 2): for every model, an end_time that
# is not a whole number of steps is reached exactly (the engine shortens
# the last step), the last history row and the last frame are at end_time,
# frames requested by field_interval are at their times (the step that
# would pass one is split), and run.log reports the steps actually taken.
# Usage: end_time.sh SPALL SRC
set -u
spall="$1"
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
cd "$tmp"
fail=0
have_h5dump=0
command -v h5dump >/dev/null && have_h5dump=1

# model name, model + materials + lattice sections, geometry max corner
run_case() {
    local name="$1" head="$2" corner="$3" out="out_$1"
    cat > "$name.yaml" <<YAML
$head
geometry:
  block: {box: {min: [0, 0, 0], max: $corner}}
body: {geometry: block, material: m}
initial_velocity:
  - {group: all, value: $4}
run: {end_time: 1.0e-4}
output: {field_interval: 3.3e-5, history_every: 7}
YAML
    if ! OMP_NUM_THREADS=1 "$spall" run "$name.yaml" -o "$out" --quiet 2>stderr.txt; then
        echo "FAIL $name: run failed"; cat stderr.txt; fail=1; return
    fi
    local reached last_t steps_done n_rows
    reached=$(sed -n 's/^time_reached: \([^ ]*\) s$/\1/p' "$out/run.log")
    steps_done=$(sed -n 's/^steps_done: //p' "$out/run.log")
    last_t=$(tail -n 1 "$out/history.csv" | cut -d, -f2)
    local last_step
    last_step=$(tail -n 1 "$out/history.csv" | cut -d, -f1)
    # to rounding: |t - 1e-4| <= 1e-12 of end_time
    if ! awk -v a="$reached" -v b="$last_t" 'BEGIN { e = 1e-4; d1 = a - e; d2 = b - e;
            if (d1 < 0) d1 = -d1; if (d2 < 0) d2 = -d2;
            exit !(d1 <= 1e-16 && d2 <= 1e-16) }'; then
        echo "FAIL $name: time_reached $reached, last history time $last_t (want 1e-4)"; fail=1
    fi
    if [ "$last_step" != "$steps_done" ]; then
        echo "FAIL $name: last history step $last_step, steps_done $steps_done"; fail=1
    fi
    if [ $have_h5dump -eq 1 ]; then
        local times="" f
        for f in "$out"/fields_*.h5; do
            times="$times $(h5dump -d time "$f" | sed -n 's/^ *(0): \([0-9.e+-]*\)$/\1/p')"
        done
        # frames at 0, 3.3e-5, 6.6e-5, 9.9e-5 and the last at end_time
        if ! echo "$times" | awk '{ n = split("0 3.3e-05 6.6e-05 9.9e-05 1e-4", w, " ");
                if (NF != n) exit 1;
                for (k = 1; k <= n; k++) { d = $k - w[k]; if (d < 0) d = -d;
                    if (d > 1e-12 * 1e-4) exit 1 } }'; then
            echo "FAIL $name: frame times$times"; fail=1
        fi
    fi
    echo "$name: time_reached $reached, steps_done $steps_done"
}

run_case lattice "model: {type: lattice}
materials:
  m: {density: 1100, youngs_modulus: 3.26e9, poisson_ratio: 0.3333333333333333,
      tensile_strength: 62.86e6}
lattice: {type: triangular, spacing: 0.001}" "[0.01, 0.01]" "[1.0, 0]"
run_case peridynamics "model: {type: peridynamics}
materials:
  m: {density: 2000, youngs_modulus: 1.0e9, critical_stretch: 0.5}
lattice: {type: square, spacing: 0.001}" "[0.008, 0.008]" "[1.0, 0]"
run_case macroparticle "model: {type: macroparticle}
materials:
  m: {density: 2700, atomic_mass_u: 26.98, cohesive_energy_ev: 3.39, exponents: [4, 9]}
lattice: {type: fcc, spacing: 0.001}" "[0.004, 0.004, 0.004]" "[1.0, 0, 0]"
run_case sph "model: {type: sph}
materials:
  m: {density: 1000, youngs_modulus: 1.0e7, poisson_ratio: 0.3}
lattice: {type: square, spacing: 0.001}" "[0.008, 0.008]" "[1.0, 0]"

# a fixed-dt run with a whole number of steps (run.steps) keeps its count
cat > steps.yaml <<YAML
model: {type: lattice}
materials:
  m: {density: 1100, youngs_modulus: 3.26e9, poisson_ratio: 0.3333333333333333,
      tensile_strength: 62.86e6}
lattice: {type: triangular, spacing: 0.001}
geometry:
  block: {box: {min: [0, 0], max: [0.01, 0.01]}}
body: {geometry: block, material: m}
run: {steps: 37}
YAML
if ! "$spall" run steps.yaml -o out_steps --quiet 2>stderr.txt; then
    echo "FAIL steps: run failed"; cat stderr.txt; fail=1
elif ! grep -q "^steps_done: 37$" out_steps/run.log; then
    echo "FAIL steps: $(grep steps_done out_steps/run.log)"; fail=1
fi
[ $fail -eq 0 ] && echo "end_time: all cases pass"
exit $fail
