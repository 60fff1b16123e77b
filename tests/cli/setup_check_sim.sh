#!/usr/bin/env bash
# Set-ups that cannot be right are refused before step 0 (issue 24 item 1):
# impactors inside a body, walls and symmetry planes through it, probes off
# every body, groups emptied by the spacing, a large initial strain energy,
# a run far beyond the machine; each refusal exits 2 with file:line:column,
# the likely cause and the run.allow name, and writes nothing; run.allow
# (and --yes for the cost) lets the run go on.  Usage: setup_check_sim.sh SPALL SRC
set -u
spall="$1"
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
cd "$tmp"
fail=0
refused() { # name pattern [extra args]: deck NAME.yaml must be refused
    local name="$1" pat="$2"
    shift 2
    "$spall" run "$name.yaml" -o "out_$name" "$@" >stdout.txt 2>stderr.txt
    local rc=$?
    if [ $rc -ne 2 ]; then echo "FAIL $name: exit $rc, expected 2"; cat stderr.txt; fail=1; fi
    if ! grep -q -- "$pat" stderr.txt; then
        echo "FAIL $name: message, expected /$pat/"; cat stderr.txt; fail=1
    fi
    if [ "$(wc -l < stderr.txt)" -ne 1 ]; then echo "FAIL $name: not one line"; fail=1; fi
    if [ -e "out_$name" ]; then echo "FAIL $name: output written"; fail=1; fi
}
runs() { # name [pattern on stderr]: deck NAME.yaml must run to the end
    local name="$1" pat="${2:-}"
    if ! OMP_NUM_THREADS=1 "$spall" run "$name.yaml" -o "out_$name" --quiet 2>stderr.txt; then
        echo "FAIL $name: refused"; cat stderr.txt; fail=1; return
    fi
    if [ -n "$pat" ] && ! grep -q -- "$pat" stderr.txt; then
        echo "FAIL $name: stderr, expected /$pat/"; cat stderr.txt; fail=1
    fi
    if [ -z "$pat" ] && grep -q "warning" stderr.txt; then
        echo "FAIL $name: unexpected warning"; cat stderr.txt; fail=1
    fi
}

# a 2D lattice plate 10 x 10 mm hit by a rigid sphere; $1 = sphere y, $2 = extra
lattice() {
    cat > "$1.yaml" <<YAML
model: {type: lattice}
materials:
  m: {density: 1100, youngs_modulus: 3.26e9, poisson_ratio: 0.3333333333333333,
      tensile_strength: 62.86e6}
lattice: {type: triangular, spacing: 0.001}
geometry:
  plate: {box: {min: [0, 0], max: [0.01, 0.01]}}
body: {geometry: plate, material: m}
impactors:
  - {name: ball, shape: sphere, position: [0.005, $2], radius: 0.002, mass: 0.01,
     velocity: [0, -10]}
run: {end_time: 2.0e-6${3:-}}
${4:-}
YAML
}
# 1. the sphere's centre 1 mm inside the plate's top row: the user's "exit 3 at step 3"
lattice overlap 0.0095
refused overlap "overlap.yaml:10:33: impactor 'ball' starts inside the body: .* particle(s) within its contact surface.*likely cause: its position or radius.*run.allow: \[overlap\]"
# 2. the same, allowed: the run goes on (it would be an unstable run, so one step)
lattice overlap_allowed 0.0095 ", allow: [overlap, initial_strain]"
sed -i 's/end_time: 2.0e-6/steps: 1/' overlap_allowed.yaml
runs overlap_allowed
# 3. the sphere clear of the plate: runs, no warning
lattice clear 0.0125
runs clear
# 4. a rigid wall impactor on the plate's face with the particles' half-spacing offset
cat > wall_impactor.yaml <<YAML
model: {type: lattice}
materials:
  m: {density: 1100, youngs_modulus: 3.26e9, poisson_ratio: 0.3333333333333333,
      tensile_strength: 62.86e6}
lattice: {type: triangular, spacing: 0.001}
geometry:
  plate: {box: {min: [0, 0], max: [0.01, 0.01]}}
body: {geometry: plate, material: m}
impactors:
  - {name: floor, shape: wall, position: [0, 0], normal: [0, 1], contact_offset: 0.0005}
initial_velocity: [{group: all, value: [0, -1]}]
run: {end_time: 2.0e-6}
YAML
refused wall_impactor "wall_impactor.yaml:10:32: impactor 'floor' starts inside the body.*its position or normal.*run.allow: \[wall\]"

