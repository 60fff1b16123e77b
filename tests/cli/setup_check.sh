#!/usr/bin/env bash
# Unit slips in material constants are refused before step 0 (issue 24
# item 1): exit 2, the message names file:line:column, the key and the
# likely cause, and nothing is written.  Usage: setup_check.sh SPALL SRC
set -u
spall="$1"
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
cd "$tmp"
deck() { # density E strength -> deck.yaml
    cat > "$1" <<YAML
model: {type: lattice}
materials:
  epoxy: {density: $2, youngs_modulus: $3, poisson_ratio: 0.3333333333333333,
          tensile_strength: $4}
lattice: {type: triangular, spacing: 0.001}
geometry:
  plate: {box: {min: [0, 0], max: [0.01, 0.01]}}
body: {geometry: plate, material: epoxy}
run: {end_time: 1.0e-6}
YAML
}
fail=0
refused() { # name deck pattern
    "$spall" run "$2" -o "out_$1" >stdout.txt 2>stderr.txt
    local rc=$?
    if [ $rc -ne 2 ]; then echo "FAIL $1: exit $rc, expected 2"; cat stderr.txt; fail=1; fi
    if ! grep -q "$3" stderr.txt; then echo "FAIL $1: message"; cat stderr.txt; fail=1; fi
    if [ -e "out_$1" ]; then echo "FAIL $1: output written"; fail=1; fi
}
deck rho_gcc.yaml 1.1 3.26e9 62.86e6
refused rho_gcc rho_gcc.yaml "rho_gcc.yaml:3:20: material 'epoxy': density = 1.1 kg/m^3 is outside .*g/cm^3"
deck e_gpa.yaml 1100 3.26 62.86e6
refused e_gpa e_gpa.yaml "e_gpa.yaml:3:42: material 'epoxy': youngs_modulus = 3.26 Pa .*GPa"
deck s_mpa.yaml 1100 3.26e9 62.86
refused s_mpa s_mpa.yaml "s_mpa.yaml:4:29: material 'epoxy': tensile_strength = 62.86 Pa .*MPa"
deck e_big.yaml 1100 3.26e15 62.86e6
refused e_big e_big.yaml "youngs_modulus = 3.26e+15 Pa is outside"
# the same deck in SI runs
deck ok.yaml 1100 3.26e9 62.86e6
if ! "$spall" run ok.yaml -o out_ok --quiet 2>stderr.txt; then echo "FAIL ok: refused"; cat stderr.txt; fail=1; fi
[ $fail -eq 0 ] && echo "setup_check: all cases pass"
exit $fail
