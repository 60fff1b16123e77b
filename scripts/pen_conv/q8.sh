#!/bin/bash
cd "$(dirname "$0")"
while kill -0 4825 2>/dev/null; do sleep 3; done
export OMP_NUM_THREADS=1
run() { tag=$1; shift; echo "== $tag $*" >> q8.log; nice -n 10 ./pc_run "$@" out=h_$tag.csv >> q8.log 2>&1; }
S1=$'sub=geometry:\n  l1:|geometry:\n  l0: {box: {min: [0, -6e-06], max: [6e-06, 0]}}\n  l1:'
S2=$'sub=- {geometry: l1, material: gelatin, lattice: {spacing: 7.5e-07, origin: [3.75e-07, -3.75e-07]}}|- {geometry: l0, material: gelatin, lattice: {spacing: 3.75e-07, origin: [1.875e-07, -1.875e-07]}}\n  - {geometry: {difference: [l1, l0]}, material: gelatin, lattice: {spacing: 7.5e-07, origin: [3.75e-07, -3.75e-07]}}'
run sc_L_10 9.84 avlen=0.65e-6 sc=1
run patch_L_r05_10 9.84 avlen=0.65e-6 rad=0.5 "$S1" "$S2"
run L_r_dt015_10 9.84 avlen=0.65e-6 rad=0.5 'sub=run: {end_time:|run: {dt_factor: 0.15, end_time:'
run fluidL_r_20 19.68 avlen=0.65e-6 rad=0.5 A=1 B=0 tend=200e-9 stop=0
echo QDONE >> q8.log
