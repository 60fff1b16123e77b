#!/bin/bash
# pen-conv3: the converging form (fixed AV length 0.65 um + contact_offset
# dx1/2, builder flag surface_contact) one level finer: d/25 (dx1 = 0.3 um)
cd "$(dirname "$0")"
export OMP_NUM_THREADS=1
run() { tag=$1; shift; echo "== $tag $*" >> q11.log; nice -n 10 ./pc_run "$@" out=h_$tag.csv >> q11.log 2>&1; }
run sc_L_25 24.6 avlen=0.65e-6 sc=1
echo QDONE >> q11.log
