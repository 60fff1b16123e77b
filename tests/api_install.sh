#!/usr/bin/env bash
# ctest api_install (cmake/SpallInstall.cmake): install the build into a
# scratch prefix, then build examples/api against the installed libspall
# only (a copy of the installed share/spall/examples/api) in three ways -
# find_package(spall) with spall::spall (shared) and spall::spall_static,
# and the Makefile through pkg-config - and run each on the example deck;
# the pkg-config build also sets the same plate up by C calls without a
# deck (plate --calls, include/spall/setup.h): the same history is printed.
# Usage: api_install.sh BUILD_DIR SOURCE_DIR CMAKE
set -euo pipefail
build="$1"; src="$2"; cmake="${3:-cmake}"
tmp="$(mktemp -d "${TMPDIR:-/tmp}/spall_api_install.XXXXXX")"
trap 'rm -rf "$tmp"' EXIT
prefix="$tmp/prefix"

"$cmake" --install "$build" --prefix "$prefix" >"$tmp/install.log"
for f in bin/spall lib/libspall.a lib/libspall.so include/spall/spall.h include/spall/sim.h \
         include/spall/error.h include/spall/setup.h lib/pkgconfig/spall.pc \
         lib/cmake/spall/spallConfig.cmake share/spall/examples/api/plate.c \
         share/spall/examples/api/plate.yaml share/spall/examples/api/Makefile \
         share/spall/examples/api/CMakeLists.txt; do
    [ -e "$prefix/$f" ] || { echo "api_install: $prefix/$f not installed"; exit 1; }
done
# the installed headers alone compile (no source-tree include path)
echo '#include <spall/sim.h>
#include <spall/setup.h>
#include <spall/spall.h>
#include <spall/penetration.h>
int main(void) { return 0; }' >"$tmp/headers.c"
cc -std=c11 -Wall -Wextra -Wpedantic -Werror -I"$prefix/include" -c "$tmp/headers.c" -o "$tmp/headers.o"
# the shared library exports the public API only
if nm -D --defined-only "$prefix/lib/libspall.so" | awk '{print $3}' | grep -v -E '^(spall_|pen_)' | grep -q .; then
    echo "api_install: libspall.so exports non-API symbols:"
    nm -D --defined-only "$prefix/lib/libspall.so" | awk '{print $3}' | grep -v -E '^(spall_|pen_)' | head
    exit 1
fi
"$prefix/bin/spall" --version >/dev/null

check_run() { # $1: label, $2: program, $3: deck or --calls; runs it in a fresh directory
    local dir="$tmp/run_$1"
    mkdir -p "$dir"
    cp "$prefix/share/spall/examples/api/plate.yaml" "$dir/"
    (cd "$dir" && "$2" "${3:-plate.yaml}" frames) >"$dir/out.txt" 2>&1 || {
        echo "api_install: $1 build failed to run:"; cat "$dir/out.txt"; exit 1; }
    cat "$dir/out.txt"
    grep -q "^frames written: 16$" "$dir/out.txt" || { echo "api_install: $1: expected 16 frames"; exit 1; }
    [ -f "$dir/frames/fields.xdmf" ] || { echo "api_install: $1: no fields.xdmf"; exit 1; }
    # intact at the first print, cracked at the last: some particle lost
    # more than half its bonds (fracture density, lattice model)
    awk '$1 ~ /^[0-9.e+-]+$/ { d[n++] = $5 } END { if (n != 10 || d[0] != 0 || d[9] <= 0.5) {
        print "api_install: expected 10 rows, intact first, cracked last"; exit 1 } }' "$dir/out.txt"
    cp "$dir/out.txt" "$tmp/$1.txt"
}

cp -r "$prefix/share/spall/examples/api" "$tmp/example"

echo "== pkg-config: $(PKG_CONFIG_PATH="$prefix/lib/pkgconfig" pkg-config --cflags --libs spall)"
make -s -C "$tmp/example" PKG_CONFIG_PATH="$prefix/lib/pkgconfig" plate
LD_LIBRARY_PATH="$prefix/lib" check_run pkgconfig "$tmp/example/plate"
LD_LIBRARY_PATH="$prefix/lib" check_run calls "$tmp/example/plate" --calls
# linked against the installed libspall.so, not some other copy
# (grep reads all of ldd's output: with -q, pipefail saw SIGPIPE in ldd once the
# MPI build made the list long)
LD_LIBRARY_PATH="$prefix/lib" ldd "$tmp/example/plate" | grep "$prefix/lib/libspall.so" >/dev/null ||
    { echo "api_install: pkg-config build does not use the installed libspall.so"; exit 1; }

for kind in shared static; do
    static=OFF; [ "$kind" = static ] && static=ON
    echo "== find_package(spall), $kind"
    "$cmake" -S "$tmp/example" -B "$tmp/build_$kind" -DCMAKE_PREFIX_PATH="$prefix" \
        -DSPALL_STATIC=$static >"$tmp/cfg_$kind.log" || { cat "$tmp/cfg_$kind.log"; exit 1; }
    "$cmake" --build "$tmp/build_$kind" >"$tmp/build_$kind.log" || { cat "$tmp/build_$kind.log"; exit 1; }
    check_run "cmake_$kind" "$tmp/build_$kind/plate"
done
if ldd "$tmp/build_static/plate" | grep libspall >/dev/null; then
    echo "api_install: the static build links libspall.so"; exit 1
fi
# same deck, same library code: the three builds print the same numbers
cmp "$tmp/pkgconfig.txt" "$tmp/cmake_shared.txt"
cmp "$tmp/pkgconfig.txt" "$tmp/cmake_static.txt"
# set up by calls, no deck: the same simulation, the same history
cmp "$tmp/pkgconfig.txt" "$tmp/calls.txt"
echo "api_install: OK"
