/*
 * Tests of the particle-particle contact (core/contact_particles.c, issue 3):
 * bonds never cross bodies; two lattice blocks colliding through the contact
 * conserve momentum and energy and bounce apart without interpenetrating;
 * the result is bitwise the same on 1 and 2 threads; unbonded particles of
 * one body touch too; deck refusals.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include "tests/test_support.h"

#include "core/bond_list.h"
#include "core/contact_particles.h"
#include "core/particles.h"
#include "core/sim.h"
#include "io/deck.h"
#include "io/deck_build.h"
#include "core/model.h"
#include "spall/error.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#ifdef _OPENMP
#include <omp.h>
#endif

static int build_fails(const char *yaml, const char *needle)
{
    struct deck *d = NULL;
    struct spall_error err = {0};
    struct sim *s = NULL;
    struct run_output ro;
    int rc = deck_load_string(&d, "bad.yaml", yaml, &err);
    if (!rc)
        rc = deck_build_sim(d, &s, &ro, &err);
    sim_destroy(&s);
    deck_destroy(&d);
    if (rc && !strstr(err.msg, needle))
        fprintf(stderr, "unexpected message: %s\n", err.msg);
    return rc != SPALL_OK && strstr(err.msg, needle) != NULL;
}

/* Block A (bottom) and block B (top) on one triangular lattice, B's lowest
 * row one row above A's top row (nearest cross pairs exactly r0 apart), B
 * moving down at 20 m/s.  r0 = 1 mm, E = 1 GPa: k = E r0 = 1e6 N/m. */
static void blocks_deck(char *buf, size_t len, double width, const char *contact)
{
    double row = 0.5 * sqrt(3.0) * 1e-3;
    snprintf(buf, len,
             "model: {type: lattice, law: linear}\n"
             "materials:\n"
             "  m: {density: 1000, youngs_modulus: 1.0e9, poisson_ratio: 0.3333333333333333,\n"
             "      failure_strain: 10}\n"
             "lattice: {type: triangular, spacing: 1.0e-3}\n"
             "geometry:\n"
             "  a: {box: {min: [-1e-5, -1e-5], max: [%.17g, %.17g]}}\n"
             "  b: {box: {min: [-1e-5, %.17g], max: [%.17g, %.17g]}}\n"
             "bodies: [{geometry: a, material: m}, {geometry: b, material: m}]\n"
             "%s"
             "groups: {b: b}\n"
             "initial_velocity: [{group: b, value: [0, -20]}]\n"
             "run: {end_time: 4.0e-5, dt_factor: 0.25}\n",
             width, 9.5 * row, 9.5 * row, width, 19.5 * row, contact);
}

static void test_no_bonds_across_bodies(void **state)
{
    (void)state;
    char deck[2048];
    blocks_deck(deck, sizeof deck, 0.01, "contact: {distance: 1.0e-3, stiffness: 1.0e6}\n");
    struct sim *s = test_build_ok(deck);
    const struct bond_list *bl = s->ops->bonds(s->model);
    assert_non_null(bl);
    size_t cross = 0;
    for (size_t i = 0; i < bl->n; i++)
        for (size_t k = bl->offset[i]; k < bl->offset[i + 1]; k++)
            cross += s->p->body[i] != s->p->body[bl->partner[k]];
    assert_int_equal(cross, 0);
    /* no force at t = 0: the cross pairs sit exactly at the contact distance */
    assert_true(particle_contact_energy(s) == 0.0);
    sim_destroy(&s);
}

static void run_blocks(double width, int threads, double **xout, size_t *nout, double *p0,
                       double *p1, double *e_rel, double *vb_end, double *gap_min)
{
#ifdef _OPENMP
    int saved = omp_get_max_threads();
    omp_set_num_threads(threads);
#else
    (void)threads;
#endif
    char deck[2048];
    blocks_deck(deck, sizeof deck, width, "contact: {distance: 1.0e-3, stiffness: 1.0e6}\n");
    struct sim *s = test_build_ok(deck);
    struct spall_error err = {0};
    const struct particles *p = s->p;
    int gb = sim_find_group(s, "b");
    assert_true(gb >= 0);
    double mom0 = 0.0;
    for (size_t i = 0; i < p->n; i++)
        mom0 += p->mass[i] * p->v[1][i];
    double e0 = s->energy.kinetic;
    double gmin = INFINITY;
    while (!sim_done(s)) {
        assert_int_equal(sim_step(s, &err), SPALL_OK);
        /* lowest particle of B above the highest of A (no interpenetration) */
        double ya = -INFINITY, yb = INFINITY;
        for (size_t i = 0; i < p->n; i++) {
            if (p->body[i] == 0)
                ya = fmax(ya, p->x[1][i]);
            else
                yb = fmin(yb, p->x[1][i]);
        }
        gmin = fmin(gmin, yb - ya);
    }
    sim_update_energy(s);
    double mom1 = 0.0, vb = 0.0;
    for (size_t i = 0; i < p->n; i++)
        mom1 += p->mass[i] * p->v[1][i];
    const struct group *g = &s->groups[gb];
    for (size_t q = 0; q < g->n; q++)
        vb += p->v[1][g->idx[q]] / (double)g->n;
    *p0 = mom0;
    *p1 = mom1;
    *e_rel = fabs(s->energy.balance) / e0;
    *vb_end = vb;
    *gap_min = gmin;
    if (xout) {
        *nout = p->n;
        *xout = malloc(2 * p->n * sizeof **xout);
        assert_non_null(*xout);
        memcpy(*xout, p->x[0], p->n * sizeof **xout);
        memcpy(*xout + p->n, p->x[1], p->n * sizeof **xout);
    }
    sim_destroy(&s);
#ifdef _OPENMP
    omp_set_num_threads(saved);
#endif
}

