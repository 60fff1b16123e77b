/**
 * @file main.c
 * @brief The `spall` command line: a thin layer over libspall that turns
 *        every error into one line on stderr and a non-zero exit status.
 */
#include "cli/cli.h"

#include "core/parallel/comm.h"
#include "spall/spall.h"

#include <stdio.h>
#if defined(__GLIBC__)
#include <malloc.h>
#endif
#include <string.h>

static void usage(FILE *out)
{
    fprintf(out,
            "usage: spall COMMAND [ARGS]\n"
            "\n"
            "Particle simulations of dynamic fracture, fragmentation and impact.\n"
            "\n"
            "commands:\n"
            "  run DECK.yaml [-o DIR]   run a simulation described by a YAML deck\n"
            "  validate [CASE ...]      run the built-in validation cases (--list, --quick, --json)\n"
            "  bench [CASE ...]         throughput benchmarks (--list, --json, --threads)\n"
            "  calibrate MODEL ...      model constants from continuum data, with a patch test\n"
            "  penetrate MODE ...       analytical sphere-penetration models, fits, sweeps\n"
            "  render RUN_DIR [...]     PNG pictures of a particle field (--field, --all)\n"
            "  plot RUN_DIR [COLUMN..]  history.csv columns against time as a PNG\n"
            "  fragments RUN_DIR        fragment mass/size distribution (CSV + PNG)\n"
            "\n"
            "options:\n"
            "  -h, --help               this help (spall COMMAND --help for a command)\n"
            "  --version                version and git revision\n"
            "\n"
            "Units are SI everywhere.  Decks are documented in docs/decks.md.\n");
}

int cli_exit_status(int code)
{
    switch (code) {
    case SPALL_OK: return 0;
    case SPALL_ERR_INPUT:
    case SPALL_ERR_PHYSICS: return 2;
    case SPALL_ERR_UNSTABLE: return 3;
    case SPALL_ERR_IO: return 4;
    default: return 1;
    }
}

static int dispatch(int argc, char **argv);

int main(int argc, char **argv)
{
#if defined(__GLIBC__)
    /* Program-level allocator policy (the library leaves it alone): glibc
     * raises its mmap threshold after large temporaries of the set-up are
     * freed, and then keeps later large arrays and the freed temporaries in
     * its heap -- about 16 bytes per particle of dead memory.  A fixed
     * threshold serves every large array by mmap and returns it on free.
     * (malloc_trim after set-up saved the memory too but split transparent
     * huge pages and cost 25 % of the lattice benchmark's speed.) */
    mallopt(M_MMAP_THRESHOLD, 128 * 1024);
#endif
    /* under mpirun (and only there) MPI is initialised; core/parallel/comm.h */
    if (par_world_init(&argc, &argv)) {
        fprintf(stderr, "spall: error: MPI_Init failed\n");
        return 1;
    }
    int rc = dispatch(argc, argv);
    par_world_finalize();
    return rc;
}

static int dispatch(int argc, char **argv)
{
    if (argc < 2) {
        usage(stderr);
        return 2;
    }
    const char *cmd = argv[1];
    if (strcmp(cmd, "-h") == 0 || strcmp(cmd, "--help") == 0 || strcmp(cmd, "help") == 0) {
        usage(stdout);
        return 0;
    }
    if (strcmp(cmd, "--version") == 0 || strcmp(cmd, "version") == 0) {
        printf("spall %s (git %s)\n", spall_version(), spall_git_revision());
        return 0;
    }
    if (strcmp(cmd, "run") == 0)
        return cli_run(argc - 1, argv + 1);
    /* validate and bench distribute what can be (docs/parallel.md) */
    if (strcmp(cmd, "validate") == 0)
        return cli_validate(argc - 1, argv + 1);
    if (strcmp(cmd, "bench") == 0)
        return cli_bench(argc - 1, argv + 1);
    if (par_size() > 1) { /* one line, once, and the same status on every rank */
        if (par_rank() == 0)
            fprintf(stderr, "spall: error: 'spall %s' does not run distributed yet (%d MPI "
                            "ranks); run it without mpirun (docs/parallel.md)\n",
                    cmd, par_size());
        return 2;
    }
    if (strcmp(cmd, "calibrate") == 0)
        return cli_calibrate(argc - 1, argv + 1);
    if (strcmp(cmd, "penetrate") == 0)
        return cli_penetrate(argc - 1, argv + 1);
    if (strcmp(cmd, "render") == 0)
        return cli_render(argc - 1, argv + 1);
    if (strcmp(cmd, "plot") == 0)
        return cli_plot(argc - 1, argv + 1);
    if (strcmp(cmd, "fragments") == 0)
        return cli_fragments(argc - 1, argv + 1);
    fprintf(stderr, "spall: unknown command '%s'; expected run, validate, bench, calibrate, "
                    "penetrate, render, plot or fragments "
                    "(see spall --help)\n",
            cmd);
    return 2;
}
