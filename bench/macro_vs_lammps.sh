#!/usr/bin/env bash
# Race and cross-check: spall's macro-particle model against LAMMPS
# `pair_style mie/cut` (Debian's `lammps`) on the same FCC rod.  Usage:
#     bench/macro_vs_lammps.sh [--check] [--ranks] [path/to/spall] [NPHI NH STEPS]
# --check (the ctest `macro_vs_lammps`, label lammps): the agreement checks
# only (no timings); exit 77 (skipped) without `lmp`, 1 when a check fails.
# --ranks: spall's 2-core run is 2 MPI ranks x 1 thread (rank for rank with
# LAMMPS' 2 ranks) instead of 2 OpenMP threads in one process; the
# agreement run is made on 2 ranks too, checked against LAMMPS as the
# 1-rank run and its positions after 100 steps bitwise against 1 rank's.
# Without --check a missing `lmp` is installed (Debian package, root) and the
# throughput is measured too.
#
# Problem (identical in both codes): the Al rod of [Saitoh] section 2.6,
# diameter 14 mm, NPHI cubic cells of edge a = 14 mm / NPHI across it and NH
# along it (default 16 x 64: 51 413 particles, bench `macro-rod`),
# r0 = a / sqrt2, Mie exponents p = 4, q = 9, D = P_atom / 6 (Eq. 13,
# calibration eq15), particle mass rho r0^3 / sqrt2; cut-off r_c = 1.5 r0
# (first and second FCC shells, 1 and 1.414 r0: the second shell gives the
# rod's surface particles a net force at step 0, so the step-0 forces are not
# round-off), Verlet skin 0.1 r0 (LAMMPS `neighbor 0.1 r0 bin`, checked every
# step), dt = 3.2e-6 s/m x r0 (0.32 of spall's stability limit), velocity
# Verlet (LAMMPS fix nve), the end layers given -/+ 5 m/s along z at t = 0,
# no damping, temperature or plasticity (spall's defaults).
# The Mie pair phi = D/(q-p) [p (r0/r)^q - q (r0/r)^p] is LAMMPS' mie/cut
# C eps [(sigma/r)^gR - (sigma/r)^gA], C = gR/(gR-gA) (gR/gA)^(gA/(gR-gA)),
# with eps = D, gR = q, gA = p, sigma = r0 (p/q)^(1/(q-p)) (then
# C eps sigma^q = D p r0^q/(q-p) and C eps sigma^p = D q r0^p/(q-p)).
# spall multiplies phi by a cubic switch from r_on = taper r0 to r_c; LAMMPS
# cuts it off plainly.  With taper 1.45 no pair is in [r_on, r_c) (the
# shells sit at 1 and 1.414 r0, the next at 1.732): the script checks that
# no pair is there at step 0 and after the compared steps, so there the two
# potentials are the same function.
# Data flow: spall writes its step-0 positions, velocities and masses
# (fields_000000.h5, read with h5dump -b); the LAMMPS data file is written
# from them, so both start from the same bits.
# Checks: forces at step 0, max over particles of |f_spall - f_lammps|_inf
# over max over particles of |f_lammps|_inf, <= 1e-12; positions after 100
# steps, max |x_spall - x_lammps|_inf over the largest displacement, <= 1e-9
# (and velocities, over the largest velocity); spall's 1- and 2-thread
# positions bitwise equal.  Throughput (not --check): STEPS steps (default
# 1000) on 1 and 2 cores (spall: OpenMP threads, or MPI ranks with
# --ranks; LAMMPS: MPI ranks, the Debian build has no OPENMP package),
# particle-steps/s and pair-steps/s (each pair r < r_c at step 0 counted
# once), spall / LAMMPS per core, on
# the wall clock and per CPU-second (user + sys of the process: on a loaded
# machine the wall clock measures the load more than the code).
set -euo pipefail
CHECK=0 RANKS=0
while [ $# -gt 0 ]; do
    case "$1" in
        --check) CHECK=1; shift ;;
        --ranks) RANKS=1; shift ;;
        *) break ;;
    esac
