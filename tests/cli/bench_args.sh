#!/usr/bin/env bash
# spall bench refuses a bad --scale / --threads with one line and exit 2,
# and lists its cases.  Usage: bench_args.sh SPALL SRC
set -u
spall="$1"
fail=0
refuse() { # name expected-substring args...
    local name="$1" expect="$2"
    shift 2
    "$spall" bench "$@" >/dev/null 2>err.txt
    local rc=$?
    if [ "$rc" -ne 2 ]; then echo "FAIL $name: exit $rc, expected 2"; fail=1; return; fi
    if [ "$(wc -l < err.txt)" -ne 1 ]; then echo "FAIL $name: not one line"; cat err.txt; fail=1; return; fi
    grep -q -- "$expect" err.txt || { echo "FAIL $name: lacks '$expect'"; cat err.txt; fail=1; }
}
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
cd "$tmp"
refuse "scale above 16" "(0, 16]" sph-taylor-cu-tl --scale 17
refuse "scale zero" "(0, 16]" sph-taylor-cu-tl --scale 0
refuse "scale text" "(0, 16]" sph-taylor-cu-tl --scale many
refuse "threads zero" "positive integers" sph-taylor-cu-tl --threads 0
refuse "old name" "case 'sph_taylor_cu_tl' is now called 'sph-taylor-cu-tl'" sph_taylor_cu_tl
refuse "unknown case" "unknown case 'no-such-case'" no-such-case
"$spall" bench --list > list.txt || { echo "FAIL list: exit $?"; fail=1; }
grep -q "^sph-taylor-cu-tl-bal " list.txt || { echo "FAIL list: no sph-taylor-cu-tl-bal"; fail=1; }
# one convention: every case name typed on the command line uses hyphens
if awk '{print $1}' list.txt | grep -q _; then echo "FAIL list: a case name with '_'"; fail=1; fi
[ "$fail" -eq 0 ] && echo "bench_args: all checks passed"
exit "$fail"
