#!/usr/bin/env bash
# docs/restart.md's example runs as written: its yaml block is saved as
# plate.yaml and its sh block run with `set -e` (the `cmp` lines are the
# bitwise checks).  Usage: restart_doc.sh SPALL SRC
set -u
spall="$1"
src="$2"
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
cd "$tmp"
doc="$src/docs/restart.md"
awk '/^```yaml$/{on=1; next} /^```$/{if(on){exit}} on' "$doc" > plate.yaml
awk '/^```sh$/{on=1; next} /^```$/{if(on){exit}} on' "$doc" > example.sh
[ -s plate.yaml ] && [ -s example.sh ] || { echo "FAIL: no example in $doc"; exit 1; }
mkdir bin
ln -s "$spall" bin/spall
PATH="$tmp/bin:$PATH" bash -e -x example.sh > out.txt 2>&1 || { cat out.txt; echo "FAIL: the example"; exit 1; }
tail -n 1 plate/history.csv | grep -q '^1000,' || { echo "FAIL: the longer run did not reach step 1000"; exit 1; }
[ "$(ls plate/checkpoint_*.h5 | xargs -n1 basename | tr '\n' ' ')" = "checkpoint_0000000800.h5 checkpoint_0000001000.h5 " ] ||
    { ls plate; echo "FAIL: keep: 2"; exit 1; }
echo "restart_doc: ok"
