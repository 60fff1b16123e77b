/* Tests for the `inclusions:` deck section (io/deck_inclusions.c): seeded
 * determinism, count and non-overlap, refusals naming the entry. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

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

static int build(const char *incl, struct sim **s, struct spall_error *err)
{
    char yaml[4096];
    snprintf(yaml, sizeof yaml,
             "model: {type: lattice, law: linear}\n"
             "materials:\n"
             "  host: {density: 2700, youngs_modulus: 70.0e9, poisson_ratio: 0.25, failure_strain: 0.01}\n"
             "  inc: {density: 5000, youngs_modulus: 200.0e9, poisson_ratio: 0.25, failure_strain: 0.01}\n"
             "lattice: {type: triangular, spacing: 1.0e-3}\n"
             "geometry:\n"
             "  plate: {box: {min: [0, 0], max: [0.06, 0.06]}}\n"
             "body: {geometry: plate, material: host}\n"
             "inclusions:\n%s"
             "run: {end_time: 1.0e-6}\n",
             incl);
    struct deck *d = NULL;
    int rc = deck_load_string(&d, "test_inclusions", yaml, err);
    if (rc)
        return rc;
    struct run_output ro;
    rc = deck_build_sim(d, s, &ro, err);
    deck_destroy(&d);
    return rc;
}

static int32_t *materials_of(const char *incl, size_t *n)
{
    struct sim *s = NULL;
    struct spall_error err = {0};
    int rc = build(incl, &s, &err);
    if (rc)
        fprintf(stderr, "%s\n", err.msg);
    assert_int_equal(rc, SPALL_OK);
    *n = s->p->n;
    int32_t *m = malloc(*n * sizeof *m);
    assert_non_null(m);
    memcpy(m, s->p->material, *n * sizeof *m);
    /* masses follow the re-assigned material */
    for (size_t i = 0; i < *n; i++)
        assert_true(fabs(s->p->mass[i] - s->materials[m[i]].density * s->p->volume[i]) <=
                    1e-12 * s->p->mass[i]);
    sim_destroy(&s);
    return m;
}

#define ENTRY(seed) "  - {material: inc, count: 6, radius: [0.003, 0.005], within: plate, " \
                    "seed: " #seed ", min_gap: 0.002}\n"

static void test_seed_determinism(void **state)
{
    (void)state;
    size_t na, nb, nc;
    int32_t *a = materials_of(ENTRY(7), &na);
    int32_t *b = materials_of(ENTRY(7), &nb);
    int32_t *c = materials_of(ENTRY(8), &nc);
    assert_int_equal(na, nb);
    assert_int_equal(na, nc);
    assert_memory_equal(a, b, na * sizeof *a);
    assert_memory_not_equal(a, c, na * sizeof *a);
    size_t inc = 0;
    for (size_t i = 0; i < na; i++)
        inc += a[i] == 1;
    /* 6 discs of radius 3-5 mm on a 1 mm triangular lattice (site area
     * sqrt3/2 mm^2): between 6 * pi 9 / 0.866 ~ 196 and 6 * pi 25 / 0.866
     * ~ 544 sites, up to lattice rounding */
    assert_true(inc > 150 && inc < 600);
    free(a);
    free(b);
    free(c);
}

/* Count and non-overlap: connected clusters of inclusion particles (bond
 * distance ~ spacing) must number exactly `count` when min_gap exceeds the
 * spacing. */
static void test_count_nonoverlap(void **state)
{
    (void)state;
    struct sim *s = NULL;
    struct spall_error err = {0};
    assert_int_equal(build(ENTRY(3), &s, &err), SPALL_OK);
    const struct particles *p = s->p;
    const size_t n = p->n;
    int *label = malloc(n * sizeof *label);
    size_t *stack = malloc(n * sizeof *stack);
    assert_non_null(label);
    assert_non_null(stack);
    for (size_t i = 0; i < n; i++)
        label[i] = -1;
    int clusters = 0;
    const double h2 = (1.1e-3) * (1.1e-3);
    for (size_t i = 0; i < n; i++) {
        if (p->material[i] != 1 || label[i] >= 0)
            continue;
        size_t top = 0;
        stack[top++] = i;
        label[i] = clusters;
        while (top) {
            const size_t a = stack[--top];
            for (size_t j = 0; j < n; j++) {
                if (p->material[j] != 1 || label[j] >= 0)
                    continue;
                const double dx = p->x0[0][j] - p->x0[0][a], dy = p->x0[1][j] - p->x0[1][a];
                if (dx * dx + dy * dy < h2) {
                    label[j] = clusters;
                    stack[top++] = j;
                }
            }
        }
        clusters++;
    }
    assert_int_equal(clusters, 6);
    free(label);
    free(stack);
    sim_destroy(&s);
}

