/*
 * Tests of the general SPH penetration deck builder
 * (validation/pen_sph_setup.c): scale invariance in d, input checks, the
 * gelatin deck of validation/pen_sph.c as a special case (same particles),
 * and the shipped examples/pen_sph_sebs_* decks against the builder (same
 * particles, material and impactor as the validation case pen-sph-sebs),
 * and the grids of pen-sph-gelatin-convergence (levels tile the box).
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include "tests/test_support.h"

#include "core/particles.h"
#include "core/rigid.h"
#include "core/sim.h"
#include "io/deck.h"
#include "io/deck_build.h"
#include "models/sph/sph.h"
#include "spall/error.h"
#include "validation/lattice_cases.h"
#include "validation/pen_cases.h"
#include "validation/pen_sph_setup.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* The grid of pen-sph-sebs (validation/pen_sph_sebs.c, sebs_grid). */
static struct pen_sph_grid sebs_grid(void)
{
    struct pen_sph_grid g = {.dx1_d = 0.1, .width = 1.0, .depth = 1.5, .t_end = 1.6e-6,
                             .cavity_depth = 0.0};
    return g;
}

static struct sim *build_file(const char *path)
{
    struct spall_error e = {0};
    struct deck *d = NULL;
    int rc = deck_load_file(&d, path, &e);
    if (rc)
        fprintf(stderr, "%s\n", e.msg);
    assert_int_equal(rc, SPALL_OK);
    struct sim *s = NULL;
    struct run_output ro;
    rc = deck_build_sim(d, &s, &ro, &e);
    if (rc)
        fprintf(stderr, "%s\n", e.msg);
    assert_int_equal(rc, SPALL_OK);
    deck_destroy(&d);
    return s;
}

/* Same particles (count, positions, masses) to a relative 1e-9 of d. */
static void same_particles(const struct sim *a, const struct sim *b, double d)
{
    assert_int_equal(a->p->n, b->p->n);
    for (size_t i = 0; i < a->p->n; i++) {
        assert_true(fabs(a->p->x[0][i] - b->p->x[0][i]) < 1e-9 * d);
        assert_true(fabs(a->p->x[1][i] - b->p->x[1][i]) < 1e-9 * d);
        assert_true(fabs(a->p->mass[i] / b->p->mass[i] - 1.0) < 1e-8);
    }
}

static void same_impactor(const struct sim *a, const struct sim *b)
{
    const struct impactor *p = &a->rigid->im[0], *q = &b->rigid->im[0];
    assert_true(fabs(p->radius / q->radius - 1.0) < 1e-8);
    assert_true(fabs(p->mass / q->mass - 1.0) < 1e-8);
    assert_true(fabs(p->x[1] / q->x[1] - 1.0) < 1e-8);
    assert_true(fabs(p->v[1] / q->v[1] - 1.0) < 1e-12);
}

/* Every length scales with d: the five SEBS shots have the same particle
 * count, and positions scale exactly by the ratio of diameters. */
static void test_scale_invariance(void **state)
{
    (void)state;
    static const double ds[5] = {20e-6, 16e-6, 13e-6, 12e-6, 22e-6};
    struct spall_error e = {0};
    char buf[4096];
    struct pen_sph_target t = pen_sph_target_sebs(40e6);
    struct pen_sph_grid g = sebs_grid();
    struct pen_sph_shot s0 = {20e-6, 7800.0, 215.0};
    assert_int_equal(pen_sph_setup_deck(buf, sizeof buf, &t, &s0, &g, &e), SPALL_OK);
    struct sim *a = test_build_ok(buf);
    for (int k = 1; k < 5; k++) {
        struct pen_sph_shot s = {ds[k], 7800.0, 500.0};
        assert_int_equal(pen_sph_setup_deck(buf, sizeof buf, &t, &s, &g, &e), SPALL_OK);
        struct sim *b = test_build_ok(buf);
        assert_int_equal(a->p->n, b->p->n);
        const double f = ds[k] / 20e-6;
        for (size_t i = 0; i < a->p->n; i += 37)
            assert_true(fabs(a->p->x[1][i] * f - b->p->x[1][i]) < 1e-9 * ds[k]);
        assert_true(fabs(b->rigid->im[0].mass / a->rigid->im[0].mass - f * f * f) < 1e-8);
        sim_destroy(&b);
    }
    sim_destroy(&a);
}

