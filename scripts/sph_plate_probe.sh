#!/bin/sh
# Build and run scripts/sph_plate_probe.c (sph-plate diagnostics, docs/validation.md)
# against build/libspall.a (configure and build the Release tree first).
# usage: scripts/sph_plate_probe.sh ROWS fixed|mirror|free "MODEL KEYS" period|static [V|g] [END] [DAMPING]
# e.g.   scripts/sph_plate_probe.sh 16 mirror "kernel: cubic_spline, h_factor: 1.5, cspm: true, \
#          viscosity: [0.1, 0.1], time_integration: leapfrog" static 1.0 0.15
set -e
root=$(cd "$(dirname "$0")/.." && pwd)
exe="$root/build/sph_plate_probe"
# the CLI's link line after "-o spall", with the library's full path
libs=$(sed -n "s| \(libspall[a-z_]*\.a\)| $root/build/\1|g; s|.* -o spall *||p" \
       "$root/build/CMakeFiles/spall.dir/link.txt")
cc -O2 -Wall -Wextra -Wpedantic -std=c11 -fopenmp -I"$root/include" -I"$root/src" -I"$root" \
   "$root/scripts/sph_plate_probe.c" -o "$exe" $libs
exec "$exe" "$@"
