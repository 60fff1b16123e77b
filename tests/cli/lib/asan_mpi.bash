# Sourced by everything that starts MPI ranks in the suite (tests/cli/lib/
# mpi_env.bash, tests/cli/mpi_errors.sh, tests/mpi/run.sh; not a test
# itself): the sanitizer options of the ranks in the ASan build (make asan),
# which sets ASAN_OPTIONS.  Every rank checks memory errors and undefined
# behaviour.  Leaks are checked where SPALL_MPI_LEAKS=1 (CMakeLists.txt
# names those tests): Open MPI keeps its run-time state until exit, so
# telling its blocks from spall's (tests/lsan.supp) takes full stacks (the
# slow unwinder on every malloc, its MCA components kept loaded) and a
# symbolised stack for each of its ~3 400 blocks at exit.  Measured
# 2026-12-07 on the rings deck (tests/cli/decks/mpi_ul.yaml, 3 ranks, CPU
# time summed over the ranks): 8.9 s with leak checks, 1.2 s without, 0.25 s
# for the whole serial run under ASan.
if [ -n "${ASAN_OPTIONS:-}" ]; then
    if [ "${SPALL_MPI_LEAKS:-0}" = 1 ]; then
        export OMPI_MCA_mca_base_component_disable_dlclose=1
        export ASAN_OPTIONS="$ASAN_OPTIONS:fast_unwind_on_malloc=0"
    else
        export ASAN_OPTIONS="$ASAN_OPTIONS:detect_leaks=0"
    fi
fi
[ -n "${LSAN_OPTIONS:-}" ] && export LSAN_OPTIONS="$LSAN_OPTIONS:print_suppressions=0"
