/**
 * @file test_sph_av_options.c
 * @brief The artificial-viscosity options of the SPH model (issue 7,
 *        resolution study of pen-sph-gelatin): `viscosity_length` puts a
 *        fixed length L in mu_ij instead of h_ij (Eq. 2.21), so with q_b = 0
 *        the AV of (q_a, L = 2 h) is exactly that of (2 q_a, h), in the
 *        planar and the axisymmetric pair loops; `viscosity_switch:
 *        balsara` (axisymmetric, TLSPH: formulation total, and the
 *        updated form in plane strain / stress through the two-pass loops)
 *        removes the AV from a pure shear flow and keeps it in a pure
 *        compression, and is refused with symmetry planes.
 */
#include "core/particles.h"
#include "core/sim.h"
#include "io/deck.h"
#include "io/deck_build.h"
#include "spall/error.h"

#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "tests/test_support.h"

#include <math.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* A 24 x 24 mm block, dx = 1 mm (h = 1.3 mm), in the given plane, with the
 * model options @p av (the updated form unless they start with a type,
 * e.g. "type: tlsph, "); fixed dt so that runs with different AV take the
 * same step. */
#define BLOCK 0.024
static struct sim *block(const char *plane, const char *av)
{
    char yaml[1024];
    snprintf(yaml, sizeof yaml,
             "model: {%skernel: wendland, h_factor: 1.3, plane: %s,\n"
             "        adaptive_dt: false, %s}\n"
             "materials: {m: {density: 1000, youngs_modulus: 1.0e7, poisson_ratio: 0.3}}\n"
             "lattice: {type: square, spacing: 1.0e-3, origin: [0.0005, 0.0005]}\n"
             "body: {geometry: {box: {min: [0, 0], max: [%g, %g]}}, material: m}\n"
             "run: {steps: 1, dt: 1.0e-6}\n",
             strncmp(av, "type:", 5) == 0 ? "" : "type: sph, ", plane, av, BLOCK, BLOCK);
    return test_build_ok(yaml);
}

enum flow { FLOW_COMPRESSION, FLOW_SHEAR };

/* One step from the velocity field @p f (linear: the corrected gradient is
 * exact); returns the velocity change of every particle in dv[2][n]. */
static void one_step(struct sim *s, enum flow f, double *dv[2])
{
    struct spall_error err = {0};
    /* 1/s; compression strong enough that Balsara's floor 1e-4 c / h
     * (~9 /s here) is 0.3 % of |div v| = 3 g */
    const double g = f == FLOW_COMPRESSION ? 1000.0 : 100.0;
    for (size_t i = 0; i < s->p->n; i++) {
        const double x = s->p->x[0][i], y = s->p->x[1][i];
        s->p->v[0][i] = f == FLOW_COMPRESSION ? -g * x : 0.0;
        s->p->v[1][i] = f == FLOW_COMPRESSION ? -g * y : g * x;
    }
    double *v0[2];
    for (int d = 0; d < 2; d++) {
        v0[d] = malloc(s->p->n * sizeof(double));
        assert_non_null(v0[d]);
        memcpy(v0[d], s->p->v[d], s->p->n * sizeof(double));
    }
    assert_int_equal(sim_step(s, &err), SPALL_OK);
    for (int d = 0; d < 2; d++) {
        for (size_t i = 0; i < s->p->n; i++)
            dv[d][i] = s->p->v[d][i] - v0[d][i];
        free(v0[d]);
    }
}

/* Particles whose neighbours' neighbours (2 x 2h = 5.2 mm) are inside the
 * block and off the axis: there the corrected gradient of a linear field is
 * exact for every particle in reach (the axis images make v_z = g r a kink). */
static int deep(double x, double y)
{
    const double m = 5.3e-3;
    return x > m && y > m && x < BLOCK - m && y < BLOCK - m;
}

/* max |a - b| / max |b - c| over particles (all, or deep ones: xy given)
 * and components */
static double rel_gap(size_t n, double *a[2], double *b[2], double *c[2], const double *xy[2])
{
    double num = 0.0, den = 0.0;
    for (int d = 0; d < 2; d++)
        for (size_t i = 0; i < n; i++) {
            if (xy && !deep(xy[0][i], xy[1][i]))
                continue;
            num = fmax(num, fabs(a[d][i] - b[d][i]));
            den = fmax(den, fabs(b[d][i] - c[d][i]));
        }
    assert_true(den > 0.0);
    return num / den;
}

/* Velocity changes of one step of @p flow with AV options @p av; the
 * initial positions into xy if given. */
