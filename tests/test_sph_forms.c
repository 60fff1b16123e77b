/**
 * @file test_sph_forms.c
 * @brief Formulation per body (sph_forms.c, `model.body_formulation`): an
 *        updated-form block and a TLSPH block collide head-on through the
 *        interface (momentum to round-off, energy within 1 %, no
 *        interpenetration); every body marked total is the run-level
 *        `type: tlsph` bitwise; a TLSPH body that meets nothing
 *        evolves bitwise as when it is alone; mixed runs without the
 *        interface and unknown body names are refused.
 */
#include "core/neighbor.h"
#include "core/particles.h"
#include "core/sim.h"
#include "core/fields.h"
#include "models/sph/sph.h"
#include "spall/error.h"

#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "tests/test_support.h"
#include "tests/test_sph_two_bodies.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* The model's counters (interface pairs, det F range, TLSPH particles). */
static struct sph_stats stats(const struct model *m)
{
    struct sph_stats st;
    sph_stats_get(m, &st);
    return st;
}

/* Head-on run of two_bodies with @p model_extra; @p n_tl_expect TLSPH
 * particles.  Momentum to round-off, energy balance within 1 %, no
 * interpenetration, the top block stopped and compressed. */
static void run_head_on(const char *label, const char *type, const char *model_extra,
                        size_t n_tl_expect)
{
    struct sim *s = test_two_bodies(type, model_extra, 10.0, 0.0);
    assert_non_null(s);
    const struct model *m = s->model;
    const uint8_t *form = sph_formulations(m);
    assert_non_null(form);
    size_t n_tl = 0;
    for (size_t i = 0; i < s->p->n; i++)
        n_tl += form[i];
    assert_int_equal(n_tl, n_tl_expect);
    struct spall_error err = {0};
    double P0[2], P[2], dp = 0.0, dmin = INFINITY;
    test_momentum_2d(s, P0);
    const double ke0 = s->energy.kinetic;
    size_t maxpairs = 0;
    while (!sim_done(s)) {
        assert_int_equal(sim_step(s, &err), 0);
        test_momentum_2d(s, P);
        for (int d = 0; d < 2; d++)
            dp = fmax(dp, fabs(P[d] - P0[d]) / fabs(P0[1]));
        dmin = fmin(dmin, test_min_cross_distance(s));
        if (stats(m).iface_pairs > maxpairs)
            maxpairs = stats(m).iface_pairs;
    }
    sim_update_energy(s);
    const double de = s->energy.balance / ke0;
    double mv = 0.0, mt = 0.0, jmin = INFINITY;
    for (size_t i = 0; i < s->p->n; i++)
        if (s->p->body[i] == 1) {
            mv += s->p->mass[i] * s->p->v[1][i];
            mt += s->p->mass[i];
        }
    jmin = stats(m).tl_jmin; /* smallest det F of the TLSPH block, last step */
    print_message("%s: |dP|/P0 %.3g, energy %.4g of KE0, min cross distance %.4g dx, "
                  "TLSPH block v_y %.4g m/s, min det F %.4f, max pairs %zu, %ld steps\n",
                  label, dp, de, dmin / 1e-3, mv / mt, jmin, maxpairs, s->step);
    assert_true(maxpairs > 0);        /* the bodies met */
    assert_true(dp < 1e-12);          /* every force pair equal and opposite */
    assert_true(fabs(de) < 1e-2);     /* kinetic + internal + penalty */
    assert_true(dmin > 0.8e-3);       /* overlap < 20 % of d = dx */
    assert_true(mv / mt > -25.0);     /* the TLSPH block was stopped */
    assert_true(jmin < 1.0 && jmin > 0.5); /* it was compressed: TLSPH F moved */
    sim_destroy(&s);
}

static void test_mixed_head_on(void **state)
{
    (void)state;
    /* updated target on the fused loop, TLSPH projectile */
    run_head_on("updated (fused) + TLSPH", "sph",
                ",\n        interface: bodies, body_formulation: {proj: total}", 36);
    /* the two-pass loops: CSPM, and the leapfrog (state advanced inside
     * both formulations' force passes) */
    run_head_on("updated (cspm, split) + TLSPH", "sph",
                ", cspm: true,\n        interface: bodies, body_formulation: {proj: total}", 36);
    /* Balsara's switch on both: TLSPH's stage 1 and the updated form's
     * two-pass loops (sph_rates.c) in one run */
    run_head_on("updated (balsara) + TLSPH (balsara)", "sph",
                ", viscosity_switch: balsara,\n        interface: bodies, "
                "body_formulation: {proj: total}",
                36);
    run_head_on("updated (leapfrog) + TLSPH", "sph",
                ", time_integration: leapfrog,\n        interface: bodies, "
                "body_formulation: {proj: total}",
                36);
    /* two TLSPH bodies through the interface (no updated particle) */
    run_head_on("TLSPH + TLSPH", "tlsph", ", interface: bodies", 136);
}

