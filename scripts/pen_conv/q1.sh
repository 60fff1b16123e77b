#!/bin/bash
# queue 1: fixed L + enlarged sphere reference; no AV; fluid
cd "$(dirname "$0")"
export OMP_NUM_THREADS=1
run() { tag=$1; shift; echo "== $tag $*" >> q1.log; nice -n 10 ./pc_run "$@" out=h_$tag.csv >> q1.log 2>&1; }
run L_r_10 9.84 avlen=0.65e-6 rad=0.5
run L_r_15 14.76 avlen=0.65e-6 rad=0.5
run noav_r_10 9.84 av_a=0 av_b=0 rad=0.5
run fluidL_r_10 9.84 avlen=0.65e-6 rad=0.5 A=1 B=0 tend=200e-9 stop=0
run noav_r_15 14.76 av_a=0 av_b=0 rad=0.5
run fluidL_r_15 14.76 avlen=0.65e-6 rad=0.5 A=1 B=0 tend=200e-9 stop=0
echo QDONE >> q1.log
