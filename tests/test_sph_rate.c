/**
 * @file test_sph_rate.c
 * @brief Cowper-Symonds rate scaling of the SPH yield stress
 *        (sph_material.c): sigma_y (1 + (epdot / D)^(1/q)) at known strain
 *        rates for the perfect and the A + B ep^n laws; no scaling without
 *        rate_model; the deck refuses non-positive D or q and the
 *        combination with Johnson-Cook.
 */
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
             "                %s}}\n"
             "lattice: {type: square, spacing: 1.0e-3}\n"
             "body: {geometry: {box: {min: [0, 0], max: [0.004, 0.004]}}, material: m}\n"
             "run: {steps: 1}\n",
             mat_extra);
    struct spall_error err = {0};
    return vlat_build("t", yaml, out, &err);
}

static void test_yield_scaling(void **state)
{
    (void)state;
    struct sph_material mt;
    memset(&mt, 0, sizeof mt);
    mt.yield = SPH_YIELD_PERFECT;
    mt.sy = 21.0e6;
    mt.rate = SPH_RATE_COWPER_SYMONDS;
    mt.cs_d = 1.0e4;
    mt.cs_q = 2.0;
    /* epdot = D: factor 2; epdot = 4 D: 1 + 2 = 3; epdot = D/100: 1.1 */
    assert_near(sph_yield_stress(&mt, 0.0, 1.0e4, 293.0), 42.0e6, 1.0);
    assert_near(sph_yield_stress(&mt, 0.0, 4.0e4, 293.0), 63.0e6, 1.0);
    assert_near(sph_yield_stress(&mt, 0.0, 1.0e2, 293.0), 21.0e6 * 1.1, 1.0);
    assert_near(sph_yield_stress(&mt, 0.0, 0.0, 293.0), 21.0e6, 1e-6);
    /* power law A + B ep^n times the factor; q = 5 at epdot = 32 D: 1 + 2 */
    mt.yield = SPH_YIELD_POWER;
    mt.A = 21.0e6;
    mt.B = 1.0e4;
    mt.n = 0.1;
    mt.cs_q = 5.0;
    double base = 21.0e6 + 1.0e4 * pow(0.5, 0.1);
    assert_near(sph_yield_stress(&mt, 0.5, 32.0e4, 293.0), 3.0 * base, 1e-3);
    assert_near(sph_rate_factor(&mt, 32.0e4), 3.0, 1e-12);
    /* no rate model: rate independent */
    mt.rate = SPH_RATE_NONE;
    assert_near(sph_yield_stress(&mt, 0.5, 32.0e4, 293.0), base, 1e-3);
    assert_near(sph_rate_factor(&mt, 1.0e9), 1.0, 0.0);
}

static void test_deck(void **state)
{
    (void)state;
    struct sim *s = NULL;
    assert_int_equal(build_rc("yield: perfect, yield_stress: 1e6, rate_model: cowper_symonds, "
                              "cs_d: 1e4, cs_q: 2",
                              &s),
                     SPALL_OK);
    assert_non_null(s);
    const struct sph_material *mt0 = sph_material_get(s->model, 0);
    assert_int_equal(mt0->rate, SPH_RATE_COWPER_SYMONDS);
    assert_near(mt0->cs_d, 1.0e4, 0.0);
    assert_near(mt0->cs_q, 2.0, 0.0);
    sim_destroy(&s);
    static const char *const bad[] = {
        "yield: perfect, yield_stress: 1e6, rate_model: cowper_symonds, cs_d: 0, cs_q: 2",
        "yield: perfect, yield_stress: 1e6, rate_model: cowper_symonds, cs_d: 1e4, cs_q: -1",
        "yield: perfect, yield_stress: 1e6, rate_model: cowper_symonds, cs_q: 2",
        "yield: johnson_cook, yield_a: 1e6, specific_heat: 400, melt_temperature: 1800, "
        "rate_model: cowper_symonds, cs_d: 1e4, cs_q: 2",
    };
    for (size_t k = 0; k < sizeof bad / sizeof bad[0]; k++) {
        s = NULL;
        assert_int_not_equal(build_rc(bad[k], &s), SPALL_OK);
        sim_destroy(&s);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_yield_scaling),
        cmocka_unit_test(test_deck),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
