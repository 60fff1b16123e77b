/*
 * Tests of the rigid impactors (core/rigid.c, issue 3): momentum
 * conservation of a sphere bouncing on an elastic lattice block (both contact
 * laws), free fall under gravity, Coulomb friction of a block sliding on a
 * wall (deceleration mu g), the no-slip law keeping contact particles on the
 * surface, the energy balance of a penalty impact, the signed distance of
 * each shape, and deck refusals.
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
#include "spall/error.h"

#include <math.h>
#include <stdio.h>
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

static void run_steps(struct sim *s, long n)
{
    struct spall_error err = {0};
    for (long k = 0; k < n; k++) {
        int rc = sim_step(s, &err);
        if (rc)
            fprintf(stderr, "%s\n", err.msg);
        assert_int_equal(rc, SPALL_OK);
    }
}

static void momentum(const struct sim *s, double P[3])
{
    P[0] = P[1] = P[2] = 0.0;
    for (size_t i = 0; i < s->p->n_owned; i++)
        for (int d = 0; d < s->dim; d++)
            P[d] += s->p->mass[i] * s->p->v[d][i];
    for (size_t k = 0; s->rigid && k < s->rigid->n; k++)
        for (int d = 0; d < s->dim; d++)
            P[d] += s->rigid->im[k].mass * s->rigid->im[k].v[d];
}

static const char *bounce_deck(const char *contact)
{
    static char buf[1024];
    snprintf(buf, sizeof buf,
             "model: {type: lattice}\n"
             "materials:\n"
             "  m: {density: 1000, youngs_modulus: 1.0e9, poisson_ratio: 0.3333333333333333,\n"
             "      failure_strain: 1.0}\n"
             "lattice: {type: triangular, spacing: 1.0e-3}\n"
             "body: {geometry: {box: {min: [0, 0], max: [0.02, 0.008]}}, material: m}\n"
             "impactors:\n"
             "  - {name: ball, shape: sphere, position: [0.0101, 0.0129], radius: 0.005,\n"
             "     mass: 0.005, velocity: [0.3, -5.0], contact: %s}\n"
             "run: {steps: 400}\n",
             contact);
    return buf;
}

static void check_bounce(const char *contact)
{
    struct sim *s = test_build_ok(bounce_deck(contact));
    double P0[3], P1[3];
    momentum(s, P0);
    double contacts = 0;
    for (int k = 0; k < 400; k++) {
        run_steps(s, 1);
        contacts += (double)s->rigid->im[0].n_contact;
    }
    assert_true(contacts > 0); /* it did hit the block */
    momentum(s, P1);
    double scale = 0.005 * 5.0;
    for (int d = 0; d < 2; d++)
        assert_true(fabs(P1[d] - P0[d]) < 1e-12 * scale);
    /* the ball slowed down: momentum went into the block */
    assert_true(s->rigid->im[0].v[1] > -4.99);
    sim_destroy(&s);
}

static void test_momentum_penalty(void **state)
{
    (void)state;
    check_bounce("penalty");
}

static void test_momentum_no_slip(void **state)
{
    (void)state;
    check_bounce("no_slip");
}

static void test_energy_penalty(void **state)
{
    (void)state;
    struct sim *s = test_build_ok(bounce_deck("penalty"));
    double e0 = 0.5 * 0.005 * (0.3 * 0.3 + 25.0);
    double worst = 0.0;
    for (int k = 0; k < 400; k++) {
        run_steps(s, 1);
        sim_update_energy(s);
        if (fabs(s->energy.balance) > worst)
            worst = fabs(s->energy.balance);
    }
    assert_true(worst < 1e-3 * e0);
    sim_destroy(&s);
}

static void test_free_fall(void **state)
{
    (void)state;
    struct sim *s = test_build_ok("model: {type: lattice}\n"
                          "materials:\n"
                          "  m: {density: 1000, youngs_modulus: 1.0e9,\n"
                          "      poisson_ratio: 0.3333333333333333, failure_strain: 1.0}\n"
                          "lattice: {type: triangular, spacing: 1.0e-3}\n"
                          "body: {geometry: {box: {min: [0, 0], max: [0.004, 0.004]}}, material: m}\n"
                          "gravity: [0, -9.8]\n"
                          "impactors:\n"
                          "  - {name: w, shape: cylinder, position: [1.0, 2.0], radius: 0.01,\n"
                          "     mass: 3.0, velocity: [0.5, 1.0]}\n"
                          "run: {steps: 1000}\n");
    run_steps(s, 1000);
    const struct impactor *im = &s->rigid->im[0];
    double t = s->t;
    assert_true(fabs(im->x[0] - (1.0 + 0.5 * t)) < 1e-12);
    assert_true(fabs(im->x[1] - (2.0 + 1.0 * t - 0.5 * 9.8 * t * t)) < 1e-12);
    assert_true(fabs(im->v[1] - (1.0 - 9.8 * t)) < 1e-12);
    /* absorbed energy of a free flight is zero: KE change = gravity work */
    assert_true(fabs(rigid_absorbed(im)) < 1e-12 * 3.0);
    sim_destroy(&s);
}

