#!/usr/bin/env bash
# Checkpoint and restart from the command line (issue 21, docs/restart.md):
#  - a run killed with SIGKILL between checkpoints, restarted from its run
#    directory, ends bitwise identical to the uninterrupted run (history.csv,
#    XDMF index and the final checkpoint, whose bytes hold every particle
#    field and state slot);
#  - SIGTERM makes a run finish its step, checkpoint, say how to continue
#    and exit with status 75; the continued run is identical too;
#  - bad checkpoints: one line on stderr, exit 2, nothing written or changed.
# Usage: cli_restart.sh SPALL SRC
set -u
spall="$1"
src="$2"
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
cd "$tmp"
fail=0
pass=0
ok() { pass=$((pass+1)); }
ko() { echo "FAIL $*"; fail=$((fail+1)); }

# a plate with a hole pulled apart: ~4900 particles, fracture after ~1000 steps
deck() { # steps every_steps [youngs_modulus]
    cat <<YAML
model: {type: lattice, law: linear}
materials:
  m: {density: 1100, youngs_modulus: ${3:-3.26e9}, poisson_ratio: 0.3333333333333333,
      tensile_strength: 30.0e6}
lattice: {type: triangular, spacing: 1.0e-3}
geometry:
  plate: {box: {min: [0, 0], max: [0.07, 0.07]}}
  hole: {circle: {center: [0.035, 0.035], radius: 0.005}}
  specimen: {difference: [plate, hole]}
body: {geometry: specimen, material: m}
groups:
  bottom: {box: {min: [-1, -1], max: [1, 0.0015]}}
  top: {box: {min: [-1, 0.0685], max: [1, 1]}}
boundary_conditions:
  - {group: bottom, type: velocity, components: [x, y], value: [0, -10.0]}
  - {group: top, type: velocity, components: [x, y], value: [0, 10.0]}
run: {steps: $1}
output: {field_every: 500, history_every: 25, checkpoint: {every_steps: $2, keep: 2}}
YAML
}
deck 4000 500 > deck.yaml

same() { # name dirA dirB: identical results
    local name="$1" a="$2" b="$3" f
    for f in history.csv fields.xdmf checkpoint_0000004000.h5 fields_000008.h5.exists; do
        if [ "$f" = fields_000008.h5.exists ]; then
            [ -f "$b/fields_000008.h5" ] || { ko "$name: no last frame"; return; }
            continue
        fi
        cmp -s "$a/$f" "$b/$f" || { ko "$name: $f differs from the uninterrupted run"; return; }
    done
    ok
}

wait_for() { # file pid: wait until file exists (or the process ended)
    local k
    for k in $(seq 1 3000); do
        [ -e "$1" ] && return 0
        kill -0 "$2" 2>/dev/null || return 1
        sleep 0.01
    done
    return 1
}

"$spall" run deck.yaml -o ref --threads 2 >/dev/null 2>&1 || ko "reference run failed"

# ---- SIGKILL between checkpoints, restart from the run directory -----------
"$spall" run deck.yaml -o killed --threads 2 >/dev/null 2>&1 &
pid=$!
if wait_for killed/checkpoint_0000001000.h5 $pid; then
    kill -KILL $pid 2>/dev/null
    wait $pid 2>/dev/null
    if grep -q '^status:' killed/run.log; then
        ko "kill: the run had ended before SIGKILL (machine too fast for this deck?)"
    else
        "$spall" run deck.yaml --restart killed --threads 1 >stdout.txt 2>stderr.txt
        rc=$?
        [ $rc -eq 0 ] || { ko "kill: restart exit $rc"; cat stderr.txt; }
        grep -q '^restart_from: ' killed/run.log || ko "kill: run.log does not record the restart"
        same "kill" ref killed
    fi
else
    ko "kill: no checkpoint appeared"
    kill -KILL $pid 2>/dev/null
fi

