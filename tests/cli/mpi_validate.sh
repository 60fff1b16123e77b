#!/usr/bin/env bash
# `spall validate` and `spall bench` under mpirun (docs/parallel.md,
# "validate and bench under mpirun"):
#  - distributed cases (lattice-waves, pd-bimaterial-bar, pd-lps-waves,
#    impact-spall with particle contact between two bodies, macro-rod-large's
#    reduced rods, and sph-taylor-3d: SPH with symmetry planes) on 2 ranks,
#    and thermal-expansion (angular springs), write the same --json
#    as one rank, byte for byte; a case that is not distributed
#    (pen-check-value) runs on rank 0 alone with one "serial:" note; every
#    case header and the summary are printed once; the exit status is the
#    serial one;
#  - `spall bench lattice2d pd3d macro-rod` on 2 ranks reports the whole
#    body's particles and bonds (the serial counts), ghosts and halo bytes;
#    the SPH Taylor bars' timed loops (sph-taylor-cu, updated form, on the
#    spatial ghosts) report the serial particle count on 2 ranks; a case
#    that is not distributed (sph-taylor-cu-rest: its bar shape reads one
#    rank's particle arrays) is refused in one line.
# Usage: mpi_validate.sh SPALL SRC MPIEXEC
set -u
spall="$1"
mpiexec="$3"
# shellcheck source=lib/mpi_env.bash
source "$2/tests/cli/lib/mpi_env.bash"
fail=0
launch() { OMP_NUM_THREADS=1 timeout 900 "$mpiexec" --allow-run-as-root --oversubscribe -q "$@"; }

cases="lattice-waves pd-bimaterial-bar pd-lps-waves thermal-expansion impact-spall macro-rod-large
       pen-check-value sph-taylor-3d"
# shellcheck disable=SC2086
OMP_NUM_THREADS=1 timeout 900 "$spall" validate $cases --quick --json one.json > one.txt 2>&1
rc1=$?
# shellcheck disable=SC2086
launch -np 2 "$spall" validate $cases --quick --json two.json > two.txt 2> two.err
rc2=$?
[ "$rc1" -eq "$rc2" ] || { echo "FAIL validate: exit $rc1 on one rank, $rc2 on two"; fail=1; }
# the per-case wall and CPU seconds are the only values that may differ
untimed() { sed 's/"wall_s": [0-9.e+-]*, "cpu_s": [0-9.e+-]*//' "$1"; }
[ -s one.json ] && cmp -s <(untimed one.json) <(untimed two.json) ||
    { echo "FAIL validate: --json differs between 1 and 2 ranks"; diff one.json two.json | head; fail=1; }
for c in $cases; do
    n=$(grep -c "^== $c:" two.txt)
    [ "$n" -eq 1 ] || { echo "FAIL validate: case $c printed $n times on 2 ranks"; fail=1; }
done
n=$(grep -c "^[0-9]* passed, [0-9]* failed" two.txt)
[ "$n" -eq 1 ] || { echo "FAIL validate: summary printed $n times"; fail=1; }
n=$(grep -c "^  serial: " two.txt)
[ "$n" -eq 1 ] || { echo "FAIL validate: $n serial notes (expected 1)"; cat two.txt; fail=1; }
grep -A1 "^== pen-check-value:" two.txt | grep -q "serial: " ||
    { echo "FAIL validate: pen-check-value has no serial note"; fail=1; }
grep -q "serial: " one.txt && { echo "FAIL validate: serial notes on one rank"; fail=1; }
# apart from the notes and the wall-clock times (also the seconds an SPH
# case prints after a run), rank 0 prints what one rank prints
clock() { grep -v "^  serial: \|^  wall: " "$1" | sed 's/, [0-9.]* s wall, [0-9.]* s CPU$//; s/ ([0-9]* s)$//'; }
diff <(clock two.txt) <(clock one.txt) > /dev/null ||
    { echo "FAIL validate: 2-rank report differs from 1 rank"; diff one.txt two.txt | head; fail=1; }

OMP_NUM_THREADS=1 timeout 900 "$spall" bench lattice2d pd3d macro-rod --scale 0.02 --threads 1 \
    --json b1.json > b1.txt 2>&1 || { echo "FAIL bench on one rank"; cat b1.txt; fail=1; }
launch -np 2 "$spall" bench lattice2d pd3d macro-rod --scale 0.02 --threads 1 --json b2.json > b2.txt 2>&1 ||
    { echo "FAIL bench on 2 ranks"; cat b2.txt; fail=1; }
field() { # file case key: the value of "key" in the case's JSON row
    grep "\"case\": \"$2\"" "$1" | sed -n "s/.*\"$3\": \([^,}]*\).*/\1/p"
}
for c in lattice2d pd3d macro-rod; do
    for k in particles bonds steps; do
        [ -n "$(field b1.json $c $k)" ] && [ "$(field b1.json $c $k)" = "$(field b2.json $c $k)" ] ||
            { echo "FAIL bench $c: $k $(field b1.json $c $k) on 1 rank, $(field b2.json $c $k) on 2"; fail=1; }
    done
    [ "$(field b1.json $c ranks)" = 1 ] && [ "$(field b2.json $c ranks)" = 2 ] ||
        { echo "FAIL bench $c: ranks not reported"; fail=1; }
    [ "$(field b1.json $c ghosts)" = 0 ] && [ "$(field b2.json $c ghosts)" -gt 0 ] ||
        { echo "FAIL bench $c: ghosts $(field b2.json $c ghosts) on 2 ranks"; fail=1; }
    awk -v h="$(field b2.json $c halo_bytes_per_step)" -v m="$(field b2.json $c bytes_per_particle)" \
        'BEGIN { exit !(h > 0 && m > 0) }' ||
        { echo "FAIL bench $c: no halo bytes or memory per particle on 2 ranks"; fail=1; }
    grep -q "^    mpi: 2 ranks x 1 threads" b2.txt || { echo "FAIL bench: no mpi line"; fail=1; }
done
"$spall" bench sph-taylor-cu --scale 0.02 --threads 1 --json u1.json > u1.txt 2>&1 ||
    { echo "FAIL bench sph-taylor-cu on 1 rank"; cat u1.txt; fail=1; }
launch -np 2 "$spall" bench sph-taylor-cu --scale 0.02 --threads 1 --json u2.json > u2.txt 2>&1 ||
    { echo "FAIL bench sph-taylor-cu on 2 ranks"; cat u2.txt; fail=1; }
for k in particles steps; do
    [ -n "$(field u1.json sph-taylor-cu $k)" ] &&
        [ "$(field u1.json sph-taylor-cu $k)" = "$(field u2.json sph-taylor-cu $k)" ] ||
        { echo "FAIL bench sph-taylor-cu: $k $(field u1.json sph-taylor-cu $k) on 1 rank," \
            "$(field u2.json sph-taylor-cu $k) on 2"; fail=1; }
done
[ "$(field u2.json sph-taylor-cu ranks)" = 2 ] || { echo "FAIL bench sph-taylor-cu: ranks"; fail=1; }
launch -np 2 "$spall" bench sph-taylor-cu-rest --scale 0.02 --threads 1 > m.txt 2> m.err; rc=$?
[ "$rc" -eq 2 ] && [ "$(wc -l < m.err)" -eq 1 ] && grep -q "does not run distributed" m.err ||
    { echo "FAIL bench sph-taylor-cu-rest on 2 ranks: exit $rc"; cat m.err; fail=1; }
[ $fail -eq 0 ] && echo "validate and bench under mpirun: OK"
exit $fail
