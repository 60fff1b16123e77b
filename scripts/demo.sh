#!/usr/bin/env bash
# `make demo`: run the seed's epoxy plate with holes in tension and say where
# the results are.
set -euo pipefail
build="${1:-build}"
cd "$(dirname "$0")/.."
out="out/epoxy_holes"
"$build/spall" run examples/epoxy_holes/epoxy_holes.yaml -o "$out" --overwrite
echo
echo "demo: history (energies, grip forces):  $out/history.csv"
echo "demo: fields for ParaView:               $out/fields.xdmf"
echo "demo: run log:                           $out/run.log"
# picture of the cracked plate (last frame, fracture density; see spall render --help)
png="$out/fracture_density.png"
"$build/spall" render "$out" --field fracture_density -o "$png" >/dev/null
echo "demo: picture of the cracked plate:      $png"