static void test_bad_input(void **state)
{
    (void)state;
    struct spall_error e = {0};
    char buf[4096];
    struct pen_sph_target t = pen_sph_target_sebs(40e6);
    struct pen_sph_grid g = sebs_grid();
    struct pen_sph_shot s = {-20e-6, 7800.0, 215.0};
    assert_int_equal(pen_sph_setup_deck(buf, sizeof buf, &t, &s, &g, &e), SPALL_ERR_INPUT);
    assert_non_null(strstr(e.msg, "diameter"));
    s.d = 20e-6;
    t.nu = 0.5;
    assert_int_equal(pen_sph_setup_deck(buf, sizeof buf, &t, &s, &g, &e), SPALL_ERR_INPUT);
    assert_non_null(strstr(e.msg, "Poisson"));
    t.nu = 0.495;
    g.dx1_d = 0.0;
    assert_int_equal(pen_sph_setup_deck(buf, sizeof buf, &t, &s, &g, &e), SPALL_ERR_INPUT);
    g.dx1_d = 0.1;
    assert_int_equal(pen_sph_setup_deck(buf, 200, &t, &s, &g, &e), SPALL_ERR_INPUT);
    assert_non_null(strstr(e.msg, "buffer"));
}

/* At d = 7.38 um, dx1 = 0.75 um, width and depth 1 the builder lays out the
 * gelatin deck of validation/pen_sph.c (pen_sph_deck, a wrapper of the
 * builder since the two were merged): same particles and sphere. */
static void test_gelatin_special_case(void **state)
{
    (void)state;
    struct spall_error e = {0};
    char buf[4096], ref[4096];
    pen_sph_deck(ref, sizeof ref, 1290.0, 20e6, 0.75e-6, 1.0, 260e-9);
    struct pen_sph_target t = pen_sph_target_gelatin(20e6);
    struct pen_sph_shot s = {7.38e-6, 1850.0, 1290.0};
    struct pen_sph_grid g = {.dx1_d = 0.75 / 7.38, .width = 1.0, .depth = 1.0,
                             .t_end = 260e-9, .cavity_depth = 15e-6, .k_first_contact = 1};
    assert_int_equal(pen_sph_setup_deck(buf, sizeof buf, &t, &s, &g, &e), SPALL_OK);
    struct sim *a = test_build_ok(ref), *b = test_build_ok(buf);
    same_particles(a, b, 7.38e-6);
    same_impactor(a, b);
    sim_destroy(&a);
    sim_destroy(&b);
}

/* The shipped examples are the validation case's decks at E = 40 MPa. */
static void test_examples_match(void **state)
{
    (void)state;
    static const double shots[5][2] = {
        {20e-6, 215.0}, {16e-6, 440.0}, {13e-6, 630.0}, {12e-6, 735.0}, {22e-6, 300.0}};
    const char *src = getenv("SPALL_SOURCE_DIR");
    struct spall_error e = {0};
    char buf[4096], path[1024];
    struct pen_sph_target t = pen_sph_target_sebs(40e6);
    struct pen_sph_grid g = sebs_grid();
    for (int k = 0; k < 5; k++) {
        struct pen_sph_shot s = {shots[k][0], 7800.0, shots[k][1]};
        assert_int_equal(pen_sph_setup_deck(buf, sizeof buf, &t, &s, &g, &e), SPALL_OK);
        snprintf(path, sizeof path, "%s/examples/pen_sph_sebs_%.0fum_%.0fms/"
                 "pen_sph_sebs_%.0fum_%.0fms.yaml", src ? src : "..", s.d * 1e6, s.v0,
                 s.d * 1e6, s.v0);
        struct sim *a = test_build_ok(buf), *b = build_file(path);
        same_particles(a, b, s.d);
        same_impactor(a, b);
        assert_true(fabs(a->end_time / b->end_time - 1.0) < 1e-12);
        sim_destroy(&a);
        sim_destroy(&b);
    }
}

/* The runner on a coarse grid for 30 ns: the sphere has entered, is still
 * moving, the history is filled and the tip depth grows with time. */
