/**
 * @file test_reflect.c
 * @brief Core reflection of a particle in a plane x_k = 0
 *        (sim_reflect_particle, core/integrator.c; field parities,
 *        core/fields.h): which components change sign, that the
 *        integrator's velocity copy (predictor-corrector v_half) and every
 *        registered odd component follow, that nothing else moves, and that
 *        reflecting twice restores the state bit for bit.
 */
#include "core/fields.h"
#include "core/particles.h"
#include "core/sim.h"
#include "models/sph/sph.h"
#include "spall/error.h"

#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "tests/test_support.h"

#include <stdlib.h>
#include <string.h>

/* Parity tables: vector components are odd in their own plane; a
 * symmetric-tensor shear ab in planes a and b; diagonals never; the sign
 * under several planes is the product (the table sph_symmetry.c used for
 * the ghosts of a quarter model). */
static void test_parity_tables(void **state)
{
    (void)state;
    for (int c = 0; c < 3; c++) {
        assert_int_equal(field_parity_planes(FIELD_VECTOR, c), 1u << c);
        assert_int_equal(field_parity_planes(FIELD_EVEN, c), 0u);
    }
    /* xx yy zz xy yz xz */
    static const unsigned sym[6] = {0u, 0u, 0u, 3u, 6u, 5u};
    for (int c = 0; c < 6; c++)
        assert_int_equal(field_parity_planes(FIELD_SYMTENSOR, c), sym[c]);
    for (int a = 0; a < 3; a++)
        for (int b = 0; b < 3; b++)
            assert_int_equal(field_parity_planes(FIELD_TENSOR, 3 * a + b),
                             a == b ? 0u : (1u << a) | (1u << b));
    static const double tsign[4][6] = {{1, 1, 1, 1, 1, 1},
                                       {1, 1, 1, -1, 1, -1},
                                       {1, 1, 1, -1, -1, 1},
                                       {1, 1, 1, 1, -1, -1}};
    for (unsigned mask = 0; mask < 4; mask++)
        for (int c = 0; c < 6; c++)
            assert_true(field_reflect_sign(FIELD_SYMTENSOR, c, mask) == tsign[mask][c]);
    assert_true(field_reflect_sign(FIELD_VECTOR, 2, 7u) == -1.0);
    assert_true(field_reflect_sign(FIELD_VECTOR, 2, 3u) == 1.0);
}

static void dummy_compute(const void *ctx, size_t n, double *out)
{
    (void)ctx;
    for (size_t i = 0; i < n; i++)
        out[i] = 0.0;
}

/* A parity needs stored doubles with the right component count. */
static void test_parity_refused(void **state)
{
    (void)state;
    struct field_registry *r = NULL;
    struct spall_error err = {0};
    assert_int_equal(field_registry_create(&r, &err), SPALL_OK);
    double *a[6] = {0};
    double **pa[6] = {&a[0], &a[1], &a[2], &a[3], &a[4], &a[5]};
    assert_int_equal(field_registry_add_f64_parity(r, "t5", "1", 5, pa, 0, FIELD_SYMTENSOR, &err),
                     SPALL_ERR_INTERNAL);
    assert_non_null(strstr(err.msg, "t5"));
    assert_int_equal(field_registry_add_f64_parity(r, "v4", "1", 4, pa, 0, FIELD_VECTOR, &err),
                     SPALL_ERR_INTERNAL);
    struct field_desc d;
    memset(&d, 0, sizeof d);
    strcpy(d.name, "computed");
    d.ncomp = 3;
    d.type = FIELD_F64;
    d.compute = dummy_compute;
    d.parity = FIELD_VECTOR;
    assert_int_equal(field_registry_add(r, &d, &err), SPALL_ERR_INTERNAL);
    assert_int_equal(field_registry_add_f64_parity(r, "t6", "1", 6, pa, 0, FIELD_SYMTENSOR, &err),
                     SPALL_OK);
    field_registry_destroy(&r);
}

/* Every double array the reflection may touch, in a fixed order, for
 * snapshots: x, x0, v, f, v_half (3 each), S, S_n, dS_n, dS (6 each), rho, e. */
