#!/usr/bin/env bash
# Run pvbatch under a virtual X server (ctest label `client`).  Exit 77 (ctest
# SKIP_RETURN_CODE) when the clients are not installed: `make check` installs
# them (scripts/install-test-deps.sh); a bare `ctest` reports them skipped.
# Each attempt starts its own Xvfb, which picks a free display number itself
# (-displayfd) and reports it once it accepts connections; a run that stops
# before pv_check.py's verdict line (X server or GLX failure) is retried
# (3 attempts).
# Usage: pvbatch.sh SCRIPT.py [ARGS...]
set -uo pipefail
for tool in pvbatch Xvfb; do
    command -v "$tool" >/dev/null || {
        echo "client test skipped: $tool not installed (bash scripts/install-test-deps.sh)"; exit 77; }
done
log="$(mktemp "${TMPDIR:-/tmp}/spall_pvbatch.XXXXXX")"
xvfb_pid=""
stop_x() { [ -n "$xvfb_pid" ] && kill "$xvfb_pid" 2>/dev/null && wait "$xvfb_pid" 2>/dev/null; xvfb_pid=""; }
trap 'stop_x; rm -f "$log" "$log.x" "$log.d"' EXIT
for attempt in 1 2 3; do
    # Our own Xvfb on a display number it chooses (-displayfd): choosing
    # one here (a random free-looking number) raced the Xvfbs that other
    # test runs on the machine start at the same time - two servers meant
    # for one number, the loser's pvbatch then talking to the winner's
    # server until that one was stopped mid-render ("bad X server
    # connection", issue 23 item 5).  The X server takes a display number
    # atomically (its lock file) and writes it to fd 3 when it listens.
    # 24-bit screen for Mesa's GLX.
    : >"$log.d"
    Xvfb -displayfd 3 -screen 0 1024x768x24 -nolisten tcp -ac 3>"$log.d" >"$log.x" 2>&1 &
    xvfb_pid=$!
    for _ in $(seq 1 600); do
        [ -s "$log.d" ] && break
        kill -0 "$xvfb_pid" 2>/dev/null || break
        sleep 0.1
    done
    num="$(head -n 1 "$log.d" | tr -cd '0-9')"
    if [ -z "$num" ] || ! kill -0 "$xvfb_pid" 2>/dev/null; then
        echo "pvbatch.sh: Xvfb did not start (attempt $attempt):"
        tail -3 "$log.x"
        stop_x
        sleep $(( 1 + RANDOM % 4 ))
        continue
    fi
    DISPLAY=":$num" pvbatch "$@" >"$log" 2>&1
    rc=$?
    # pv_check.py always ends with its verdict line; without it pvbatch or
    # the X server died first (a display-number race, a GLX failure)
    if [ $rc -ne 0 ] && ! grep -q "^pv_check: " "$log"; then
        alive=yes; kill -0 "$xvfb_pid" 2>/dev/null || alive=no
        echo "pvbatch.sh: pvbatch stopped before a verdict (attempt $attempt, exit $rc, display :$num, our Xvfb alive: $alive):"
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