# ---- SIGTERM: checkpoint, message, status 75, then continue ----------------
"$spall" run deck.yaml -o termed --threads 2 >stdout.txt 2>stderr.txt &
pid=$!
if wait_for termed/checkpoint_0000000500.h5 $pid; then
    kill -TERM $pid
    wait $pid
    rc=$?
    if [ $rc -ne 75 ]; then
        ko "sigterm: exit $rc, expected 75"; cat stderr.txt
    else
        ok
        grep -q -- "--restart termed" stderr.txt || { ko "sigterm: no continue line"; cat stderr.txt; }
        grep -q '^status: interrupted by signal 15' termed/run.log || ko "sigterm: run.log status"
        n=$(ls termed/checkpoint_*.h5 | wc -l)
        [ "$n" -ge 1 ] && [ "$n" -le 2 ] || ko "sigterm: $n checkpoints, keep is 2"
        "$spall" run deck.yaml --restart termed -o termed2 >/dev/null 2>stderr.txt ||
            { ko "sigterm: restart into another directory failed"; cat stderr.txt; }
        same "sigterm, continued copy" ref termed2
    fi
else
    ko "sigterm: no checkpoint appeared"
    kill -KILL $pid 2>/dev/null
fi

# ---- SIGUSR1 and SIGINT do the same ------------------------------------------
for sig in USR1 INT; do
    "$spall" run deck.yaml -o sig_$sig --threads 2 >stdout.txt 2>stderr.txt &
    pid=$!
    if wait_for sig_$sig/checkpoint_0000000500.h5 $pid; then
        kill -$sig $pid
        wait $pid
        rc=$?
        [ $rc -eq 75 ] || { ko "SIG$sig: exit $rc, expected 75"; cat stderr.txt; continue; }
        grep -q "^status: interrupted by signal $(kill -l $sig)" sig_$sig/run.log ||
            { ko "SIG$sig: run.log status"; continue; }
        ok
    else
        ko "SIG$sig: no checkpoint appeared"
        kill -KILL $pid 2>/dev/null
    fi
done

# ---- wall-clock checkpoints: when they fall depends on the machine, what a
# restart continues does not (and the checkpoint keys may change) ------------
sed 's/checkpoint: {every_steps: 500, keep: 2}/checkpoint: {every_minutes: 0.0005, keep: 2}/' deck.yaml > minutes.yaml
"$spall" run minutes.yaml -o minutes --threads 2 >/dev/null 2>stderr.txt || { ko "minutes: run"; cat stderr.txt; }
first=$(ls minutes/checkpoint_*.h5 2>/dev/null | head -1)
if [ -n "$first" ]; then
    "$spall" run deck.yaml --restart "$first" -o minutes2 --threads 1 >/dev/null 2>stderr.txt ||
        { ko "minutes: restart"; cat stderr.txt; }
    for f in history.csv fields.xdmf checkpoint_0000004000.h5; do
        cmp -s ref/$f minutes2/$f || ko "minutes: $f differs after restarting from $first"
    done
    ok
else
    ko "minutes: no checkpoint written (the run took under 30 ms?)"
fi

