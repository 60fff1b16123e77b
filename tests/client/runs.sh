#!/usr/bin/env bash
# ctest client_runs (fixture of the `client` label, cmake/SpallClientTests.cmake):
# runs the epoxy demo deck (2D lattice), the 3D Taylor bar (SPH), the
# drop-weight test (2D lattice, rigid bodies) and the axisymmetric Taylor rod
# (SPH, a wall) with
# shortened end times into OUT_DIR/epoxy_holes and OUT_DIR/sph_taylor_3d, so
# that the real-client tests open a genuine `spall run` output in seconds.
# Only run.end_time (and the frame interval of the Taylor bar) change: the
# deck's fields, lattice and output layout are the demo's own.
# Usage: runs.sh SPALL SOURCE_DIR OUT_DIR
set -euo pipefail
spall="$1"; src="$2"; out="$3"
mkdir -p "$out"

short_deck() { # $1 deck, $2 copy, then sed expressions that must each match
    local deck="$1" copy="$2"; shift 2
    cp "$deck" "$copy"
    for e in "$@"; do
        grep -q -E "$(echo "$e" | sed -E 's#^s/([^/]*)/.*#\1#')" "$copy" ||
            { echo "runs.sh: '$e' does not match $deck (deck changed?)"; exit 1; }
        sed -i -E "$e" "$copy"
    done
}
# epoxy plate: the demo runs to 2.5 ms (minutes); 0.2 ms gives frames 0, 1, 2;
# with the stress (a 2D symmetric tensor) among the fields
short_deck "$src/examples/epoxy_holes/epoxy_holes.yaml" "$out/epoxy_holes.yaml" \
    's/end_time: 2\.5e-3/end_time: 2.0e-4/' \
    's/fields: \[position, velocity, displacement, fracture_density, strain_energy, id\]/fields: [position, velocity, displacement, fracture_density, strain_energy, id, stress]/'
# axisymmetric SPH Taylor rod on the wall (x = r, y = z): 4 us with a frame
# every 2 us (frames 0, 1, 2), with the deviatoric stress (rr zz theta-theta
# rz as xx yy zz xy) among the default fields
short_deck "$src/examples/sph_taylor_2d/sph_taylor_2d.yaml" "$out/sph_taylor_2d.yaml" \
    's/end_time: 8\.0e-5/end_time: 4.0e-6/' \
    's/output: \{field_interval: 1\.0e-5, history_every: 20\}/output: {field_interval: 2.0e-6, history_every: 20, fields: [position, velocity, displacement, density, pressure, plastic_strain, deviatoric_stress, id]}/'
# 3D Taylor bar: 20 us with a frame every 10 us (frames 0, 1, 2)
short_deck "$src/examples/sph_taylor_3d/sph_taylor_3d.yaml" "$out/sph_taylor_3d.yaml" \
    's/end_time: 9\.0e-5/end_time: 2.0e-5/'
# 2D drop-weight test with a round-nose tup and two roller supports (rigid
# bodies in the index): 0.5 ms, frames every 0.25 ms
short_deck "$src/examples/impact_vinylester/impact_vinylester.yaml" "$out/impact_vinylester.yaml" \
    's/end_time: 3\.0e-3/end_time: 5.0e-4/'
"$spall" run "$out/impact_vinylester.yaml" -o "$out/impact_vinylester" --overwrite --quiet
"$spall" run "$out/epoxy_holes.yaml" -o "$out/epoxy_holes" --overwrite --quiet
"$spall" run "$out/sph_taylor_3d.yaml" -o "$out/sph_taylor_3d" --overwrite --quiet
"$spall" run "$out/sph_taylor_2d.yaml" -o "$out/sph_taylor_2d" --overwrite --quiet
# bonds as line cells (output.fields lists `bonds`): the API example's plate
# (2D lattice, 3 534 particles, 10 278 bonds), run to its end: it cracks
short_deck "$src/examples/api/plate.yaml" "$out/plate_bonds.yaml" \
    's/fields: \[position, velocity, displacement, fracture_density\]/fields: [position, velocity, displacement, fracture_density, bonds]/'
"$spall" run "$out/plate_bonds.yaml" -o "$out/plate_bonds" --overwrite --quiet
[ -f "$out/plate_bonds/bonds_000015.h5" ] || { echo "runs.sh: plate_bonds wrote no bonds frame 15"; exit 1; }
for d in epoxy_holes sph_taylor_3d impact_vinylester sph_taylor_2d; do
    [ -f "$out/$d/fields_000002.h5" ] || { echo "runs.sh: $d wrote no frame 2"; exit 1; }
done
