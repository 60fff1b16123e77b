#!/usr/bin/env bash
# `spall plot` and `spall fragments` (issue 23 item 4, docs/postprocessing.md)
# on a small plate torn apart: the PNGs are PNGs, the plot takes columns with
# or without their [unit] and refuses an unknown one listing the columns, the
# fragment distribution has one row per fragment of fragments.csv, heaviest
# first, its cumulative mass fraction ends at 1, and a run without
# fragments.csv is refused with the reason.  Usage: post.sh SPALL SRC
set -u
spall="$1"
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
cd "$tmp"
fail() { echo "post.sh: $*"; exit 1; }
is_png() { [ "$(head -c 8 "$1" | od -An -tx1 | tr -d ' \n')" = "89504e470d0a1a0a" ]; }
# a 2 x 1 cm plate, both ends pulled apart at 20 m/s: it breaks within 40 us
cat > tear.yaml <<YAML
model: {type: lattice}
materials:
  m: {density: 1100, youngs_modulus: 3.26e9, poisson_ratio: 0.3333333333333333,
      tensile_strength: 20.0e6}
lattice: {type: triangular, spacing: 1.0e-3}
body: {geometry: {box: {min: [0, 0], max: [0.02, 0.01]}}, material: m}
groups:
  left: {box: {min: [-1, -1], max: [0.0015, 1]}}
  right: {box: {min: [0.0185, -1], max: [1, 1]}}
boundary_conditions:
  - {group: left, type: velocity, components: [x, y], value: [-20.0, 0]}
  - {group: right, type: velocity, components: [x, y], value: [20.0, 0]}
run: {end_time: 4.0e-5}
output: {field_interval: 2.0e-5, history_every: 10}
YAML
"$spall" run tear.yaml -o run --quiet || fail "spall run failed"
[ -f run/fragments.csv ] || fail "no fragments.csv"

out="$("$spall" plot run)" || fail "spall plot run failed"
is_png run/history.png || fail "run/history.png is not a PNG"
rows=$(grep -v -c -E '^(step|#)' run/history.csv)
echo "$out" | grep -q "($rows rows)" || fail "plot reports '$out', history.csv has $rows rows"
"$spall" plot run "kinetic [J]" strain -o k.png >/dev/null || fail "columns with and without unit"
is_png k.png || fail "k.png is not a PNG"
msg="$("$spall" plot run no_such_column -o x.png 2>&1)"; rc=$?
[ $rc -eq 2 ] || fail "unknown column: exit $rc, expected 2"
echo "$msg" | grep -q "no column 'no_such_column'; its columns: step, time \[s\], kinetic \[J\]" ||
    fail "unknown column message: $msg"
[ ! -e x.png ] || fail "a refused plot wrote x.png"

"$spall" fragments run >/dev/null || fail "spall fragments failed"
csv=run/fragment_distribution.csv
is_png run/fragment_distribution.png || fail "fragment_distribution.png is not a PNG"
nfrag=$(grep -v -c -E '^(fragment_id|#)' run/fragments.csv)
ndist=$(grep -v -c -E '^(rank|#)' "$csv")
[ "$nfrag" -ge 2 ] || fail "the plate did not break ($nfrag fragment)"
[ "$nfrag" -eq "$ndist" ] || fail "$ndist distribution rows for $nfrag fragments"
awk -F, -v n="$nfrag" '
    /^(rank|#)/ { next }
    { if (NR > 0 && seen && $3 > prev) { print "not heaviest first at rank " $1; bad = 1 }
      if ($4 != $1) { print "count column " $4 " at rank " $1; bad = 1 }
      prev = $3; seen = 1; last = $5; total += $3 }
    END { if (last < 1 - 1e-9 || last > 1 + 1e-9) { print "mass fraction ends at " last; bad = 1 }
          exit bad }' "$csv" || fail "bad distribution $csv"
# the total mass equals fragments.csv's
awk -F, '/^[0-9]/ { s += $3 } END { printf "%.6e\n", s }' run/fragments.csv >a.txt
awk -F, '/^[0-9]/ { s += $3 } END { printf "%.6e\n", s }' "$csv" >b.txt
cmp -s a.txt b.txt || fail "masses differ: $(cat a.txt) vs $(cat b.txt)"

mkdir norun && cp run/history.csv norun/
msg="$("$spall" fragments norun 2>&1)"; rc=$?
[ $rc -eq 4 ] || fail "no fragments.csv: exit $rc, expected 4"
echo "$msg" | grep -q "written at the end of a run of a bonded model" || fail "message: $msg"
echo "post.sh: plot and fragments ok ($rows history rows, $nfrag fragments)"
