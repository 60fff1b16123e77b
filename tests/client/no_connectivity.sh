#!/usr/bin/env bash
# ctest client_pv_no_connectivity: the check of pv_check.py must be able to
# fail.  Rewrites the epoxy run's fields.xdmf the way spall wrote it before
# issue 23 (Polyvertex topology without the explicit /connectivity DataItem)
# and expects ParaView's default reader to give 0 cells and an empty image.
# Usage: no_connectivity.sh SOURCE_DIR RUNS_DIR PNG_DIR PYTHON
set -uo pipefail
src="$1"; runs="$2"; pngdir="$3"; py="$4"
run="$runs/epoxy_holes"
old="$run/fields_no_connectivity.xdmf"
"$py" - "$run/fields.xdmf" "$old" <<'PY' || exit 1
import sys
import xml.etree.ElementTree as ET
tree = ET.parse(sys.argv[1])
n = 0
for topo in tree.getroot().iter("Topology"):
    for item in list(topo):
        topo.remove(item)
        n += 1
if n == 0:
    sys.exit("no connectivity DataItem found to remove")
tree.write(sys.argv[2])
PY
bash "$src/tests/client/pvbatch.sh" "$src/tests/client/pv_check.py" --xdmf "$old" \
    --reader default --png "$pngdir/epoxy_no_connectivity.png" >"$pngdir/no_connectivity.log"
rc=$?
cat "$pngdir/no_connectivity.log"
[ $rc -eq 77 ] && exit 77
if [ $rc -eq 0 ]; then
    echo "no_connectivity: the check passed on output without /connectivity"; exit 1
fi
grep -q "FAIL: .* 0 cells" "$pngdir/no_connectivity.log" &&
    grep -q "FAIL: coloured by .*particle pixels" "$pngdir/no_connectivity.log" || {
    echo "no_connectivity: failed, but not for the missing cells and the empty image"; exit 1; }
echo "no_connectivity: the check fails as it must (0 cells, empty image)"
