#!/bin/bash
# lead, after pen-conv3: d/30 of the converging form (AV length 0.65 um,
# contact offset dx1/2) run to P_max (q13 stopped it at 120 ns), one thread,
# idle machine: 1329 s.  P_max 71.801 um at 262.2 ns (docs/validation.md,
# pen-sph-gelatin, convergence table in the converging form).
cd "$(dirname "$0")"
export OMP_NUM_THREADS=1
run() { tag=$1; shift; echo "== $tag $*" >> q14.log; nice -n 10 ./pc_run "$@" out=h_$tag.csv >> q14.log 2>&1; }
run sc_L_30 29.52 avlen=0.65e-6 sc=1
echo QDONE >> q14.log
