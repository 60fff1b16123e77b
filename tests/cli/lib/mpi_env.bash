# Sourced by the MPI rank tests (tests/cli/mpi_*.sh; not a test itself): the
# environment they run ranks in and a scratch directory they work in.
export OMP_WAIT_POLICY=passive
# shellcheck source=asan_mpi.bash
source "$(dirname "${BASH_SOURCE[0]}")/asan_mpi.bash"
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
cd "$tmp" || exit 1
