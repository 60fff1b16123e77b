#!/usr/bin/env bash
# Run an MPI unit test (tests/mpi/test_*.c) on N ranks with the environment
# of tests/cli/mpi_ranks.sh: under `make asan`, full stacks and Open MPI's
# components kept loaded, so that tests/lsan.supp can name Open MPI's own
# run-time state.
# Usage: run.sh MPIEXEC N PROGRAM
set -u
export OMP_WAIT_POLICY=passive OMP_NUM_THREADS=1
export OMPI_MCA_mca_base_component_disable_dlclose=1
[ -n "${ASAN_OPTIONS:-}" ] && export ASAN_OPTIONS="$ASAN_OPTIONS:fast_unwind_on_malloc=0"
[ -n "${LSAN_OPTIONS:-}" ] && export LSAN_OPTIONS="$LSAN_OPTIONS:print_suppressions=0"
exec timeout 300 "$1" --allow-run-as-root --oversubscribe -q -np "$2" "$3"
