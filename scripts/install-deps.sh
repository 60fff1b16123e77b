#!/usr/bin/env bash
# Install the Debian packages spall needs, only those that are missing.
# Safe to run repeatedly; needs root (or sudo) only when something is missing.
set -euo pipefail
pkgs=(build-essential cmake pkg-config git libyaml-dev libhdf5-dev libcairo2-dev libcmocka-dev libgsl-dev
      librandom123-dev  # counter-based random streams (macro-particle Langevin forces)
      libopenmpi-dev openmpi-bin libhdf5-openmpi-dev hdf5-tools libtrilinos-zoltan-dev  # SPALL_MPI=ON (issue 20)
      python3)  # python3: scripts/mutate (ctest mutate_catalogue, make mutate)
missing=()
for p in "${pkgs[@]}"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
    exit 0
fi
echo "spall: installing missing Debian packages: ${missing[*]}"
SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
