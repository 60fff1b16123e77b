#!/usr/bin/env bash
# Error agreement under MPI (docs/parallel.md, "Error agreement"): one rank
# fails alone at a chosen site (SPALL_FAULT=site:rank, core/parallel/comm.h
# par_fault) between deck load and the first step, at a frame, at a
# checkpoint and at a restart's load; every launch must end within seconds
# (under `timeout`: a hang fails) with a non-zero status, print the failing
# rank's cause once, and leave no output behind (set-up sites) or the
# outputs already written untouched (the restart into its own directory).
# The faulted ranks vary (the last, a middle and rank 0), so the cause
# travels to rank 0, which prints it, from any of them.  Ten sites on 3
# ranks and three again on 2; under SPALL_MPI_RANK_COUNTS (the sanitized
# suite) three sites on its largest rank count.
# Usage: mpi_fault.sh SPALL SRC MPIEXEC
set -u
spall="$1"
mpiexec="$3"
# shellcheck source=lib/mpi_env.bash
source "$2/tests/cli/lib/mpi_env.bash"
decks="$2/tests/cli/decks"
export OMP_NUM_THREADS=1
np="${SPALL_MPI_RANK_COUNTS:-3}"
np="${np##* }" # the largest listed rank count (ASan: 3)
[ "$np" -ge 2 ] 2>/dev/null || np=3
on() { # rank count: the launches from here on
    np="$1"
    last=$((np - 1))
    launch="timeout 60 $mpiexec --allow-run-as-root --oversubscribe -q -np $np"
}
on "$np"
fail=0
# the lattice plate (distributed set-up) with a checkpoint every 10 steps;
# the same replicated (Zoltan partitions the whole body); the LPS plate with
# the surface correction (its passes exchange halo values in the set-up)
sed 's/^run: {steps: 300}$/run: {steps: 20}/;
     s/^output: {field_every: 100, history_every: 10}$/output: {field_every: 10, history_every: 5, checkpoint: {every_steps: 10}}/' \
    "$decks/mpi_frac.yaml" > lat.yaml
{ cat lat.yaml; echo 'parallel: {setup: replicated}'; } > rep.yaml
sed 's/^model: {type: peridynamics}$/model: {type: peridynamics, formulation: lps, surface_correction: true}/;
     s/youngs_modulus: 72.0e9, fracture_energy/youngs_modulus: 72.0e9, poisson_ratio: 0.22, fracture_energy/;
     s/^run: {steps: 300}$/run: {steps: 10}/' "$decks/mpi_pd.yaml" > lps.yaml
grep -q "checkpoint: {every_steps: 10}" lat.yaml && grep -q "surface_correction: true" lps.yaml ||
    { echo "FAIL: cannot make lat.yaml, lps.yaml"; exit 1; }

# site rank deck out expect-out(absent|kept) [extra spall args]
faulted() {
    local site="$1" rank="$2" deck="$3" out="$4" want="$5"
    shift 5
    [ "$want" = absent ] && rm -rf "$out"
    local t0=$SECONDS
    SPALL_FAULT="$site:$rank" $launch "$spall" run "$deck" -o "$out" --quiet "$@" \
        >stdout.txt 2>stderr.txt
    local rc=$? secs=$((SECONDS - t0))
    local cause="fault injected at '$site' on rank $rank"
    # 4: the fault's SPALL_ERR_IO; 2: a body's fill error names its deck
    # key (an input error); anything else is a hang (124, 137), a crash or
    # a sanitizer's report (LeakSanitizer: 23)
    if [ $rc -ne 4 ] && [ $rc -ne 2 ]; then
        echo "FAIL $site:$rank: exit $rc after $secs s (expected 2 or 4, no hang)"
        cat stderr.txt; fail=1
    elif [ "$(grep -c "^spall: error: .*$cause" stderr.txt)" -ne 1 ] ||
        [ "$(grep -c "fault injected" stderr.txt)" -ne 1 ]; then
        echo "FAIL $site:$rank: the cause is not printed once"; cat stderr.txt; fail=1
    elif [ "$(grep -o "$deck:[0-9]*:[0-9]*:" stderr.txt | wc -l)" -gt 1 ]; then
        # the ranks word an agreed error alike: one location, not the
        # failing rank's and again the others'
        echo "FAIL $site:$rank: the location is repeated"; cat stderr.txt; fail=1
    elif [ "$want" = absent ] && [ -e "$out" ]; then
        echo "FAIL $site:$rank: output directory '$out' created"; fail=1
    else
        echo "ok $site:$rank ($np ranks): exit $rc in $secs s"
    fi
}
if [ -n "${SPALL_MPI_RANK_COUNTS:-}" ]; then
    # the sanitized suite (SPALL_MPI_RANK_COUNTS=3; a launch there takes
    # 10-20 s): a set-up site, the set-up's halo exchange and a frame; every
    # site ran clean under ASan by hand (docs/parallel.md)
    faulted setup_fill "$last" lat.yaml o_fill absent
    faulted halo_values 1 lps.yaml o_halo absent
    faulted frame 0 lat.yaml o_frame kept
    [ $fail -eq 0 ] && echo "mpi_fault: all passed (3 sites)"
    exit $fail
fi
faulted deck "$last" lat.yaml o_deck absent
faulted setup_fill "$last" lat.yaml o_fill absent
faulted halo_values 1 lps.yaml o_halo absent
faulted model_init "$last" lps.yaml o_init absent
faulted partition 1 rep.yaml o_part kept
faulted localize "$last" lat.yaml o_loc absent
faulted output_open "$last" lat.yaml o_open kept
faulted frame 0 lat.yaml o_frame kept
faulted checkpoint "$last" lat.yaml o_ckpt kept
# o_ckpt stopped at its first checkpoint, with none written; a complete run
# gives the restart its checkpoints, and the faulted restart into the same
# directory must leave every file there as it was
if ! $launch "$spall" run lat.yaml -o run --quiet >stdout.txt 2>stderr.txt; then
    echo "FAIL: the run to restart from"; cat stderr.txt; fail=1
fi
if [ ! -e o_ckpt/run.log ] || ls o_ckpt/checkpoint_*.h5 >/dev/null 2>&1 ||
    ! grep -q "status: FAILED: fault injected at 'checkpoint'" o_ckpt/run.log; then
    echo "FAIL checkpoint: run.log lacks the failure, or a checkpoint was left"; fail=1
fi
before="$(cd run && md5sum ./* | sort)"
faulted restart "$last" lat.yaml run kept --restart run
if [ "$(cd run && md5sum ./* | sort)" != "$before" ]; then
    echo "FAIL restart: the run's files changed"; fail=1
fi
# and on 2 ranks: a set-up, a frame and a checkpoint site, rank 1 and rank
# 0 failing
on 2
faulted setup_fill 1 lat.yaml o2_fill absent
faulted frame 1 lat.yaml o2_frame kept
faulted checkpoint 0 lat.yaml o2_ckpt kept
[ $fail -eq 0 ] && echo "mpi_fault: all passed"
[ $fail -eq 0 ]
