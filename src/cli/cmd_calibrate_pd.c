/**
 * @file cmd_calibrate_pd.c
 * @brief `spall calibrate peridynamics`: micromoduli and critical stretches
 *        of the PD model from continuum data, and the moduli it achieves,
 *        measured by a patch test (uniform strains through the model's own
 *        bond coefficients, virial stress of an interior particle).
 */
#include "cli/cli.h"

#include "core/bond_list.h"
#include "core/mathconst.h"
#include "core/sim.h"
#include "io/deck.h"
#include "io/deck_build.h"
#include "io/run_summary.h"
#include "core/model.h"
#include "models/peridynamics/pd.h"
#include "spall/error.h"

#include <math.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static void usage(FILE *out)
{
    fprintf(out,
            "usage: spall calibrate peridynamics [--variant pmb|pdlm] [--spacing M]\n"
            "         [--horizon-factor M] [--thickness M] [--lattice square|triangular]\n"
            "         [--angle DEG] [--fiber-model lattice|angular] [--rho KG_M3]\n"
            "         isotropic: --E PA [--G0 J_M2] [--plane stress|strain]\n"
            "         lamina:    --E1 PA --E2 PA --G12 PA --nu12 NU [--GIc J_M2] [--Gf J_M2]\n"
            "\n"
            "Prints c (isotropic) or c_f, c_m (lamina), the critical stretches, and the\n"
            "achieved plane-stress E1, E2, G12, nu12 of a 2D plate (21 x 21 spacings)\n"
            "against the targets (a pair-bond model fixes nu: it cannot match all four).\n"
            "The plate is built as `spall run` builds a deck (density --rho, default\n"
            "1000 kg/m^3), so the time step printed is a run's with these values.\n"
            "Defaults: spacing 1 mm, horizon 3.015 spacings, thickness 1 mm, plane stress.\n");
}

