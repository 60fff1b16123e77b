#!/usr/bin/env bash
# Run an MPI unit test (tests/mpi/test_*.c) on N ranks with the environment
# of tests/cli/mpi_ranks.sh (the sanitizer options: tests/cli/lib/asan_mpi.bash).
# Usage: run.sh MPIEXEC N PROGRAM
set -u
export OMP_WAIT_POLICY=passive OMP_NUM_THREADS=1
# shellcheck source=../cli/lib/asan_mpi.bash
source "$(dirname "$0")/../cli/lib/asan_mpi.bash"
exec timeout 300 "$1" --allow-run-as-root --oversubscribe -q -np "$2" "$3"
