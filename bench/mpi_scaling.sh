#!/usr/bin/env bash
# MPI scaling measured with `spall bench` (issue 20): the lattice2d and pd3d
# cases on 1 rank x 1 thread (no mpirun), 2 ranks x 1 thread and 1 rank x 2
# threads.  Prints, per case and configuration, the whole run's
# particle-steps/s and bond-steps/s (the slowest rank's loop time), the
# ratio to 1 x 1, the halo's bytes and seconds per step and the resident
# memory per particle held (ghosts included).  Run it on an otherwise idle
# machine: on a loaded one the ratios measure the load, not spall.  That the
# distributed results are those of one rank is tested elsewhere
# (ctest -L mpi; docs/parallel.md).
#
#   bench/mpi_scaling.sh [SPALL] [MPIRUN]     (defaults: build/spall, mpirun)
#   SCALE=0.05 CASES="lattice2d pd3d" bench/mpi_scaling.sh
#       SCALE is `spall bench --scale` (default 1: the documented sizes,
#       lattice2d 10^6 particles x 500 steps, pd3d 48 x 32 x 32 sites x 100
#       steps; below 1 the cases also take fewer steps: a smoke test)
set -euo pipefail
SPALL=${1:-build/spall}
MPIRUN=${2:-mpirun}
SCALE=${SCALE:-1}
CASES=${CASES:-lattice2d pd3d}
WORK=$(mktemp -d "${TMPDIR:-/tmp}/spall_mpi_scaling.XXXXXX")
trap 'rm -rf "$WORK"' EXIT
[ -x "$SPALL" ] || { echo "mpi_scaling.sh: no spall binary at $SPALL" >&2; exit 2; }

for cfg in 1x1 2x1 1x2; do
    ranks=${cfg%x*} threads=${cfg#*x}
    # shellcheck disable=SC2086
    if [ "$ranks" = 1 ]; then
        "$SPALL" bench $CASES --threads "$threads" --scale "$SCALE" --json "$WORK/$cfg.json" \
            > "$WORK/$cfg.txt" 2>&1
    else
        OMP_NUM_THREADS=$threads "$MPIRUN" --allow-run-as-root --oversubscribe -np "$ranks" \
            "$SPALL" bench $CASES --threads "$threads" --scale "$SCALE" --json "$WORK/$cfg.json" \
            > "$WORK/$cfg.txt" 2>&1
    fi || { echo "mpi_scaling.sh: spall bench on $cfg failed:" >&2; cat "$WORK/$cfg.txt" >&2; exit 1; }
done

field() { # file case key: the value of "key" in the case's row of spall bench --json
    grep "\"case\": \"$2\"" "$1" | sed -n "s/.*\"$3\": \([^,}]*\).*/\1/p"
}
printf '%-10s %-11s %10s %10s %6s %13s %13s %6s %12s %10s %8s\n' case ranks_x_thr particles \
    bonds steps particle-st/s bond-st/s ratio halo_B/step halo_s/step B/part
for c in $CASES; do
    base=$(field "$WORK/1x1.json" "$c" particle_steps_per_s)
    for cfg in 1x1 2x1 1x2; do
        f="$WORK/$cfg.json"
        ps=$(field "$f" "$c" particle_steps_per_s)
        printf '%-10s %-11s %10s %10s %6s %13s %13s %6s %12s %10s %8s\n' "$c" \
            "${cfg%x*} x ${cfg#*x}" "$(field "$f" "$c" particles)" "$(field "$f" "$c" bonds)" \
            "$(field "$f" "$c" steps)" "$ps" "$(field "$f" "$c" bond_steps_per_s)" \
            "$(awk -v a="$ps" -v b="$base" 'BEGIN{printf "%.3f", a / b}')" \
            "$(field "$f" "$c" halo_bytes_per_step)" "$(field "$f" "$c" halo_seconds_per_step)" \
            "$(field "$f" "$c" bytes_per_particle)"
    done
done
echo "(ratio: particle-steps/s against 1 x 1 of the same case; halo: position/velocity"
echo " exchange, bytes sent by all ranks and the slowest rank's seconds per step; B/part:"
echo " resident memory held after the partition per particle held, ghosts included)"
