/**
 * @file test_rigid_offset.c
 * @brief Impactor `contact_offset` (core/rigid.c): the contact surface is
 *        pushed out by the offset, so that particle surfaces (dx/2 ahead of
 *        their centres) rather than centres meet the body.  For a sphere of
 *        radius R with offset o the run must be the run of a sphere of radius
 *        R + o (same centre); the deck refuses a negative offset; the
 *        penetration deck builder writes o = dx1/2 only when asked
 *        (pen_sph_grid.surface_contact).
 */
#include "core/rigid.h"
#include "core/sim.h"
#include "io/deck.h"
#include "io/deck_build.h"
#include "spall/error.h"
#include "validation/pen_sph_setup.h"

#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "tests/test_support.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

/* A rigid disc at 200 m/s onto a plane-strain SPH block (as
 * test_rigid_kdt.c); returns the disc's final velocity and position. */
static void run(double radius, double offset, double *vy, double *y, size_t *contacts)
{
    char yaml[1024];
    snprintf(yaml, sizeof yaml,
             "model: {type: sph, kernel: wendland, h_factor: 1.3, viscosity: [0.5, 0.2],\n"
             "        plane: strain}\n"
             "materials: {a: {density: 1000, youngs_modulus: 1.0e7, poisson_ratio: 0.3}}\n"
             "lattice: {type: square, spacing: 1.0e-3, origin: [0.0005, 0.0005]}\n"
             "body: {geometry: {box: {min: [0, 0], max: [0.012, 0.008]}}, material: a}\n"
             "impactors:\n"
             "  - {name: ball, shape: sphere, position: [0.006, 0.0108], radius: %.17g,\n"
             "     mass: 2.0e-2, velocity: [0, -200], gravity: false, contact: penalty,\n"
             "     stiffness_dt: first_contact, contact_offset: %.17g}\n"
             "run: {end_time: 3.0e-5}\n",
             radius, offset);
    struct deck *d = NULL;
    struct sim *s = NULL;
    struct run_output ro;
    struct spall_error err = {0};
    if (deck_load_string(&d, "t", yaml, &err) || deck_build_sim(d, &s, &ro, &err))
        print_error("%s\n", err.msg);
    deck_destroy(&d);
    assert_non_null(s);
    size_t most = 0;
    while (!sim_done(s)) {
        assert_int_equal(sim_step(s, &err), 0);
        if (s->rigid->im[0].n_contact > most)
            most = s->rigid->im[0].n_contact;
    }
    *vy = s->rigid->im[0].v[1];
    *y = s->rigid->im[0].x[1];
    *contacts = most;
    sim_destroy(&s);
}

static void test_offset_is_larger_sphere(void **state)
{
    (void)state;
    double v1, y1, v2, y2, v3, y3;
    size_t c1, c2, c3;
    run(0.002, 0.0005, &v1, &y1, &c1); /* R + o */
    run(0.0025, 0.0, &v2, &y2, &c2);   /* the larger sphere */
    run(0.002, 0.0, &v3, &y3, &c3);    /* no offset: a different run */
    print_message("offset: vy %.9g y %.9g (%zu contacts); R+o: vy %.9g y %.9g (%zu); "
                  "R: vy %.9g y %.9g (%zu)\n",
                  v1, y1, c1, v2, y2, c2, v3, y3, c3);
    assert_true(c1 > 0 && c1 == c2);
    assert_true(fabs(v1 - v2) <= 1e-9 * 200.0);
    assert_true(fabs(y1 - y2) <= 1e-12);
    /* the offset acts: without it fewer particles touch (12 against 16)
     * and the disc is slowed less (measured: 0.064 m/s of 200 in 30 us) */
    assert_true(c3 < c1);
    assert_true(v3 - v1 < -0.02);
}

static void test_negative_offset_refused(void **state)
{
    (void)state;
    const char *yaml =
        "model: {type: sph}\n"
        "materials: {a: {density: 1000, youngs_modulus: 1.0e7, poisson_ratio: 0.3}}\n"
        "lattice: {type: square, spacing: 1.0e-3, origin: [0.0005, 0.0005]}\n"
        "body: {geometry: {box: {min: [0, 0], max: [0.004, 0.004]}}, material: a}\n"
        "impactors: [{name: b, shape: sphere, position: [0.002, 0.006], radius: 0.001,\n"
        "             mass: 1.0e-3, contact_offset: -1.0e-4}]\n"
        "run: {steps: 1}\n";
    test_deck_refused(yaml, "contact_offset");
}

static void test_builder_key(void **state)
{
    (void)state;
    static char deck[8192];
    struct pen_sph_target t = pen_sph_target_gelatin(20e6);
    struct pen_sph_shot sh = {7.38e-6, 1850.0, 1290.0};
    struct pen_sph_grid g = {.dx1_d = 0.75e-6 / 7.38e-6, .width = 1.0, .depth = 1.0,
                             .t_end = 1e-9, .k_first_contact = 1};
    struct spall_error err = {0};
    assert_int_equal(pen_sph_setup_deck(deck, sizeof deck, &t, &sh, &g, &err), 0);
    assert_null(strstr(deck, "contact_offset")); /* the cases' decks are unchanged */
    g.surface_contact = 1;
    assert_int_equal(pen_sph_setup_deck(deck, sizeof deck, &t, &sh, &g, &err), 0);
    assert_non_null(strstr(deck, "contact_offset: 3.75e-07")); /* dx1 / 2 */
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_offset_is_larger_sphere),
        cmocka_unit_test(test_negative_offset_refused),
        cmocka_unit_test(test_builder_key),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