int cli_calibrate_peridynamics(int argc, char **argv)
{
    const char *variant = "pmb", *lat = NULL, *fm = "lattice";
    const char *plane = "stress";
    double dx = 1e-3, hf = 3.015, t = 1e-3, ang = 0, E = NAN, G0 = 0, rho = 1000.0;
    double E1 = NAN, E2 = NAN, G12 = NAN, nu12 = NAN, GIc = 0, Gf = 0;
    for (int k = 2; k < argc; k++) {
        const char *a = argv[k];
        if (strcmp(a, "-h") == 0 || strcmp(a, "--help") == 0) {
            usage(stdout);
            return 0;
        }
        if (k + 1 >= argc) {
            fprintf(stderr, "spall calibrate peridynamics: %s needs a value\n", a);
            return 2;
        }
        static const char *const known[] = {
            "--variant", "--lattice", "--fiber-model", "--plane", "--spacing", "--horizon-factor",
            "--thickness", "--angle", "--E", "--G0", "--E1", "--E2", "--G12", "--nu12", "--GIc",
            "--Gf", "--rho"};
        bool ok = false;
        for (size_t q = 0; q < sizeof known / sizeof known[0]; q++)
            ok = ok || strcmp(a, known[q]) == 0;
        if (!ok) {
            fprintf(stderr, "spall calibrate peridynamics: unknown option '%s' (see --help)\n", a);
            return 2;
        }
        const char *v = argv[++k];
        char *end = NULL;
        double x = strtod(v, &end);
        int num = end != v && *end == '\0' && isfinite(x);
        if (strcmp(a, "--variant") == 0) variant = v;
        else if (strcmp(a, "--lattice") == 0) lat = v;
        else if (strcmp(a, "--fiber-model") == 0) fm = v;
        else if (strcmp(a, "--plane") == 0) plane = v;
        else if (!num) {
            fprintf(stderr, "spall calibrate peridynamics: %s needs a number, got '%s'\n", a, v);
            return 2;
        }
        else if (strcmp(a, "--spacing") == 0) dx = x;
        else if (strcmp(a, "--horizon-factor") == 0) hf = x;
        else if (strcmp(a, "--thickness") == 0) t = x;
        else if (strcmp(a, "--angle") == 0) ang = x;
        else if (strcmp(a, "--E") == 0) E = x;
        else if (strcmp(a, "--G0") == 0) G0 = x;
        else if (strcmp(a, "--E1") == 0) E1 = x;
        else if (strcmp(a, "--E2") == 0) E2 = x;
        else if (strcmp(a, "--G12") == 0) G12 = x;
        else if (strcmp(a, "--nu12") == 0) nu12 = x;
        else if (strcmp(a, "--GIc") == 0) GIc = x;
        else if (strcmp(a, "--Gf") == 0) Gf = x;
        else rho = x; /* --rho: the last of the known names */
    }
    int lamina = !isnan(E1);
    if (lamina && (isnan(E2) || isnan(G12) || isnan(nu12))) {
        fprintf(stderr, "spall calibrate peridynamics: a lamina needs --E1 --E2 --G12 --nu12\n");
        return 2;
    }
    if (!lamina && isnan(E)) {
        fprintf(stderr, "spall calibrate peridynamics: give --E (isotropic) or --E1 ... "
                        "(lamina)\n");
        return 2;
    }
    if (strcmp(plane, "stress") != 0 && strcmp(plane, "strain") != 0) {
        fprintf(stderr, "spall calibrate peridynamics: --plane must be stress or strain, got "
                        "'%s'\n", plane);
        return 2;
    }
    if (!lat)
        lat = strcmp(variant, "pdlm") == 0 ? "triangular" : "square";
    char mat[512], deck[2048];
    if (lamina)
        snprintf(mat, sizeof mat,
                 "{density: %.17g, fiber_modulus: %.17g, transverse_modulus: %.17g, "
                 "shear_modulus: %.17g, major_poisson_ratio: %.17g, fiber_angle: %.17g, "
                 "matrix_fracture_energy: %.17g, fiber_fracture_energy: %.17g}",
                 rho, E1, E2, G12, nu12, ang, GIc, Gf);
    else
        snprintf(mat, sizeof mat, "{density: %.17g, youngs_modulus: %.17g, fracture_energy: %.17g}",
                 rho, E, G0);
    snprintf(deck, sizeof deck,
             "model: {type: peridynamics, variant: %s, horizon_factor: %.17g, fiber_model: %s%s}\n"
             "materials:\n  m: %s\n"
             "lattice: {type: %s, spacing: %.17g, thickness: %.17g, angle: %.17g}\n"
             "geometry:\n  p: {box: {min: [0, 0], max: [%.17g, %.17g]}}\n"
             "body: {geometry: p, material: m}\nrun: {steps: 1}\n",
             variant, hf, fm,
             lamina ? "" : strcmp(plane, "strain") == 0 ? ", plane: plane_strain" : "", mat, lat, dx, t, ang, 20.5 * dx, 20.5 * dx);
    struct spall_error err = {0};
    struct deck *d = NULL;
    struct sim *s = NULL;
    struct run_output ro;
    int rc = deck_load_string(&d, "options of spall calibrate peridynamics", deck, &err);
    if (!rc)
        rc = deck_build_sim(d, &s, &ro, &err);
    deck_destroy(&d);
    if (rc) {
        fprintf(stderr, "spall: error: %s\n", err.msg);
        sim_destroy(&s);
        return cli_exit_status(rc);
    }
    run_summary_write(stdout, s);
    struct model *m = s->model;
    size_t i = pd_patch_particle(m, s, 0);
    double C[3][3], S[3][3];
    const struct pd_material *mt = pd_material_get(m, 0);
    double th = lamina ? mt->fiber_angle : 0.0;
    pd_patch_stiffness(m, s, i, th, C);
    if (pd_invert3(C, S)) {
        fprintf(stderr, "spall calibrate peridynamics: singular patch stiffness\n");
        sim_destroy(&s);
        return 1;
    }
    double a[4] = {1.0 / S[0][0], 1.0 / S[1][1], 1.0 / S[2][2], -S[0][1] / S[0][0]};
    double nu_fix = mt->nu;
    double tg[4];
    if (lamina) {
        tg[0] = E1, tg[1] = E2, tg[2] = G12, tg[3] = nu12;
    } else {
        tg[0] = tg[1] = E, tg[2] = E / (2.0 * (1.0 + nu_fix)), tg[3] = nu_fix;
        if (strcmp(plane, "strain") == 0) { /* the in-plane constants a 2D patch measures */
            tg[0] = tg[1] = E / (1.0 - nu_fix * nu_fix);
            tg[3] = nu_fix / (1.0 - nu_fix);
        }
    }
    static const char *const names[4] = {"E1", "E2", "G12", "nu12"};
    printf("patch test, in-plane constants%s (particle %zu, %zu bonds, material axes at "
           "%g deg):\n",
           strcmp(plane, "strain") == 0 && !lamina ? " (plane strain: E/(1-nu^2), nu/(1-nu))" : "",
           i,
           pd_bonds(m)->offset[i + 1] - pd_bonds(m)->offset[i], th * 180.0 / SPALL_PI);
    for (int k = 0; k < 4; k++)
        printf("  %-5s achieved %-12.6g target %-12.6g (%+.2f %%)\n", names[k], a[k], tg[k],
               100.0 * (a[k] / tg[k] - 1.0));
    sim_destroy(&s);
    return 0;
}
