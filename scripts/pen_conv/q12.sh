#!/bin/bash
# pen-conv3: the converging form (fixed AV length 0.65 um + contact_offset
# dx1/2) at d/10, d/15, d/20 with the offset key itself (q5/q8 used the
# enlarged radius, rad=0.5), and the width check: d/15 with the two outer
# radial levels 1.5x wider (r to 216 um instead of 144 um)
cd "$(dirname "$0")"
export OMP_NUM_THREADS=1
run() { tag=$1; shift; echo "== $tag $*" >> q12.log; nice -n 10 ./pc_run "$@" out=h_$tag.csv >> q12.log 2>&1; }
run sc_L_15_w15 14.76 avlen=0.65e-6 sc=1 width=1.5
run sc_L_15 14.76 avlen=0.65e-6 sc=1
run sc_L_20 19.68 avlen=0.65e-6 sc=1
echo QDONE >> q12.log