static size_t run_dv(const char *plane, const char *av, enum flow flow, double *dv[2],
                     double *xy[2])
{
    struct sim *s = block(plane, av);
    size_t n = s->p->n;
    for (int d = 0; xy && d < 2; d++) {
        xy[d] = malloc(n * sizeof(double));
        assert_non_null(xy[d]);
        memcpy(xy[d], s->p->x[d], n * sizeof(double));
    }
    for (int d = 0; d < 2; d++) {
        dv[d] = malloc(n * sizeof(double));
        assert_non_null(dv[d]);
    }
    one_step(s, flow, dv);
    sim_destroy(&s);
    return n;
}

static void free_dv(double *dv[2])
{
    free(dv[0]);
    free(dv[1]);
}

/* (q_a, L = 2 h) == (2 q_a, h) with q_b = 0, and differs from (q_a, h). */
static void check_length(const char *plane)
{
    double *a[2], *b[2], *c[2];
    size_t n =
        run_dv(plane, "viscosity: [1, 0], viscosity_length: 2.6e-3", FLOW_COMPRESSION, a, NULL);
    assert_int_equal(run_dv(plane, "viscosity: [2, 0]", FLOW_COMPRESSION, b, NULL), n);
    assert_int_equal(run_dv(plane, "viscosity: [1, 0]", FLOW_COMPRESSION, c, NULL), n);
    double gap = rel_gap(n, a, b, c, NULL);
    print_message("%s: |dv(q_a = 1, L = 2h) - dv(q_a = 2)| / |dv(2) - dv(1)| = %.3g\n", plane,
                  gap);
    assert_true(gap < 1e-9);
    free_dv(a);
    free_dv(b);
    free_dv(c);
}

static void test_length_planar(void **state)
{
    (void)state;
    check_length("strain");
}

static void test_length_axisymmetric(void **state)
{
    (void)state;
    check_length("axisymmetric");
}

/* Balsara: shear v_z = g r (div v = 0): the AV's share of dv vanishes;
 * compression v = -g x (curl v = 0): it stays (f = 1 - O(1e-4 c / (h |div v|))).
 * @p pre: model keys before the AV's (the model type, CSPM). */
static void check_balsara(const char *pl, const char *pre, bool deep_only)
{
    char bal[160], on[160], off[160];
    snprintf(bal, sizeof bal, "%sviscosity: [1, 1], viscosity_switch: balsara", pre);
    snprintf(on, sizeof on, "%sviscosity: [1, 1]", pre);
    snprintf(off, sizeof off, "%sviscosity: [0, 0]", pre);
    double *sw[2], *av[2], *no[2], *xy[2];
    size_t n = run_dv(pl, bal, FLOW_SHEAR, sw, xy);
    run_dv(pl, on, FLOW_SHEAR, av, NULL);
    run_dv(pl, off, FLOW_SHEAR, no, NULL);
    const double *cxy[2] = {xy[0], xy[1]};
    /* |switch - none| / |none - AV| on the deep particles */
    double shear = rel_gap(n, sw, no, av, deep_only ? cxy : NULL);
    free_dv(sw);
    free_dv(av);
    free_dv(no);
    n = run_dv(pl, bal, FLOW_COMPRESSION, sw, NULL);
    run_dv(pl, on, FLOW_COMPRESSION, av, NULL);
    run_dv(pl, off, FLOW_COMPRESSION, no, NULL);
    double comp = rel_gap(n, sw, av, no, deep_only ? cxy : NULL); /* |switch - AV| / |AV - none| */
    free_dv(xy);
    free_dv(sw);
    free_dv(av);
    free_dv(no);
    print_message("balsara (%s%s): AV left in shear %.3g, AV removed in compression %.3g\n", pre,
                  pl, shear, comp);
    assert_true(shear < 1e-6);
    assert_true(comp < 1e-2);
}

static void test_balsara(void **state)
{
    (void)state;
    check_balsara("axisymmetric", "", true);
}

/* the same switch in TLSPH's stage 1 / stage 2 (sph_tlsph.c), plane strain,
 * over all particles: in the planar interior the AV of a linear field
 * cancels pair by pair (mirror partners), so only the edges feel it; the
 * corrected reference gradient is exact for a linear field there too */
static void test_balsara_tlsph(void **state)
{
    (void)state;
    check_balsara("strain", "type: tlsph, ", false);
}

/* the updated form in plane strain and plane stress (sph_rates.c pass C,
 * the switch from pass A's gradient of the same call), over all particles:
 * in the planar interior the AV of a linear field cancels pair by pair, so
 * only the edges feel it, and there the gradient is exact only when
 * corrected (CSPM; the plain one leaves a spurious divergence at the edge
 * of a shear flow, 9 % of the AV left there) */
static void test_balsara_updated_planar(void **state)
{
    (void)state;
    check_balsara("strain", "cspm: true, ", false);
    check_balsara("stress", "cspm: true, ", false);
}

