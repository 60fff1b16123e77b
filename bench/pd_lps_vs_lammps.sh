#!/usr/bin/env bash
# Side by side: the 3D problem of bench/pd_vs_lammps.sh with the state-based
# models, spall `formulation: lps | eps` against LAMMPS pair peri/lps and
# peri/eps (Debian's `lammps`): damage and probe values, and the race
# (loop wall time, bond-steps/s, peak memory per particle).  Usage:
#     bench/pd_lps_vs_lammps.sh [--check] [--ranks | --mem] [path/to/spall] [NX NY NZ STEPS]
# --check (the ctest `pd_lps_vs_lammps`, label lammps): exit 77 (skipped)
# without `lmp`, exit 1 when a check below fails; the 1-core times are
# printed, not checked, and the 2-core runs are left out (fast); without
# --check a missing `lmp` is installed (Debian package, root).
# --ranks: spall's 2-core runs are 2 MPI ranks x 1 thread (rank for rank
# with LAMMPS; memory = the sum of the ranks' peaks, and each rank's peak
# against LAMMPS' largest rank, with the set-up run.log names: distributed
# or replicated); default 2 OpenMP threads in one process.
# --mem: only the 2-rank memory of lps and eps-elastic at the size given
# (e.g. `--mem build/spall 72 48 48 5`: memory only, few steps): each
# rank's peak RSS of both codes (/usr/bin/time inside mpirun, one line per
# rank), per rank and summed; no values, no times.
#
# Race (as bench/pd_vs_lammps.sh): the lps and eps-elastic cases on 1 core
# (spall 1 thread, LAMMPS `lmp` serial) and 2 cores (LAMMPS: 2 MPI ranks,
# Debian's build has no OPENMP package).  Wall time = spall's loop ("s wall"
# of `spall run`, the stepping loop with its output) and LAMMPS' "Loop time
# of"; bond-steps/s with each bond counted once (spall run.log
# `interactions`); peak RSS by /usr/bin/time -f %M (per process; LAMMPS on 2
# ranks: the largest rank's peak x 2, as bench/pd_vs_lammps.sh), divided by
# the particles.  Also printed: each code's own count of its arrays (spall
# run.log "model arrays", LAMMPS "Per MPI rank memory allocation").
#
# Problem: simple-cubic sites dx = 1 mm, NX x NY x NZ (default 36 x 24 x 24),
# delta = 3.015 dx, PDLAMMPS partial volumes (spall partial_volume_rule:
# lammps), E = 72 GPa, nu = 0.3 (K = 60 GPa, G = 27.7 GPa), rho = 2440,
# s0 = 0.002 (LAMMPS alpha = 0), end slabs pulled apart at -/+ 5 m/s,
# dt = 5e-8 s, STEPS steps (default 200), a bond acting in the step it
# breaks (spall break_order: next_step).  LAMMPS' influence function is
# omega = 1/|xi| with the weighted volume m = sum omega beta |xi|^2 V; spall's
# `influence: inverse` is delta/|xi|: m scales by delta and every force
# state, omega/m, is the same.  Cases (docs/performance.md explains each):
#   lps          peri/lps vs formulation lps: the same model, compared
#   eps-elastic  peri/eps vs formulation eps with sigma_Y = 1e11 Pa (never
#                yields): LAMMPS' eps takes the deviatoric extension of
#                both halves of a bond from theta_i; spall's (and peri/lps)
#                the j half from theta_j.  Checked: spall eps = LAMMPS lps
#                (the same elastic model), and the spall-LAMMPS eps gap is
#                that of LAMMPS lps vs LAMMPS eps (the theta_i term only)
#   eps-plastic  sigma_Y = 100 MPa: printed, not compared (LAMMPS' yield
#                function differs, docs/performance.md)
# LAMMPS input: `run 0` before the run.  peri/lps and peri/eps (Debian's
# 29 Sep 2021 build) compute their first forces before fix PERI_NEIGH has
# made the bond families, which leaves every particle's critical stretch s0
# at 0 for step 1: every bond in tension then breaks at step 1 (peri/pmb keeps
# its initial s0).  The set-up of a second run has the families and sets s0.
set -euo pipefail
CHECK=0 RANKS=0 MEM=0
while [ $# -gt 0 ]; do
    case "$1" in
        --check) CHECK=1; shift ;;
        --ranks) RANKS=1; shift ;;
        --mem) MEM=1; shift ;;
        *) break ;;
    esac