done
MPIRUN=(mpirun --allow-run-as-root --oversubscribe -np 2)
SPALL=${1:-build/spall}
NPHI=${2:-16}; NH=${3:-64}; STEPS=${4:-1000}
NAME=macro_vs_lammps
. "$(dirname "$0")/lammps_setup.sh"
export OMP_NUM_THREADS=1
python3 - "$W" "$NPHI" "$NH" "$STEPS" <<'PY'
import sys, math
W, nphi, nh, steps = sys.argv[1], int(sys.argv[2]), int(sys.argv[3]), int(sys.argv[4])
D_rod = 14.0e-3
a = D_rod / nphi
r0 = a / math.sqrt(2.0)
L = nh * a
e = 1e-7 * D_rod
dt = float("%.4g" % (3.2e-6 * r0))
def deck(name, nsteps, fields):
    return f"""title: {name} - macro-particle rod side by side with LAMMPS mie/cut
model: {{type: macroparticle, cutoff: 1.5, taper: 1.45, skin: 0.1}}
materials:
  al: {{density: 2700, atomic_mass_u: 26.98, cohesive_energy_ev: 3.39, exponents: [4, 9]}}
lattice: {{type: fcc, spacing: {r0!r}}}
geometry:
  rod: {{cylinder: {{base: [0, 0, {-e!r}], top: [0, 0, {L + e!r}], radius: {0.5 * D_rod + e!r}}}}}
body: {{geometry: rod, material: al}}
groups:
  bottom: {{box: {{min: [-1, -1, -1], max: [1, 1, {0.25 * r0!r}]}}}}
  top: {{box: {{min: [-1, -1, {L - 0.25 * r0!r}], max: [1, 1, 1]}}}}
initial_velocity:
  - {{group: bottom, value: [0, 0, -5.0]}}
  - {{group: top, value: [0, 0, 5.0]}}
run: {{dt: {dt!r}, steps: {nsteps}, max_particles: 1e9}}
output: {{field_every: {nsteps}, history_every: {nsteps}, fields: [{fields}]}}
"""
open(f"{W}/agree.yaml", "w").write(deck("agree", 100, "position, velocity, force, mass"))
open(f"{W}/race.yaml", "w").write(deck("race", steps, "position"))
# the pair constants exactly as macro_calibrate computes them (same operations)
PI, AMU, EV, PACK = math.pi, 1.66053906660e-27, 1.602176634e-19, 0.74
rho, p, q = 2700.0, 4.0, 9.0
n_atom = (rho * PI * r0 * r0 * r0 / 6.0) / (26.98 * AMU * PACK)
D = n_atom * (3.39 * EV) / 6.0
sigma = r0 * (p / q) ** (1.0 / (q - p))
open(f"{W}/pair.txt", "w").write(f"{r0!r} {dt!r} {D!r} {sigma!r} {q!r} {p!r} {1.5 * r0!r} {0.1 * r0!r}\n")
PY
read -r R0 DT EPS SIGMA GR GA RC SKIN < "$W/pair.txt"
# ---- spall: the agreement run (100 steps, frames at steps 0 and 100) -----
run_or_show() { # $1 log file, rest: the command (run in $W); its log is shown when it fails
    local log=$1; shift
    (cd "$W" && "$@" > "$log" 2>&1) || { cat "$W/$log"; echo "macro_vs_lammps: '$*' failed"; exit 1; }
}
run_or_show agree.out "$SPALL" run agree.yaml -o agree --threads 1
run_or_show agree2.out "$SPALL" run agree.yaml -o agree2 --threads 2
if [ $RANKS = 1 ]; then
    run_or_show agree_r2.out "${MPIRUN[@]}" "$SPALL" run agree.yaml -o agree_r2 --threads 1
    for f in position velocity force; do
        for k in 000000 000001; do
            h5dump -d /$f -b LE -o "$W/agree_r2_${f}_$k.bin" "$W/agree_r2/fields_$k.h5" >/dev/null
        done
    done
fi
# ---- LAMMPS data file from spall's step-0 state ---------------------------
for f in position velocity force mass; do
    for k in 000000 000001; do
        h5dump -d /$f -b LE -o "$W/agree_${f}_$k.bin" "$W/agree/fields_$k.h5" >/dev/null
    done
done
h5dump -d /position -b LE -o "$W/agree2_position_000001.bin" "$W/agree2/fields_000001.h5" >/dev/null
python3 - "$W" "$R0" "$RC" <<'PY'
import sys, array
W, r0, rc = sys.argv[1], float(sys.argv[2]), float(sys.argv[3])
def load(name):
    a = array.array("d")
    a.frombytes(open(f"{W}/{name}.bin", "rb").read())
    return a
x, v, m = load("agree_position_000000"), load("agree_velocity_000000"), load("agree_mass_000000")
n = len(m)
if any(mi != m[0] for mi in m):
    sys.exit("macro_vs_lammps: particle masses differ; atom_style atomic needs one mass")
lo = [min(x[d::3]) - 2 * r0 for d in range(3)]
hi = [max(x[d::3]) + 2 * r0 for d in range(3)]
with open(f"{W}/rod.data", "w") as f:
    f.write(f"spall macro-particle rod, {n} particles (from agree/fields_000000.h5)\n\n")
    f.write(f"{n} atoms\n1 atom types\n\n")
    for d, ax in enumerate("xyz"):
        f.write(f"{lo[d]!r} {hi[d]!r} {ax}lo {ax}hi\n")
    f.write(f"\nMasses\n\n1 {m[0]!r}\n\nAtoms # atomic\n\n")
    for i in range(n):
        f.write(f"{i + 1} 1 {x[3*i]!r} {x[3*i+1]!r} {x[3*i+2]!r}\n")
    f.write("\nVelocities\n\n")
    for i in range(n):
        f.write(f"{i + 1} {v[3*i]!r} {v[3*i+1]!r} {v[3*i+2]!r}\n")