static void test_blocks_bounce(void **state)
{
    (void)state;
    double p0, p1, erel, vb, gmin;
    run_blocks(0.01, 1, NULL, NULL, &p0, &p1, &erel, &vb, &gmin);
    /* pair forces are equal and opposite: momentum to round-off */
    assert_true(fabs(p1 - p0) <= 1e-9 * fabs(p0));
    /* Verlet with a conservative contact: the balance error is the
     * integrator's O(dt^2) (measured 1.5e-3 at dt_factor 0.5, 3.8e-4 at 0.25) */
    assert_true(erel < 1e-3);
    /* equal blocks, equal impedance: B hands its momentum to A and stops
     * (1D: B at rest after 2 h_B / c = 16 us); never passes through A */
    assert_true(fabs(vb) < 0.2 * 20.0);
    assert_true(gmin > 0.5e-3);
}

static void test_threads_bitwise(void **state)
{
    (void)state;
    /* wide enough (> SPALL_OMP_MIN_PARTICLES) for the contact loop to fork */
    double *x1 = NULL, *x2 = NULL, p0, p1, erel, vb, gmin;
    size_t n1 = 0, n2 = 0;
    run_blocks(0.26, 1, &x1, &n1, &p0, &p1, &erel, &vb, &gmin);
    run_blocks(0.26, 2, &x2, &n2, &p0, &p1, &erel, &vb, &gmin);
    assert_true(n1 > 4096);
    assert_int_equal(n1, n2);
    assert_memory_equal(x1, x2, 2 * n1 * sizeof *x1);
    free(x1);
    free(x2);
}

/* One body made of two blocks two rows apart (1.73 r0: never bonded): the
 * same-body unbonded pair rule must stop them like two bodies. */
static void test_same_body_unbonded(void **state)
{
    (void)state;
    double row = 0.5 * sqrt(3.0) * 1e-3;
    char deck[2048];
    snprintf(deck, sizeof deck,
             "model: {type: lattice, law: linear}\n"
             "materials:\n"
             "  m: {density: 1000, youngs_modulus: 1.0e9, poisson_ratio: 0.3333333333333333,\n"
             "      failure_strain: 10}\n"
             "lattice: {type: triangular, spacing: 1.0e-3}\n"
             "geometry:\n"
             "  a: {box: {min: [-1e-5, -1e-5], max: [0.01, %.17g]}}\n"
             "  b: {box: {min: [-1e-5, %.17g], max: [0.01, %.17g]}}\n"
             "body: {geometry: {union: [a, b]}, material: m}\n"
             "contact: {distance: 1.0e-3, stiffness: 1.0e6}\n"
             "groups: {b: b}\n"
             "initial_velocity: [{group: b, value: [0, -50]}]\n"
             "run: {end_time: 6.0e-5, dt_factor: 0.25}\n",
             9.5 * row, 10.5 * row, 20.5 * row);
    struct sim *s = test_build_ok(deck);
    struct spall_error err = {0};
    const struct particles *p = s->p;
    double gmin = INFINITY;
    size_t touched = 0;
    while (!sim_done(s)) {
        assert_int_equal(sim_step(s, &err), SPALL_OK);
        touched += particle_contact_pairs(s) > 0;
        double ya = -INFINITY, yb = INFINITY;
        for (size_t i = 0; i < p->n; i++) {
            if (p->x0[1][i] < 10.0 * row)
                ya = fmax(ya, p->x[1][i]);
            else
                yb = fmin(yb, p->x[1][i]);
        }
        gmin = fmin(gmin, yb - ya);
    }
    assert_true(touched > 0);
    assert_true(gmin > 0.5e-3);
    sim_destroy(&s);
}

static void test_deck_refusals(void **state)
{
    (void)state;
    char deck[2048];
    blocks_deck(deck, sizeof deck, 0.01, "contact: {distance: -1.0e-3, stiffness: 1.0e6}\n");
    assert_true(build_fails(deck, "distance"));
    blocks_deck(deck, sizeof deck, 0.01, "contact: {distance: 1.0e-3}\n");
    assert_true(build_fails(deck, "stiffness"));
    blocks_deck(deck, sizeof deck, 0.01,
                "contact: {distance: 1.0e-3, stiffness: 1.0e6, exponent: 3}\n");
    assert_true(build_fails(deck, "exponent"));
    blocks_deck(deck, sizeof deck, 0.01,
                "contact: {distance: 1.0e-3, stiffness: 1.0e6, friction: 0.3}\n");
    assert_true(build_fails(deck, "friction"));
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_no_bonds_across_bodies),
        cmocka_unit_test(test_blocks_bounce),
        cmocka_unit_test(test_threads_bitwise),
        cmocka_unit_test(test_same_body_unbonded),
        cmocka_unit_test(test_deck_refusals),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
