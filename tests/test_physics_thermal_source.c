/**
 * @file test_physics_thermal_source.c
 * @brief Heating and melting of the thermal lattice
 *        (src/models/lattice/lattice_thermal.c) against exact statements:
 *  - a body with a uniform volumetric power density P and no thermal
 *    boundary stays uniform (no conduction) and heats as
 *    T(t) = T0 + P t / (rho C): the energy put in, P V t, is the heat
 *    m C (T - T0) it holds;
 *  - melting: a bond is removed once either of its particles is past the
 *    melting temperature (docs/decks.md, melting_temperature), so the bond
 *    from a face held above T_m to its cold neighbour is gone from the start
 *    and no heat crosses it, while the bonds between cold particles stay.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include "core/bond_list.h"
#include "core/fields.h"
#include "models/lattice/lattice.h"
#include "tests/test_support.h"

#include <float.h>
#include <stdio.h>
#include <stdlib.h>

/* Temperatures of all owned particles (malloc'd). */
static double *temperatures(const struct sim *s)
{
    const struct field_desc *f = field_registry_find(s->fields, "temperature");
    assert_non_null(f);
    double *T = malloc(s->p->n_owned * sizeof *T);
    assert_non_null(T);
    field_gather_f64(f, s->p->n_owned, T);
    return T;
}

/* Uniform heating: forward Euler integrates a constant heating rate exactly,
 * so every particle's T is T0 + P t / (rho C) to round-off (N additions of
 * a rate ~ 1 K: ~N eps T).  Conduction is on (k > 0) but sees no
 * temperature difference.  A heat capacity or a source off by 5-10 % moves T
 * by 5-10 % of the rise. */
static void test_uniform_heating(void **state)
{
    (void)state;
    const double rho = 2000.0, C = 800.0, P = 4.0e8, T0 = 300.0, dt = 1.0e-4;
    const int N = 200;
    char yaml[1536];
    snprintf(yaml, sizeof yaml,
             "model: {type: lattice, law: linear, thermal: {}}\n"
             "materials:\n"
             "  m: {density: %g, youngs_modulus: 100, failure_strain: 0.5,\n"
             "      specific_heat: %g, conductivity: 50, initial_temperature: %g,\n"
             "      power_density: %g}\n"
             "lattice: {type: chain, spacing: 1.0e-3}\n"
             "body: {geometry: {box: {min: [-0.0005], max: [0.0105]}}, material: m}\n"
             "run: {dt: %g, steps: %d}\n",
             rho, C, T0, P, dt, N);
    struct sim *s = test_build_ok(yaml);
    struct spall_error err = {0};
    for (int k = 0; k < N; k++)
        assert_int_equal(sim_step(s, &err), SPALL_OK);
    const double t = s->t, T_exact = T0 + P * t / (rho * C); /* a 5 K rise */
    double *T = temperatures(s);
    print_message("t = %g s: T = %.12f K, T0 + P t / (rho C) = %.12f K\n", t, T[0], T_exact);
    for (size_t i = 0; i < s->p->n_owned; i++) {
        /* mass = rho V: the heat held equals the power put in */
        assert_true(fabs(s->p->mass[i] - rho * s->p->volume[i]) <= 1e-12 * s->p->mass[i]);
        assert_true(fabs(T[i] - T_exact) <= N * DBL_EPSILON * T_exact);
    }
    free(T);
    sim_destroy(&s);
}

/* Face (first particle) held at T1 > T_m, the rest at T0 < T_m.  Each bond
 * must be broken exactly when one of its ends is past T_m: from the
 * set-up on (the rest lengths and melting are evaluated before the first
 * step) and after the run.  With the face's bond gone no heat reaches the
 * rest of the chain, which stays at T0 exactly. */
static void test_melting_either_end(void **state)
{
    (void)state;
    const double T0 = 300.0, T1 = 900.0, Tm = 600.0;
    char yaml[1536];
    snprintf(yaml, sizeof yaml,
             "model: {type: lattice, law: linear,\n"
             "        thermal: {boundary: [{group: face, temperature: %g}]}}\n"
             "materials:\n"
             "  m: {density: 1000, youngs_modulus: 100, failure_strain: 0.5,\n"
             "      specific_heat: 1000, conductivity: 100, initial_temperature: %g,\n"
             "      melting_temperature: %g}\n"
             "lattice: {type: chain, spacing: 1.0e-3}\n"
             "body: {geometry: {box: {min: [-0.0005], max: [0.0105]}}, material: m}\n"
             "groups: {face: {box: {min: [-0.001], max: [0.0005]}}}\n"
             "run: {dt: 2.5e-3, steps: 40}\n",
             T1, T0, Tm);
    struct sim *s = test_build_ok(yaml);
    struct bond_list *bl = lattice_bond_list(s->model);
    assert_non_null(bl);
    struct spall_error err = {0};
    for (int pass = 0; pass < 2; pass++) {
        if (pass == 1)
            for (int k = 0; k < 40; k++) /* alpha t / dx^2 = 10: heat would spread */
                assert_int_equal(sim_step(s, &err), SPALL_OK);
        double *T = temperatures(s);
        size_t hot = 0, melted = 0;
        for (size_t i = 0; i < bl->n; i++)
            for (size_t q = bl->offset[i]; q < bl->offset[i + 1]; q++) {
                const size_t j = (size_t)bl->partner[q];
                const int molten = T[i] > Tm || T[j] > Tm;
                const int broken = (bl->state[q] & BOND_BROKEN) != 0;
                hot += (size_t)molten;
                melted += (size_t)broken;
                if (molten != broken)
                    print_error("bond %zu-%zu: T = %g, %g K, broken %d\n", i, j, T[i], T[j], broken);
                assert_int_equal(molten, broken);
            }
        print_message("pass %d: %zu half-bonds with a molten end, %zu broken\n", pass, hot, melted);
        assert_true(hot > 0);
        /* only the held face is molten; the cut-off chain has not warmed */
        for (size_t i = 0; i < s->p->n_owned; i++)
            if (T[i] < Tm)
                assert_true(T[i] == T0);
        free(T);
    }
    sim_destroy(&s);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_uniform_heating),
        cmocka_unit_test(test_melting_either_end),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
