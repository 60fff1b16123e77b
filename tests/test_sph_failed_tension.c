/**
 * @file test_sph_failed_tension.c
 * @brief Material key failed_tension of the SPH model (sph_material.c):
 *        by default a failed particle carries no tension (P clipped at 0);
 *        with failed_tension: true it keeps the EOS pressure in tension
 *        (the hydrodynamic behaviour without a pressure cut-off); intact
 *        particles keep their tension either way; the key must be a bool.
 */
#include "core/fields.h"
#include "core/sim.h"
#include "models/sph/sph.h"
#include "spall/error.h"

#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "tests/test_assert.h"

#include "tests/test_support.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

static int build_rc(const char *mat_extra, struct sim **out)
{
    char yaml[1024];
    snprintf(yaml, sizeof yaml,
             "model: {type: sph, kernel: wendland, h_factor: 1.3}\n"
             "materials: {m: {density: 1000, youngs_modulus: 1.0e7, poisson_ratio: 0.3,\n"
             "                yield: perfect, yield_stress: 1.0e6, failure: stress,\n"
             "                failure_value: 1.0e6%s}}\n"
             "lattice: {type: square, spacing: 1.0e-3}\n"
             "body: {geometry: {box: {min: [0, 0], max: [0.004, 0.004]}}, material: m}\n"
             "run: {steps: 1}\n",
             mat_extra);
    struct spall_error err = {0};
    return vlat_build("t", yaml, out, &err);
}

/* P of particle 0 (failed) and 1 (intact), both stretched to 0.99 rho0 */
static void pressures(const char *extra, double *p_failed, double *p_intact)
{
    struct sim *s = NULL;
    assert_int_equal(build_rc(extra, &s), SPALL_OK);
    double *rho = field_stored_data(s->fields, "density", 0);
    const double *P = field_stored_data(s->fields, "pressure", 0);
    uint8_t *failed = field_stored_data(s->fields, "failed", 0);
    assert_true(rho && P && failed);
    rho[0] = rho[1] = 0.99 * sph_material_get(s->model, 0)->rho0;
    failed[0] = 1;
    failed[1] = 0;
    sph_refresh_pressure(s->model, s);
    *p_failed = P[0];
    *p_intact = P[1];
    sim_destroy(&s);
}

static void test_failed_tension(void **state)
{
    (void)state;
    double pf = 1.0, pi = 1.0;
    const double K = 1.0e7 / (3.0 * (1.0 - 0.6)); /* linear EOS: P = K (rho/rho0 - 1) */
    pressures("", &pf, &pi);
    assert_near(pf, 0.0, 0.0);
    assert_near(pi, -0.01 * K, 1e-6 * K);
    pressures(", failed_tension: false", &pf, &pi);
    assert_near(pf, 0.0, 0.0);
    pressures(", failed_tension: true", &pf, &pi);
    assert_near(pf, -0.01 * K, 1e-6 * K);
    assert_near(pi, -0.01 * K, 1e-6 * K);
    struct sim *s = NULL;
    assert_int_not_equal(build_rc(", failed_tension: 3", &s), SPALL_OK);
    sim_destroy(&s);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_failed_tension),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
