/**
 * @file test_sph_axisym_vec.c
 * @brief The axisymmetric pair sums as vector rows (sph_axisym_vec.c)
 *        against the scalar loops of sph_axisym.c (sph_set_scalar_rows):
 *        bitwise the same positions and velocities after an impact on the
 *        wall with AV, XSPH and the axis images, with fixed and with
 *        variable h (pairs of unequal h), on 1 and 2 threads.
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

/* a short iron rod, 8 rings across, onto the wall at 221 m/s
 * (tests/test_sph_axisym_wall.c), 120 steps */
static const char *ROD =
    "model: {type: sph, kernel: wendland, h_factor: 1.5, viscosity: [1.0, 1.0], xsph: 0.1,\n"
    "        plane: axisymmetric, variable_h: %s, wall: {point: [0, 0], normal: [0, 1]}}\n"
    "materials:\n"
    "  iron: {density: 7850, youngs_modulus: 208.0e9, poisson_ratio: 0.3,\n"
    "         eos: mie_gruneisen, sound_speed: 3630, hugoniot_slope: 1.80,\n"
    "         gruneisen: 1.80, yield: perfect, yield_stress: 600.0e6}\n"
    "lattice: {type: square, spacing: 9.525e-4, origin: [4.7625e-4, 4.7625e-4]}\n"
    "body: {geometry: {box: {min: [0, 0], max: [0.00381, 0.0254]}}, material: iron}\n"
    "initial_velocity: [{group: all, value: [0, -221.0]}]\n"
    "run: {steps: 120, dt_factor: 0.3}\n";

static void vec_vs_scalar_rod(const char *variable_h, int threads)
{
    char y[2048], what[64];
    snprintf(y, sizeof y, ROD, variable_h);
    snprintf(what, sizeof what, "rod, variable_h %s, %d thread(s)", variable_h, threads);
    omp_set_num_threads(threads);
    vec_vs_scalar(y, what);
}

static void test_fixed_h(void **state)
{
    (void)state;
    vec_vs_scalar_rod("false", 1);
    vec_vs_scalar_rod("false", 2);
}

static void test_variable_h(void **state)
{
    (void)state;
    vec_vs_scalar_rod("true", 2);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_fixed_h),
        cmocka_unit_test(test_variable_h),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
