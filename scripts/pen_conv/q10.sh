#!/bin/bash
# the cases' deck (AV with h) with the contact offset dx1/2, d/20
cd "$(dirname "$0")"
export OMP_NUM_THREADS=1
run() { tag=$1; shift; echo "== $tag $*" >> q10.log; nice -n 10 ./pc_run "$@" out=h_$tag.csv >> q10.log 2>&1; }
run sc_h_20 19.68 sc=1
echo QDONE >> q10.log
