/**
 * @file test_sph_fused.c
 * @brief The fused SPH pair loop (sph_fused.c) against the split passes of
 *        sph_rates.c (same equations, different summation order: positions
 *        agree to 1e-12 of the size after 40 steps), in 2D with artificial
 *        stress and the generic kernel path and in 3D with the Wendland fast
 *        path; and symmetry planes: a quarter Taylor bar with mirror planes
 *        x = 0, y = 0 reproduces the full bar's quarter (1e-9 of the size),
 *        bitwise the same on 1 and 2 threads.  The vector rows of the
 *        fused loop (Wendland, no artificial stress) against its scalar rows
 *        (sph_set_scalar_rows): bitwise the same positions and velocities,
 *        in 3D with fixed h and in 2D with variable h (pairs of unequal h).
 */
#include "core/particles.h"
#include "core/sim.h"
#include "models/sph/sph.h"
#include "spall/error.h"

#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "tests/test_support.h"
#include "tests/test_sph_rows.h"

#include <math.h>
#include <omp.h>
#include <stdio.h>
#include <string.h>

/* Max |x_a - x_b| over particles with the same index. */
static double max_diff(const struct sim *a, const struct sim *b)
{
    assert_int_equal(a->p->n, b->p->n);
    double d = 0.0;
    for (int k = 0; k < a->dim; k++)
        for (size_t i = 0; i < a->p->n; i++)
            d = fmax(d, fabs(a->p->x[k][i] - b->p->x[k][i]));
    return d;
}

static const char *BLOCK2D =
    "model: {type: sph, kernel: cubic_spline, h_factor: 1.3, viscosity: [0.5, 0.5],\n"
    "        artificial_stress: 0.3, xsph: 0.5, plane: strain}\n"
    "materials: {m: {density: 1000, youngs_modulus: 1.0e7, poisson_ratio: 0.3}}\n"
    "lattice: {type: square, spacing: 1.0e-3, origin: [0.0005, 0.0005]}\n"
    "body: {geometry: {box: {min: [0, 0], max: [0.012, 0.008]}}, material: m}\n"
    "groups: {left: {box: {min: [0, 0], max: [0.004, 1]}}}\n"
    "initial_velocity: [{group: left, value: [20.0, 5.0]}]\n"
    "run: {steps: 40}\n";

static void test_fused_vs_split_2d(void **state)
{
    (void)state;
    struct sim *a = test_build(BLOCK2D);
    struct sim *b = test_build(BLOCK2D);
    assert_non_null(a);
    assert_non_null(b);
    sph_set_split_loops(b->model);
    test_run_to_end(a);
    test_run_to_end(b);
    double d = max_diff(a, b);
    double moved = fabs(a->p->x[0][0] - a->p->x0[0][0]);
    assert_true(moved > 1e-6); /* something happened */
    print_message("2D fused vs split: max |dx| = %.3g m (moved %.3g m)\n", d, moved);
    assert_true(d < 1e-12 * 0.012);
    sim_destroy(&a);
    sim_destroy(&b);
}

static const char *BAR3D =
    "model: {type: sph, kernel: wendland, h_factor: 1.5, viscosity: [1.5, 1.5], xsph: 0.1,\n"
    "        wall: {point: [0, 0, 0], normal: [0, 0, 1]}, symmetry: %s}\n"
    "materials:\n"
    "  s: {density: 7830, bulk_modulus: 169.1e9, shear_modulus: 89.2e9, yield: johnson_cook,\n"
    "      yield_a: 792.0e6, yield_b: 510.0e6, yield_n: 0.26, jc_c: 0.014, jc_m: 1.03,\n"
    "      melt_temperature: 1793, specific_heat: 477}\n"
    "lattice: {type: sc, spacing: 1.0e-3, origin: [0.0005, 0.0005, 0.0005]}\n"
    "body: {geometry: %s, material: s}\n"
    "initial_velocity: [{group: all, value: [0, 0, -181.0]}]\n"
    "run: {steps: 40, dt_factor: 0.3}\n";

#define FULL "{cylinder: {base: [0, 0, 0], top: [0, 0, 0.012], radius: 0.003}}"
#define QUARTER                                                                                   \
    "{intersection: [" FULL ", {box: {min: [0, 0, -1], max: [1, 1, 1]}}]}"