static void test_run_short(void **state)
{
    (void)state;
    struct spall_error e = {0};
    struct pen_sph_target t = pen_sph_target_sebs(40e6);
    struct pen_sph_shot s = {20e-6, 7800.0, 215.0};
    struct pen_sph_grid g = {.dx1_d = 0.34, .width = 1.0, .depth = 1.0, .t_end = 30e-9,
                             .cavity_depth = 0.0};
    struct pen_sph_outcome o;
    assert_int_equal(pen_sph_setup_run(NULL, &t, &s, &g, &o, &e), SPALL_OK);
    assert_false(o.at_rest);
    assert_true(o.nh > 2);
    assert_true(o.pmax > 1e-6 && o.pmax < 30e-9 * 215.0 + 1e-6);
    assert_true(o.P[o.nh - 1] > o.P[0]);
    assert_true(o.v_end > 0.0 && o.v_end < 215.0);
    pen_sph_outcome_free(&o);
    assert_null(o.t);
}

/* The rebound option: gelatin at 200 m/s on a coarse grid; with
 * t_rebound the runner goes on past P_max ([Meng2021] sec. 5: the spheres
 * rebound in the experiments), sees V turn upward after P_max and the tip
 * come back; without it the run stops at rest, as before. */
static void test_run_rebound(void **state)
{
    (void)state;
    struct spall_error e = {0};
    struct pen_sph_target t = pen_sph_target_gelatin(20e6);
    struct pen_sph_shot s = {7.38e-6, 1850.0, 200.0};
    struct pen_sph_grid g = {.dx1_d = 0.34, .width = 1.0, .depth = 1.0, .t_end = 400e-9,
                             .cavity_depth = 15e-6, .k_first_contact = 1};
    struct pen_sph_outcome a, b;
    assert_int_equal(pen_sph_setup_run(NULL, &t, &s, &g, &a, &e), SPALL_OK);
    assert_true(a.at_rest);
    assert_false(a.rebounded);
    g.t_rebound = 160e-9;
    assert_int_equal(pen_sph_setup_run(NULL, &t, &s, &g, &b, &e), SPALL_OK);
    assert_true(b.at_rest);
    assert_true(b.rebounded);
    /* same run up to rest: the same maximum */
    assert_true(fabs(b.pmax - a.pmax) < 1e-12);
    assert_true(b.t_rev >= b.t_pmax && b.t_rev <= b.t_pmax + 1e-9);
    assert_true(b.v_reb > 0.0 && b.t_reb >= b.t_rev);
    assert_true(b.recovery > 0.0 && fabs(b.recovery - (b.pmax - b.p_end)) < 1e-15);
    assert_true(b.t[b.nh - 1] >= 160e-9 - 1e-9); /* ran on to t_rebound */
    pen_sph_outcome_free(&a);
    pen_sph_outcome_free(&b);
}

/* The AV options reach the deck only when set: the default gelatin deck is
 * unchanged, and the deck with them builds. */
static void test_av_options_in_deck(void **state)
{
    (void)state;
    struct spall_error e = {0};
    char buf[4096];
    struct pen_sph_target t = pen_sph_target_gelatin(20e6);
    struct pen_sph_shot s = {7.38e-6, 1850.0, 1290.0};
    struct pen_sph_grid g = {.dx1_d = 0.1, .width = 1.0, .depth = 1.0, .t_end = 1e-9,
                             .cavity_depth = 15e-6, .k_first_contact = 1};
    assert_int_equal(pen_sph_setup_deck(buf, sizeof buf, &t, &s, &g, &e), SPALL_OK);
    assert_null(strstr(buf, "viscosity_length"));
    assert_null(strstr(buf, "viscosity_switch"));
    t.av_length = 6.5e-7;
    t.av_balsara = 1;
    assert_int_equal(pen_sph_setup_deck(buf, sizeof buf, &t, &s, &g, &e), SPALL_OK);
    assert_non_null(strstr(buf, "viscosity_length: 6.5e-07"));
    assert_non_null(strstr(buf, "viscosity_switch: balsara"));
    struct sim *a = test_build_ok(buf);
    sim_destroy(&a);
    t.av_length = -1.0;
    assert_int_equal(pen_sph_setup_deck(buf, sizeof buf, &t, &s, &g, &e), SPALL_ERR_INPUT);
}

/* Richardson: f = 2 + 3 h^1.7 at the study's spacings (ratios 1.5, 1.33)
 * gives p = 1.7 and f_inf = 2; a non-monotonic or diverging sequence and
 * unordered spacings are refused. */
