/**
 * @file test_sph_beam_transient.c
 * @brief sph-beam's type 1 row (cubic spline, fixed clamp, [Meng2021]'s
 *        CSPM, AV, pointwise AS 0.5 and XSPH at 1.75 kN) through its
 *        start-up transient: the artificial stress's particle-scale
 *        instability grows from t = 0 until AV and XSPH hold it, the
 *        kinetic energy peaking at ~320 times the small work the quadratic
 *        ramp has put in by 0.17 ms (0.19 J).  The beam driver's blow-up bound
 *        (SPH_BEAM_ENERGY_BLOWUP, validation/sph_beam.h) must let it
 *        through: with sim_step's default (100) the row stopped at step
 *        1361 and sph-beam reported NaN (docs/notes/validation-log.md).
 *        Checked over the first 0.3 ms (about 3000 steps): every step
 *        succeeds, the transient stays well below the bound, and it has
 *        decayed by 0.3 ms to the kinetic share of a loaded elastic beam
 *        (about 0.9 of the work put in there).
 */
#include "validation/sph_beam.h"

#include "core/sim.h"
#include "spall/error.h"

#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include <math.h>
#include <stdio.h>

static const char *const THESIS = "cspm: true, viscosity: [0.1, 0.1], artificial_stress: 0.5, "
                                  "xsph: 0.5";

static void test_cubic_row_passes_transient(void **state)
{
    (void)state;
    struct spall_error err = {0};
    struct sim *s = NULL;
    assert_int_equal(sph_beam_build("cubic_spline", 1750.0, 1.2, THESIS, SPH_BEAM_FIXED, &s, &err),
                     SPALL_OK);
    assert_true(s->energy_blowup == SPH_BEAM_ENERGY_BLOWUP);
    double peak = 0.0, t_peak = 0.0;
    int rc = SPALL_OK;
    while (s->t < 3.0e-4) {
        if ((rc = sim_step(s, &err)))
            break;
        const double ratio = sph_beam_kinetic_ratio(s);
        if (ratio > peak) {
            peak = ratio;
            t_peak = s->t;
        }
    }
    const double end = sph_beam_kinetic_ratio(s);
    printf("cubic row: peak kinetic energy %.4g x the work put in at %.4g ms; %.3g at %.3g ms; "
           "step %ld: %s\n",
           peak, t_peak * 1e3, end, s->t * 1e3, s->step, rc ? err.msg : "ok");
    assert_int_equal(rc, SPALL_OK);
    /* the transient itself (measured 321 at 0.166 ms): bounded, and over
     * by 0.3 ms */
    assert_true(peak < 1.0e3);
    assert_true(t_peak < 2.5e-4);
    assert_true(end < 2.0);
    sim_destroy(&s);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_cubic_row_passes_transient),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
