/**
 * @file test_physics_macro_thermal.c
 * @brief Macro-particle model (src/models/macroparticle/macro_forces.c):
 *  - the pairwise Langevin thermostat's random forces act in equal and
 *    opposite pairs, so a free block heated by them keeps its total
 *    momentum (zero) to round-off;
 *  - pair plasticity: in a block squeezed between a moving and a fixed
 *    plate the work booked for the plates equals kinetic + strain energy +
 *    the plastic work dissipated (each pair's slip counted once).
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include "tests/test_support.h"

#include <float.h>
#include <stdio.h>

#define MATERIAL                                                                                   \
    "materials:\n"                                                                                 \
    "  al: {density: 2700, atomic_mass_u: 26.98, cohesive_energy_ev: 3.39, exponents: [4, 9],\n"   \
    "       debye_temperature: 428, yield_strain: 0.002, hardening: 0.1}\n"                        \
    "lattice: {type: fcc, spacing: 1.0e-3}\n"                                                      \
    "body: {geometry: {box: {min: [0, 0, 0], max: [4.3e-3, 4.3e-3, 5.1e-3]}}, material: al}\n"

/* Free block, pairwise damping and a bath temperature: no external force, so
 * P stays 0; the round-off of the pair sums is ~eps sum m |v| per step. */
static void test_pair_noise_keeps_momentum(void **state)
{
    (void)state;
    struct sim *s = test_build_ok(
        "model: {type: macroparticle, damping: pairwise, mu: 2.0e-3, temperature: 1.0e12}\n" MATERIAL
        "run: {steps: 100, seed: 7}\n");
    struct spall_error err = {0};
    const int N = 100;
    for (int k = 0; k < N; k++)
        assert_int_equal(sim_step(s, &err), SPALL_OK);
    double P[3];
    const double scale = test_momentum_3d(s, P);
    print_message("%zu particles: P = (%.3e, %.3e, %.3e), sum m |v| = %.3e\n", s->p->n_owned, P[0],
                  P[1], P[2], scale);
    assert_true(scale > 0.0); /* the noise did move the particles */
    for (int d = 0; d < 3; d++)
        assert_true(fabs(P[d]) <= 10.0 * N * DBL_EPSILON * scale);
    sim_destroy(&s);
}

/* Squeeze at 40 m/s well past the yield strain (most of the work goes into
 * plastic slip); no damping, no noise: the account must balance to the
 * integrator's error, measured at 9e-4 of the work (tolerance 3e-3); a
 * plastic work booked twice would leave it off by ~0.8 of the work. */
static void test_plastic_squeeze_energy(void **state)
{
    (void)state;
    struct sim *s = test_build_ok(
        "model: {type: macroparticle}\n" MATERIAL
        "groups:\n"
        "  top: {box: {min: [-1, -1, 4.6e-3], max: [1, 1, 1]}}\n"
        "  bottom: {box: {min: [-1, -1, -1], max: [1, 1, 0.3e-3]}}\n"
        "boundary_conditions:\n"
        "  - {group: top, type: velocity, components: [z], value: -40.0}\n"
        "  - {group: bottom, type: fixed}\n"
        "run: {steps: 400}\n");
    struct spall_error err = {0};
    sim_update_energy(s);
    const double e0 = s->energy.kinetic + s->energy.strain;
    while (!sim_done(s))
        assert_int_equal(sim_step(s, &err), SPALL_OK);
    sim_update_energy(s);
    const struct energy_account *a = &s->energy;
    print_message("t = %.3e: W = %.6e, KE = %.6e, strain gained = %.6e, plastic = %.6e, balance = %.3e\n",
                  s->t, a->external, a->kinetic, a->strain - e0, a->model_dissipated, a->balance);
    assert_true(a->model_dissipated > 0.1 * a->external); /* it did yield */
    assert_true(fabs(a->balance) < 3.0e-3 * a->external);
    sim_destroy(&s);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_pair_noise_keeps_momentum),
        cmocka_unit_test(test_plastic_squeeze_energy),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