static void test_refusals(void **state)
{
    (void)state;
    struct sim *s = NULL;
    struct spall_error err = {0};
    /* impossible packing: named entry and counts */
    assert_int_equal(build("  - {material: inc, count: 500, radius: 0.01, within: plate}\n", &s,
                           &err),
                     SPALL_ERR_INPUT);
    assert_non_null(strstr(err.msg, "inclusions[0]"));
    assert_non_null(strstr(err.msg, "test_inclusions:"));
    assert_null(s);
    assert_int_equal(build("  - {material: nope, count: 1, radius: 0.01, within: plate}\n", &s,
                           &err),
                     SPALL_ERR_INPUT);
    assert_non_null(strstr(err.msg, "nope"));
    assert_int_equal(build("  - {material: inc, count: 1, radius: [0.005, 0.001], within: plate}\n",
                           &s, &err),
                     SPALL_ERR_INPUT);
    assert_non_null(strstr(err.msg, "Rmin"));
    assert_int_equal(build("  - {material: inc, count: 1, radius: 0.01, within: plate, bad: 1}\n",
                           &s, &err),
                     SPALL_ERR_INPUT);
    assert_non_null(strstr(err.msg, "bad"));
    assert_int_equal(build("  - {material: inc, count: 1, radius: 1.0e-5, within: plate}\n", &s,
                           &err),
                     SPALL_ERR_INPUT);
    assert_non_null(strstr(err.msg, "no particle"));
}


/* ---- youngs_modulus_table (thermal lattice, lattice_thermal.c) ---------- */

static int build_pair(const char *extra, double T0, struct sim **s, struct spall_error *err)
{
    char yaml[2048];
    snprintf(yaml, sizeof yaml,
             "model: {type: lattice, law: linear}\n"
             "materials:\n"
             "  m: {density: 1000, youngs_modulus: 1.0e9, failure_strain: 0.5,\n"
             "      specific_heat: 800, initial_temperature: %g%s}\n"
             "lattice: {type: chain, spacing: 1.0e-3}\n"
             "body: {geometry: {box: {min: [-0.0005], max: [0.0015]}}, material: m}\n"
             "run: {end_time: 1.0e-6}\n",
             T0, extra);
    struct deck *d = NULL;
    int rc = deck_load_string(&d, "test_etab", yaml, err);
    if (rc)
        return rc;
    struct run_output ro;
    rc = deck_build_sim(d, s, &ro, err);
    deck_destroy(&d);
    return rc;
}

/* force on particle 0 of a two-particle chain stretched by 1 um */
static double pair_force(const char *extra, double T0)
{
    struct sim *s = NULL;
    struct spall_error err = {0};
    int rc = build_pair(extra, T0, &s, &err);
    if (rc)
        fprintf(stderr, "%s\n", err.msg);
    assert_int_equal(rc, SPALL_OK);
    assert_int_equal(s->p->n, 2);
    s->p->x[0][1] += 1.0e-6;
    s->p->f[0][0] = s->p->f[0][1] = 0.0;
    assert_int_equal(s->ops->compute_forces(s->model, s, &err), SPALL_OK);
    const double f = s->p->f[0][0];
    assert_true(f > 0.0 && fabs(f + s->p->f[0][1]) <= 1e-12 * f);
    sim_destroy(&s);
    return f;
}

static void test_etable_stiffness(void **state)
{
    (void)state;
    const char *tab = ", youngs_modulus_table: [[300, 1.0e9], [900, 0.5e9]]";
    const double f_ref = pair_force("", 600.0);
    /* both particles at 600 K: E(600) = 0.75 E_ref, piecewise linear */
    assert_true(fabs(pair_force(tab, 600.0) / f_ref - 0.75) < 1e-12);
    /* held outside the table */
    assert_true(fabs(pair_force(tab, 1200.0) / f_ref - 0.5) < 1e-12);
    assert_true(fabs(pair_force(tab, 100.0) / f_ref - 1.0) < 1e-12);
}

static void test_etable_refusals(void **state)
{
    (void)state;
    struct sim *s = NULL;
    struct spall_error err = {0};
    static const char *const bad[][2] = {
        {", youngs_modulus_table: [[300, 1.0e9], [300, 0.5e9]]", "strictly increasing"},
        {", youngs_modulus_table: [[300, 1.0e9], [900, 0]]", "expected > 0"},
        {", youngs_modulus_table: [[300, 2.0e9]]", "above youngs_modulus"},
        {", youngs_modulus_table: [[300, 1.0e9, 5]]", "expected [T, E]"},
        {", youngs_modulus_table: 5", "[temperature K, youngs_modulus Pa]"},
    };
    for (size_t k = 0; k < sizeof bad / sizeof bad[0]; k++) {
        assert_int_equal(build_pair(bad[k][0], 300.0, &s, &err), SPALL_ERR_INPUT);
        if (!strstr(err.msg, bad[k][1]) || !strstr(err.msg, "test_etab:"))
            fprintf(stderr, "case %zu: %s\n", k, err.msg);
        assert_non_null(strstr(err.msg, bad[k][1]));
        assert_non_null(strstr(err.msg, "test_etab:"));
        assert_null(s);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_seed_determinism),
        cmocka_unit_test(test_count_nonoverlap),
        cmocka_unit_test(test_refusals),
        cmocka_unit_test(test_etable_stiffness),
        cmocka_unit_test(test_etable_refusals),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
