/**
 * @file test_tlsph_bar.h
 * @brief The small TLSPH copper Taylor bar (about 280 particles, dx = 1 mm,
 *        227 m/s onto a wall) shared by the TLSPH tests: one deck text
 *        instead of one per test file.  Include after test_support.h.
 */
#ifndef SPALL_TEST_TLSPH_BAR_H
#define SPALL_TEST_TLSPH_BAR_H

#include <stdio.h>

/** The bar with @p extra model keys (text appended inside `model: {...}`,
 *  starting with a space), run for @p steps steps; the test fails if it
 *  does not build. */
static inline struct sim *test_tlsph_bar(const char *extra, long steps)
{
    char yaml[1024];
    snprintf(yaml, sizeof yaml,
             "model: {type: tlsph, kernel: wendland, h_factor: 1.005,%s\n"
             "        viscosity: [1.0, 1.0], wall: {point: [0, 0, 0], normal: [0, 0, 1]}}\n"
             "materials:\n"
             "  copper: {density: 8930, youngs_modulus: 117.0e9, poisson_ratio: 0.35,\n"
             "           yield: power, yield_a: 0.4e9, yield_b: 0.1e9, yield_n: 1.0}\n"
             "lattice: {type: sc, spacing: 1.0e-3, origin: [0.0005, 0.0005, 0.0005]}\n"
             "body: {geometry: {cylinder: {base: [0, 0, 0], top: [0, 0, 0.010], "
             "radius: 0.003}},\n"
             "       material: copper}\n"
             "initial_velocity: [{group: all, value: [0, 0, -227.0]}]\n"
             "run: {steps: %ld}\n",
             extra, steps);
    return test_build_ok(yaml);
}

#endif
