#!/usr/bin/env bash
# ctest client_docs_snippets: the ParaView and h5py snippets of
# docs/postprocessing.md (the fenced block after each "<!-- snippet: NAME -->")
# run as written on a real run directory.
# Usage: doc_snippets.sh SOURCE_DIR RUN_DIR PYTHON
set -uo pipefail
src="$1"; run="$2"; py="$3"
"$py" -c 'import h5py' 2>/dev/null || { echo "client test skipped: python3-h5py not installed"; exit 77; }
tmp="$(mktemp -d "${TMPDIR:-/tmp}/spall_snippets.XXXXXX")"
trap 'rm -rf "$tmp"' EXIT
extract() { # $1: snippet name -> $tmp/snippet_$1.py (h5py.py would shadow the module)
    awk -v want="<!-- snippet: $1 -->" '
        $0 == want { armed = 1; next }
        armed && /^```python/ { inside = 1; next }
        inside && /^```/ { exit }
        inside { print }' "$src/docs/postprocessing.md" >"$tmp/snippet_$1.py"
    [ -s "$tmp/snippet_$1.py" ] || { echo "doc_snippets: no snippet '$1' in docs/postprocessing.md"; exit 1; }
}
extract h5py
extract pvbatch
echo "--- h5py snippet"
"$py" "$tmp/snippet_h5py.py" "$run" || { echo "doc_snippets: the h5py snippet failed"; exit 1; }
echo "--- pvbatch snippet"
rm -f "$run/last_frame.png"
bash "$src/tests/client/pvbatch.sh" "$tmp/snippet_pvbatch.py" "$run"
rc=$?
[ $rc -eq 77 ] && exit 77
[ $rc -eq 0 ] || { echo "doc_snippets: the pvbatch snippet failed ($rc)"; exit 1; }
[ -s "$run/last_frame.png" ] || { echo "doc_snippets: the pvbatch snippet wrote no picture"; exit 1; }
echo "doc_snippets: both snippets ran"
