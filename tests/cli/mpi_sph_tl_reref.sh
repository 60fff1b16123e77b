#!/usr/bin/env bash
# Rank-count independence of the reference updates of TLSPH bodies behind
# the penalty interface (issue 22 item 1; docs/parallel.md, "Re-referencing
# on several ranks"): a re-reference regathers the ghosts around the
# current positions and keeps the spatial ones, and the updated list is
# found again from its build positions, smoothing lengths and h_max.  A
# TLSPH strip on an updated-form block (tests/cli/decks/mpi_tl_ifc_reref.yaml,
# model.body_formulation, a re-reference every 15 steps with h grown)
# without mpirun, on 2 ranks and rebalanced every 20 steps on 3:
# history.csv, fields.xdmf byte for byte, every frame under h5diff; its
# checkpoints written by 2 ranks (the serial ones under h5diff) and the one
# of step 60 (just after a re-reference that grew h_max, the list of an
# older h_max kept until after step 75) continued on 1 (without mpirun) and
# on 3 ranks.  Not under ASan (the launches cost most): the continuation on
# 1, the strip on 3 and 4 ranks, with isotropy 0.97 (h grown at more re-references) on 2 ranks
# with a checkpoint every 5 steps, and two TLSPH blocks (type: tlsph,
# tests/cli/decks/mpi_tl_ifc.yaml) re-referenced every 5 steps on 3 and 2
# ranks, a checkpoint of 2 ranks continued on 3 (mpi_sph.sh runs them on 2
# ranks under ASan too).
# Usage: mpi_sph_tl_reref.sh SPALL SRC MPIEXEC
set -u
spall="$1"
mpiexec="$3"
# shellcheck source=lib/rank_compare.bash
source "$2/tests/cli/lib/rank_compare.bash"
value() { # checkpoint dataset: its first value
    h5dump -y -d "$2" "$1" | sed -n 's/^ *\([-0-9.e+]*\),\{0,1\} *$/\1/p' | head -1
}
cp "$2/tests/cli/decks/mpi_tl_ifc_reref.yaml" rr.yaml
serial rr
nr=$(col rr_serial/history.csv reference_updates)
[ "${nr:-0}" -ge 8 ] || { echo "FAIL: rr: ${nr:-0} reference updates"; fail=1; }
np=$(awk -F, 'NR == 1 {for (k = 1; k <= NF; k++) if ($k == "interface_pairs") c = k}
              NR > 1 && $c > 0 {n++} END {print n + 0}' rr_serial/history.csv)
[ "$np" -gt 10 ] || { echo "FAIL: rr: interface pairs in $np history rows"; fail=1; }
# what the restart of step 60 must show: h grown by the re-references, and
# at step 75 a list whose h_max (that of its build) is below the h_max now
ck=rr_serial/checkpoint_0000000075.h5
grown=$(value "$ck" /state/sph.tl_hgrown)
lh=$(value "$ck" /state/sph.list_hmax)
[ "${grown:-0}" -gt 50 ] || { echo "FAIL: rr: h grown ${grown:-0} times by step 75"; fail=1; }
awk -v l="${lh:-1}" 'BEGIN {exit !(l < 0.0017)}' ||
    { echo "FAIL: rr: the list of step 75 has h_max ${lh:-?} (expected the older 0.0015552)"; fail=1; }
written_on_2 rr
rebalanced rr 3
continued rr rr2/checkpoint_0000000060.h5 3
# the ASan build sets SPALL_MPI_RANK_COUNTS=3 (CMakeLists.txt): 3 ranks
# there are the rebalanced run and the continuation; the launches cost most
# (the serial continuation of the 2-rank checkpoint reads it as the 3-rank
# one does, without the partition: Release only, for make check's budget)
if [ -z "${SPALL_MPI_RANK_COUNTS:-}" ]; then
    continued rr rr2/checkpoint_0000000060.h5 1
    ranks rr 3
    ranks rr 4
    # isotropy 0.97: h_max reaches 2 h_0 at step 15, and later re-references
    # grow h of particles whose pairs the trim at the build's h decides (a
    # checkpoint every 5 steps holds such a list at step 60)
    sed 's/isotropy: 0.95}/isotropy: 0.97}/; s/every_steps: 15, keep: 20/every_steps: 5, keep: 40/' \
        rr.yaml > rr97.yaml
    grep -q "isotropy: 0.97}" rr97.yaml || { echo "FAIL: cannot make rr97.yaml"; exit 1; }
    serial rr97
    written_on_2 rr97
fi
# every body TLSPH (no updated loops): the same on the two blocks
sed 's/, interface: bodies}$/, interface: bodies, reference_update: {every: 5}}/' \
    "$2/tests/cli/decks/mpi_tl_ifc.yaml" > tt.yaml
echo "output: {field_interval: 1.0e-7, checkpoint: {every_steps: 10, keep: 5}}" >> tt.yaml
grep -q "reference_update: {every: 5}}" tt.yaml || { echo "FAIL: cannot make tt.yaml"; exit 1; }
if [ -z "${SPALL_MPI_RANK_COUNTS:-}" ]; then # (under ASan: on 2 ranks in mpi_sph.sh)
    serial tt
    nr=$(col tt_serial/history.csv reference_updates)
    [ "${nr:-0}" -ge 4 ] || { echo "FAIL: tt: ${nr:-0} reference updates"; fail=1; }
    ranks tt 3
    written_on_2 tt
    continued tt tt2/checkpoint_0000000010.h5 3
fi
[ $fail -eq 0 ] && echo "mpi_sph_tl_reref: OK"
exit $fail
