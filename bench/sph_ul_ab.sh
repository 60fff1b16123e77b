#!/bin/sh
# Issue 25 item 4: the updated-form SPH cases of two builds side by side,
# interleaved, one thread, REPS repetitions (docs/performance.md, "SPH,
# updated form: vector rows").  The bench notes print the loop's CPU time
# and particle-steps per CPU-second, the figure to compare on a loaded
# machine (wall time there measures the other jobs).
#   sh bench/sph_ul_ab.sh BASE_BUILD NEW_BUILD [REPS] [CASES...]
# e.g. sh bench/sph_ul_ab.sh ../main/build build 2
set -eu
base=${1:?base build directory}
new=${2:?new build directory}
reps=${3:-1}
shift 2
[ $# -gt 0 ] && shift
cases=${*:-sph-taylor-cu sph-taylor-cu-tl pen-gelatin}
r=1
while [ "$r" -le "$reps" ]; do
    for b in "$base" "$new"; do
        for c in $cases; do
            echo "== $b/spall bench $c --threads 1 (repetition $r)"
            /usr/bin/time -f "process CPU %U s user, %e s wall" "$b/spall" bench "$c" --threads 1 2>&1 |
                grep -v "^case "
        done
    done
    r=$((r + 1))
done
