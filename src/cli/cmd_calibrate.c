#include "cli/cli.h"

#include "core/lattice_gen.h"
#include "models/lattice/lattice_calib.h"
#include "spall/error.h"

#include <math.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static void overview_usage(FILE *out)
{
    fprintf(out,
            "usage: spall calibrate DECK.yaml\n"
            "       spall calibrate lattice       --E PA --nu NU --rho KG_M3 --spacing M ...\n"
            "       spall calibrate peridynamics  --E PA [--rho KG_M3] [--spacing M] ...\n"
            "       spall calibrate macroparticle [--material al|cu] [--rho KG_M3] ...\n"
            "       spall calibrate sph           --E PA --nu NU --rho KG_M3 --spacing M ...\n"
            "\n"
            "DECK.yaml: builds the deck's simulation exactly as `spall run` does (nothing\n"
            "is run or written) and prints what run.log would: particles, materials,\n"
            "the time step and its stability limit, steps, and every constant the model\n"
            "derives.  The model forms derive a model's constants from material data;\n"
            "`spall calibrate MODEL --help` describes each.\n");
}

static void calibrate_usage(FILE *out)
{
    fprintf(out,
            "usage: spall calibrate lattice --E PA --nu NU --rho KG_M3 --spacing M\n"
            "                       [--strength PA | --failure-strain EPS]\n"
            "                       [--lattice triangular|square|chain|sc|fcc|triple_honeycomb]\n"
            "                       [--layers 1|2]\n"
            "                       [--angular auto|on|off] [--thickness M]\n"
            "\n"
            "Prints the lattice model's constants from continuum data: axial stiffness S0\n"
            "(k1, k2), angular stiffness S_phi, failure strain eps_max = sigma_TS / E\n"
            "([Wang2010] Eq. 26), the particle mass, the stable time step (Eq. 25), the\n"
            "paper's Eq. 16/18 values for comparison, and a numerical patch test of the\n"
            "constants (measured E and nu under uniform strain).  triple_honeycomb: the\n"
            "alpha-beta-gamma model for nu in [1/3, 1) (three honeycomb bond families).\n"
            "Thickness default (2D): 2 r0 / sqrt(3) for triangular and triple_honeycomb\n"
            "(volume r0^3 per particle, the paper's convention), r0 otherwise; 1D:\n"
            "cross-section r0^2.\n");
}

static int parse_num(const char *opt, const char *s, double *out)
{
    char *end = NULL;
    *out = strtod(s, &end);
    if (end == s || *end || !isfinite(*out)) {
        fprintf(stderr, "spall calibrate: %s needs a number, got '%s'\n", opt, s);
        return 2;
    }
    return 0;
}

