#!/bin/bash
cd "$(dirname "$0")"
while kill -0 3577 2>/dev/null; do sleep 3; done
export OMP_NUM_THREADS=1
run() { tag=$1; shift; echo "== $tag $*" >> q5.log; nice -n 10 ./pc_run "$@" out=h_$tag.csv >> q5.log 2>&1; }
run fl_probe_10 9.84 avlen=0.65e-6 rad=0.5 A=1 B=0 tend=25.5e-9 stop=0 probe=1
run fl_probe_15 14.76 avlen=0.65e-6 rad=0.5 A=1 B=0 tend=25.5e-9 stop=0 probe=1
run L_r_k005_10 9.84 avlen=0.65e-6 rad=0.5 'sub=contact: penalty|contact: penalty, stiffness_factor: 0.05'
run L_r_E200_10 9.84 avlen=0.65e-6 rad=0.5 E=200e6
run L_r_E200_15 14.76 avlen=0.65e-6 rad=0.5 E=200e6
run L_r_20 19.68 avlen=0.65e-6 rad=0.5
echo QDONE >> q5.log
