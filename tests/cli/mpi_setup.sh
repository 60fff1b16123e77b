#!/usr/bin/env bash
# Distributed set-up (issue 20, docs/parallel.md "Distributed set-up"): under
# mpirun each rank builds only its block of the body and a halo; the run must
# give the bytes of one rank and of the replicated set-up (every rank
# building the whole body, parallel.setup: replicated): cmp of history.csv,
# h5diff of every frame.  Lattice (2D triangular, 3D fcc) and PMB (2D
# square, 3D sc) decks, each with a pre-crack, groups, velocity or force or
# traction BCs and a probe, on 2, 3 and 4 ranks (3D: 4); the replicated
# set-up of the 2D lattice and 3D PMB decks on 3 ranks.  Several bodies
# (bodies:, one window per body): two lattice bodies (one on a rotated
# lattice, closer than a bond range), two PMB bodies more than a range
# apart, the thermal deck's inclusions and a reduced flyer-plate spall with
# particle contact, on 2, 3 and 4 ranks and replicated on 3.  State-based
# PD (formulation lps on the 2D PMB deck, eps with plasticity and the cubic
# influence correction on the 3D one) and the surface correction (PMB and
# lps, 2D) on 2, 3 and 4 ranks and replicated on 3 (their stable step,
# whose bound reads the partners' families, is the serial one bit for bit;
# the lps correction's fixed point takes the halo's factors from their
# blocks' ranks every pass).  run.log says which set-up ran and gives the
# whole body's counts, and a deck the distributed set-up does not support
# (PMB bodies within a range of each other, whose bonds may join them)
# keeps the replicated one with a one-line reason.
# SPALL_TEST_LIGHT=1 (the sanitizer build, CMakeLists.txt) runs each
# distributed set-up formulation once, with 9 launches of mpirun instead of
# 23: the 3D lattice and PMB decks, the several bodies, the contact deck,
# eps and both surface corrections on 3 ranks (the 2D lattice and PMB, lps
# and thermal decks are left out: cli_mpi_ranks and cli_mpi_models run
# those very decks on 3 ranks under the sanitizers, set up distributed),
# the bodies within a range (replicated set-up) on 2, no deck with
# parallel.setup: replicated (the same set-up as those bodies'), and the
# runs of 300 and 120 steps to 100 (the references still break 145 bonds
# or more, the check below unchanged).
# Usage: mpi_setup.sh SPALL SRC MPIEXEC
set -u
spall="$1"
mpiexec="$3"
# shellcheck source=lib/mpi_env.bash
source "$2/tests/cli/lib/mpi_env.bash"
decks="$2/tests/cli/decks"
cp "$decks/mpi_frac.yaml" lat2.yaml
cp "$decks/mpi_pd.yaml" pd2.yaml
cp "$decks/mpi_setup_fcc.yaml" lat3.yaml
cp "$decks/mpi_setup_pd3.yaml" pd3.yaml
cp "$decks/mpi_thermal.yaml" thermal.yaml
cp "$decks/mpi_setup_bodies.yaml" bod2.yaml
cp "$decks/mpi_setup_pd_bodies.yaml" pdb2.yaml
cp "$decks/mpi_setup_contact.yaml" con2.yaml
# the PMB strip (its groups, pre-crack and probe) moved 4 mm down, 2 mm
# above the plate: within the family radius, so bonds join the bodies
sed -e 's/0\.02599/0.02199/; s/0\.03601/0.03201/; s/0\.0335/0.0295/; s/0\.0255/0.0215/' \
    -e 's/0\.0275/0.0235/; s/0\.0305/0.0265/g' pdb2.yaml > pdnear.yaml
# state-based PD: lps (2D), eps with plasticity and the cubic influence
# correction (3D); the surface correction of PMB and lps (2D: its 21 rows
# take 56 passes of the lps fixed point, more than a window's halo holds)
sed 's/^model: {type: peridynamics}$/model: {type: peridynamics, formulation: lps}/;
     s/youngs_modulus: 72.0e9, fracture_energy/youngs_modulus: 72.0e9, poisson_ratio: 0.22, fracture_energy/' \
    pd2.yaml > lps2.yaml
sed 's/^model: {type: peridynamics}$/model: {type: peridynamics, formulation: eps, influence_correction: cubic}/;
     s/youngs_modulus: 72.0e9, fracture_energy/youngs_modulus: 72.0e9, poisson_ratio: 0.22, yield_stress: 3.0e6, fracture_energy/;
     s/^output: {field_every: 40, history_every: 10}$/output: {field_every: 40, history_every: 10, fields: [position, damage, plastic_strain]}/' \
    pd3.yaml > eps3.yaml
sed 's/^model: {type: peridynamics}$/model: {type: peridynamics, surface_correction: true}/' pd2.yaml > pdsc2.yaml
sed 's/^model: {type: peridynamics, formulation: lps}$/model: {type: peridynamics, formulation: lps, surface_correction: true}/' \
    lps2.yaml > lpssc.yaml
grep -q "formulation: lps}" lps2.yaml && grep -q "poisson_ratio: 0.22" lps2.yaml &&
    grep -q "formulation: eps, influence_correction: cubic}" eps3.yaml &&
    grep -q "yield_stress: 3.0e6" eps3.yaml && grep -q "plastic_strain" eps3.yaml &&
    grep -q "surface_correction: true}" pdsc2.yaml && grep -q "lps, surface_correction: true}" lpssc.yaml ||
    { echo "FAIL: cannot make lps2, eps3, pdsc2, lpssc.yaml"; exit 1; }
