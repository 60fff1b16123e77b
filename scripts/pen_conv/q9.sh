#!/bin/bash
# the cases' deck (AV with h) with the contact offset dx1/2
cd "$(dirname "$0")"
export OMP_NUM_THREADS=1
run() { tag=$1; shift; echo "== $tag $*" >> q9.log; nice -n 10 ./pc_run "$@" out=h_$tag.csv >> q9.log 2>&1; }
run sc_h_10 9.84 sc=1
run sc_h_15 14.76 sc=1
echo QDONE >> q9.log
