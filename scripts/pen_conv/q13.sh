#!/bin/bash
# pen-conv3: after q12 — d/10 of the converging form with the offset key
# (plastic-zone line), d/30 up to 120 ns only (d/30 to P_max did not fit
# in the session: ~1.7-2.5x the CPU of d/25), and the failure variant
# (von Mises failure at A = 21 MPa, the former default) at d/10 and d/15
# to see how the failed zone scales with dx1
cd "$(dirname "$0")"
while ! grep -q QDONE q12.log 2>/dev/null; do sleep 10; done
export OMP_NUM_THREADS=1
run() { tag=$1; shift; echo "== $tag $*" >> q13.log; nice -n 10 ./pc_run "$@" out=h_$tag.csv >> q13.log 2>&1; }
run sc_L_10 9.84 avlen=0.65e-6 sc=1
run sc_L_30_t120 29.52 avlen=0.65e-6 sc=1 tend=120e-9 stop=0
run sc_L_fail_10 9.84 avlen=0.65e-6 sc=1 fail=21e6
run sc_L_fail_15 14.76 avlen=0.65e-6 sc=1 fail=21e6
echo QDONE >> q13.log
