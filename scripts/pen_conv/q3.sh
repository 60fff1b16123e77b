#!/bin/bash
cd "$(dirname "$0")"
while ! grep -q QDONE q1.log; do sleep 5; done
export OMP_NUM_THREADS=1
run() { tag=$1; shift; echo "== $tag $*" >> q3.log; nice -n 10 ./pc_run "$@" out=h_$tag.csv >> q3.log 2>&1; }
run W_L_r_10 9.84 avlen=0.65e-6 rad=0.5 'sub=max: [9e-06, 0]|max: [1.8e-05, 0]' 'sub=max: [2.1e-05, 0]|max: [3e-05, 0]'
run L_r_hf195_10 9.84 avlen=0.65e-6 rad=0.5 hf=1.95
run L_r_k005_10 9.84 avlen=0.65e-6 rad=0.5 'sub=contact: penalty|contact: penalty, stiffness_factor: 0.05'
run W_L_r_15 14.76 avlen=0.65e-6 rad=0.5 'sub=max: [8e-06, 0]|max: [1.6e-05, 0]' 'sub=max: [2e-05, 0]|max: [3e-05, 0]'
echo QDONE >> q3.log