int cli_calibrate(int argc, char **argv)
{
    if (argc < 2 || strcmp(argv[1], "-h") == 0 || strcmp(argv[1], "--help") == 0) {
        overview_usage(argc < 2 ? stderr : stdout);
        return argc < 2 ? 2 : 0;
    }
    if (strcmp(argv[1], "macroparticle") == 0)
        return cli_calibrate_macroparticle(argc, argv);
    if (strcmp(argv[1], "peridynamics") == 0)
        return cli_calibrate_peridynamics(argc, argv);
    if (strcmp(argv[1], "sph") == 0 || strcmp(argv[1], "tlsph") == 0) /* one material law */
        return cli_calibrate_sph(argc, argv);
    if (strcmp(argv[1], "lattice") != 0) {
        size_t len = strlen(argv[1]);
        bool yaml = (len > 5 && strcmp(argv[1] + len - 5, ".yaml") == 0) ||
                    (len > 4 && strcmp(argv[1] + len - 4, ".yml") == 0);
        if (yaml && argc == 2)
            return cli_calibrate_deck(argv[1]);
        if (yaml) {
            fprintf(stderr, "spall calibrate: a deck takes no options ('%s' after '%s')\n",
                    argv[2], argv[1]);
            return 2;
        }
        fprintf(stderr,
                "spall calibrate: unknown model '%s'; expected a deck (.yaml) or one of "
                "lattice, peridynamics, macroparticle, sph (or tlsph)\n",
                argv[1]);
        return 2;
    }
    struct lattice_calib c;
    memset(&c, 0, sizeof c);
    c.kind = LATTICE_TRIANGULAR;
    c.angular = -1;
    c.nu = NAN;
    c.E = NAN;
    for (int k = 2; k < argc; k++) {
        const char *a = argv[k];
        if (strcmp(a, "-h") == 0 || strcmp(a, "--help") == 0) {
            calibrate_usage(stdout);
            return 0;
        }
        if (k + 1 >= argc) {
            fprintf(stderr, "spall calibrate: option '%s' needs a value (see --help)\n", a);
            return 2;
        }
        const char *v = argv[++k];
        int rc = 0;
        double x = 0;
        if (strcmp(a, "--E") == 0)
            rc = parse_num(a, v, &c.E);
        else if (strcmp(a, "--nu") == 0)
            rc = parse_num(a, v, &c.nu);
        else if (strcmp(a, "--rho") == 0)
            rc = parse_num(a, v, &c.rho);
        else if (strcmp(a, "--spacing") == 0)
            rc = parse_num(a, v, &c.r0);
        else if (strcmp(a, "--strength") == 0)
            rc = parse_num(a, v, &c.sigma_ts);
        else if (strcmp(a, "--failure-strain") == 0)
            rc = parse_num(a, v, &c.eps_max);
        else if (strcmp(a, "--thickness") == 0)
            rc = parse_num(a, v, &c.thickness);
        else if (strcmp(a, "--layers") == 0) {
            rc = parse_num(a, v, &x);
            c.layers = (int)x;
            if (!rc && x != 1 && x != 2) {
                fprintf(stderr, "spall calibrate: --layers must be 1 or 2\n");
                rc = 2;
            }
        } else if (strcmp(a, "--angular") == 0) {
            if (strcmp(v, "auto") == 0)
                c.angular = -1;
            else if (strcmp(v, "on") == 0)
                c.angular = 1;
            else if (strcmp(v, "off") == 0)
                c.angular = 0;
            else {
                fprintf(stderr, "spall calibrate: --angular must be auto, on or off\n");
                rc = 2;
            }
        } else if (strcmp(a, "--lattice") == 0) {
            int kind = lattice_kind_from_name(v);
            if (kind < 0) {
                fprintf(stderr, "spall calibrate: unknown lattice '%s'; expected chain, "
                                "triangular, square, sc, fcc or triple_honeycomb\n",
                        v);
                rc = 2;
            }
            c.kind = (enum lattice_kind)kind;
        } else {
            fprintf(stderr, "spall calibrate: unknown option '%s' (see --help)\n", a);
            rc = 2;
        }
        if (rc)
            return rc;
    }
    if (!isfinite(c.E) || !isfinite(c.nu) || !(c.r0 > 0) || !(c.rho > 0)) {
        fprintf(stderr, "spall calibrate: --E, --nu, --rho and --spacing are required (see --help)\n");
        return 2;
    }
    if (!(c.thickness > 0)) {
        if (c.kind == LATTICE_TRIANGULAR || c.kind == LATTICE_TRIPLE_HONEYCOMB)
            c.thickness = 2.0 * c.r0 / sqrt(3.0);
        else if (c.kind == LATTICE_CHAIN)
            c.thickness = c.r0 * c.r0;
        else
            c.thickness = c.r0;
    }
    struct spall_error err = {0};
    int rc = lattice_calibrate(&c, &err);
    if (rc) {
        fprintf(stderr, "spall: error: %s\n", err.msg);
        return cli_exit_status(rc);
    }
    printf("lattice model constants (%s lattice, r0 = %g m, %s = %g %s)\n",
           lattice_kind_name(c.kind), c.r0, c.kind == LATTICE_CHAIN ? "area" : "thickness",
           c.thickness, c.kind == LATTICE_CHAIN ? "m^2" : "m");
    printf("  input: E = %g Pa, nu = %g, rho = %g kg/m^3, sigma_TS = %g Pa\n", c.E, c.nu, c.rho,
           c.sigma_ts);
    printf("  axial layers: %d, angular springs: %s\n", c.layers_used,
           c.area_used        ? "area springs (nu > 1/3)"
           : c.angular_used   ? "yes (alpha-beta)"
           : c.honeycomb_used ? "no (alpha-beta-gamma: three central-spring families)"
                              : "no (alpha)");
    if (c.honeycomb_used)
        printf("  honeycomb families (alpha-beta-gamma): alpha = %.6g N/m, beta = gamma = "
               "%.6g N/m\n", c.k_family[0], c.k_family[1]);
    else
        printf("  S0 = k1 (nearest neighbours)      %.6g N/m\n", c.k1);
    if (c.layers_used > 1)
        printf("  k2 (second neighbours)            %.6g N/m\n", c.k2);
    if (c.area_used)
        printf("  k_area (triangle area springs)    %.6g J\n", c.k_area);
    else if (c.angular_used)
        printf("  S_phi = k_phi (angular)           %.6g N m/rad^2\n", c.k_phi);
    printf("  eps_max = sigma_TS / E (Eq. 26)   %.6g\n", c.eps_max);
    printf("  volume per particle               %.6g m^3\n", c.site_volume);
    printf("  particle mass                     %.6g kg\n", c.mass);
    printf("  stable time step (Eq. 25)         %.6g s\n", c.dt);
    if (c.kind == LATTICE_TRIANGULAR && !c.area_used) {
        printf("  [Wang2010] Eq. 16 S0                %.6g N/m (for t = 2 r0/sqrt3)\n", c.paper_S0);
        printf("  [Wang2010] Eq. 18 S_phi             %.6g N (x r0 = %.6g N m/rad^2)\n",
               c.paper_S_phi, c.paper_S_phi * c.r0);
    }
    double Em = 0, num = 0;
    rc = lattice_patch_test(&c, 1e-6, 0, &Em, &num, &err);
    if (rc) {
        fprintf(stderr, "spall: error: patch test: %s\n", err.msg);
        return cli_exit_status(rc);
    }
    printf("patch test (uniform strain 1e-6, real force code%s):\n",
           c.honeycomb_used ? ", sublattice shifts relaxed" : "");
    printf("  E  measured %.6g Pa (input %.6g, error %.3g %%)\n", Em, c.E,
           100.0 * fabs(Em - c.E) / c.E);
    printf("  nu measured %.6g (input %.6g, error %.3g)\n", num, c.nu, fabs(num - c.nu));
    if (c.kind == LATTICE_TRIANGULAR && c.angular_used && !c.area_used) {
        double Ep = 0, nup = 0;
        if (lattice_patch_test(&c, 1e-6, 1, &Ep, &nup, &err) == 0)
            printf("  with the paper's Eq. 16/18 constants: E %.6g Pa, nu %.6g\n", Ep, nup);
    }
    return 0;
}
