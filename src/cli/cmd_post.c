/**
 * @file cmd_post.c
 * @brief `spall plot RUN_DIR [COLUMN ...]` and `spall fragments RUN_DIR`:
 *        the post-processing a user reaches for after a run
 *        (io/postprocess.h, docs/postprocessing.md).
 */
#include "cli/cli.h"

#include "io/postprocess.h"
#include "spall/error.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static void plot_usage(FILE *out)
{
    fprintf(out, "usage: spall plot RUN_DIR [COLUMN ...] [-o FILE.png]\n"
                 "\n"
                 "Plots columns of RUN_DIR/history.csv against time (names with or without\n"
                 "their [unit], e.g. kinetic, tup_force_y, centre_vy).  Without COLUMN: the\n"
                 "energy balance (kinetic, strain, dissipated, damping, external_work,\n"
                 "energy_balance).  Default output: RUN_DIR/history.png.\n");
}

static void fragments_usage(FILE *out)
{
    fprintf(out, "usage: spall fragments RUN_DIR [-o PREFIX]\n"
                 "\n"
                 "Fragment mass and size distribution from RUN_DIR/fragments.csv (written at\n"
                 "the end of lattice and peridynamics runs): PREFIX.csv, one row per fragment,\n"
                 "heaviest first, with the number of fragments at least that heavy and their\n"
                 "mass fraction, and PREFIX.png, that count against mass on log axes.\n"
                 "Default PREFIX: RUN_DIR/fragment_distribution.\n");
}

static char *joined(const char *a, const char *b)
{
    size_t n = strlen(a) + strlen(b) + 1;
    char *p = malloc(n);
    if (p)
        snprintf(p, n, "%s%s", a, b);
    return p;
}

int cli_plot(int argc, char **argv)
{
    const char *dir = NULL, *png = NULL;
    const char **cols = calloc((size_t)argc, sizeof *cols);
    size_t ncol = 0;
    if (!cols)
        return 1;
    for (int i = 1; i < argc; i++) {
        if (strcmp(argv[i], "-h") == 0 || strcmp(argv[i], "--help") == 0) {
            plot_usage(stdout);
            free(cols);
            return 0;
        } else if (strcmp(argv[i], "-o") == 0 && i + 1 < argc) {
            png = argv[++i];
        } else if (argv[i][0] == '-') {
            fprintf(stderr, "spall plot: unknown option '%s'\n", argv[i]);
            plot_usage(stderr);
            free(cols);
            return 2;
        } else if (!dir) {
            dir = argv[i];
        } else {
            cols[ncol++] = argv[i];
        }
    }
    if (!dir) {
        plot_usage(stderr);
        free(cols);
        return 2;
    }
    char *def = png ? NULL : joined(dir, "/history.png");
    struct spall_error err = {0};
    size_t rows = 0;
    int rc = (png || def) ? post_plot_history(dir, cols, ncol, png ? png : def, &rows, &err)
                          : SPALL_ERR_NOMEM;
    if (rc)
        fprintf(stderr, "spall plot: %s\n", err.msg[0] ? err.msg : "out of memory");
    else
        printf("%s (%zu rows)\n", png ? png : def, rows);
    free(def);
    free(cols);
    return cli_exit_status(rc);
}

int cli_fragments(int argc, char **argv)
{
    const char *dir = NULL, *prefix = NULL;
    for (int i = 1; i < argc; i++) {
        if (strcmp(argv[i], "-h") == 0 || strcmp(argv[i], "--help") == 0) {
            fragments_usage(stdout);
            return 0;
        } else if (strcmp(argv[i], "-o") == 0 && i + 1 < argc) {
            prefix = argv[++i];
        } else if (argv[i][0] == '-' || dir) {
            fprintf(stderr, "spall fragments: unexpected argument '%s'\n", argv[i]);
            fragments_usage(stderr);
            return 2;
        } else {
            dir = argv[i];
        }
    }
    if (!dir) {
        fragments_usage(stderr);
        return 2;
    }
    char *def = prefix ? NULL : joined(dir, "/fragment_distribution");
    const char *pre = prefix ? prefix : def;
    char *csv = pre ? joined(pre, ".csv") : NULL, *png = pre ? joined(pre, ".png") : NULL;
    struct spall_error err = {0};
    size_t n = 0;
    int rc = (csv && png) ? post_fragments(dir, csv, png, &n, &err) : SPALL_ERR_NOMEM;
    if (rc)
        fprintf(stderr, "spall fragments: %s\n", err.msg[0] ? err.msg : "out of memory");
    else
        printf("%s, %s (%zu fragments)\n", csv, png, n);
    free(def);
    free(csv);
    free(png);
    return cli_exit_status(rc);
}
