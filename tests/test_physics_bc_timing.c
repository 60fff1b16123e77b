/**
 * @file test_physics_bc_timing.c
 * @brief Timing of prescribed velocities in the velocity-Verlet step
 *        (src/core/integrator.c): the first half kick must impose the
 *        boundary velocity of the half step, v(t + dt/2), the drift then
 *        moves the particle by dt v(t + dt/2) (midpoint rule), and the
 *        second half kick imposes v(t + dt).
 *
 * Exact solution: a group driven by the velocity ramp v(t) = a t (a linear
 * ramp whose duration lies beyond the run) moves by u(t) = a t^2 / 2.  The
 * midpoint rule integrates a linear v exactly, so u after N steps equals
 * a t^2 / 2 to round-off for any dt; imposing v(t) instead of v(t + dt/2)
 * in the first kick loses a t dt / 2 (a relative error 1/N).  The chain's
 * free particles are pulled along by their springs, which does not touch the
 * driven particle's prescribed motion.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include "tests/test_assert.h"

#include "tests/test_support.h"

#include <stdio.h>

/* Lattice chain of 11 particles, the first one driven by v = V t / T_ramp
 * (x component) for T_ramp well beyond the run; fixed dt, @p steps steps. */
static struct sim *build_chain(double V, double t_ramp, double dt, int steps)
{
    char yaml[1024];
    snprintf(yaml, sizeof yaml,
             "model: {type: lattice, law: linear}\n"
             "materials: {m: {density: 1000, youngs_modulus: 1.0e9, failure_strain: 0.5}}\n"
             "lattice: {type: chain, spacing: 1.0e-3}\n"
             "body: {geometry: {box: {min: [-0.0005], max: [0.0105]}}, material: m}\n"
             "groups: {end: {box: {min: [-0.001], max: [0.0005]}}}\n"
             "boundary_conditions:\n"
             "  - {group: end, type: velocity, value: %.17g,\n"
             "     function: {type: linear_ramp, duration: %.17g}}\n"
             "run: {dt: %.17g, steps: %d}\n",
             V, t_ramp, dt, steps);
    return test_build_ok(yaml);
}

/* u = a t^2 / 2 after N steps, and v(t) = a t, for two step counts (the
 * error of the late-kick bug, a t dt / 2, differs by a factor 2 between
 * them; the right timing is exact for both). */
static void test_velocity_ramp_displacement(void **state)
{
    (void)state;
    const double V = 10.0, t_ramp = 1.0e-4; /* a = 1e5 m/s^2 */
    const double a = V / t_ramp;
    const int counts[2] = {40, 80};
    for (int k = 0; k < 2; k++) {
        const int N = counts[k];
        /* dt well below the chain's stable step (dx / c = 1e-6 s) */
        const double dt = 1.0e-8 * 40.0 / N;
        struct sim *s = build_chain(V, t_ramp, dt, N);
        const int g = sim_find_group(s, "end");
        assert_true(g >= 0);
        assert_int_equal(s->groups[g].n, 1);
        const size_t i = s->groups[g].idx[0];
        const double x0 = s->p->x[0][i];
        struct spall_error err = {0};
        for (int n = 0; n < N; n++)
            assert_int_equal(sim_step(s, &err), SPALL_OK);
        const double t = s->t;
        assert_near(t, N * dt, 1e-12 * t);
        const double u = s->p->x[0][i] - x0, u_exact = 0.5 * a * t * t;
        print_message("N = %d: u = %.15e, a t^2/2 = %.15e, rel. error %.2e "
                      "(late kick would give %.2e)\n",
                      N, u, u_exact, (u - u_exact) / u_exact, -1.0 / N);
        /* exact to round-off (the driven particle starts at x = 0, so the
         * N drifts add ~N eps u; measured ~1e-15 relative) */
        assert_near(u, u_exact, 1e-12 * u_exact);
        /* end of step: v(t) = a t imposed by the second kick */
        assert_near(s->p->v[0][i], a * t, 1e-12 * a * t);
        sim_destroy(&s);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_velocity_ramp_displacement),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