/* Positions and velocities after the run. */
static void final_state(struct sim *s, double *out, size_t n)
{
    struct spall_error err = {0};
    while (!sim_done(s))
        assert_int_equal(sim_step(s, &err), 0);
    assert_int_equal(s->p->n * 4, n);
    for (size_t i = 0; i < s->p->n; i++)
        for (int d = 0; d < 2; d++) {
            out[4 * i + d] = s->p->x[d][i];
            out[4 * i + 2 + d] = s->p->v[d][i];
        }
}

static void test_all_total_is_run_total(void **state)
{
    (void)state;
    /* the two blocks glued through the kernel sums (no interface): the
     * run-level TLSPH path, reached by either key */
    struct sim *a = test_two_bodies("tlsph", "", 0.0, -1.5e-3);
    struct sim *b = test_two_bodies("sph", ", body_formulation: {proj: total, target: total}", 0.0,
                                    -1.5e-3);
    assert_non_null(a);
    assert_non_null(b);
    assert_null(sph_formulations(b->model));
    assert_true(stats(b->model).total_lagrangian);
    const size_t n = a->p->n * 4;
    double *xa = calloc(n, sizeof *xa), *xb = calloc(n, sizeof *xb);
    final_state(a, xa, n);
    final_state(b, xb, n);
    assert_memory_equal(xa, xb, n * sizeof *xa);
    /* in a tlsph run, marking bodies updated splits the run */
    sim_destroy(&b);
    b = test_two_bodies("tlsph", ", interface: bodies, "
                   "body_formulation: {target: updated}", 0.0, 0.0);
    assert_non_null(b);
    assert_non_null(sph_formulations(b->model));
    assert_int_equal(stats(b->model).n_total, 36);
    free(xa);
    free(xb);
    sim_destroy(&a);
    sim_destroy(&b);
}

/* A TLSPH body that never meets the updated body (far apart, fixed dt)
 * follows bitwise the same path as the same body alone in a TLSPH run:
 * the split touches no TLSPH sum. */
static void test_tlsph_body_unchanged(void **state)
{
    (void)state;
    static const char *fmt =
        TEST_SPH_AB_HEAD
        "bodies:\n"
        "  - {name: proj, geometry: {box: {min: [0, 0], max: [0.006, 0.004]}}, material: b,\n"
        "     lattice: {spacing: 1.0e-3, origin: [0.0005, 0.0005]}}\n"
        "%s"
        "groups: {left: {box: {min: [0, 0], max: [0.002, 0.004]}}}\n"
        "initial_velocity: [{group: left, value: [-20, 5]}]\n"
        "run: {end_time: 1.0e-4, dt: 2.0e-7}\n";
    char ya[2048], yb[2048];
    snprintf(ya, sizeof ya, fmt, "tlsph", "", "");
    snprintf(yb, sizeof yb, fmt, "sph", ", interface: bodies, body_formulation: {proj: total}",
             "  - {name: far, geometry: {box: {min: [0.05, 0], max: [0.06, 0.01]}}, "
             "material: a,\n     lattice: {spacing: 1.0e-3, origin: [0.0505, 0.0005]}}\n");
    struct sim *a = test_build_ok(ya), *b = test_build_ok(yb);
    assert_non_null(sph_formulations(b->model));
    struct spall_error err = {0};
    while (!sim_done(a))
        assert_int_equal(sim_step(a, &err), 0);
    while (!sim_done(b))
        assert_int_equal(sim_step(b, &err), 0);
    assert_int_equal(a->step, b->step);
    const double *ea = field_stored_data(a->fields, "internal_energy", 0);
    const double *eb = field_stored_data(b->fields, "internal_energy", 0);
    assert_true(ea && eb);
    for (size_t i = 0; i < a->p->n; i++) {
        assert_int_equal(b->p->body[i], 0);
        for (int d = 0; d < 2; d++) {
            assert_true(a->p->x[d][i] == b->p->x[d][i]);
            assert_true(a->p->v[d][i] == b->p->v[d][i]);
        }
        assert_true(ea[i] == eb[i]);
    }
    sim_destroy(&a);
    sim_destroy(&b);
}

/* interface: materials with a TLSPH body: the updated target made of two
 * bodies of one material stays one continuum (kernel pairs across them),
 * the TLSPH body has no pair in the current kernel list and touches the
 * target through the interface list only. */
