/**
 * @file test_energy_bc_ramp.c
 * @brief Work of a prescribed velocity that changes in time
 *        (src/core/integrator.c, core/bc_work.h): an elastic strip pulled
 *        through a ramp keeps its energy account to second order in dt.
 *        Booking each half kick's constraint impulse at the new velocity,
 *        m (v_new - v_kick) v_new, adds 1/2 m (v_new - v_prev)^2 per half
 *        kick while the prescribed velocity changes: first order in dt
 *        (measured: a balance ratio of 2.0 between dt and dt/2).
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include "tests/test_support.h"

#include <math.h>
#include <stdio.h>

/* A 2D lattice strip, bottom fixed, top pulled at 2 m/s through time
 * function @p fn, at run.dt_factor @p factor; returns balance / work. */
static double strip_balance(const char *fn, double factor)
{
    char deck[1536];
    snprintf(deck, sizeof deck,
             "model: {type: lattice, law: linear}\n"
             "materials: {m: {density: 1190, youngs_modulus: 3.0e9,\n"
             "                poisson_ratio: 0.3333333333333333, failure_strain: 1.0}}\n"
             "lattice: {type: triangular, spacing: 1.0e-3}\n"
             "body: {geometry: {box: {min: [0, 0], max: [0.0105, 0.0105]}}, material: m}\n"
             "groups:\n"
             "  bottom: {box: {min: [-1, -1], max: [1, 0.0005]}}\n"
             "  top: {box: {min: [-1, 0.0099], max: [1, 1]}}\n"
             "boundary_conditions:\n"
             "  - {group: bottom, type: fixed}\n"
             "  - {group: top, type: velocity, components: [x, y], value: [0.5, 2.0],\n"
             "     function: %s}\n"
             "run: {end_time: 2.0e-5, dt_factor: %g}\n",
             fn, factor);
    struct sim *s = test_build_ok(deck);
    struct spall_error err = {0};
    while (!sim_done(s))
        assert_int_equal(sim_step(s, &err), SPALL_OK);
    sim_update_energy(s);
    const struct energy_account *a = &s->energy;
    print_message("%s, dt_factor %g: W = %.6e, KE = %.6e, strain = %.6e, balance = %.3e\n", fn,
                  factor, a->external, a->kinetic, a->strain, a->balance);
    assert_true(a->external > 0.0);
    const double rel = a->balance / a->external;
    sim_destroy(&s);
    return rel;
}

/* Halving dt divides the balance by ~4 (second order) for each way the
 * prescribed velocity changes in time; the old booking gave 2. */
static void check_second_order(const char *fn, double tol)
{
    const double b1 = strip_balance(fn, 0.5), b2 = strip_balance(fn, 0.25);
    print_message("%s: balance/W %.3e -> %.3e, ratio %.2f\n", fn, b1, b2, b1 / b2);
    assert_true(fabs(b1) < tol);
    assert_true(fabs(b1 / b2) > 3.5);
}

static void test_linear_ramp(void **state)
{
    (void)state;
    check_second_order("{type: linear_ramp, duration: 1.0e-5}", 2e-5);
}

static void test_quadratic_ramp(void **state)
{
    (void)state;
    check_second_order("{type: quadratic_ramp, duration: 1.0e-5}", 2e-5);
}

static void test_table(void **state)
{
    (void)state;
    check_second_order("{type: table, points: [[0, 0], [5.0e-6, 1.0], [1.2e-5, -0.5], "
                       "[2.0e-5, 0.25]]}",
                       2e-3); /* measured 9.7e-4: slope jumps, W small */
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_linear_ramp),
        cmocka_unit_test(test_quadratic_ramp),
        cmocka_unit_test(test_table),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