light=${SPALL_TEST_LIGHT:-0}
all="lat2 pd2 lat3 pd3 bod2 pdb2 thermal con2 lps2 eps3 pdsc2 lpssc"
if [ "$light" = 1 ]; then
    all="lat3 pd3 bod2 pdb2 con2 eps3 pdsc2 lpssc"
    for d in lat3 bod2 pdb2 con2 pdsc2 lpssc pdnear; do
        sed -i 's/^run: {steps: \(300\|120\)}$/run: {steps: 100}/' "$d.yaml"
        grep -q "^run: {steps: 100}$" "$d.yaml" || { echo "FAIL: cannot shorten $d.yaml"; exit 1; }
    done
fi
fail=0
mpi() { # ranks out deck
    OMP_NUM_THREADS=1 timeout 120 "$mpiexec" --allow-run-as-root --oversubscribe -q -np "$1" \
        "$spall" run "$3" -o "$2" --quiet --no-progress || { echo "FAIL $2: exit $?"; fail=1; }
}
compare() { # reference out
    cmp -s "$1/history.csv" "$2/history.csv" || { echo "FAIL $2: history.csv differs"; fail=1; }
    local f
    for f in "$1"/fields_*.h5; do
        h5diff -q "$f" "$2/$(basename "$f")" || { echo "FAIL $2: $(basename "$f") differs"; fail=1; }
    done
}
setup_line() { # out expected-prefix
    grep -q "^setup: $2" "$1/run.log" || { echo "FAIL $1/run.log: no 'setup: $2'"; fail=1; }
}
for d in $all; do
    OMP_NUM_THREADS=1 timeout 120 "$spall" run "$d.yaml" -o "$d-1" --quiet --no-progress ||
        { echo "FAIL $d serial run"; exit 1; }
    # the references must break bonds beyond the pre-crack, else the test proves little
    b=$(awk -F, 'NR == 1 {for (k = 1; k <= NF; k++) if ($k == "bonds_broken") c = k}
                 END {print $c}' "$d-1/history.csv")
    awk -v b="$b" 'BEGIN {exit !(b > 20)}' || { echo "FAIL $d broke too few bonds ($b)"; fail=1; }
    case $d in thermal | con2) ;; *) # (no pre-crack: heating, an impact)
        grep -q "^precut_bonds: [1-9]" "$d-1/run.log" || { echo "FAIL $d: no pre-cut bonds"; fail=1; }
    esac
    # (the ASan build sets SPALL_MPI_RANK_COUNTS=3: 3 ranks only, CMakeLists.txt)
    counts="${SPALL_MPI_RANK_COUNTS:-2 3 4}"
    case $d in lat3 | pd3) counts="${SPALL_MPI_RANK_COUNTS:-4}" ;; esac
    last=${counts##* }
    for n in $counts; do
        mpi "$n" "$d-$n" "$d.yaml"
        compare "$d-1" "$d-$n"
        setup_line "$d-$n" "distributed"
    done
    # the whole body's counts in run.log, not a rank's
    for k in particles interactions precut_bonds; do
        [ "$(grep "^$k:" "$d-1/run.log")" = "$(grep "^$k:" "$d-$last/run.log")" ] ||
            { echo "FAIL $d: run.log $k differs from one rank's"; fail=1; }
    done
    [ "$light" = 1 ] && continue
    case $d in lat3 | pd2) continue ;; esac
    # the replicated set-up of the same deck: the same bytes
    { cat "$d.yaml"; echo "parallel: {setup: replicated}"; } > "$d-rep.yaml"
    mpi 3 "$d-r3" "$d-rep.yaml"
    compare "$d-1" "$d-r3"
    setup_line "$d-r3" "replicated on every rank (parallel.setup: replicated)"
done
# not supported: PMB bodies whose bonds may join them keep the replicated
# set-up, said in run.log, and still give one rank's bytes
grep -q "0.02199" pdnear.yaml || { echo "FAIL pdnear.yaml: the strip did not move"; fail=1; }
OMP_NUM_THREADS=1 timeout 120 "$spall" run pdnear.yaml -o pdnear-1 --quiet --no-progress ||
    { echo "FAIL pdnear serial run"; fail=1; }
mpi 2 pdnear-2 pdnear.yaml
compare pdnear-1 pdnear-2
setup_line pdnear-2 "replicated on every rank (bodies within one interaction range"
# eps3 must yield, else its plastic state proves little
h5dump -y -w 0 -d /plastic_strain -o eps3-plastic.txt eps3-1/fields_000002.h5 > /dev/null
yielded=$(tr ', ' '\n\n' < eps3-plastic.txt | awk 'NF && $1 > 0 {n++} END {print n + 0}')
[ "$yielded" -gt 20 ] || { echo "FAIL eps3: $yielded particles yielded"; fail=1; }
[ $fail -eq 0 ] && [ "$light" = 1 ] && echo "mpi_setup (light): distributed set-up = one rank" \
    "($all on 3 ranks; bodies within a range replicated on 2)"
[ $fail -eq 0 ] && [ "$light" != 1 ] && echo "mpi_setup: distributed set-up = replicated = one rank" \
    "(lattice and PMB, 2D and 3D, several bodies, inclusions, contact, lps, eps, surface" \
    "correction, 2-4 ranks)"
[ $fail -eq 0 ]
