/**
 * @file test_physics_breaking.c
 * @brief Breaking thresholds of a single bond, pulled slowly: the bond
 *        must hold at every stretch up to its critical value and break in
 *        the first step past it.
 *
 * Two particles of a chain, the left one fixed, the right one driven at a
 * constant velocity V: both are prescribed, so the bond's stretch is
 * s(t) = V t / r0 exactly, whatever the bond force.  The step in which the
 * bond breaks (history bonds_broken) brackets the threshold:
 * s(t_{n-1}) <= s_c < s(t_n), with a bracket V dt / r0 ~ s_c / 1000 wide.
 *
 *  - peridynamics (PMB, [SillingAskari2005]): the critical stretch given
 *    directly, and the one implied by the fracture energy: in 1D, G0 =
 *    A c s0^2 delta^3 / 6 with c = 2 E / (A delta^2), i.e. s0 = sqrt(3 G0 /
 *    (E delta)) — the energy of all bonds crossing a unit section equals G0
 *    ([SillingAskari2005] Eqs. 26-27 in one dimension).
 *  - lattice ([Wang2010] Eq. 26): a bond breaks when its strain passes the
 *    failure strain eps_max, or sigma_TS / E for the linear law given a
 *    tensile strength.
 * And a notched PD plate: the first bond breaks at the notch tip when the
 * plate's largest stretch passes s_c (the G_c-based initiation load is not
 * checked here).
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include "tests/test_support.h"

#include <stdio.h>
#include <stdlib.h>

/* Two-particle chain (spacing r0 = 1 mm): left fixed, right pulled at V =
 * 1 m/s with dt such that one step stretches the bond by ~s_c / 1000.  Returns
 * the stretch of the last intact step and of the breaking step. */
static void pull_until_broken(const char *model, const char *material, double s_c,
                              double *s_hold, double *s_break)
{
    const double r0 = 1.0e-3, V = 1.0;
    /* 999.5 steps to s_c: the threshold falls mid-step, half a step (5e-4
     * s_c) from either end of the bracket, far above round-off */
    const double dt = s_c * r0 / (999.5 * V);
    const int max_steps = 2000;
    char yaml[1536];
    snprintf(yaml, sizeof yaml,
             "model: %s\n"
             "materials: {m: {density: 1000, youngs_modulus: 1.0e9, %s}}\n"
             "lattice: {type: chain, spacing: 1.0e-3, thickness: 1.0e-6}\n"
             "body: {geometry: {box: {min: [-0.0005], max: [0.0015]}}, material: m}\n"
             "groups:\n"
             "  l: {box: {min: [-0.001], max: [0.0005]}}\n"
             "  r: {box: {min: [0.0005], max: [0.002]}}\n"
             "boundary_conditions:\n"
             "  - {group: l, type: fixed}\n"
             "  - {group: r, type: velocity, value: %g}\n"
             "run: {dt: %.17g, steps: %d}\n",
             model, material, V, dt, max_steps);
    struct sim *s = test_build_ok(yaml);
    assert_int_equal(s->p->n, 2);
    struct spall_error err = {0};
    double s_prev = 0.0, s_now = 0.0;
    int broke = 0;
    for (int n = 0; n < max_steps && !broke; n++) {
        s_prev = s_now;
        assert_int_equal(sim_step(s, &err), SPALL_OK);
        s_now = fabs(s->p->x[0][1] - s->p->x[0][0]) / r0 - 1.0;
        broke = vlat_history(s, "bonds_broken") > 0.0;
    }
    assert_true(broke);
    *s_hold = s_prev;
    *s_break = s_now;
    sim_destroy(&s);
}

static void check_bracket(const char *what, const char *model, const char *material,
                          double s_c)
{
    double hold, brk;
    pull_until_broken(model, material, s_c, &hold, &brk);
    print_message("%s: held at s = %.7g, broke at s = %.7g, s_c = %.7g\n", what, hold, brk, s_c);
    assert_true(hold < s_c);
    assert_true(brk > s_c);
    assert_true(brk - hold < 1.01e-3 * s_c); /* one step */
}

static void test_pd_critical_stretch(void **state)
{
    (void)state;
    check_bracket("PD, critical_stretch", "{type: peridynamics}", "critical_stretch: 0.01", 0.01);
}

static void test_pd_fracture_energy(void **state)
{
    (void)state;
    /* s0 = sqrt(3 G0 / (E delta)), delta = horizon_factor dx (default 3.015) */
    const double G0 = 100.0, E = 1.0e9, delta = 3.015e-3;
    check_bracket("PD, fracture_energy", "{type: peridynamics}", "fracture_energy: 100",
                  sqrt(3.0 * G0 / (E * delta)));
}

