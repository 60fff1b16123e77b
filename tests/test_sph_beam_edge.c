/**
 * @file test_sph_beam_edge.c
 * @brief The clamp forms of the SPH cantilever driver (validation/sph_beam.h,
 *        sph-beam and sph-beam-large): the edge clamp is one column of
 *        fixed particles behind x = 0 (the thesis' "left edge of the beam is
 *        fixed", [Meng2021] sec. 3.4.1), the fixed clamp three, the mirrored
 *        clamp five; the beam itself is the same 100 x 10 particles.  Then
 *        100 steps of the 17.5 kN edge-clamp deck (sph-beam-large, averaged
 *        AS): the clamp column stays at rest and the tension-side corner
 *        pair across the clamp plane stays closed (measured over the whole
 *        3 ms run: <= 1.16 dx, docs/validation.md).
 */
#include "validation/lattice_cases.h"
#include "validation/sph_beam.h"

#include "core/particles.h"
#include "core/sim.h"
#include "spall/error.h"

#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include <math.h>

static const char *const EXTRA = "cspm: true, viscosity: [0.5, 0.8], artificial_stress: 0.9, "
                                 "xsph: 0.5, artificial_stress_smoothing: true";

static struct sim *build(enum sph_beam_clamp clamp)
{
    char deck[3072];
    struct spall_error err = {0};
    struct sim *s = NULL;
    sph_beam_deck("wendland", 17500.0, 1.4, EXTRA, clamp, deck, sizeof deck);
    assert_int_equal(vlat_build("sph_beam_edge", deck, &s, &err), SPALL_OK);
    return s;
}

static void test_clamp_columns(void **state)
{
    (void)state;
    const enum sph_beam_clamp forms[3] = {SPH_BEAM_EDGE, SPH_BEAM_FIXED, SPH_BEAM_MIRROR};
    const size_t cols[3] = {1, 3, 5};
    for (int f = 0; f < 3; f++) {
        struct sim *s = build(forms[f]);
        const struct particles *p = s->p;
        size_t clamp = 0, beam = 0;
        double xmin = 0.0;
        for (size_t i = 0; i < p->n; i++) {
            if (p->x0[0][i] < 0.0)
                clamp++;
            else
                beam++;
            xmin = fmin(xmin, p->x0[0][i]);
        }
        assert_int_equal(beam, 1000);
        assert_int_equal(clamp, 10 * cols[f]);
        assert_true(fabs(xmin + (cols[f] - 0.5) * 1e-3) < 1e-9);
        sim_destroy(&s);
    }
}

static void test_edge_clamp_runs(void **state)
{
    (void)state;
    struct sim *s = build(SPH_BEAM_EDGE);
    struct spall_error err = {0};
    const struct particles *p = s->p;
    size_t corner = 0, fixed = 0;
    for (size_t i = 0; i < p->n; i++) {
        if (fabs(p->x0[0][i] - 0.5e-3) < 1e-9 && fabs(p->x0[1][i] - 4.5e-3) < 1e-9)
            corner = i;
        if (fabs(p->x0[0][i] + 0.5e-3) < 1e-9 && fabs(p->x0[1][i] - 4.5e-3) < 1e-9)
            fixed = i;
    }
    assert_int_equal(sim_initial_forces(s, &err), SPALL_OK);
    for (int k = 0; k < 100; k++)
        assert_int_equal(sim_step(s, &err), SPALL_OK);
    for (size_t i = 0; i < p->n; i++)
        if (p->x0[0][i] < 0.0)
            assert_true(p->x[0][i] == p->x0[0][i] && p->x[1][i] == p->x0[1][i]);
    double gap = hypot(p->x[0][corner] - p->x[0][fixed], p->x[1][corner] - p->x[1][fixed]);
    assert_true(gap > 0.99e-3 && gap < 1.01e-3); /* 12 us: the load is still 6e-5 of F */
    assert_true(isfinite(p->x[1][corner]));
    sim_destroy(&s);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_clamp_columns),
        cmocka_unit_test(test_edge_clamp_runs),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
