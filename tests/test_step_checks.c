/**
 * @file test_step_checks.c
 * @brief The time step's ownership rules seen from the library API:
 *        sim_step itself stops an energy blow-up (not only the CLI), and
 *        the model's drift velocity (XSPH) never moves a particle whose
 *        velocity a BC prescribes.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include "tests/test_support.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* A lattice plate pulled at 1 m/s with dt 14x above its stability limit
 * (the deck of tests/cli/unstable_run.sh): the energy grows without
 * bound.  sim_step must stop it with SPALL_ERR_UNSTABLE on the energy
 * criterion while the state is still finite (the NaN check would fire only
 * later, after overflow), naming step, time and particle. */
static void test_energy_blowup_in_sim_step(void **state)
{
    (void)state;
    struct sim *s = test_build_ok(
        "model: {type: lattice}\n"
        "materials: {m: {density: 1000, youngs_modulus: 1.0e9, "
        "poisson_ratio: 0.3333333333333333, failure_strain: 10}}\n"
        "lattice: {type: triangular, spacing: 0.001}\n"
        "body: {geometry: {box: {min: [0, 0], max: [0.02, 0.02]}}, material: m}\n"
        "groups: {left: {box: {min: [-1, -1], max: [0.0006, 1]}}}\n"
        "boundary_conditions: [{group: left, type: velocity, components: [x], value: 1.0}]\n"
        "run: {steps: 400, dt: 2.0e-6, dt_override: true}\n");
    struct spall_error err = {0};
    int rc = SPALL_OK;
    while (!sim_done(s) && !(rc = sim_step(s, &err)))
        ;
    print_message("%s\n", err.msg);
    assert_int_equal(rc, SPALL_ERR_UNSTABLE);
    assert_non_null(strstr(err.msg, "times the energy put in"));
    assert_non_null(strstr(err.msg, "fastest particle"));
    for (size_t i = 0; i < s->p->n_owned; i++)
        for (int d = 0; d < s->dim; d++)
            assert_true(isfinite(s->p->x[d][i]) && isfinite(s->p->v[d][i]));
    sim_destroy(&s);
}

/* SPH plate with XSPH, clamped at x < 0, its free part moving: the clamp
 * particles' XSPH velocity is not zero (their neighbours move), yet a
 * prescribed velocity is the particle's whole motion, so they stay at x0
 * bit for bit; the free particles do move by it (the drift differs from
 * dt v). */
static void test_drift_velocity_skips_prescribed(void **state)
{
    (void)state;
    struct sim *s = test_build_ok(
        "model: {type: sph, kernel: cubic_spline, h_factor: 1.5, plane: strain, "
        "viscosity: [0, 0], xsph: 0.5, time_integration: leapfrog}\n"
        "materials: {rubber: {density: 1000, youngs_modulus: 2.0e6, poisson_ratio: 0.3975}}\n"
        "lattice: {type: square, spacing: 0.002, origin: [0.001, 0.001], thickness: 1.0}\n"
        "body: {geometry: {box: {min: [-0.01, -0.01], max: [0.04, 0.01]}}, material: rubber}\n"
        "groups: {clamp: {box: {min: [-1, -1], max: [0, 1]}}, "
        "free: {box: {min: [0, -1], max: [1, 1]}}}\n"
        "boundary_conditions: [{group: clamp, type: fixed}]\n"
        "initial_velocity: [{group: free, value: [0, 0.5]}]\n"
        "run: {steps: 20}\n");
    const struct particles *p = s->p;
    const struct group *clamp = &s->groups[sim_find_group(s, "clamp")];
    assert_true(clamp->n > 0);
    struct spall_error err = {0};
    double xsph_move = 0.0; /* largest |x_n+1 - x_n - dt v_n+1/2| of a free particle */
    for (int k = 0; k < 5; k++) {
        const size_t n = p->n_owned;
        double *x1 = malloc(n * sizeof *x1), *vh = malloc(n * sizeof *vh);
        assert_non_null(x1);
        assert_non_null(vh);
        for (size_t i = 0; i < n; i++) { /* y of the drift by v_n+1/2 alone */
            vh[i] = p->v[1][i] + 0.5 * s->dt * p->f[1][i] / p->mass[i];
            x1[i] = p->x[1][i];
        }
        const double dt = s->dt;
        assert_int_equal(sim_step(s, &err), SPALL_OK);
        for (size_t i = 0; i < n; i++)
            if (p->x0[0][i] > 0.0)
                xsph_move = fmax(xsph_move, fabs(p->x[1][i] - x1[i] - dt * vh[i]));
        free(x1);
        free(vh);
    }
    for (size_t q = 0; q < clamp->n; q++) {
        size_t i = clamp->idx[q];
        for (int d = 0; d < s->dim; d++)
            assert_true(p->x[d][i] == p->x0[d][i]);
    }
    /* XSPH moves the free particles: well above round-off of x (~1e-18 m) */
    print_message("largest XSPH displacement of a free particle %g m\n", xsph_move);
    assert_true(xsph_move > 1e-12);
    sim_destroy(&s);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_energy_blowup_in_sim_step),
        cmocka_unit_test(test_drift_velocity_skips_prescribed),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
