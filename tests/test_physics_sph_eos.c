/**
 * @file test_physics_sph_eos.c
 * @brief The SPH equations of state (src/models/sph/sph_material.c) against
 *        the thermodynamic definitions of their parameters:
 *  - linear EOS: the bulk modulus K = rho dP/drho at the rest density is the
 *    elastic one of the input, E / (3 (1 - 2 nu));
 *  - Mie-Grueneisen: at the reference state rho0 dP/drho = rho0 C^2 (C the
 *    bulk sound speed of the Hugoniot U_s = C + S u_p), and the Grueneisen
 *    parameter is by definition Gamma = (1/rho) (dP/de)_rho, at any density,
 *    in compression and in tension.
 * P is linear in rho (linear EOS) and in e, so those central differences
 * are exact up to round-off (~eps P / h); the MG slope at eta = 0 is
 * bounded below.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include "models/sph/sph.h"
#include "tests/test_support.h"

#include <stdio.h>

/* A small 2D SPH block of material @p mat (only its material is used). */
static struct sim *build_block(const char *mat)
{
    char yaml[1536];
    snprintf(yaml, sizeof yaml,
             "model: {type: sph, kernel: wendland}\n"
             "materials: {m: {%s}}\n"
             "lattice: {type: square, spacing: 1.0e-3, origin: [0.0005, 0.0005]}\n"
             "body: {geometry: {box: {min: [0, 0], max: [0.004, 0.004]}}, material: m}\n"
             "run: {steps: 1}\n",
             mat);
    return test_build_ok(yaml);
}

static void test_linear_bulk_modulus(void **state)
{
    (void)state;
    const double rho0 = 2700.0, E = 70.0e9, nu = 0.33;
    char mat[256];
    snprintf(mat, sizeof mat, "density: %g, youngs_modulus: %g, poisson_ratio: %g", rho0, E, nu);
    struct sim *s = build_block(mat);
    const struct sph_material *mt = sph_material_get(s->model, 0);
    assert_non_null(mt);
    const double K = E / (3.0 * (1.0 - 2.0 * nu)), h = 1.0e-3 * rho0;
    assert_true(fabs(sph_eos_pressure(mt, rho0, 0.0)) <= 1e-6); /* stress-free at rest */
    const double Kfd = rho0 * (sph_eos_pressure(mt, rho0 + h, 0.0) - sph_eos_pressure(mt, rho0 - h, 0.0)) / (2.0 * h);
    print_message("rho dP/drho = %.12e Pa, E / (3 (1 - 2 nu)) = %.12e Pa\n", Kfd, K);
    assert_true(fabs(Kfd - K) <= 1.0e-9 * K);
    sim_destroy(&s);
}

static void test_mie_grueneisen_definitions(void **state)
{
    (void)state;
    const double rho0 = 7830.0, C = 4570.0, S = 1.49, Gamma = 2.17;
    char mat[512];
    snprintf(mat, sizeof mat,
             "density: %g, bulk_modulus: 169.1e9, shear_modulus: 89.2e9, eos: mie_gruneisen,"
             " sound_speed: %g, hugoniot_slope: %g, gruneisen: %g",
             rho0, C, S, Gamma);
    struct sim *s = build_block(mat);
    const struct sph_material *mt = sph_material_get(s->model, 0);
    assert_non_null(mt);
    /* bulk sound speed of the reference state; the Hugoniot's curvature
     * (compression) and the linear tension branch differ in dP^2/drho^2, so
     * the central difference errs by ~(hr / rho0) (2 S - 1) / 2 = 1e-8, and
     * eta = rho / rho0 - 1 is rounded by ~eps: 2e-8 of hr / rho0 */
    const double hr = 1.0e-8 * rho0;
    const double K0 = rho0 * (sph_eos_pressure(mt, rho0 + hr, 0.0) - sph_eos_pressure(mt, rho0 - hr, 0.0)) / (2.0 * hr);
    print_message("rho0 dP/drho = %.12e Pa, rho0 C^2 = %.12e Pa\n", K0, rho0 * C * C);
    assert_true(fabs(K0 - rho0 * C * C) <= 1.0e-7 * rho0 * C * C);
    /* Gamma = (1/rho) dP/de at fixed rho, from 10 % tension to 30 % compression */
    const double etas[5] = {-0.1, -0.01, 0.0, 0.1, 0.3};
    const double e0 = 2.0e5, he = 1.0e3; /* J/kg */
    for (int k = 0; k < 5; k++) {
        const double rho = rho0 * (1.0 + etas[k]);
        const double dPde = (sph_eos_pressure(mt, rho, e0 + he) - sph_eos_pressure(mt, rho, e0 - he)) / (2.0 * he);
        const double G = dPde / rho;
        print_message("eta = %+.2f: (1/rho) dP/de = %.12f\n", etas[k], G);
        /* round-off: eps P / he ~ 1e-8 with P up to ~1e11 Pa, against
         * rho Gamma ~ 2e4 */
        assert_true(fabs(G - Gamma) <= 1.0e-9 * Gamma);
    }
    sim_destroy(&s);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_linear_bulk_modulus),
        cmocka_unit_test(test_mie_grueneisen_definitions),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
