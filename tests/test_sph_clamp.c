/**
 * @file test_sph_clamp.c
 * @brief The mirrored SPH clamp (sph_clamp.c): (1) a velocity field that
 *        vanishes on the clamp plane and is linear near it gets its exact
 *        CSPM gradient next to the plane (the fixed clamp loses it there);
 *        (2) with no artificial viscosity the clamp does no work: kinetic +
 *        internal energy of a vibrating cantilever stays constant;
 *        (3) decks the clamp cannot serve are refused.
 */
#include "core/particles.h"
#include "core/sim.h"
#include "io/deck.h"
#include "io/deck_build.h"
#include "core/model.h"
#include "models/sph/sph.h"
#include "spall/error.h"

#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include <math.h>
#include <stdio.h>
#include <string.h>

static int build(const char *yaml, struct sim **s, struct spall_error *err)
{
    struct deck *d = NULL;
    struct run_output ro;
    *s = NULL;
    int rc = deck_load_string(&d, "t", yaml, err);
    if (!rc)
        rc = deck_build_sim(d, s, &ro, err);
    deck_destroy(&d);
    return rc;
}

/* A rubber cantilever 30 x 6 mm, dx = 1 mm, clamp of 8 columns behind x = 0. */
static void deck_of(char *buf, size_t len, const char *type, const char *clamp,
                    const char *extra)
{
    snprintf(buf, len,
             "model: {type: %s, kernel: cubic_spline, h_factor: 1.5, plane: strain,\n"
             "        time_integration: leapfrog, cspm: true, viscosity: [0, 0]%s%s}\n"
             "materials: {r: {density: 1000, youngs_modulus: 2.0e6, poisson_ratio: 0.3975}}\n"
             "lattice: {type: square, spacing: 1.0e-3, origin: [0.0005, 0.0005], "
             "thickness: 1.0}\n"
             "body: {geometry: {box: {min: [-0.008, -0.003], max: [0.03, 0.003]}}, "
             "material: r}\n"
             "groups: {clamp: {box: {min: [-1, -1], max: [0, 1]}}}\n"
             "boundary_conditions: [{group: clamp, type: fixed}]\n"
             "run: {steps: 1500}\n",
             type, clamp, extra);
}

static void deck(char *buf, size_t len, const char *clamp, const char *extra)
{
    deck_of(buf, len, "sph", clamp, extra);
}

static const char *const MIRROR = ",\n        clamp: {group: clamp, point: [0, 0], normal: [1, 0]}";

/* Largest |L - A| / |A| over the free particles in the clamp's reach that
 * are not within one support of a free surface (there CSPM is exact anyway). */
static double clamp_gradient_error(const char *clamp)
{
    char yaml[2048];
    deck(yaml, sizeof yaml, clamp, "");
    struct sim *s = NULL;
    struct spall_error err = {0};
    if (build(yaml, &s, &err))
        print_error("%s\n", err.msg);
    assert_non_null(s);
    struct particles *p = s->p;
    const double a[2] = {3.0, -2.0}; /* v = a x: zero on the plane x = 0 */
    for (size_t i = 0; i < p->n; i++)
        for (int d = 0; d < 2; d++)
            p->v[d][i] = p->x0[0][i] > 0.0 ? a[d] * p->x0[0][i] : 0.0;
    assert_int_equal(sim_initial_forces(s, &err), 0);
    double e = 0.0;
    for (size_t i = 0; i < p->n; i++) {
        double x = p->x0[0][i];
        if (x < 0.0 || x > 0.005)
            continue;
        double L[9];
        sph_velocity_gradient(s->model, i, L);
        for (int d = 0; d < 2; d++) {
            e = fmax(e, fabs(L[d * 3 + 0] - a[d]) / 3.0);
            e = fmax(e, fabs(L[d * 3 + 1]) / 3.0);
        }
    }
    sim_destroy(&s);
    return e;
}

static void test_clamp_gradient(void **state)
{
    (void)state;
    double em = clamp_gradient_error(MIRROR);
    double ef = clamp_gradient_error("");
    print_message("velocity gradient next to the clamp: mirrored %.3g, fixed %.3g\n", em, ef);
    assert_true(em < 1e-10);
    assert_true(ef > 0.05); /* why the mirrored clamp exists */
}

static void test_clamp_energy(void **state)
{
    (void)state;
    char yaml[2048];
    deck(yaml, sizeof yaml, MIRROR, "");
    struct sim *s = NULL;
    struct spall_error err = {0};
    if (build(yaml, &s, &err))
        print_error("%s\n", err.msg);
    assert_non_null(s);
    struct particles *p = s->p;
    for (size_t i = 0; i < p->n; i++) {
        double x = p->x0[0][i] / 0.03;
        p->v[1][i] = x > 0.0 ? 0.1 * x * x : 0.0;
    }
    assert_int_equal(sim_initial_forces(s, &err), 0);
    const double e0 = s->energy.kinetic;
    double worst = 0.0, kmin = e0;
    while (!sim_done(s)) {
        int rc = sim_step(s, &err);
        if (rc)
            print_error("%s\n", err.msg);
        assert_int_equal(rc, 0);
        sim_update_energy(s);
        worst = fmax(worst, fabs(s->energy.balance) / e0);
        kmin = fmin(kmin, s->energy.kinetic);
    }
    print_message("clamp energy: max |balance| / E0 = %.3g over %ld steps, min KE / E0 = %.3f\n",
                  worst, s->step, kmin / e0);
    assert_true(kmin < 0.5 * e0); /* it did vibrate: energy went into strain */
    assert_true(worst < 1e-3);
    sim_destroy(&s);
}

static void test_clamp_refused(void **state)
{
    (void)state;
    static const char *const bad[][3] = {
        {"sph", ",\n        clamp: {group: nope, point: [0, 0], normal: [1, 0]}", "no group"},
        {"sph", ",\n        clamp: {group: clamp, point: [0.0003, 0], normal: [1, 0]}",
         "mirror image"},
        {"sph", ",\n        clamp: {group: clamp, point: [0, 0], normal: [0, 0]}",
         "normal is zero"},
        {"tlsph", ",\n        clamp: {group: clamp, point: [0, 0], normal: [1, 0]}",
         "plain fixed group"}, /* TLSPH: pointed at the fixed-group clamp */
    };
    for (size_t k = 0; k < sizeof bad / sizeof bad[0]; k++) {
        char yaml[2048];
        deck_of(yaml, sizeof yaml, bad[k][0], bad[k][1], "");
        struct sim *s = NULL;
        struct spall_error err = {0};
        int rc = build(yaml, &s, &err);
        assert_int_not_equal(rc, 0);
        if (!strstr(err.msg, bad[k][2]))
            print_error("expected '%s' in: %s\n", bad[k][2], err.msg);
        assert_non_null(strstr(err.msg, bad[k][2]));
        sim_destroy(&s);
    }
    /* a clamp group without a fixed boundary condition */
    char yaml[2048];
    deck(yaml, sizeof yaml, MIRROR, "");
    char *bc = strstr(yaml, "boundary_conditions");
    assert_non_null(bc);
    *bc = '\0';
    strcat(yaml, "run: {steps: 1}\n");
    struct sim *s = NULL;
    struct spall_error err = {0};
    assert_int_not_equal(build(yaml, &s, &err), 0);
    assert_non_null(strstr(err.msg, "fixed boundary condition"));
    sim_destroy(&s);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_clamp_gradient),
        cmocka_unit_test(test_clamp_energy),
        cmocka_unit_test(test_clamp_refused),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
