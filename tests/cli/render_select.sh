#!/usr/bin/env bash
# spall render picks a field the run has, lists the fields on error, names
# tensor components and slices 3D runs along any axis (issue 24 item 4).
# Usage: render_select.sh SPALL SRC
set -u
spall="$1"
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
cd "$tmp"
fail=0
ok() { # name args...: render must succeed and print the PNG it wrote
    local name="$1"
    shift
    if ! "$spall" render "$@" >stdout.txt 2>stderr.txt; then
        echo "FAIL $name: exit $?"; cat stderr.txt; fail=1; return
    fi
    local png
    png=$(tail -n 1 stdout.txt)
    if [ ! -s "$png" ]; then echo "FAIL $name: no picture $png"; fail=1; fi
    echo "$png"
}
bad() { # name pattern args...: exit 2 with the pattern
    local name="$1" pat="$2"
    shift 2
    "$spall" render "$@" >stdout.txt 2>stderr.txt
    local rc=$?
    if [ $rc -ne 2 ]; then echo "FAIL $name: exit $rc, expected 2"; cat stderr.txt; fail=1; fi
    if ! grep -q -- "$pat" stderr.txt; then echo "FAIL $name: /$pat/"; cat stderr.txt; fail=1; fi
}
# a 3D SPH block: writes density, velocity, stress, ... but no fracture_density
cat > sph3.yaml <<YAML
model: {type: sph}
materials:
  m: {density: 2700, youngs_modulus: 70.0e9, poisson_ratio: 0.3}
lattice: {type: sc, spacing: 0.001}
geometry:
  block: {box: {min: [0, 0, 0], max: [0.006, 0.004, 0.008]}}
body: {geometry: block, material: m}
initial_velocity: [{group: all, value: [0, 0, -10]}]
run: {steps: 3}
output: {fields: [velocity, deviatoric_stress, density]}
YAML
if ! "$spall" run sph3.yaml -o sph3 --quiet 2>stderr.txt; then echo "FAIL sph3 run"; cat stderr.txt; exit 1; fi
# 1. the default field is one the run has (velocity, not fracture_density)
png=$(ok default sph3)
case "$png" in */velocity_*.png) ;; *) echo "FAIL default: picked $png"; fail=1 ;; esac
# 2. an unknown field lists the fields the frame holds
bad unknown "has no field 'fracture_density'; this run wrote: .*density.*deviatoric_stress.*velocity" \
    sph3 --field fracture_density
# 3. tensor components by name: xy, its alias yx, zz
ok stress_xy sph3 --field deviatoric_stress --component xy -o s_xy.png >/dev/null
ok stress_yx sph3 --field deviatoric_stress --component yx -o s_yx.png >/dev/null
ok stress_zz sph3 --field deviatoric_stress --component zz -o s_zz.png >/dev/null
# 4. a component the field lacks names the valid ones
bad comp_bad "field 'velocity' has 3 component(s), a vector: x, y, z or mag" \
    sph3 --field velocity --component xy
# 5. slices along x, y (at a value) and z
ok slice_x sph3 --field density --slice x -o sx.png >/dev/null
ok slice_y sph3 --field density --slice y=0.002 -o sy.png >/dev/null
ok slice_z sph3 --field density --slice z -o sz.png >/dev/null
bad slice_bad "slice needs x, y or z" sph3 --slice w
bad slice_far "no particle within 0.6 spacing of the slice y = 1 m" sph3 --slice y=1
# 6. a 2D PD run: damage by default; a 2D tensor has xx, yy, xy
cat > pd2.yaml <<YAML
model: {type: peridynamics}
materials:
  m: {density: 2000, youngs_modulus: 1.0e9, critical_stretch: 0.5}
lattice: {type: square, spacing: 0.001}
geometry:
  plate: {box: {min: [0, 0], max: [0.008, 0.008]}}
body: {geometry: plate, material: m}
run: {steps: 2}
YAML
if ! "$spall" run pd2.yaml -o pd2 --quiet 2>stderr.txt; then echo "FAIL pd2 run"; cat stderr.txt; exit 1; fi
png=$(ok pd_default pd2)
case "$png" in */damage_*.png) ;; *) echo "FAIL pd default: picked $png"; fail=1 ;; esac
bad pd_slice "is a 2D run: there is no slice" pd2 --slice x
ok pd_stress_xy pd2 --field stress --component xy -o pd_xy.png >/dev/null
# a 2D symmetric tensor is written as a Tensor6 (zz = yz = xz = 0: the virial of
# in-plane bonds), so that ParaView names its components; zz is there, xy is column 3
ok pd_stress_zz pd2 --field stress --component zz -o pd_zz.png >/dev/null
bad pd_stress_zw "field 'stress' has 6 component(s), a symmetric tensor: xx, yy, zz, xy, yz, xz or mag" \
    pd2 --field stress --component zw
[ $fail -eq 0 ] && echo "render_select: all cases pass"
exit $fail