done
SPALL=${1:-build/spall}
NX=${2:-36}; NY=${3:-24}; NZ=${4:-24}; STEPS=${5:-200}
NAME=pd_lps_vs_lammps
. "$(dirname "$0")/lammps_setup.sh"
python3 - "$W" "$NX" "$NY" "$NZ" "$STEPS" <<'PY'
import sys, math
W, nx, ny, nz, steps = sys.argv[1], *map(int, sys.argv[2:6])
dx, E, nu, rho, s0 = 1.0e-3, 72.0e9, 0.3, 2440.0, 0.002
K, G = E / (3 * (1 - 2 * nu)), E / (2 * (1 + nu))
delta = 3.015 * dx
px, py, pz = (nx * 3 // 4) * dx, (ny // 2) * dx, (nz // 2) * dx
cases = {"lps": ("lps", None), "eps-elastic": ("eps", 1.0e11), "eps-plastic": ("eps", 1.0e8),
         "lmp-lps-ref": ("lps", None)}
for name, (form, sy) in cases.items():
    pair = f"peri/{form}"
    coeff = f"{K!r} {G!r} {delta!r} {s0} 0.0" + (f" {sy!r}" if sy else "")
    pi, pj, pk = nx * 3 // 4, ny // 2, nz // 2
    open(f"{W}/in.{name}", "w").write(f"""units si
dimension 3
boundary s s s
atom_style peri
atom_modify map array
lattice sc {dx!r}
region box block -0.5 {nx - 0.5} -0.5 {ny - 0.5} -0.5 {nz - 0.5}
create_box 1 box
create_atoms 1 region box
pair_style {pair}
pair_coeff * * {coeff}
set group all density {rho}
set group all volume {dx**3!r}
region left block INF 1.5 INF INF INF INF
region right block {nx - 2.5} INF INF INF INF INF
region pr block {pi - 0.5} {pi + 0.5} {pj - 0.5} {pj + 0.5} {pk - 0.5} {pk + 0.5}
group left region left
group right region right
group probe region pr
velocity all set 0 0 0
velocity left set -5 NULL NULL units box
velocity right set 5 NULL NULL units box
fix 1 all nve
fix 2 left setforce 0.0 NULL NULL
fix 3 right setforce 0.0 NULL NULL
compute dmg all damage/atom
compute dsum all reduce sum c_dmg
compute dsp probe displace/atom
compute pux probe reduce sum c_dsp[1]
thermo_style custom step c_dsum c_pux
thermo_modify format float %.17g
thermo {steps}
timestep 5e-8
run 0 post no
run {steps}
""")
    if name.startswith("lmp-"):
        continue
    ys = f", yield_stress: {sy!r}" if sy else ""
    open(f"{W}/{name}.yaml", "w").write(f"""title: {name} side by side with LAMMPS peri/{form}
model: {{type: peridynamics, horizon_factor: 3.015, partial_volume_rule: lammps, break_order: next_step,
        formulation: {form}, influence: inverse}}
materials:
  glass: {{density: {rho}, youngs_modulus: {E!r}, poisson_ratio: {nu}, critical_stretch: {s0}{ys}}}
lattice: {{type: sc, spacing: {dx!r}}}
geometry:
  block: {{box: {{min: [-0.0005, -0.0005, -0.0005], max: [{(nx - 0.5) * dx!r}, {(ny - 0.5) * dx!r}, {(nz - 0.5) * dx!r}]}}}}
body: {{geometry: block, material: glass}}
groups:
  left: {{box: {{min: [-1, -1, -1], max: [0.0015, 1, 1]}}}}
  right: {{box: {{min: [{(nx - 2.5) * dx!r}, -1, -1], max: [1, 1, 1]}}}}
boundary_conditions:
  - {{group: left, type: velocity, components: [x], value: -5.0}}
  - {{group: right, type: velocity, components: [x], value: 5.0}}
probes:
  - {{name: p, position: [{px!r}, {py!r}, {pz!r}]}}
run: {{dt: 5.0e-8, dt_override: true, steps: {steps}, threads: 1}}
output: {{history_every: {steps}, field_interval: 1.0}}
""")
PY
if [ $MEM = 1 ]; then
    for c in lps eps-elastic; do
        ( cd "$W" && OMP_NUM_THREADS=1 mpirun --allow-run-as-root --oversubscribe -np 2 \
            /usr/bin/time -f "%M" -a -o "spall_${c}_mem.mem" "$SPALL" run "$c.yaml" \
            > "spall_${c}_mem.out" 2>&1 ) ||
            { echo "spall 2-rank run $c failed:"; tail -5 "$W/spall_${c}_mem.out"; exit 1; }
        ( cd "$W" && OMP_NUM_THREADS=1 mpirun --allow-run-as-root --oversubscribe -np 2 \
            /usr/bin/time -f "%M" -a -o "lmp_${c}_mem.mem" "$LMP" -in "in.$c" \
            -log "lmp_${c}_mem.log" -screen none > "lmp_${c}_mem.out" 2>&1 ) ||
            { echo "lammps 2-rank run $c failed:"; tail -5 "$W/lmp_${c}_mem.out"; exit 1; }
    done
    python3 - "$W" <<'PY'
import sys, re
W = sys.argv[1]
print(f"{'case':<12} {'code':<7} {'peak RSS per rank MiB':>22} {'sum MiB':>8} {'B/particle':>10}")
for c in ("lps", "eps-elastic"):
    n = int(re.search(r"^particles: (\d+)", open(f"{W}/{c}/run.log").read(), re.M).group(1))
    setup = re.search(r"^setup: (\w+)", open(f"{W}/{c}/run.log").read(), re.M)
    pk = {code: [float(v) * 1024 for v in open(f"{W}/{code}_{c}_mem.mem").read().split()]
          for code in ("spall", "lmp")}
    for code, name in (("spall", "spall"), ("lmp", "LAMMPS")):
        v = pk[code]
        print(f"{c:<12} {name:<7} {' / '.join(f'{x / 2**20:.1f}' for x in v):>22} "
              f"{sum(v) / 2**20:8.1f} {sum(v) / n:10.0f}")
    print(f"  {c} ({n} particles, spall set-up {setup.group(1) if setup else '?'}): largest rank "
          f"{max(pk['spall']) / max(pk['lmp']):.2f} of LAMMPS', sum {sum(pk['spall']) / sum(pk['lmp']):.2f}")
PY
    rm -rf "$W"
    exit 0
fi
# values (and the 1-core race): spall 1 thread, serial lmp
for c in lps eps-elastic eps-plastic; do
    ( cd "$W" && OMP_NUM_THREADS=1 /usr/bin/time -f "%M" -o "spall_${c}_1.mem" \
        "$SPALL" run "$c.yaml" > "spall_$c.out" 2>&1 ) ||
        { echo "spall run $c failed:"; tail -5 "$W/spall_$c.out"; exit 1; }
done
for c in lps eps-elastic eps-plastic lmp-lps-ref; do
    ( cd "$W" && OMP_NUM_THREADS=1 /usr/bin/time -f "%M" -o "lmp_${c}_1.mem" \
        "$LMP" -in "in.$c" -log "lmp_$c.log" -screen none ) ||
        { echo "lammps run $c failed:"; tail -5 "$W/lmp_$c.log"; exit 1; }
done
# the 2-core race (not under --check)
if [ $CHECK = 0 ]; then
    for c in lps eps-elastic; do
        if [ $RANKS = 1 ]; then
            cp "$W/$c.yaml" "$W/${c}_2.yaml"
            ( cd "$W" && OMP_NUM_THREADS=1 mpirun --allow-run-as-root --oversubscribe -np 2 \
                /usr/bin/time -f "%M" -a -o "spall_${c}_2.mem" "$SPALL" run "${c}_2.yaml" \
                > "spall_${c}_2.out" 2>&1 )
        else
            sed -e "s/threads: 1}/threads: 2}/" "$W/$c.yaml" > "$W/${c}_2.yaml"
            ( cd "$W" && OMP_NUM_THREADS=2 /usr/bin/time -f "%M" -o "spall_${c}_2.mem" \
                "$SPALL" run "${c}_2.yaml" > "spall_${c}_2.out" 2>&1 )
        fi || { echo "spall 2-core run $c failed:"; tail -5 "$W/spall_${c}_2.out"; exit 1; }
        ( cd "$W" && OMP_NUM_THREADS=1 /usr/bin/time -f "%M" -o "lmp_${c}_2.mem" \
            mpirun --allow-run-as-root --oversubscribe -np 2 "$LMP" -in "in.$c" \
            -log "lmp_${c}_2.log" -screen none > "lmp_${c}_2.out" 2>&1 ) ||
            { echo "lammps 2-rank run $c failed:"; tail -5 "$W/lmp_${c}_2.out"; exit 1; }
    done
fi
python3 - "$W" "$CHECK" "$RANKS" <<'PY'
import sys, csv, re, os
W, check, ranks = sys.argv[1], sys.argv[2] == "1", sys.argv[3] == "1"
def spall(c):
    last = list(csv.DictReader(open(f"{W}/{c}/history.csv")))[-1]
    return float(last["damage_sum"]), float([v for k, v in last.items() if k.startswith("p_ux")][0])
def lmp(c):
    th = re.findall(r"^\s*(\d+)\s+([-0-9.eE+]+)\s+([-0-9.eE+]+)\s*$", open(f"{W}/lmp_{c}.log").read(), re.M)
    return float(th[-1][1]), float(th[-1][2])
def rel(a, b):
    return abs(a - b) / max(abs(b), 1e-300)
S = {c: spall(c) for c in ("lps", "eps-elastic", "eps-plastic")}
L = {c: lmp(c) for c in ("lps", "eps-elastic", "eps-plastic", "lmp-lps-ref")}
print(f"{'case':<12} {'spall damage_sum':>18} {'LAMMPS damage_sum':>18} {'spall probe ux':>22} {'LAMMPS probe ux':>22} {'rel diff ux':>11}")
for c in S:
    print(f"{c:<12} {S[c][0]:18.10g} {L[c][0]:18.10g} {S[c][1]:22.15g} {L[c][1]:22.15g} {rel(S[c][1], L[c][1]):11.3g}")
ok = True
def expect(what, good):
    global ok
    print(f"  {'ok  ' if good else 'FAIL'} {what}")
    ok = ok and good
# the same model: identical up to the order of floating-point sums (1e-9 on
# u_x; the damage sum of a fracturing block is a count of broken bonds /
# family sizes and must match exactly)
expect(f"lps: damage_sum equal ({S['lps'][0]!r} vs {L['lps'][0]!r})", abs(S['lps'][0] - L['lps'][0]) <= 1e-9 * max(1.0, abs(L['lps'][0])))
expect(f"lps: probe u_x rel. diff {rel(S['lps'][1], L['lps'][1]):.2e} <= 1e-9", rel(S['lps'][1], L['lps'][1]) <= 1e-9)
expect(f"eps-elastic: spall eps = LAMMPS lps (u_x rel. diff {rel(S['eps-elastic'][1], L['lmp-lps-ref'][1]):.2e} <= 1e-9)",
       rel(S['eps-elastic'][1], L['lmp-lps-ref'][1]) <= 1e-9 and abs(S['eps-elastic'][0] - L['lmp-lps-ref'][0]) <= 1e-9 * max(1.0, abs(L['lmp-lps-ref'][0])))
gap, lgap = rel(S['eps-elastic'][1], L['eps-elastic'][1]), rel(L['lmp-lps-ref'][1], L['eps-elastic'][1])
print(f"  eps-elastic: spall-LAMMPS gap on u_x {gap:.3e}; LAMMPS lps-vs-eps gap {lgap:.3e} (the theta_i term)")
print(f"  eps-plastic: spall / LAMMPS damage_sum {S['eps-plastic'][0]:.6g} / {L['eps-plastic'][0]:.6g}, u_x {S['eps-plastic'][1]:.6g} / {L['eps-plastic'][1]:.6g} (not compared)")
# the race: loop wall time, bond-steps/s (each bond once), peak RSS per particle
def spall_time(c, T):
    out = open(f"{W}/spall_{c}{'' if T == 1 else '_2'}.out").read()
    log = open(f"{W}/{c if T == 1 else c + '_2'}/run.log").read()
    n = int(re.search(r"^particles: (\d+)", log, re.M).group(1))
    bonds = int(re.search(r"^interactions: (\d+)", log, re.M).group(1))
    steps = int(re.search(r"^steps_done: (\d+)", log, re.M).group(1))
    wall = float(re.search(r"([0-9.eE+-]+) s wall", out).group(1))
    # one peak per process (ranks append theirs): the run's memory is their sum
    peaks = [float(v) * 1024 for v in open(f"{W}/spall_{c}_{T}.mem").read().split()]
    ma = re.search(r"model arrays: (\d+) B, (\d+) B/particle", log)
    setup = re.search(r"^setup: (\w+)", log, re.M)
    return (n, bonds, steps, wall, sum(peaks), int(ma.group(2)) if ma else None, peaks,
            setup.group(1) if setup else "serial")
def lmp_time(c, T):
    lg = open(f"{W}/lmp_{c}{'' if T == 1 else '_2'}.log").read()
    m = re.findall(r"Loop time of ([0-9.eE+-]+) on \d+ procs for (\d+) steps with (\d+) atoms", lg)[-1]
    own = re.findall(r"Per MPI rank memory allocation \(min/avg/max\) = [0-9.]+ \| ([0-9.]+) \|", lg)[-1]
    # /usr/bin/time sees the largest process of the tree: x ranks (as pd_vs_lammps.sh)
    mem = float(open(f"{W}/lmp_{c}_{T}.mem").read().split()[-1]) * 1024 * T
    return int(m[2]), float(m[0]), mem, float(own) * 2**20 * T
cores = (1,) if check else (1, 2)
print(f"\n{'case':<12} {'cores':>5} {'code':<7} {'loop wall s':>11} {'bond-steps/s':>13} "
      f"{'RSS B/part':>11} {'own B/part':>11}")
ratio, per_rank = [], []
for c in ("lps", "eps-elastic"):
    for T in cores:
        n, bonds, steps, sw, sm, sown, peaks, setup = spall_time(c, T)
        ln, lw, lm, lown = lmp_time(c, T)
        how = "" if T == 1 else (" (2 ranks)" if ranks else " (2 threads)")
        print(f"{c:<12} {T:>5} {'spall':<7} {sw:11.4g} {bonds * steps / sw:13.4g} {sm / n:11.0f} "
              f"{sown if sown is not None else float('nan'):11.0f}{how}")
        print(f"{'':<12} {T:>5} {'LAMMPS':<7} {lw:11.4g} {bonds * steps / lw:13.4g} {lm / ln:11.0f} "
              f"{lown / ln:11.0f} ({T} rank{'s' if T > 1 else ''})")
        ratio.append((c, T, lw / sw, sm / lm))
        if T > 1 and ranks: # each rank's peak against LAMMPS' largest rank
            per_rank.append((c, setup, peaks, lm / T, n))
for c, T, thr, mem in ratio:
    print(f"  {c} on {T} core{'s' if T > 1 else ''}: spall / LAMMPS throughput {thr:.2f}x per core, "
          f"peak memory per particle {mem:.2f} of LAMMPS'")
for c, setup, peaks, lrank, n in per_rank:
    print(f"  {c} on 2 ranks ({setup} set-up): peak RSS per rank "
          f"{' / '.join(f'{v / 2**20:.1f}' for v in peaks)} MiB "
          f"({' / '.join(f'{v / n:.0f}' for v in peaks)} B per particle of the body), LAMMPS' "
          f"largest rank {lrank / 2**20:.1f} MiB ({lrank / n:.0f} B): "
          f"{max(peaks) / lrank:.2f} of LAMMPS'")
if check and not ok:
    sys.exit(1)
PY
if [ $CHECK = 1 ]; then rm -rf "$W"; fi