#define N_ARR (5 * 3 + 4 * 6 + 2)
static size_t arrays(struct sim *s, double *a[N_ARR])
{
    struct model *m = s->model;
    double *S[6], *S_n[6], *dS_n[6];
    for (int c = 0; c < 6; c++) {
        S[c] = field_stored_data(s->fields, "deviatoric_stress", c);
        S_n[c] = field_stored_data(s->fields, "deviatoric_stress_n", c);
        dS_n[c] = field_stored_data(s->fields, "deviatoric_stress_rate_n", c);
    }
    size_t k = 0;
    for (int d = 0; d < 3; d++) {
        a[k++] = s->p->x[d];
        a[k++] = s->p->x0[d];
        a[k++] = s->p->v[d];
        a[k++] = s->p->f[d];
        a[k++] = s->v_half[d];
    }
    for (int c = 0; c < 6; c++) {
        a[k++] = S[c];
        a[k++] = S_n[c];
        a[k++] = dS_n[c];
        a[k++] = sph_stress_rate_data(m, c);
    }
    a[k++] = field_stored_data(s->fields, "density", 0);
    a[k++] = field_stored_data(s->fields, "internal_energy", 0);
    return k;
}

/* The sign the reflection of particle i in plane k must give array q of
 * arrays() at particle j. */
static double expected_sign(size_t q, int k, size_t i, size_t j)
{
    if (i != j)
        return 1.0;
    if (q < 15) {
        int d = (int)(q / 5), what = (int)(q % 5); /* x x0 v f v_half */
        return what != 1 && d == k ? -1.0 : 1.0;
    }
    if (q < 39) {
        int c = (int)((q - 15) / 4), what = (int)((q - 15) % 4); /* S S_n dS_n dS */
        if (what == 3)
            return 1.0; /* the rate of this force call: recomputed, not registered */
        return field_reflect_sign(FIELD_SYMTENSOR, c, 1u << k);
    }
    return 1.0;
}

/* A small 3D SPH block with the predictor-corrector (v_half allocated):
 * every array filled with distinct non-zero values, particle i reflected in
 * each plane: exactly the odd components of particle i change sign (v_half,
 * S, S_n, dS_n included; x0, dS, rho, e and the other particles untouched),
 * and a second reflection restores every array bit for bit. */
static void test_reflect_particle(void **state)
{
    (void)state;
    struct sim *s = test_build_ok(
        "model: {type: sph, kernel: wendland, h_factor: 1.3}\n"
        "materials: {m: {density: 1000, youngs_modulus: 1.0e7, poisson_ratio: 0.3}}\n"
        "lattice: {type: sc, spacing: 1.0e-3, origin: [0.0005, 0.0005, 0.0005]}\n"
        "body: {geometry: {box: {min: [0, 0, 0], max: [0.003, 0.003, 0.003]}}, material: m}\n"
        "run: {end_time: 1.0e-5}\n");
    assert_int_equal(s->integrator, INTEGRATOR_PREDICTOR_CORRECTOR);
    const size_t n = s->p->n;
    assert_true(n == 27);
    double *a[N_ARR];
    const size_t na = arrays(s, a);
    assert_int_equal(na, N_ARR);
    for (size_t q = 0; q < na; q++) {
        assert_non_null(a[q]);
        for (size_t j = 0; j < n; j++)
            a[q][j] = 1.0 + 0.01 * (double)q + 1e-4 * (double)j;
    }
    double *snap = malloc(na * n * sizeof(double));
    assert_non_null(snap);
    for (size_t q = 0; q < na; q++)
        memcpy(snap + q * n, a[q], n * sizeof(double));
    const size_t i = 13;
    for (int k = 0; k < 3; k++) {
        sim_reflect_particle(s, i, k);
        for (size_t q = 0; q < na; q++)
            for (size_t j = 0; j < n; j++)
                assert_true(a[q][j] == expected_sign(q, k, i, j) * snap[q * n + j]);
        sim_reflect_particle(s, i, k); /* twice: the identity */
        for (size_t q = 0; q < na; q++)
            assert_memory_equal(a[q], snap + q * n, n * sizeof(double));
    }
    /* a plane outside the dimension or a particle out of range: no-op */
    sim_reflect_particle(s, i, 3);
    sim_reflect_particle(s, n, 0);
    for (size_t q = 0; q < na; q++)
        assert_memory_equal(a[q], snap + q * n, n * sizeof(double));
    free(snap);
    sim_destroy(&s);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_parity_tables),
        cmocka_unit_test(test_parity_refused),
        cmocka_unit_test(test_reflect_particle),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