PY
lmp_input() { # $1 steps, $2 dump (1) or not (0)
    cat <<LMP
units si
atom_style atomic
boundary f f f
read_data rod.data
pair_style mie/cut $RC
pair_coeff 1 1 $EPS $SIGMA $GR $GA
neighbor $SKIN bin
neigh_modify every 1 delay 0 check yes
timestep $DT
fix 1 all nve
thermo_style custom step pe ke
thermo_modify format float %.17g
thermo $1
LMP
    if [ "$2" = 1 ]; then
        echo "dump d all custom $1 dump.agree id x y z vx vy vz fx fy fz"
        echo "dump_modify d sort id format float %.17g"
    fi
    echo "run $1"
}
lmp_input 100 1 > "$W/in.agree"
run_or_show lmp_agree.out "$LMP" -in in.agree -log lmp_agree.log
python3 - "$W" "$R0" "$RC" <<'PY'
import sys, array, math
W, r0, rc = sys.argv[1], float(sys.argv[2]), float(sys.argv[3])
r_on = 1.45 * r0
def load(name):
    a = array.array("d")
    a.frombytes(open(f"{W}/{name}.bin", "rb").read())
    return a
import os
runs = {"": "1 rank"}
if os.path.exists(f"{W}/agree_r2_position_000001.bin"):
    runs["_r2"] = "2 ranks"
s = {k: {f: load(f"agree_{f}_{k}") for f in ("position", "velocity", "force")}
     for k in ("000000", "000001")}
n = len(s["000000"]["position"]) // 3
# LAMMPS dump: two snapshots (steps 0 and 100), sorted by id
snaps, cur = [], None
for line in open(f"{W}/dump.agree"):
    t = line.split()
    if line.startswith("ITEM: ATOMS"):
        cur = [None] * n
        snaps.append(cur)
    elif line.startswith("ITEM"):
        cur = None if not line.startswith("ITEM: ATOMS") else cur
    elif cur is not None and len(t) == 10:
        cur[int(t[0]) - 1] = [float(u) for u in t[1:]]
if len(snaps) != 2 or any(r is None for sn in snaps for r in sn):
    sys.exit("macro_vs_lammps: LAMMPS dump incomplete (see lmp_agree.log)")
def pairs_in(x, lo, hi):
    """number of pairs with lo <= r < hi (cell list of edge hi)"""
    cells = {}
    for i in range(n):
        c = tuple(int(math.floor(x[3*i+d] / hi)) for d in range(3))
        cells.setdefault(c, []).append(i)
    cnt = 0
    for c, mem in cells.items():
        for dx in (-1, 0, 1):
            for dy in (-1, 0, 1):
                for dz in (-1, 0, 1):
                    for j in cells.get((c[0]+dx, c[1]+dy, c[2]+dz), ()):
                        for i in mem:
                            if j <= i:
                                continue
                            r = math.sqrt(sum((x[3*j+d] - x[3*i+d]) ** 2 for d in range(3)))
                            cnt += lo <= r < hi
    return cnt
def rel(a, b, scale_of):
    """max_i |a_i - b_i|_inf / max_i |scale_i|_inf"""
    num = max(abs(a[3*i+d] - b[i][d]) for i in range(n) for d in range(3))
    den = max(abs(scale_of(i, d)) for i in range(n) for d in range(3))
    return num / den, num, den
fl, xl, vl = [r[6:9] for r in snaps[0]], [r[0:3] for r in snaps[1]], [r[3:6] for r in snaps[1]]
x0, xs = s["000000"]["position"], s["000001"]["position"]
t0 = pairs_in(x0, r_on, rc)
t1 = pairs_in(xs, r_on, rc)
npairs = pairs_in(x0, 0.0, rc)
open(f"{W}/pairs.txt", "w").write(f"{n} {npairs}\n")
print(f"particles {n}, pairs r < r_c {npairs}; pairs in the taper [1.45, 1.5) r0: step 0 {t0}, step 100 {t1}")
ok = t0 == 0 and t1 == 0
for tag, how in runs.items():
    f0, x1, v1 = (load(f"agree{tag}_{f}_{k}") for f, k in
                  (("force", "000000"), ("position", "000001"), ("velocity", "000001")))
    ef = rel(f0, fl, lambda i, d: fl[i][d])
    ex = rel(x1, xl, lambda i, d: xl[i][d] - x0[3*i+d])
    ev = rel(v1, vl, lambda i, d: vl[i][d])
    print(f"spall on {how}:")
    print(f"forces step 0:      max |df| {ef[1]:.3e} N / max |f| {ef[2]:.6g} N = {ef[0]:.3e} (limit 1e-12)")
    print(f"positions step 100: max |dx| {ex[1]:.3e} m / max displacement {ex[2]:.6g} m = {ex[0]:.3e} (limit 1e-9)")
    print(f"velocities step 100: max |dv| {ev[1]:.3e} m/s / max |v| {ev[2]:.6g} m/s = {ev[0]:.3e} (limit 1e-9)")
    ok = ok and ef[0] <= 1e-12 and ex[0] <= 1e-9 and ev[0] <= 1e-9
