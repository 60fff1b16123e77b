#!/usr/bin/env bash
# Writes the decks of issue 7 items 4a and 4b as variants of the working
# axisymmetric deck examples/pen_sph_gelatin/pen_sph_gelatin.yaml (silica
# 7.38 um into 10 wt% gelatin, graded spacing d/10):
#   velocity/pen_gelatin_vV.yaml  v0 = 200, 700, 1050, 1290, 1420 m/s, E = 20 MPa
#   modulus/pen_gelatin_EX.yaml   v0 = 1290 m/s, E = 1, 10, 20, 40 MPa
# These are the decks the validation cases pen-sph-gelatin-sweep and
# pen-sph-gelatin-modulus build in validation/pen_sph.c; run each with `spall run`.
# Item 4c: sebs/pen_sph_sebs_<d>um_<v>ms_E40.yaml and _E50.yaml, the five
# steel-into-SEBS examples (examples/pen_sph_sebs_*, E = 40 MPa) and their
# E = 50 MPa variants: the ten runs of validation case pen-sph-sebs.
# Usage: scripts/pen_decks.sh [outdir]   (default pen_decks)
set -euo pipefail
here="$(cd "$(dirname "$0")/.." && pwd)"
base="$here/examples/pen_sph_gelatin/pen_sph_gelatin.yaml"
out="${1:-pen_decks}"
mkdir -p "$out/velocity" "$out/modulus" "$out/sebs"
for v in 200 700 1050 1290 1420; do
    sed -e "s/velocity: \[0, -1290\]/velocity: [0, -$v]/" \
        -e "s/at 1290 m\/s/at $v m\/s/" "$base" > "$out/velocity/pen_gelatin_v$v.yaml"
done
for e in 1 10 20 40; do
    sed -e "s/youngs_modulus: 2e+07/youngs_modulus: ${e}e+06/" \
        -e "s/E = 20 MPa/E = $e MPa/" "$base" > "$out/modulus/pen_gelatin_E$e.yaml"
done
for ex in "$here"/examples/pen_sph_sebs_*um_*ms/pen_sph_sebs_*.yaml; do
    b="$(basename "$ex" .yaml)"
    cp "$ex" "$out/sebs/${b}_E40.yaml"
    { echo "# E = 50 MPa variant of examples/$b (scripts/pen_decks.sh)"
      sed -e "s/youngs_modulus: 40000000,/youngs_modulus: 50000000,/" \
          -e "1s/E = 40 MPa/E = 50 MPa/" -e "/^title:/s/E = 40 MPa/E = 50 MPa/" "$ex"
    } > "$out/sebs/${b}_E50.yaml"
done
echo "wrote $(ls "$out"/velocity/*.yaml "$out"/modulus/*.yaml "$out"/sebs/*.yaml | wc -l) decks under $out"
