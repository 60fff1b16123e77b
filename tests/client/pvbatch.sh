#!/usr/bin/env bash
# Run pvbatch under a virtual X server (ctest label `client`).  Exit 77 (ctest
# SKIP_RETURN_CODE) when the clients are not installed: `make check` installs
# them (scripts/install-test-deps.sh); a bare `ctest` reports them skipped.
# xvfb-run -a can race another xvfb-run for the same display number, and the
# loser's GL window then fails with "bad X server connection": a run that
# stops before pv_check.py's verdict line is retried (3 attempts).
# Usage: pvbatch.sh SCRIPT.py [ARGS...]
set -uo pipefail
for tool in pvbatch xvfb-run; do
    command -v "$tool" >/dev/null || {
        echo "client test skipped: $tool not installed (bash scripts/install-test-deps.sh)"; exit 77; }
done
log="$(mktemp "${TMPDIR:-/tmp}/spall_pvbatch.XXXXXX")"
trap 'rm -f "$log"' EXIT
for attempt in 1 2 3; do
    # 24-bit screen: Mesa's GLX visual needs it
    xvfb-run -a -s "-screen 0 1024x768x24" pvbatch "$@" >"$log" 2>&1
    rc=$?
    # pv_check.py always ends with its verdict line; without it pvbatch or
    # the X server died first (a display-number race, a GLX failure)
    if [ $rc -ne 0 ] && ! grep -q "^pv_check: " "$log"; then
        echo "pvbatch.sh: pvbatch stopped before a verdict (attempt $attempt, exit $rc):"
        grep -v -E '^\s*[0-9]+\s+0x[0-9a-f]+ ' "$log" | tail -5
        sleep 2
        continue
    fi
    # pvbatch's own logging of a Python exception is long; the findings are short
    grep -v -E '^\s*[0-9]+\s+0x[0-9a-f]+ ' "$log"
    exit $rc
done
cat "$log"
echo "pvbatch.sh: no usable virtual X server after 3 attempts"
exit 1
