#!/usr/bin/env bash
# Install the real clients the `client` ctest label drives (issue 23): ParaView's
# pvbatch with its Python modules, a virtual X server for it to render into, and
# h5py for the user-script test; Debian's LAMMPS for the ctest label `lammps`
# (bench/pd_lps_vs_lammps.sh --check).  Called by `make check` (test set-up), never by
# `make demo`.  Only missing packages are installed; needs root (or sudo) then.
set -euo pipefail
pkgs=(paraview python3-paraview  # pvbatch + paraview.simple
      xvfb xauth                 # xvfb-run: pvbatch needs an X display for its GL context
      libgl1-mesa-dri            # Mesa software rasteriser behind Xvfb's GLX
      python3-h5py python3-numpy
      lammps)                    # `lmp` for the ctest pd_lps_vs_lammps (label lammps)
missing=()
for p in "${pkgs[@]}"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
    exit 0
fi
echo "spall: installing missing Debian packages for the client and lammps tests: ${missing[*]}"
SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
export DEBIAN_FRONTEND=noninteractive
# Another apt run (install-deps.sh, an admin) holds the dpkg lock: wait for it.
$SUDO apt-get -o DPkg::Lock::Timeout=600 update -qq
$SUDO apt-get -o DPkg::Lock::Timeout=600 install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