# ---- bad checkpoints ----------------------------------------------------------
good=$(ls ref/checkpoint_*.h5 | head -1) # the older of the two kept (keep: 2)
snapshot() { find ref -type f -exec md5sum {} + | sort; }
before=$(snapshot)
bad() { # name expected-substring deck restart-arg [-o dir]
    local name="$1" expect="$2" d="$3" arg="$4"
    shift 4
    "$spall" run "$d" --restart "$arg" "$@" >stdout.txt 2>stderr.txt
    local rc=$? lines
    lines=$(wc -l < stderr.txt)
    if [ $rc -ne 2 ]; then ko "$name: exit $rc, expected 2"; cat stderr.txt; return; fi
    if [ "$lines" -ne 1 ]; then ko "$name: $lines lines on stderr"; cat stderr.txt; return; fi
    if ! grep -q -- "$expect" stderr.txt; then ko "$name: message lacks '$expect'"; cat stderr.txt; return; fi
    if [ -e newdir ]; then ko "$name: created the output directory"; rm -rf newdir; return; fi
    if [ "$(snapshot)" != "$before" ]; then ko "$name: changed the run directory"; return; fi
    echo "ok $name: $(cat stderr.txt)"
    ok
}
size=$(stat -c %s $good)
head -c $((size / 2)) $good > truncated.h5
bad "truncated" "not a readable HDF5 file" deck.yaml truncated.h5 -o newdir
cp $good corrupt.h5
# one byte in the particle data (the file's middle): the checksum sees it
printf '\xff' | dd of=corrupt.h5 bs=1 seek=$((size / 2)) conv=notrunc status=none
bad "corrupt" "corrupt" deck.yaml corrupt.h5 -o newdir
deck 4000 500 4.0e9 > other.yaml
bad "changed key" "deck key 'materials.m.youngs_modulus' differs" other.yaml $good
sed 's/poisson_ratio: 0.3333333333333333,/poisson_ratio: 0.3333333333333333, compressive_failure_strain: 0.1,/' deck.yaml > added.yaml
bad "added key" "deck key 'materials.m.compressive_failure_strain' differs from the checkpointed run ('(absent)', now '0.1')" added.yaml $good -o newdir
# a key the checkpointed run had and the deck now lacks
deck 200 100 > short.yaml
sed 's/poisson_ratio: 0.3333333333333333,/poisson_ratio: 0.3333333333333333, compressive_failure_strain: 0.1,/' short.yaml > short_key.yaml
"$spall" run short_key.yaml -o withkey --quiet 2>stderr.txt || { ko "short run"; cat stderr.txt; }
bad "removed key" "deck key 'materials.m.compressive_failure_strain' differs from the checkpointed run ('0.1', now '(absent)')" short.yaml withkey -o newdir
sed 's/type: lattice, law: linear/type: peridynamics/; s/tensile_strength: 30.0e6/fracture_energy: 100/; s/, poisson_ratio: 0.3333333333333333//' deck.yaml > pd.yaml
bad "other model" "model 'lattice', the deck's model is 'peridynamics'" pd.yaml $good -o newdir
bad "missing" "No such file" deck.yaml ref/checkpoint_0000000007.h5 -o newdir
bad "frame, not a checkpoint" "not a spall checkpoint" deck.yaml ref/fields_000001.h5 -o newdir
bad "text, not HDF5" "not a readable HDF5 file" deck.yaml deck.yaml -o newdir
mkdir empty
bad "no checkpoint in directory" "holds no checkpoint" deck.yaml empty
bad "in place, changed key" "differs" other.yaml ref

# bad output.checkpoint keys: file:line:column, exit 2, nothing written
deckbad() { # name sed-expression expected
    sed "$2" deck.yaml > badck.yaml
    "$spall" run badck.yaml -o badout >stdout.txt 2>stderr.txt
    local rc=$?
    if [ $rc -ne 2 ] || [ -e badout ] || [ "$(wc -l < stderr.txt)" -ne 1 ] ||
        ! grep -q "badck\.yaml:[0-9]*:[0-9]*: .*$3" stderr.txt; then
        ko "deck $1: exit $rc"; cat stderr.txt; rm -rf badout; return
    fi
    ok
}
deckbad "two intervals" 's/every_steps: 500,/every_steps: 500, every_time: 1.0e-6,/' "exactly one of every_time"
deckbad "no interval" 's/every_steps: 500, //' "exactly one of every_time"
deckbad "keep 0" 's/keep: 2/keep: 0/' "keep"
deckbad "unknown key" 's/keep: 2/kep: 2/' "unknown key 'kep'"
deckbad "negative time" 's/every_steps: 500/every_time: -1/' "every_time"

# the safe keys may change: a longer run continues from the last checkpoint
deck 4400 500 > longer.yaml
"$spall" run longer.yaml --restart ref -o longer >/dev/null 2>stderr.txt ||
    { ko "longer end: refused"; cat stderr.txt; }
tail -1 longer/history.csv | grep -q '^4400,' || ko "longer end: did not reach step 4400"
ok

echo "cli_restart: $pass passed, $fail failed"
[ $fail -eq 0 ]
