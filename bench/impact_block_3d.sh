#!/usr/bin/env bash
# The 4.2 M-particle 3D problem of issue 20 on 2 ranks (bench/impact_block_3d.yaml:
# FCC cube struck by a rigid sphere), run by hand, not part of the suite:
#     [HALF=0.072] [SETUP=distributed|replicated] \
#     bench/impact_block_3d.sh [path/to/spall] [STEPS] [RANKS]
# Prints per rank the peak resident memory (/usr/bin/time %M) and, sampled
# every 0.5 s, the resident memory during the time loop (the median of the
# samples between set-up and the last frame); the set-up and loop wall
# times and particle-steps/s from run.log; then opens the frames in ParaView
# (bench/pv_points.py under tests/client/pvbatch.sh) and prints the number
# of points it reads.  Needs about 1.3 GB per rank (docs/parallel.md).
set -euo pipefail
SPALL=$(realpath "${1:-build/spall}")
STEPS=${2:-100}
RANKS=${3:-2}
HERE=$(cd "$(dirname "$0")" && pwd)
W=$(mktemp -d /tmp/impact_block_3d.XXXX)
# HALF: half the cube's side [m] (0.072: 4.2 M particles; 0.104: 12.6 M);
# SETUP: parallel.setup (distributed, the default, or replicated)
HALF=${HALF:-0.072}
sed -e "s/steps: 100,/steps: $STEPS,/" -e "s/max_particles: 1e7/max_particles: 1e8/" \
    -e "s/0\.072/$HALF/g" -e "s/0\.144/$(python3 -c "print(2 * $HALF)")/" \
    -e "s/0\.159/$(python3 -c "print(round(2 * $HALF + 0.015, 6))")/" \
    "$HERE/impact_block_3d.yaml" > "$W/deck.yaml"
[ -n "${SETUP:-}" ] && echo "parallel: {setup: $SETUP}" >> "$W/deck.yaml"
cat > "$W/rank.sh" <<'SH'
#!/bin/bash
exec /usr/bin/time -f "%M %e %U" -o "mem_rank${OMPI_COMM_WORLD_RANK}.txt" "$@"
SH
chmod +x "$W/rank.sh"
echo "work dir: $W"
cd "$W"
start=$(date +%s.%N)
OMP_NUM_THREADS=1 mpirun --allow-run-as-root --oversubscribe -np "$RANKS" ./rank.sh "$SPALL" run \
    deck.yaml -o out --no-progress > run.out 2>&1 &
MP=$!
: > rss.txt
while kill -0 $MP 2>/dev/null; do # ranks = grandchildren of mpirun (mpirun - time - spall)
  for t in $(pgrep -P $MP || true); do
    for p in $(pgrep -P "$t" || true); do
      r=$(awk '/VmRSS/{print $2}' "/proc/$p/status" 2>/dev/null || true)
      [ -n "$r" ] && echo "$(date +%s.%N) $p $r" >> rss.txt
    done
  done
  sleep 0.5
done
wait $MP
cat run.out
python3 - "$W" "$start" <<'PY'
import sys, re, glob, statistics, collections
W, start = sys.argv[1], float(sys.argv[2])
log = open(f"{W}/out/run.log").read()
n = int(re.search(r"^particles: (\d+)", log, re.M).group(1))
loop = float(re.search(r"^wall_seconds: ([0-9.eE+-]+)", log, re.M).group(1))
rate = re.search(r"^particle_steps_per_s: (\S+)", log, re.M).group(1)
dec = re.search(r"set-up ([0-9.]+) s\)", log)
print(f"{n} particles; loop {loop:.1f} s wall, {rate} particle-steps/s; "
      f"partitioning {dec.group(1) if dec else '?'} s")
for f in sorted(glob.glob(f"{W}/mem_rank*.txt")):
    kb, wall, user = open(f).read().split()[:3]
    print(f"{f.split('/')[-1][4:-4]}: peak RSS {int(kb)/2**20:.2f} GiB ({int(kb)*1024/n:.0f} B per particle "
          f"of the whole body), process {float(wall):.0f} s wall (set-up + output about "
          f"{float(wall)-loop:.0f} s), {float(user):.1f} s user CPU")
rows = collections.defaultdict(list)
for l in open(f"{W}/rss.txt"):
    t, p, r = l.split()
    rows[p].append((float(t) - start, int(r) * 1024))
for p, v in rows.items():
    if len(v) < 10:
        continue
    end = v[-1][0]
    loop_rss = [r for t, r in v if end - loop * 0.9 < t < end - loop * 0.1]
    if loop_rss:
        print(f"pid {p}: resident during the loop (median) {statistics.median(loop_rss)/2**20:.0f} MiB")
PY
bash "$HERE/../tests/client/pvbatch.sh" "$HERE/pv_points.py" out/fields.xdmf