static void test_richardson(void **state)
{
    (void)state;
    struct spall_error e = {0};
    const double h[3] = {0.75, 0.5, 0.375};
    double f[3], p = 0.0, fi = 0.0;
    for (int k = 0; k < 3; k++)
        f[k] = 2.0 + 3.0 * pow(h[k], 1.7);
    assert_int_equal(pen_richardson(h, f, &p, &fi, &e), SPALL_OK);
    assert_true(fabs(p - 1.7) < 1e-9);
    assert_true(fabs(fi - 2.0) < 1e-9);
    for (int k = 0; k < 3; k++) /* converging from below, order 1 */
        f[k] = 5.0 - 2.0 * h[k];
    assert_int_equal(pen_richardson(h, f, &p, &fi, &e), SPALL_OK);
    assert_true(fabs(p - 1.0) < 1e-9 && fabs(fi - 5.0) < 1e-9);
    const double osc[3] = {1.0, 2.0, 1.5}, grow[3] = {1.0, 1.1, 1.6};
    assert_int_equal(pen_richardson(h, osc, &p, &fi, &e), SPALL_ERR_INPUT);
    assert_non_null(strstr(e.msg, "monotonic"));
    assert_int_equal(pen_richardson(h, grow, &p, &fi, &e), SPALL_ERR_INPUT);
    assert_non_null(strstr(e.msg, "shrink"));
    const double hb[3] = {0.5, 0.75, 0.375};
    assert_int_equal(pen_richardson(hb, f, &p, &fi, &e), SPALL_ERR_INPUT);
}

/* The grids of pen-sph-gelatin-convergence (validation/pen_sph.c): d/10,
 * d/15, d/20, d/25 at full width and d/15 1.5x wider, converging form.
 * The four graded levels must tile the (r, z) box without gaps or
 * overlaps (sum of dx_i^2 = the box's area, the box's corner from the
 * particles), the 1.5x grid reach r = 216 um (144 um x 1.5), and the
 * sphere's contact surface sit dx1/2 out (contact_offset). */
static void test_convergence_grids(void **state)
{
    (void)state;
    static const double dx[5] = {0.75e-6, 0.5e-6, 0.375e-6, 0.3e-6, 0.5e-6};
    static const double width[5] = {1.0, 1.0, 1.0, 1.0, 1.5};
    struct pen_sph_target t = pen_sph_target_gelatin(20e6);
    t.av_length = 0.65e-6;
    const struct pen_sph_shot s = {7.38e-6, 1850.0, 1290.0};
    for (int k = 0; k < 5; k++) {
        struct pen_sph_grid g = {.dx1_d = dx[k] / 7.38e-6, .width = width[k], .depth = 1.0,
                                 .t_end = 300e-9, .cavity_depth = 15e-6,
                                 .k_first_contact = 1, .surface_contact = 1};
        static char deck[4096];
        struct spall_error e = {0};
        assert_int_equal(pen_sph_setup_deck(deck, sizeof deck, &t, &s, &g, &e), SPALL_OK);
        assert_non_null(strstr(deck, "viscosity_length: 6.5e-07"));
        struct sim *sim = NULL;
        assert_int_equal(vlat_build("conv", deck, &sim, &e), SPALL_OK);
        const struct model *m = sim->model;
        double area = 0.0, rmax = 0.0, zmax = 0.0;
        for (size_t i = 0; i < sim->p->n; i++) {
            const double dxi = sph_spacing(m, i);
            area += dxi * dxi;
            rmax = fmax(rmax, sim->p->x[0][i] + 0.5 * dxi);
            zmax = fmax(zmax, -sim->p->x[1][i] + 0.5 * dxi);
        }
        assert_true(fabs(area / (rmax * zmax) - 1.0) < 1e-9);
        assert_true(fabs(rmax - 144e-6 * width[k]) < 1e-3 * dx[k]);
        assert_true(fabs(sim->rigid->im[0].contact_offset - 0.5 * dx[k]) < 1e-9 * dx[k]);
        sim_destroy(&sim);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_scale_invariance),
        cmocka_unit_test(test_bad_input),
        cmocka_unit_test(test_gelatin_special_case),
        cmocka_unit_test(test_examples_match),
        cmocka_unit_test(test_run_short),
        cmocka_unit_test(test_run_rebound),
        cmocka_unit_test(test_av_options_in_deck),
        cmocka_unit_test(test_richardson),
        cmocka_unit_test(test_convergence_grids),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
