# Sourced by the MPI rank tests (tests/cli/mpi_*.sh; not a test itself): the
# environment they run ranks in and a scratch directory they work in.
export OMP_WAIT_POLICY=passive
# ASan builds (make asan): full stacks and loaded MCA components, so that
# tests/lsan.supp can name Open MPI's own run-time state
export OMPI_MCA_mca_base_component_disable_dlclose=1
[ -n "${ASAN_OPTIONS:-}" ] && export ASAN_OPTIONS="$ASAN_OPTIONS:fast_unwind_on_malloc=0"
[ -n "${LSAN_OPTIONS:-}" ] && export LSAN_OPTIONS="$LSAN_OPTIONS:print_suppressions=0"
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
cd "$tmp" || exit 1