static void test_balsara_refused(void **state)
{
    (void)state;
    const char *yaml = "model: {type: sph, viscosity_switch: balsara, symmetry: x}\n"
                       "materials: {m: {density: 1000, youngs_modulus: 1.0e7, poisson_ratio: 0.3}}\n"
                       "lattice: {type: square, spacing: 1.0e-3}\n"
                       "body: {geometry: {box: {min: [0, 0], max: [0.01, 0.01]}}, material: m}\n"
                       "run: {steps: 1}\n";
    test_deck_refused(yaml, "symmetry");
    const char *neg = "model: {type: sph, viscosity_length: -1}\n"
                      "materials: {m: {density: 1000, youngs_modulus: 1.0e7, poisson_ratio: 0.3}}\n"
                      "lattice: {type: square, spacing: 1.0e-3}\n"
                      "body: {geometry: {box: {min: [0, 0], max: [0.01, 0.01]}}, material: m}\n"
                      "run: {steps: 1}\n";
    test_deck_refused(neg, "viscosity_length");
}

/* viscosity_length L > h: the step obeys the AV's bound h / ((L/h)(q_a c +
 * q_b L |D|)) as well as Eq. 3.38 (sph_model.c).  Two halves of a block
 * collide at 0.3 c.  At the start (D = 0) with L = 3 h and q_a = 2 the
 * limit is h / (6 c) against Eq. 3.38's h / (c + |v|) (leapfrog: no CSPM
 * factor).  The collision must then keep its energy as well as the plain
 * AV (2, 1) does at Eq. 3.38's step (within 2x: the leapfrog's energy
 * error is first order in the AV's heating; measured 2.7 % against
 * 1.6 %).  The same AV written without L, (6, 9) (q_a scales with L/h,
 * q_b with (L/h)^2), runs at Eq. 3.38's step only and blows up in 2 steps
 * (7x the input energy; (6, 0): 147 %). */
static struct sim *collision(const char *av)
{
    char yaml[1280];
    snprintf(yaml, sizeof yaml,
             "model: {type: sph, kernel: wendland, h_factor: 1.3, plane: strain,\n"
             "        time_integration: leapfrog, %s}\n"
             "materials: {m: {density: 1000, youngs_modulus: 1.0e7, poisson_ratio: 0.3}}\n"
             "lattice: {type: square, spacing: 1.0e-3, origin: [0.0005, 0.0005]}\n"
             "body: {geometry: {box: {min: [0, 0], max: [%g, %g]}}, material: m}\n"
             "groups: {left: {box: {min: [0, 0], max: [%g, %g]}},\n"
             "         right: {box: {min: [%g, 0], max: [%g, %g]}}}\n"
             "initial_velocity: [{group: left, value: [35, 0]}, {group: right, value: [-35, 0]}]\n"
             "run: {end_time: 1.0e-4, dt_factor: 0.3}\n",
             av, BLOCK, BLOCK, 0.5 * BLOCK, BLOCK, 0.5 * BLOCK, BLOCK, BLOCK);
    return test_build_ok(yaml);
}

/* worst |energy balance| / input over the collision run */
static double collision_energy(struct sim *s)
{
    sim_update_energy(s);
    const double e0 = s->energy.kinetic;
    struct spall_error err = {0};
    double worst = 0.0;
    while (!sim_done(s)) {
        assert_int_equal(sim_step(s, &err), SPALL_OK);
        sim_update_energy(s);
        worst = fmax(worst, fabs(s->energy.balance) / e0);
    }
    return worst;
}

static void test_length_step(void **state)
{
    (void)state;
    struct sim *plain = collision("viscosity: [2, 1]");
    struct sim *s = collision("viscosity: [2, 1], viscosity_length: 3.9e-3");
    /* c = sqrt((K + 4G/3) / rho) = 116 m/s, v = 35 m/s */
    const double c = sqrt(1.0e7 * 0.7 / (1.3 * 0.4) / 1000.0);
    const double ratio = s->dt_limit / plain->dt_limit;
    print_message("L = 3 h: dt limit / Eq. 3.38's = %.12g (expected %.12g)\n", ratio,
                  (c + 35.0) / (6.0 * c));
    assert_true(fabs(ratio - (c + 35.0) / (6.0 * c)) < 1e-9);
    const double e_plain = collision_energy(plain), e_len = collision_energy(s);
    print_message("collision at 0.3 c: worst |energy balance| / input: AV (2, 1) %.3g (%ld "
                  "steps), with L = 3 h %.3g (%ld steps)\n",
                  e_plain, plain->step, e_len, s->step);
    assert_true(e_len < 2.0 * e_plain);
    sim_destroy(&plain);
    sim_destroy(&s);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_length_planar),
        cmocka_unit_test(test_length_axisymmetric),
        cmocka_unit_test(test_balsara),
        cmocka_unit_test(test_balsara_tlsph),
        cmocka_unit_test(test_balsara_updated_planar),
        cmocka_unit_test(test_balsara_refused),
        cmocka_unit_test(test_length_step),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
