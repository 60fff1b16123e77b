#!/bin/sh
# Build a LAMMPS with the MACHDYN package (pair smd/tlsph) from Debian's own
# lammps source package, for the SPH race of issue 6 item 8
# (bench/sph_vs_lammps.sh).  Debian's binary lammps 20220106 is built
# without MACHDYN; its source package carries src/MACHDYN, which needs only
# Eigen3 (libeigen3-dev).
#
#   sh bench/lammps_machdyn_build.sh [PREFIX]     (default PREFIX: ~/.cache/spall/lammps-machdyn)
#
# Prints the path of the built `lmp`; bench/sph_vs_lammps.sh takes it as
# LMP=... .  Serial build (no MPI, no OpenMP): the race compares one core
# with one core, and two MPI-less ranks are not needed for that.  The apt
# lists of the source repository live in PREFIX, so the machine's apt
# configuration is not touched.  Needs network access to deb.debian.org,
# cmake, g++, xz-utils, libeigen3-dev; about 20-40 min on 2 cores.
set -eu
PREFIX=${1:-"$HOME/.cache/spall/lammps-machdyn"}
LMP="$PREFIX/build/lmp"
if [ -x "$LMP" ] && "$LMP" -h 2>/dev/null | grep -q 'smd/tlsph'; then
    echo "$LMP"
    exit 0
fi
mkdir -p "$PREFIX/apt/lists/partial" "$PREFIX/src"
codename=$(. /etc/os-release && echo "${VERSION_CODENAME:-bookworm}")
echo "deb-src http://deb.debian.org/debian $codename main" > "$PREFIX/apt/sources.list"
APT="-o Dir::Etc::SourceList=$PREFIX/apt/sources.list -o Dir::Etc::SourceParts=/nonexistent \
     -o Dir::State::Lists=$PREFIX/apt/lists -o APT::Sandbox::User=root"
# shellcheck disable=SC2086
apt-get $APT update >&2
# shellcheck disable=SC2086
(cd "$PREFIX/src" && apt-get $APT source --download-only lammps >&2)
tarball=$(ls "$PREFIX"/src/lammps_*.orig.tar.xz | head -n 1)
rm -rf "$PREFIX/tree" && mkdir -p "$PREFIX/tree"
tar -C "$PREFIX/tree" -xJf "$tarball" --strip-components=1
[ -d "$PREFIX/tree/src/MACHDYN" ] || { echo "no src/MACHDYN in $tarball" >&2; exit 1; }
dpkg -s libeigen3-dev >/dev/null 2>&1 || apt-get install -y -qq libeigen3-dev >&2
cmake -S "$PREFIX/tree/cmake" -B "$PREFIX/build" -DCMAKE_BUILD_TYPE=Release \
      -DBUILD_MPI=no -DBUILD_OMP=no -DPKG_MACHDYN=yes -DDOWNLOAD_EIGEN=no \
      -DEIGEN3_INCLUDE_DIR=/usr/include/eigen3 >&2
cmake --build "$PREFIX/build" --target lmp -j "$(nproc)" >&2
"$LMP" -h | grep -q 'smd/tlsph' || { echo "built lmp lacks smd/tlsph" >&2; exit 1; }
echo "$LMP"