static void test_friction_deceleration(void **state)
{
    (void)state;
    /* a soft block slides on a fixed wall; mean deceleration must be mu g */
    const double mu = 0.3, g = 9.8, v0 = 1.0;
    struct sim *s = test_build_ok("model: {type: lattice}\n"
                          "materials:\n"
                          "  m: {density: 1000, youngs_modulus: 1.0e7,\n"
                          "      poisson_ratio: 0.3333333333333333, failure_strain: 1.0}\n"
                          "lattice: {type: triangular, spacing: 1.0e-3}\n"
                          "body: {geometry: {box: {min: [0, 0], max: [0.008, 0.004]}}, material: m}\n"
                          "gravity: [0, -9.8]\n"
                          "initial_velocity: [{group: all, value: [1.0, 0]}]\n"
                          "impactors:\n"
                          "  - {name: floor, shape: wall, position: [0, 0], normal: [0, 1],\n"
                          "     contact: penalty, friction: 0.3}\n"
                          "run: {end_time: 0.02}\n");
    const long n = s->n_steps;
    run_steps(s, n);
    double M = 0.0, P = 0.0;
    for (size_t i = 0; i < s->p->n_owned; i++) {
        M += s->p->mass[i];
        P += s->p->mass[i] * s->p->v[0][i];
    }
    double decel = (v0 - P / M) / s->t;
    assert_true(fabs(decel - mu * g) < 0.03 * mu * g);
    /* friction work went to dissipation */
    assert_true(s->rigid->im[0].friction_loss > 0.0);
    sim_destroy(&s);
}

static void test_no_slip_surface(void **state)
{
    (void)state;
    struct sim *s = test_build_ok("model: {type: lattice}\n"
                          "materials:\n"
                          "  m: {density: 1000, youngs_modulus: 1.0e9,\n"
                          "      poisson_ratio: 0.3333333333333333, failure_strain: 1.0}\n"
                          "lattice: {type: triangular, spacing: 1.0e-3}\n"
                          "body: {geometry: {box: {min: [0, 0], max: [0.02, 0.008]}}, material: m}\n"
                          "groups: {base: {box: {min: [-1, -1], max: [1, 0.0005]}}}\n"
                          "boundary_conditions: [{group: base, type: fixed}]\n"
                          "impactors:\n"
                          "  - {name: punch, shape: round_nose, position: [0.0101, 0.0075],\n"
                          "     radius: 0.003, axis: [0, -1], motion: prescribed,\n"
                          "     velocity: [0, -2.0], contact: no_slip}\n"
                          "run: {steps: 300}\n");
    for (int k = 0; k < 300; k++) {
        run_steps(s, 1);
        const struct impactor *im = &s->rigid->im[0];
        for (size_t i = 0; i < s->p->n_owned; i++) {
            double x[3] = {s->p->x[0][i], s->p->x[1][i], 0.0}, n[3];
            double phi = rigid_distance(im, x, n);
            assert_true(phi > -1e-12);
            if (fabs(phi) < 1e-13) { /* in contact: moves with the punch */
                assert_true(fabs(s->p->v[1][i] - im->v[1]) < 1e-12);
                assert_true(fabs(s->p->v[0][i] - im->v[0]) < 1e-12);
            }
        }
    }
    assert_true(s->rigid->im[0].n_contact > 0);
    /* the body resists the punch: force on the punch points up */
    assert_true(s->rigid->im[0].f_noslip[1] > 0.0);
    sim_destroy(&s);
}

