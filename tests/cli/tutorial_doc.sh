#!/usr/bin/env bash
# docs/tutorial.md runs as written: its yaml block is saved as notch.yaml and
# its sh blocks run in order with `set -e`; then what the page says the user
# will see is checked against the run.  Usage: tutorial_doc.sh SPALL SRC
set -u
spall="$1"
src="$2"
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
cd "$tmp"
doc="$src/docs/tutorial.md"
fail=0
ko() { echo "FAIL $*"; fail=1; }
awk '/^```yaml$/{on=1; next} /^```$/{if(on){exit}} on' "$doc" > notch.yaml
awk '/^```sh$/{on=1; next} /^```$/{on=0} on' "$doc" > tutorial.sh
[ -s notch.yaml ] && [ -s tutorial.sh ] || { echo "FAIL: no deck or commands in $doc"; exit 1; }
mkdir bin
ln -s "$spall" bin/spall
PATH="$tmp/bin:$PATH" bash -e -x tutorial.sh > out.txt 2>&1 || { cat out.txt; echo "FAIL: the commands"; exit 1; }
# "972 particles, 2788 bonds, a time step of 0.18 us, 1376 steps"
grep -q "^particles: 972$" constants.txt || ko "calibrate: particles"
grep -q "^interactions: 2788$" constants.txt || ko "calibrate: bonds"
grep -q "^dt: 1.818.*e-07 s" constants.txt || ko "calibrate: dt"
grep -q "^steps: 1376$" constants.txt || ko "calibrate: steps"
grep -q "^particles: 972$" notch/run.log || ko "run.log: particles differ from calibrate"
for f in crack uy history tip fragment_distribution; do
    [ "$(head -c 4 notch/$f.png | tail -c 3)" = "PNG" ] || ko "notch/$f.png"
done
# "rises to about 1.7 kN; the first bond breaks at about 0.12 ms"
grep -q "^first broken bond at t = 0.0001[12]" out.txt || { ko "first break time"; grep first out.txt; }
grep -q "^peak grip force 1[67][0-9][0-9]\." out.txt || { ko "peak force"; grep peak out.txt; }
# "about 0.3 % of the work put in"
grep -q "^energy_balance_final: .*(input .* J; 0\.[2-4][0-9]* % of the input)" notch/run.log ||
    { ko "energy balance"; grep energy_balance_final notch/run.log; }
# "one piece of 968 particles and three particles have flown off"
[ "$(grep -vc '^#' notch/fragments.csv)" -eq 5 ] || ko "fragments.csv: 4 pieces"
grep -q "^0,968," notch/fragments.csv || ko "fragments.csv: the joined halves"
[ $fail -eq 0 ] && echo "tutorial_doc: ok"
exit $fail