static void test_fused_vs_split_3d(void **state)
{
    (void)state;
    char y[2048];
    snprintf(y, sizeof y, BAR3D, "none", FULL);
    struct sim *a = test_build(y);
    struct sim *b = test_build(y);
    assert_non_null(a);
    assert_non_null(b);
    sph_set_split_loops(b->model);
    test_run_to_end(a);
    test_run_to_end(b);
    print_message("3D fused vs split: max |dx| = %.3g m\n", max_diff(a, b));
    assert_true(max_diff(a, b) < 1e-12 * 0.012);
    sim_destroy(&a);
    sim_destroy(&b);
}

static void test_quarter_symmetry(void **state)
{
    (void)state;
    char y[2048];
    snprintf(y, sizeof y, BAR3D, "none", FULL);
    struct sim *full = test_build(y);
    snprintf(y, sizeof y, BAR3D, "xy", QUARTER);
    struct sim *q = test_build(y);
    assert_non_null(full);
    assert_non_null(q);
    assert_int_equal(q->p->n * 4, full->p->n);
    test_run_to_end(full);
    test_run_to_end(q);
    /* match each quarter particle to the full bar's particle with the same
     * initial position */
    double d = 0.0;
    size_t matched = 0;
    for (size_t i = 0; i < q->p->n; i++)
        for (size_t j = 0; j < full->p->n; j++) {
            double e = 0.0;
            for (int k = 0; k < 3; k++)
                e += fabs(q->p->x0[k][i] - full->p->x0[k][j]);
            if (e > 1e-9)
                continue;
            matched++;
            for (int k = 0; k < 3; k++)
                d = fmax(d, fabs(q->p->x[k][i] - full->p->x[k][j]));
        }
    assert_int_equal(matched, q->p->n);
    double moved = fabs(full->p->x[2][0] - full->p->x0[2][0]);
    assert_true(moved > 1e-6);
    print_message("quarter vs full: max |dx| = %.3g m (moved %.3g m)\n", d, moved);
    assert_true(d < 1e-9 * 0.012);
    sim_destroy(&full);
    sim_destroy(&q);
}

/* Ghost filling and the fused loop run in parallel: the quarter bar must
 * give bitwise the same positions on 1 and 2 threads. */
static void test_symmetry_threads(void **state)
{
    (void)state;
    char y[2048];
    snprintf(y, sizeof y, BAR3D, "xy", QUARTER);
    omp_set_num_threads(1);
    struct sim *a = test_build(y);
    assert_non_null(a);
    test_run_to_end(a);
    omp_set_num_threads(2);
    struct sim *b = test_build(y);
    assert_non_null(b);
    test_run_to_end(b);
    assert_true(max_diff(a, b) == 0.0);
    sim_destroy(&a);
    sim_destroy(&b);
}

static void test_vec_rows_3d(void **state)
{
    (void)state;
    char y[2048];
    snprintf(y, sizeof y, BAR3D, "none", FULL);
    vec_vs_scalar(y, "3D bar");
}

/* 2D Wendland, variable h (h_i != h_j pairs), AV with a fixed length, XSPH */
static const char *BLOCK2D_VH =
    "model: {type: sph, kernel: wendland, h_factor: 1.3, viscosity: [1.0, 1.0],\n"
    "        viscosity_length: 1.2e-3, xsph: 0.5, plane: strain, variable_h: true}\n"
    "materials: {m: {density: 1000, youngs_modulus: 1.0e7, poisson_ratio: 0.3}}\n"
    "lattice: {type: square, spacing: 1.0e-3, origin: [0.0005, 0.0005]}\n"
    "body: {geometry: {box: {min: [0, 0], max: [0.012, 0.008]}}, material: m}\n"
    "groups: {left: {box: {min: [0, 0], max: [0.004, 1]}}}\n"
    "initial_velocity: [{group: left, value: [40.0, 10.0]}]\n"
    "run: {steps: 60}\n";

static void test_vec_rows_2d(void **state)
{
    (void)state;
    vec_vs_scalar(BLOCK2D_VH, "2D variable h");
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_fused_vs_split_2d),
        cmocka_unit_test(test_fused_vs_split_3d),
        cmocka_unit_test(test_quarter_symmetry),
        cmocka_unit_test(test_symmetry_threads),
        cmocka_unit_test(test_vec_rows_3d),
        cmocka_unit_test(test_vec_rows_2d),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