for tag, how in (("agree2", "2 threads"), ("agree_r2", "2 ranks")):
    if tag == "agree_r2" and "_r2" not in runs:
        continue
    same = load(f"{tag}_position_000001").tobytes() == xs.tobytes()
    print(f"spall 1 rank 1 thread vs {how}, positions at step 100: {'bitwise equal' if same else 'DIFFERENT'}")
    ok = ok and same
if not ok:
    sys.exit("macro_vs_lammps: FAILED")
print("macro_vs_lammps: agreement checks passed")
PY
if [ $CHECK = 1 ]; then rm -rf "$W"; exit 0; fi
# ---- throughput -----------------------------------------------------------
lmp_input "$STEPS" 0 > "$W/in.race"
for T in 1 2; do
    if [ $T = 2 ] && [ $RANKS = 1 ]; then
        run_or_show "race_$T.out" /usr/bin/time -f "%U %S" -o "race_$T.cpu" \
            "${MPIRUN[@]}" "$SPALL" run race.yaml -o "race_$T" --threads 1
    else
        run_or_show "race_$T.out" /usr/bin/time -f "%U %S" -o "race_$T.cpu" \
            "$SPALL" run race.yaml -o "race_$T" --threads $T
    fi
    if [ $T = 1 ]; then
        run_or_show "lmp_race_$T.out" /usr/bin/time -f "%U %S" -o "lmp_race_$T.cpu" \
            "$LMP" -in in.race -log "lmp_race_$T.log"
    else
        run_or_show "lmp_race_$T.out" /usr/bin/time -f "%U %S" -o "lmp_race_$T.cpu" \
            "${MPIRUN[@]}" "$LMP" -in in.race \
            -log "lmp_race_$T.log"
    fi
done
python3 - "$W" "$STEPS" "$RANKS" <<'PY'
import sys, re
W, steps, ranks = sys.argv[1], int(sys.argv[2]), sys.argv[3] == "1"
n, npairs = map(int, open(f"{W}/pairs.txt").read().split())
def cpu(path):
    return sum(map(float, open(path).read().split()[-2:]))
print(f"{n} particles, {npairs} pairs (r < r_c, counted once), {steps} steps")
print("wall: the time loop (spall run.log wall_seconds, LAMMPS 'Loop time'); CPU: user + sys "
      "of the whole process (set-up included), the fairer measure on a loaded machine")
print("spall on 2 cores: " + ("2 MPI ranks x 1 thread" if ranks else "2 OpenMP threads, one process"))
print(f"{'code':<7} {'cores':>5} {'wall_s':>8} {'particle-steps/s':>17} {'pair-steps/s':>13} "
      f"{'cpu_s':>8} {'particle-steps/cpu-s':>21}")
res = {}
for T in (1, 2):
    log = open(f"{W}/race_{T}/run.log").read()
    ws = float(re.search(r"^wall_seconds: ([0-9.eE+-]+)", log, re.M).group(1))
    lw = float(re.search(r"Loop time of ([0-9.eE+-]+)", open(f"{W}/lmp_race_{T}.log").read()).group(1))
    for code, w, c in (("spall", ws, cpu(f"{W}/race_{T}.cpu")), ("lammps", lw, cpu(f"{W}/lmp_race_{T}.cpu"))):
        res[(code, T)] = (n * steps / w, n * steps / c)
        print(f"{code:<7} {T:>5} {w:8.3f} {n * steps / w:17.4g} {npairs * steps / w:13.4g} "
              f"{c:8.3f} {n * steps / c:21.4g}")
for T in (1, 2):
    s, l = res[("spall", T)], res[("lammps", T)]
    print(f"{T} core(s): spall / LAMMPS = {s[0] / l[0]:.2f}x on the wall clock "
          f"(per core {s[0] / T:.4g} vs {l[0] / T:.4g} particle-steps/s), "
          f"{s[1] / l[1]:.2f}x per CPU-second")
PY