# SPH: a 2D block above a wall; $1 name, $2 wall y, $3 model extra, $4 box min, $5 run extra
sph() {
    cat > "$1.yaml" <<YAML
model: {type: sph, wall: {point: [0, $2], normal: [0, 1]}$3}
materials:
  m: {density: 2700, youngs_modulus: 70.0e9, poisson_ratio: 0.3}
lattice: {type: square, spacing: 0.001, origin: [0.0005, 0.0005]}
geometry:
  block: {box: {min: [$4, 0], max: [0.01, 0.01]}}
body: {geometry: block, material: m}
initial_velocity: [{group: all, value: [0, -10]}]
run: {end_time: 1.0e-6$5}
YAML
}
# 5. model.wall on the body's face (the user's 71 J of strain energy against 1.97 J)
sph sph_wall_face 0.0005 "" 0 ""
refused sph_wall_face "sph_wall_face.yaml:1:27: model.wall cuts the body: .* closer than dx/2 = 0.0005 m.*wall placed on the body's face.*run.allow: \[wall\]"
# 6. allowed, the same set-up starts with the strain energy that check measures
sph sph_wall_strain 0.0005 "" 0 ", allow: [wall]"
refused sph_wall_strain "sph_wall_strain.yaml:9:1: the set-up starts with .* J of strain energy, .* times the .* J of kinetic energy.*run.allow: \[initial_strain\]"
# 7. the wall dx/2 below the particles (its surface on theirs): runs
sph sph_wall_ok 0 "" 0 ""
runs sph_wall_ok
# 8. a symmetry plane x = 0 through the body (the user's 25 % energy error)
sph sph_sym_cut -1 ", symmetry: x" -0.005 ""
refused sph_sym_cut "sph_sym_cut.yaml:1:60: symmetry plane x = 0 cuts the body: .* on or behind it.*intersect it with a box from x = 0.*run.allow: \[symmetry\]"
# 9. the body on the positive side, dx/2 off the plane: runs
sph sph_sym_ok -1 ", symmetry: x" 0 ""
runs sph_sym_ok

# 10. a probe 1 m outside the plate
lattice probe_far 0.0125 "" "probes: [{name: tip, position: [1.005, 0.005]}]"
refused probe_far "probe_far.yaml:13:22: probe 'tip' is outside every body: its nearest particle is 0.995 m away.*run.allow: \[probe\]"
# 11. run.allow: probe lets it run (and says nothing)
lattice probe_allowed 0.0125 ", allow: probe" "probes: [{name: tip, position: [1.005, 0.005]}]"
runs probe_allowed
# 12. a probe within a spacing of a particle: runs
lattice probe_near 0.0125 "" "probes: [{name: tip, position: [0.0051, 0.0099]}]"
runs probe_near

# 13. a group emptied by the spacing (given in mm: 1 instead of 0.001)
cat > group_mm.yaml <<YAML
model: {type: lattice}
materials:
  m: {density: 1100, youngs_modulus: 3.26e9, poisson_ratio: 0.3333333333333333,
      tensile_strength: 62.86e6}
lattice: {type: triangular, spacing: 0.001}
geometry:
  plate: {box: {min: [0, 0], max: [0.01, 0.01]}}
body: {geometry: plate, material: m}
groups:
  top: {box: {min: [0, 0.0096], max: [0.01, 0.0099]}}
boundary_conditions:
  - {group: top, type: velocity, components: [y], value: 1.0}
run: {end_time: 1.0e-6}
YAML
refused group_mm "group_mm.yaml:10:3: group 'top' contains no particle; likely cause: its region is 0.0003 m wide along y, less than the lattice spacing 0.001 m"

# 14. an unknown run.allow name is refused with the list
lattice allow_bad 0.0125 ", allow: [overlaps]"
refused allow_bad "allow_bad.yaml:12:33: run.allow: unknown check 'overlaps'; expected one of: overlap, wall"

# cost: 1.2e5 particles x 1e8 steps would take far beyond a day
cat > big.yaml <<YAML
model: {type: lattice}
materials:
  m: {density: 1100, youngs_modulus: 3.26e9, poisson_ratio: 0.3333333333333333,
      tensile_strength: 62.86e6}
lattice: {type: triangular, spacing: 0.0001}
geometry:
  plate: {box: {min: [0, 0], max: [0.03, 0.04]}}
body: {geometry: plate, material: m}
run: {steps: 100000000}
output: {field_every: 100000000}
YAML
# 15. refused at run, with the estimate
refused big "big.yaml:9:1: the run needs 1.39e+13 particle-steps (.* particles x 100000000 steps = .*; output about .*), far beyond a day"
# 16. --yes starts it (stopped here by SIGINT: exit 75, run.log has the estimate)
timeout --preserve-status -s INT 3 "$spall" run big.yaml -o out_big_yes --yes --quiet 2>stderr.txt
rc=$?
if [ $rc -ne 75 ]; then echo "FAIL big --yes: exit $rc, expected 75"; cat stderr.txt; fail=1; fi
if ! grep -q "^setup_estimate: .* particles x 100000000 steps" out_big_yes/run.log; then
    echo "FAIL big --yes: no setup_estimate in run.log"; fail=1
fi
# 17. an output that cannot fit on any disk (a frame every step)
sed 's/field_every: 100000000/field_every: 1/; s/steps: 100000000/steps: 10000000/' big.yaml > disk.yaml
refused disk "disk.yaml:10:1: the run would write about .* TB, more than the .* free where it writes"
# 18. a large run is a warning: it runs (stopped here by SIGINT)
sed 's/steps: 100000000/steps: 1000000/' big.yaml > large.yaml
timeout --preserve-status -s INT 3 "$spall" run large.yaml -o out_large --quiet 2>stderr.txt
if ! grep -q "spall: warning: large.yaml:9:1: a large run: .* particles x 1000000 steps.*run.allow: \[cost\]" stderr.txt; then
    echo "FAIL large: no warning"; cat stderr.txt; fail=1
fi
if ! grep -q "^setup_warning: large.yaml:9:1: a large run" out_large/run.log; then
    echo "FAIL large: no setup_warning in run.log"; fail=1
fi

[ $fail -eq 0 ] && echo "setup_check_sim: all cases pass"
exit $fail
