/**
 * @file test_physics_sph_plastic.c
 * @brief J2 (von Mises) radial return of an elastic-perfectly-plastic SPH
 *        body ([Meng2021], src/models/sph/sph_material.c): a homogeneous
 *        pure-shear trial stress above yield is scaled back onto the yield
 *        surface along its own direction, with the plastic strain the
 *        consistency condition gives.
 *
 * For J2 plasticity with a perfect yield stress sigma_y and shear modulus
 * G, a trial deviator S* with sigma_eq* = sqrt(3 J2*) = sqrt(3/2 S*:S*) >
 * sigma_y returns to S = (sigma_y / sigma_eq*) S*: afterwards
 * sqrt(3/2 S:S) = sigma_y, S parallel to S*, and the equivalent plastic
 * strain grows by (sigma_eq* - sigma_y) / (3 G): the return removes the
 * deviatoric stress 2G deps^p = S* - S, and the equivalent plastic strain
 * is sqrt(2/3 deps^p:deps^p) = sqrt(2/3) |S* - S| / (2G)
 * = (sigma_eq* - sigma_y) / (3G), since |S| = sqrt(2/3) sigma_eq.
 *
 * Set-up: a 2D block at rest, the trial S* = pure shear S_xy = tau written
 * through the field registry, one fixed step of dt = 1e-12 s with a huge
 * density (mass scaling, 1e15 kg/m^3): the free-surface forces of the
 * pre-stress move the particles by ~1e-4 m/s^2 x dt, so the stress rate
 * adds ~1e-20 of tau to the trial within the step and every particle
 * returns the homogeneous trial stress.  Everything is then exact to
 * round-off (measured: 0 difference in sigma_eq, S_xy and eps_p at every
 * particle; tolerances 1e-12 relative).  A radial return by
 * sqrt(sigma_y / sigma_eq*) leaves sigma_eq = 1.32 sigma_y; an equivalent
 * stress sqrt(S:S) (no 3/2) returns to 1.22 sigma_y; a plastic strain with
 * 2G instead of 3G is 1.5 times too large.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include "core/fields.h"
#include "tests/test_assert.h"
#include "tests/test_support.h"

#include <math.h>
#include <stdio.h>

#define SIGMA_Y 1.0e8 /* Pa */
#define TAU 1.0e8     /* trial shear stress: sigma_eq* = sqrt(3) tau */
#define E_MOD 2.0e11
#define NU 0.3

static double *comp(const struct field_desc *f, int c)
{
    return *(double **)f->comp[c];
}

/* Return the pure-shear trial in the body of @p model_line (one step) and
 * check the J2 return at every particle. */
static void check_return(const char *model_line)
{
    char yaml[1024];
    snprintf(yaml, sizeof yaml,
             "model: %s\n"
             "materials: {m: {density: 1.0e15, youngs_modulus: %g, poisson_ratio: %g,"
             " yield: perfect, yield_stress: %g}}\n"
             "lattice: {type: square, spacing: 1.0e-3, origin: [0.0005, 0.0005]}\n"
             "body: {geometry: {box: {min: [0, 0], max: [0.006, 0.006]}}, material: m}\n"
             "run: {dt: 1.0e-12, steps: 1}\n",
             model_line, E_MOD, NU, SIGMA_Y);
    struct sim *s = test_build_ok(yaml);
    const struct field_desc *fs = field_registry_find(s->fields, "deviatoric_stress");
    const struct field_desc *fe = field_registry_find(s->fields, "plastic_strain");
    assert_non_null(fs);
    assert_non_null(fe);
    const size_t n = s->p->n_owned;
    for (size_t i = 0; i < n; i++) {
        for (int c = 0; c < 6; c++)
            comp(fs, c)[i] = 0.0;
        comp(fs, 3)[i] = TAU; /* xy */
    }
    struct spall_error err = {0};
    assert_int_equal(sim_step(s, &err), SPALL_OK);
    const double G = E_MOD / (2.0 * (1.0 + NU));
    const double seq_trial = sqrt(3.0) * TAU;
    const double dep = (seq_trial - SIGMA_Y) / (3.0 * G);
    double worst_seq = 0.0, worst_dir = 0.0, worst_ep = 0.0;
    for (size_t i = 0; i < n; i++) {
        double S[6], ss = 0.0;
        for (int c = 0; c < 6; c++) {
            S[c] = comp(fs, c)[i];
            ss += (c < 3 ? 1.0 : 2.0) * S[c] * S[c];
        }
        const double seq = sqrt(1.5 * ss);
        /* on the yield surface */
        assert_near(seq, SIGMA_Y, 1e-12 * SIGMA_Y);
        /* along the trial direction: only S_xy, positive, = sigma_y / sqrt 3 */
        for (int c = 0; c < 6; c++)
            assert_near(S[c], c == 3 ? SIGMA_Y / sqrt(3.0) : 0.0, 1e-12 * SIGMA_Y);
        /* plastic strain of the return (consistency) */
        const double ep = comp(fe, 0)[i];
        assert_near(ep, dep, 1e-12 * dep);
        worst_seq = fmax(worst_seq, fabs(seq / SIGMA_Y - 1.0));
        worst_dir = fmax(worst_dir, fabs(S[3] * sqrt(3.0) / SIGMA_Y - 1.0));
        worst_ep = fmax(worst_ep, fabs(ep / dep - 1.0));
    }
    print_message("%s: %zu particles, max |sigma_eq/sigma_y - 1| = %.1e, |S_xy sqrt3/sigma_y - 1| = "
                  "%.1e, |eps_p/eps_p,exact - 1| = %.1e (eps_p,exact = %.6e)\n",
                  model_line, n, worst_seq, worst_dir, worst_ep, dep);
    sim_destroy(&s);
}

/* Updated form (predictor-corrector, sph_model.c): the return at the
 * predictor does not commit; the corrector returns the same trial once. */
static void test_return_updated(void **state)
{
    (void)state;
    check_return("{type: sph, kernel: wendland, h_factor: 1.3, adaptive_dt: false}");
}

/* Leapfrog integration (sph_leapfrog.c): one committed return per step. */
static void test_return_leapfrog(void **state)
{
    (void)state;
    check_return("{type: sph, kernel: wendland, h_factor: 1.3, adaptive_dt: false,"
                 " time_integration: leapfrog}");
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_return_updated),
        cmocka_unit_test(test_return_leapfrog),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
