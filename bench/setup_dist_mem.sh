#!/usr/bin/env bash
# Peak memory per rank of the distributed set-up against the replicated one
# (issue 20, docs/parallel.md "Distributed set-up"), run by hand, not part of
# the suite:
#     [SETUPS="distributed replicated"] bench/setup_dist_mem.sh SPALL DECK.yaml RANKS [RANKS ...]
# For each rank count and each parallel.setup (distributed, replicated) runs
# the deck under mpirun (one thread per rank) and prints every rank's peak
# RSS (/usr/bin/time %M) and that peak in bytes per particle of the whole
# body.  Memory does not depend on the machine's load; the deck should be
# short (a few steps, few frames).
set -euo pipefail
SPALL=$(realpath "$1")
DECK=$(realpath "$2")
shift 2
W=$(mktemp -d /tmp/setup_dist_mem.XXXX)
cd "$W"
cat > rank.sh <<'SH'
#!/bin/bash
exec /usr/bin/time -f "%M" -o "mem_${TAG}_rank${OMPI_COMM_WORLD_RANK}.txt" "$@"
SH
chmod +x rank.sh
for ranks in "$@"; do
  for setup in ${SETUPS:-distributed replicated}; do
    { cat "$DECK"; echo "parallel: {setup: $setup}"; } > deck.yaml
    TAG="$ranks-$setup" OMP_NUM_THREADS=1 mpirun --allow-run-as-root --oversubscribe -q \
        -x TAG -np "$ranks" ./rank.sh "$SPALL" run deck.yaml -o "out-$ranks-$setup" \
        --quiet --no-progress
    n=$(awk '/^particles:/ {print $2}' "out-$ranks-$setup/run.log")
    line="$ranks ranks, $setup set-up ($n particles):"
    for f in mem_"$ranks-$setup"_rank*.txt; do
      kb=$(cat "$f")
      line="$line $(awk -v k="$kb" -v n="$n" 'BEGIN {printf "%.0f MiB (%.0f B/particle)", k / 1024, k * 1024 / n}')"
    done
    echo "$line"
  done
done