static void test_materials_split(void **state)
{
    (void)state;
    static const char *yaml =
        "model: {type: sph, plane: strain, interface: materials,\n"
        "        body_formulation: {proj: total}}\n"
        "materials:\n"
        "  a: {density: 1000, youngs_modulus: 1.0e7, poisson_ratio: 0.3}\n"
        "  b: {density: 2000, youngs_modulus: 1.0e8, poisson_ratio: 0.3}\n"
        "lattice: {type: square, spacing: 1.0e-3}\n"
        "bodies:\n"
        "  - {geometry: {box: {min: [0, 0], max: [0.01, 0.005]}}, material: a,\n"
        "     lattice: {spacing: 1.0e-3, origin: [0.0005, 0.0005]}}\n"
        "  - {geometry: {box: {min: [0, 0.005], max: [0.01, 0.01]}}, material: a,\n"
        "     lattice: {spacing: 1.0e-3, origin: [0.0005, 0.0055]}}\n"
        "  - {name: proj, geometry: {box: {min: [0.002, 0.0105], max: [0.008, 0.0145]}},\n"
        "     material: b, lattice: {spacing: 1.0e-3, origin: [0.0005, 0.011]}}\n"
        "run: {steps: 1}\n";
    struct sim *s = test_build_ok(yaml);
    struct model *m = s->model;
    const uint8_t *form = sph_formulations(m);
    assert_non_null(form);
    struct spall_error err = {0};
    assert_int_equal(sph_neighbors_update(m, s, true, &err), 0);
    const struct neighbor_list *nl = sph_neighbors(m);
    size_t across = 0, with_tl = 0, iface_tl = 0, iface_other = 0;
    for (size_t i = 0; i < s->p->n; i++) {
        for (size_t k = nl->offset[i]; k < nl->offset[i + 1]; k++) {
            size_t j = (size_t)nl->idx[k];
            across += s->p->body[i] != s->p->body[j];
            with_tl += form[i] || form[j];
        }
        const int32_t *idx;
        size_t np = sph_interface_partners(m, i, &idx);
        for (size_t k = 0; k < np; k++) {
            size_t j = (size_t)idx[k];
            if (form[i] != form[j])
                iface_tl++;
            else
                iface_other++;
        }
    }
    print_message("materials split: %zu kernel pairs across the target bodies, %zu with "
                  "TLSPH, %zu interface pairs TLSPH-target, %zu others, %zu reference pairs\n",
                  across, with_tl, iface_tl, iface_other, sph_tlsph_pairs(m));
    assert_true(across > 0);
    assert_int_equal(with_tl, 0);
    assert_true(iface_tl > 0);
    assert_int_equal(iface_other, 0);
    assert_true(sph_tlsph_pairs(m) > 0);
    sim_destroy(&s);
}

static void expect_refused(const char *model_extra, const char *what)
{
    struct sim *s = NULL;
    char yaml[2048];
    snprintf(yaml, sizeof yaml,
             "model: {type: sph%s}\n"
             "materials: {m: {density: 1000, youngs_modulus: 1.0e7, poisson_ratio: 0.3}}\n"
             "lattice: {type: square, spacing: 1.0e-3}\n"
             "bodies:\n"
             "  - {name: one, geometry: {box: {min: [0, 0], max: [0.004, 0.004]}}, material: m,\n"
             "     lattice: {spacing: 1.0e-3, origin: [0.0005, 0.0005]}}\n"
             "  - {name: two, geometry: {box: {min: [0, 0.006], max: [0.004, 0.01]}},\n"
             "     material: m, lattice: {spacing: 1.0e-3, origin: [0.0005, 0.0065]}}\n"
             "run: {steps: 1}\n",
             model_extra);
    struct spall_error err = {0};
    int rc = vlat_build("t", yaml, &s, &err);
    print_message("refused: %s\n", err.msg);
    assert_int_not_equal(rc, 0);
    assert_non_null(strstr(err.msg, what));
    sim_destroy(&s);
}

static void test_refused(void **state)
{
    (void)state;
    /* mixed without the interface: the message names the cause and the fix */
    expect_refused(", body_formulation: {two: total}", "interface: bodies");
    /* a body name no bodies[] entry has */
    expect_refused(", interface: bodies, body_formulation: {three: total}", "'three'");
    expect_refused(", interface: bodies, body_formulation: {two: lagrangian}", "lagrangian");
    /* TLSPH is not axisymmetric (sph_axisym.c has its own loops) */
    expect_refused(", interface: bodies, body_formulation: {two: total}, plane: axisymmetric",
                   "axisymmetric");
    /* the old verification switch: refused, saying what to do */
    expect_refused(", pair_loop: split", "pair_loop is no longer a deck key");
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_mixed_head_on),
        cmocka_unit_test(test_all_total_is_run_total),
        cmocka_unit_test(test_tlsph_body_unchanged),
        cmocka_unit_test(test_materials_split),
        cmocka_unit_test(test_refused),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
