#!/usr/bin/env bash
# Batch runs are not mute (issue 24 item 3): with stderr not a terminal,
# one progress line per interval (step, time, %, rate, ETA, energy balance as
# a fraction of the energy put in); SIGINT and SIGTERM leave a status line in
# run.log (and a checkpoint, exit 75).  Usage: batch_progress.sh SPALL SRC
set -u
spall="$1"
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
cd "$tmp"
fail=0
# a plate hit at 1 m/s, long enough for a few lines at 0.2 s
cat > deck.yaml <<YAML
model: {type: lattice}
materials:
  m: {density: 1100, youngs_modulus: 3.26e9, poisson_ratio: 0.3333333333333333,
      tensile_strength: 62.86e6}
lattice: {type: triangular, spacing: 0.0005}
geometry:
  plate: {box: {min: [0, 0], max: [0.02, 0.02]}}
body: {geometry: plate, material: m}
initial_velocity: [{group: all, value: [1.0, 0]}]
run: {steps: 200000}
output: {field_every: 100000}
YAML
# 1. lines at the interval, each with every item, stderr a file
timeout --preserve-status -s TERM 2 "$spall" run deck.yaml -o out_p --progress-every 0.2 \
    --threads 1 >stdout.txt 2>stderr.txt
rc=$?
n=$(grep -c "^spall: progress: step [0-9]*/200000, t = .* s (.* %), .* particle-steps/s, ETA [0-9:]*, energy balance .* of the energy put in$" stderr.txt)
if [ "$n" -lt 2 ]; then echo "FAIL progress: $n lines"; cat stderr.txt; fail=1; fi
if grep -q $'\r' stderr.txt; then echo "FAIL progress: carriage return in a batch log"; fail=1; fi
# 2. SIGTERM: exit 75, a status line in run.log naming the signal and the checkpoint
if [ $rc -ne 75 ]; then echo "FAIL sigterm: exit $rc, expected 75"; cat stderr.txt; fail=1; fi
if ! grep -q "^status: interrupted by signal 15 at step [0-9]*, t = .*; checkpoint .*checkpoint_" out_p/run.log; then
    echo "FAIL sigterm: no status line"; tail -3 out_p/run.log; fail=1
fi
# 3. SIGINT the same
timeout --preserve-status -s INT 2 "$spall" run deck.yaml -o out_i --threads 1 >stdout.txt 2>stderr.txt
rc=$?
if [ $rc -ne 75 ]; then echo "FAIL sigint: exit $rc, expected 75"; cat stderr.txt; fail=1; fi
if ! grep -q "^status: interrupted by signal 2 at step" out_i/run.log; then
    echo "FAIL sigint: no status line"; tail -3 out_i/run.log; fail=1
fi
# 4. --no-progress: no lines
timeout --preserve-status -s TERM 1 "$spall" run deck.yaml -o out_n --progress-every 0.2 \
    --no-progress --threads 1 >stdout.txt 2>stderr.txt
if grep -q "progress:" stderr.txt; then echo "FAIL no-progress: lines printed"; fail=1; fi
# 5. a bad interval is refused
"$spall" run deck.yaml -o out_b --progress-every 0 2>stderr.txt
rc=$?
if [ $rc -ne 2 ] || ! grep -q "progress-every needs a positive number" stderr.txt; then
    echo "FAIL bad interval: exit $rc"; cat stderr.txt; fail=1
fi
[ $fail -eq 0 ] && echo "batch_progress: all cases pass"
exit $fail
