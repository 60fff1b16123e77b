#!/usr/bin/env bash
# Run pvbatch under a virtual X server (ctest label `client`).  Exit 77 (ctest
# SKIP_RETURN_CODE) when the clients are not installed: `make check` installs
# them (scripts/install-test-deps.sh); a bare `ctest` reports them skipped.
# Each attempt starts its own Xvfb on a random free display number; a run
# that stops before pv_check.py's verdict line (X server or GLX failure) is
# retried (3 attempts).
# Usage: pvbatch.sh SCRIPT.py [ARGS...]
set -uo pipefail
for tool in pvbatch Xvfb; do
    command -v "$tool" >/dev/null || {
        echo "client test skipped: $tool not installed (bash scripts/install-test-deps.sh)"; exit 77; }
done
log="$(mktemp "${TMPDIR:-/tmp}/spall_pvbatch.XXXXXX")"
xvfb_pid=""
stop_x() { [ -n "$xvfb_pid" ] && kill "$xvfb_pid" 2>/dev/null && wait "$xvfb_pid" 2>/dev/null; xvfb_pid=""; }
trap 'stop_x; rm -f "$log" "$log.x"' EXIT
for attempt in 1 2 3; do
    # Our own Xvfb on a free display number, used once it listens (xvfb-run
    # -a races other xvfb-runs started together, and under load its pvbatch
    # often met "bad X server connection"); 24-bit screen for Mesa's GLX.
    num=$(( 100 + RANDOM % 800 ))
    while [ -e "/tmp/.X$num-lock" ] || [ -e "/tmp/.X11-unix/X$num" ]; do num=$(( 100 + RANDOM % 800 )); done
    Xvfb ":$num" -screen 0 1024x768x24 -nolisten tcp -ac >"$log.x" 2>&1 &
    xvfb_pid=$!
    for _ in $(seq 1 300); do
        [ -S "/tmp/.X11-unix/X$num" ] && break
        kill -0 "$xvfb_pid" 2>/dev/null || break
        sleep 0.1
    done
    DISPLAY=":$num" pvbatch "$@" >"$log" 2>&1
    rc=$?
    # pv_check.py always ends with its verdict line; without it pvbatch or
    # the X server died first (a display-number race, a GLX failure)
    if [ $rc -ne 0 ] && ! grep -q "^pv_check: " "$log"; then
        echo "pvbatch.sh: pvbatch stopped before a verdict (attempt $attempt, exit $rc):"
        grep -v -E '^\s*[0-9]+\s+0x[0-9a-f]+ ' "$log" | tail -5
        tail -3 "$log.x"
        stop_x
        sleep $(( 1 + RANDOM % 4 ))
        continue
    fi
    # pvbatch's own logging of a Python exception is long; the findings are short
    grep -v -E '^\s*[0-9]+\s+0x[0-9a-f]+ ' "$log"
    stop_x
    exit $rc
done
cat "$log"
echo "pvbatch.sh: no usable virtual X server after 3 attempts"
exit 1
