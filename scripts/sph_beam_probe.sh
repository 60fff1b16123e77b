#!/bin/sh
# Build and run scripts/sph_beam_probe.c (sph-beam-large corner diagnostics, docs/validation.md)
# against build/libspall.a (configure and build the Release tree first).
# usage: scripts/sph_beam_probe.sh KERNEL fixed|mirror "EXTRA MODEL KEYS" END SAMPLE [FORCE] [DT_FACTOR] [DX_MM]
set -e
root=$(cd "$(dirname "$0")/.." && pwd)
exe="$root/build/sph_beam_probe"
# the CLI's link line after "-o spall", with the library's full path
libs=$(sed -n "s| \(libspall[a-z_]*\.a\)| $root/build/\1|g; s|.* -o spall *||p" \
       "$root/build/CMakeFiles/spall.dir/link.txt")
cc -O2 -Wall -Wextra -Wpedantic -std=c11 -fopenmp -I"$root/include" -I"$root/src" -I"$root" \
   "$root/scripts/sph_beam_probe.c" -o "$exe" $libs
exec "$exe" "$@"