static void test_lattice_failure_strain(void **state)
{
    (void)state;
    check_bracket("lattice, failure_strain", "{type: lattice, law: linear}",
                  "failure_strain: 0.02", 0.02);
    /* linear law: the tensile strength is reached at eps = sigma_TS / E */
    check_bracket("lattice, tensile_strength", "{type: lattice, law: linear}",
                  "tensile_strength: 1.5e7", 1.5e7 / 1.0e9);
}

/* Largest stretch over the reference pairs (a, b) of the list (2D). */
static double max_stretch(const struct sim *s, const size_t *pa, const size_t *pb, size_t np,
                          size_t *where)
{
    const struct particles *p = s->p;
    double best = -INFINITY;
    for (size_t k = 0; k < np; k++) {
        const size_t a = pa[k], b = pb[k];
        double l0 = 0.0, l = 0.0;
        for (int d = 0; d < 2; d++) {
            const double d0 = p->x0[d][b] - p->x0[d][a], d1 = p->x[d][b] - p->x[d][a];
            l0 += d0 * d0;
            l += d1 * d1;
        }
        const double st = sqrt(l / l0) - 1.0;
        if (st > best) {
            best = st;
            *where = a;
        }
    }
    return best;
}

/* A notched PD plate (plane stress) pulled apart by its top and bottom rows:
 * the first bond breaks at the notch tip, in the first step in which the
 * largest bond stretch of the plate passes s_c.  The notch is a slot 5 dx
 * wide, so no bond crosses it; every pair closer than the family radius
 * (delta + dx/2, partial volumes) is a bond. */
static void test_pd_notch_tip(void **state)
{
    (void)state;
    const double dx = 1.0e-3, s_c = 0.005, tip[2] = {0.0155, 0.010};
    struct sim *s = test_build_ok(
        "model: {type: peridynamics}\n"
        "materials: {m: {density: 1000, youngs_modulus: 1.0e9, critical_stretch: 0.005}}\n"
        "lattice: {type: square, spacing: 1.0e-3, thickness: 1.0e-3}\n"
        "body: {geometry: {difference: [{box: {min: [0, 0], max: [0.0405, 0.0205]}},\n"
        "                               {box: {min: [-1, 0.0075], max: [0.0155, 0.0125]}}]},\n"
        "       material: m}\n"
        "groups:\n"
        "  top: {box: {min: [-1, 0.0185], max: [1, 1]}}\n"
        "  bottom: {box: {min: [-1, -1], max: [1, 0.0015]}}\n"
        "boundary_conditions:\n"
        "  - {group: top, type: velocity, components: [y], value: 0.5}\n"
        "  - {group: bottom, type: velocity, components: [y], value: -0.5}\n"
        "run: {steps: 2000}\n");
    const struct particles *p = s->p;
    const size_t n = p->n_owned;
    const double rf = (3.015 + 0.5) * dx; /* default horizon_factor */
    size_t np = 0, cap = 32 * n;
    size_t *pa = malloc(cap * sizeof *pa), *pb = malloc(cap * sizeof *pb);
    assert_non_null(pa);
    assert_non_null(pb);
    for (size_t a = 0; a < n; a++)
        for (size_t b = a + 1; b < n; b++) {
            const double ex = p->x0[0][b] - p->x0[0][a], ey = p->x0[1][b] - p->x0[1][a];
            if (ex * ex + ey * ey <= rf * rf) {
                assert_true(np < cap);
                pa[np] = a;
                pb[np++] = b;
            }
        }
    struct spall_error err = {0};
    double hold = 0.0, brk = 0.0;
    size_t at = 0;
    int broke = 0;
    while (!sim_done(s) && !broke) {
        assert_int_equal(sim_step(s, &err), SPALL_OK);
        const double st = max_stretch(s, pa, pb, np, &at);
        broke = vlat_history(s, "bonds_broken") > 0.0;
        if (broke)
            brk = st;
        else
            hold = st;
    }
    assert_true(broke);
    const double rx = p->x0[0][at] - tip[0], ry = p->x0[1][at] - tip[1];
    print_message("notched plate (%zu bonds): largest stretch %.6g intact, %.6g at the first "
                  "break (s_c = %g), %.2f dx from the notch tip\n",
                  np, hold, brk, s_c, sqrt(rx * rx + ry * ry) / dx);
    assert_true(hold < s_c);
    assert_true(brk > s_c);
    assert_true(brk - hold < 0.1 * s_c); /* the step resolves the threshold */
    assert_true(sqrt(rx * rx + ry * ry) < 3.0 * dx);
    free(pa);
    free(pb);
    sim_destroy(&s);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_pd_critical_stretch),
        cmocka_unit_test(test_pd_fracture_energy),
        cmocka_unit_test(test_lattice_failure_strain),
        cmocka_unit_test(test_pd_notch_tip),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
