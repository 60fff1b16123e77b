#include "cli/cli.h"

#include "core/parallel/comm.h"
#include "spall/spall.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static void run_usage(FILE *out)
{
    fprintf(out, "usage: spall run DECK.yaml [-o DIR] [--overwrite] [--threads N]\n"
                 "                 [--progress | --no-progress] [--quiet] [--restart RUN|FILE]\n"
                 "                 [--progress-every SECONDS] [--yes]\n"
                 "\n"
                 "Runs the simulation of DECK.yaml and writes into DIR (default: a directory\n"
                 "named after the deck): run.log, history.csv, fields_NNNNNN.h5 and\n"
                 "fields.xdmf (open the .xdmf in ParaView).  An existing result directory is\n"
                 "never overwritten unless --overwrite is given.\n"
                 "\n"
                 "--restart RUN_DIR continues the run in RUN_DIR from its newest checkpoint\n"
                 "(deck key output.checkpoint), --restart FILE from that checkpoint; with -o\n"
                 "another directory gets a continued copy.  SIGTERM, SIGINT or SIGUSR1 end\n"
                 "the current step, write a checkpoint and exit with status 75\n"
                 "(docs/restart.md).\n"
                 "\n"
                 "Without a terminal on stderr (a batch job) a progress line is printed every\n"
                 "60 s (--progress-every): step, time, %%, rate, ETA and the energy balance as\n"
                 "a fraction of the energy put in; --no-progress turns it off.\n"
                 "\n"
                 "Before step 0 the set-up is checked (docs/decks.md, run.allow): impactors,\n"
                 "walls or symmetry planes inside a body, probes off every body, a large\n"
                 "initial strain energy, and the run's cost (particle-steps, output size,\n"
                 "printed to run.log); --yes runs a run whose cost is far beyond the machine.\n");
}

/* Under mpirun every rank parses the same arguments and fails alike; only
 * rank 0 prints (core/parallel/comm.h). */
#define RUN_ERR(...)                                                                            \
    do {                                                                                        \
        if (par_rank() == 0)                                                                    \
            fprintf(stderr, __VA_ARGS__);                                                       \
    } while (0)

int cli_run(int argc, char **argv)
{
    struct spall_run_options opt = {.progress = -1};
    for (int k = 1; k < argc; k++) {
        const char *a = argv[k];
        if (strcmp(a, "-h") == 0 || strcmp(a, "--help") == 0) {
            run_usage(stdout);
            return 0;
        } else if (strcmp(a, "-o") == 0 || strcmp(a, "--output") == 0) {
            if (++k >= argc) {
                RUN_ERR("spall run: %s needs a directory\n", a);
                return 2;
            }
            opt.out_dir = argv[k];
        } else if (strcmp(a, "--restart") == 0) {
            if (++k >= argc) {
                RUN_ERR("spall run: --restart needs a run directory or checkpoint file\n");
                return 2;
            }
            opt.restart = argv[k];
        } else if (strcmp(a, "--overwrite") == 0) {
            opt.overwrite = true;
        } else if (strcmp(a, "--threads") == 0) {
            char *end = NULL;
            if (++k >= argc || (opt.threads = (int)strtol(argv[k], &end, 10)) <= 0 || *end) {
                RUN_ERR("spall run: --threads needs a positive integer\n");
                return 2;
            }
        } else if (strcmp(a, "--progress") == 0) {
            opt.progress = 1;
        } else if (strcmp(a, "--no-progress") == 0) {
            opt.progress = 0;
        } else if (strcmp(a, "--quiet") == 0) {
            opt.quiet = true;
        } else if (strcmp(a, "--progress-every") == 0) {
            char *end = NULL;
            if (++k >= argc || !((opt.progress_every = strtod(argv[k], &end)) > 0.0) || *end) {
                fprintf(stderr, "spall run: --progress-every needs a positive number of seconds\n");
                return 2;
            }
        } else if (strcmp(a, "--yes") == 0) {
            opt.yes = true;
        } else if (a[0] == '-') {
            RUN_ERR("spall run: unknown option '%s' (see spall run --help)\n", a);
            return 2;
        } else if (!opt.deck_path) {
            opt.deck_path = a;
        } else {
            RUN_ERR("spall run: more than one deck given ('%s' and '%s')\n", opt.deck_path,
                    a);
            return 2;
        }
    }
    if (!opt.deck_path) {
        if (par_rank() == 0)
            run_usage(stderr);
        return 2;
    }
    struct spall_run_result res;
    struct spall_error err = {0};
    int rc = spall_run(&opt, &res, &err);
    const int root = par_rank() == 0; /* mpirun: every rank agrees, rank 0 speaks */
    if (rc) {
        if (root)
            fprintf(stderr, "spall: error: %s\n", err.msg);
        if (root && rc == SPALL_ERR_UNSTABLE && res.out_dir[0])
            fprintf(stderr, "spall: the last good output is in %s\n", res.out_dir);
        return cli_exit_status(rc);
    }
    if (res.signal) {
        if (root)
            fprintf(stderr,
                    "spall: stopped by signal %d at step %ld, t = %.6g s; checkpoint %s\n"
                    "spall: continue with: spall run %s --restart %s\n",
                    res.signal, res.steps, res.time, res.checkpoint, opt.deck_path, res.out_dir);
        return SPALL_EXIT_INTERRUPTED;
    }
    if (!opt.quiet && root) {
        printf("spall: %ld steps, t = %.6g s, %zu particles, %.3g s wall, %.3g particle-steps/s\n",
               res.steps, res.time, res.particles, res.wall_seconds, res.particle_steps_per_s);
        printf("spall: results in %s/ (run.log, history.csv, fields.xdmf with %zu frames)\n",
               res.out_dir, res.frames);
    }
    return 0;
}