static void test_shapes(void **state)
{
    (void)state;
    struct impactor im;
    memset(&im, 0, sizeof im);
    double n[3];
    /* flat punch with rounded edge, tip at origin facing -y */
    im.shape = RIGID_CYLINDER;
    im.radius = 1.0;
    im.length = 4.0;
    im.edge_radius = 0.2;
    im.axis[1] = -1.0;
    double below[3] = {0.0, -0.5, 0.0};
    assert_true(fabs(rigid_distance(&im, below, n) - 0.5) < 1e-14);
    assert_true(fabs(n[1] + 1.0) < 1e-14);
    double side[3] = {1.5, 2.0, 0.0};
    assert_true(fabs(rigid_distance(&im, side, n) - 0.5) < 1e-14);
    assert_true(fabs(n[0] - 1.0) < 1e-14);
    double inside[3] = {0.0, 0.1, 0.0};
    assert_true(fabs(rigid_distance(&im, inside, n) + 0.1) < 1e-14);
    /* corner: distance to the rounding circle centred at (0.8, 0.2) */
    double corner[3] = {1.8, -0.8, 0.0};
    double exp = sqrt(2.0) - 0.2;
    assert_true(fabs(rigid_distance(&im, corner, n) - exp) < 1e-12);
    /* round nose, hemispherical: the tip is the sphere's pole */
    im.shape = RIGID_ROUND_NOSE;
    im.nose_radius = 1.0;
    im.edge_radius = 0.0;
    double off[3] = {0.0, -0.25, 0.0};
    assert_true(fabs(rigid_distance(&im, off, n) - 0.25) < 1e-14);
    double diag[3] = {sqrt(0.5) * 2.0, 1.0 - sqrt(0.5) * 2.0, 0.0};
    assert_true(fabs(rigid_distance(&im, diag, n) - 1.0) < 1e-12);
    /* wall */
    im.shape = RIGID_WALL;
    im.axis[1] = 1.0;
    double above[3] = {3.0, 2.0, 0.0};
    assert_true(fabs(rigid_distance(&im, above, n) - 2.0) < 1e-14);
}

static void test_deck_refusals(void **state)
{
    (void)state;
    const char *head = "model: {type: lattice}\n"
                       "materials:\n"
                       "  m: {density: 1000, youngs_modulus: 1.0e9,\n"
                       "      poisson_ratio: 0.3333333333333333, failure_strain: 1.0}\n"
                       "lattice: {type: triangular, spacing: 1.0e-3}\n"
                       "body: {geometry: {box: {min: [0, 0], max: [0.004, 0.004]}}, material: m}\n"
                       "run: {steps: 10}\n";
    char deck[2048];
    snprintf(deck, sizeof deck, "%simpactors: [{name: a, shape: cube, position: [0, 0]}]\n", head);
    assert_true(build_fails(deck, "shape"));
    snprintf(deck, sizeof deck, "%simpactors: [{name: a, shape: sphere, position: [0, 0]}]\n",
             head);
    assert_true(build_fails(deck, "radius"));
    snprintf(deck, sizeof deck,
             "%simpactors: [{name: a, shape: sphere, position: [0, 1], radius: 1, mass: 1,"
             " colour: red}]\n",
             head);
    assert_true(build_fails(deck, "unknown key 'colour'"));
    snprintf(deck, sizeof deck,
             "%simpactors: [{name: a, shape: wall, position: [0, 0], normal: [0, 0]}]\n", head);
    assert_true(build_fails(deck, "non-zero"));
    snprintf(deck, sizeof deck,
             "%simpactors: [{name: a, shape: sphere, position: [0, 1], radius: 1, mass: 1,"
             " contact: no_slip, friction: 0.2}]\n",
             head);
    assert_true(build_fails(deck, "friction"));
    snprintf(deck, sizeof deck,
             "%simpactors: [{name: a, shape: sphere, position: [0, 1], radius: 1, mass: 1},"
             " {name: a, shape: sphere, position: [0, 5], radius: 1, mass: 1}]\n",
             head);
    assert_true(build_fails(deck, "twice"));
}

int main(void)
{
#ifdef _OPENMP
    /* tiny systems: thread start-up would dominate on a loaded machine */
    omp_set_num_threads(1);
#endif
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_shapes),
        cmocka_unit_test(test_free_fall),
        cmocka_unit_test(test_momentum_penalty),
        cmocka_unit_test(test_momentum_no_slip),
        cmocka_unit_test(test_energy_penalty),
        cmocka_unit_test(test_friction_deceleration),
        cmocka_unit_test(test_no_slip_surface),
        cmocka_unit_test(test_deck_refusals),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
