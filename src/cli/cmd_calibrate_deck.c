/**
 * @file cmd_calibrate_deck.c
 * @brief `spall calibrate DECK.yaml` and `spall calibrate sph ...`: the
 *        constants and the time step of a simulation as `spall run` builds
 *        it (io/run_summary.h).  The SPH form writes a small block deck from
 *        its options and goes through the same builder, so its c0, h and
 *        stable time step are those of a run with the same material,
 *        spacing and kernel.
 */
#include "cli/cli.h"

#include "io/run_summary.h"
#include "spall/error.h"

#include <math.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

int cli_calibrate_deck(const char *path)
{
    struct spall_error err = {0};
    int rc = run_summary_of_deck(path, NULL, stdout, &err);
    if (rc) {
        fprintf(stderr, "spall: error: %s\n", err.msg);
        return cli_exit_status(rc);
    }
    return 0;
}

static void sph_usage(FILE *out)
{
    fprintf(out,
            "usage: spall calibrate sph --E PA --nu NU --rho KG_M3 --spacing M\n"
            "         [--dim 2|3] [--plane strain|stress] [--h-factor F]\n"
            "         [--kernel cubic_spline|gaussian|quintic_spline|wendland|\n"
            "                   double_cosine|hyperbolic]\n"
            "\n"
            "Builds a block of 12 x 12 (x 12) particles of the material with the SPH\n"
            "model as `spall run` would and prints what the run log prints: bulk and\n"
            "shear moduli, sound speed c0, smoothing length h, neighbour radius, and\n"
            "the stable time step the run would take (run.dt_factor 0.3 of the\n"
            "model's limit, Eq. 3.38 of [Meng2021]).  Defaults as in a deck:\n"
            "2D plane strain, h = 1.5 spacing, Wendland kernel.  For a whole set-up\n"
            "use `spall calibrate DECK.yaml`.\n");
}

static int number(const char *opt, const char *s, double *out)
{
    char *end = NULL;
    *out = strtod(s, &end);
    if (end == s || *end || !isfinite(*out)) {
        fprintf(stderr, "spall calibrate sph: %s needs a number, got '%s'\n", opt, s);
        return 2;
    }
    return 0;
}

int cli_calibrate_sph(int argc, char **argv)
{
    double E = NAN, nu = NAN, rho = NAN, dx = NAN, hf = 1.5, dim = 2;
    const char *plane = "strain", *kernel = "wendland";
    for (int k = 2; k < argc; k++) {
        const char *a = argv[k];
        if (strcmp(a, "-h") == 0 || strcmp(a, "--help") == 0) {
            sph_usage(stdout);
            return 0;
        }
        static const char *const known[] = {"--E",   "--nu",    "--rho",      "--spacing",
                                            "--dim", "--plane", "--h-factor", "--kernel"};
        bool ok = false;
        for (size_t q = 0; q < sizeof known / sizeof known[0]; q++)
            ok = ok || strcmp(a, known[q]) == 0;
        if (!ok) {
            fprintf(stderr, "spall calibrate sph: unknown option '%s' (see --help)\n", a);
            return 2;
        }
        if (k + 1 >= argc) {
            fprintf(stderr, "spall calibrate sph: option '%s' needs a value (see --help)\n", a);
            return 2;
        }
        const char *v = argv[++k];
        int rc = 0;
        if (strcmp(a, "--plane") == 0)
            plane = v;
        else if (strcmp(a, "--kernel") == 0)
            kernel = v;
        else
            rc = number(a, v,
                        strcmp(a, "--E") == 0         ? &E
                        : strcmp(a, "--nu") == 0      ? &nu
                        : strcmp(a, "--rho") == 0     ? &rho
                        : strcmp(a, "--spacing") == 0 ? &dx
                        : strcmp(a, "--dim") == 0     ? &dim
                                                      : &hf);
        if (rc)
            return rc;
    }
    if (!isfinite(E) || !isfinite(nu) || !isfinite(rho) || !isfinite(dx)) {
        fprintf(stderr, "spall calibrate sph: --E, --nu, --rho and --spacing are required "
                        "(see --help)\n");
        return 2;
    }
    if (dim != 2 && dim != 3) {
        fprintf(stderr, "spall calibrate sph: --dim must be 2 or 3\n");
        return 2;
    }
    /* The deck's own checks (kernel and plane names, moduli, density ranges)
     * judge the values: the messages then name the deck key, which is also
     * the key a user writes next. */
    const double L = 12.0 * dx;
    char deck[2048];
    if (dim == 2)
        snprintf(deck, sizeof deck,
                 "title: spall calibrate sph\n"
                 "model: {type: sph, kernel: %s, h_factor: %.17g, plane: %s}\n"
                 "materials: {m: {density: %.17g, youngs_modulus: %.17g, poisson_ratio: %.17g}}\n"
                 "lattice: {type: square, spacing: %.17g, origin: [%.17g, %.17g]}\n"
                 "body: {geometry: {box: {min: [0, 0], max: [%.17g, %.17g]}}, material: m}\n"
                 "run: {end_time: 1}\n",
                 kernel, hf, plane, rho, E, nu, dx, 0.5 * dx, 0.5 * dx, L, L);
    else
        snprintf(deck, sizeof deck,
                 "title: spall calibrate sph\n"
                 "model: {type: sph, kernel: %s, h_factor: %.17g}\n"
                 "materials: {m: {density: %.17g, youngs_modulus: %.17g, poisson_ratio: %.17g}}\n"
                 "lattice: {type: sc, spacing: %.17g, origin: [%.17g, %.17g, %.17g]}\n"
                 "body: {geometry: {box: {min: [0, 0, 0], max: [%.17g, %.17g, %.17g]}}, "
                 "material: m}\n"
                 "run: {end_time: 1}\n",
                 kernel, hf, rho, E, nu, dx, 0.5 * dx, 0.5 * dx, 0.5 * dx, L, L, L);
    struct spall_error err = {0};
    int rc = run_summary_of_deck("options of spall calibrate sph", deck, stdout, &err);
    if (rc) {
        fprintf(stderr, "spall: error: %s\n", err.msg);
        return cli_exit_status(rc);
    }
    return 0;
}
