# Sourced by the LAMMPS side-by-side scripts (bench/pd_vs_lammps.sh,
# bench/pd_lps_vs_lammps.sh, bench/macro_vs_lammps.sh) after they set NAME
# (the script's name), CHECK (1 under ctest) and SPALL: finds Debian's
# `lmp` (LMP), in --check mode exits 77 (skipped) without it, else
# installs the package (root); makes SPALL absolute and creates the work
# directory W under /tmp.
LMP=$(command -v lmp || command -v lmp_serial || true)
if [ -z "$LMP" ]; then
    if [ "$CHECK" = 1 ]; then
        echo "$NAME skipped: LAMMPS (lmp) not installed (scripts/install-test-deps.sh installs Debian's lammps)"
        exit 77
    fi
    apt-get install -y lammps >/dev/null
    LMP=$(command -v lmp)
fi
SPALL=$(cd "$(dirname "$SPALL")" && pwd)/$(basename "$SPALL")
W=$(mktemp -d "/tmp/$NAME.XXXX")
echo "work dir: $W"
