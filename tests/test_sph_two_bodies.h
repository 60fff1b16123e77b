/**
 * @file test_sph_two_bodies.h
 * @brief Two plane-strain SPH blocks, one falling onto the other: the deck
 *        shared by the per-body formulation and re-referencing tests.
 *        Include after test_support.h.
 */
#ifndef SPALL_TEST_SPH_TWO_BODIES_H
#define SPALL_TEST_SPH_TWO_BODIES_H

#include <stdio.h>

/* The decks' head: plane-strain Wendland SPH with the model map's tail a
 * %s, materials a (soft) and b (stiff, dense), a 1 mm square lattice. */
#define TEST_SPH_AB_HEAD                                                                           \
    "model: {type: %s, kernel: wendland, h_factor: 1.3, viscosity: [0.5, 0.2],\n"                  \
    "        plane: strain%s}\n"                                                                    \
    "materials:\n"                                                                                  \
    "  a: {density: 1000, youngs_modulus: 1.0e7, poisson_ratio: 0.3}\n"                             \
    "  b: {density: 2000, youngs_modulus: 1.0e8, poisson_ratio: 0.3}\n"                             \
    "lattice: {type: square, spacing: 1.0e-3}\n"

/* Body 0 `target`: soft block 10 x 10 mm (material a); body 1 `proj`:
 * stiffer, denser block 6 x 6 mm, 2.5 mm above, at (vx, -50) m/s; dx =
 * 1 mm, plane strain; model @p type (sph or tlsph), @p model_extra
 * appended to the model map. */
static inline struct sim *test_two_bodies(const char *type, const char *model_extra, double vx,
                                          double gap_y)
{
    char yaml[2048];
    snprintf(yaml, sizeof yaml,
             TEST_SPH_AB_HEAD
             "geometry:\n"
             "  g1: {box: {min: [0, 0], max: [0.010, 0.010]}}\n"
             "  g2: {box: {min: [0.002, %g], max: [0.008, %g]}}\n"
             "bodies:\n"
             "  - {name: target, geometry: g1, material: a,\n"
             "     lattice: {spacing: 1.0e-3, origin: [0.0005, 0.0005]}}\n"
             "  - {name: proj, geometry: g2, material: b,\n"
             "     lattice: {spacing: 1.0e-3, origin: [0.0005, %g]}}\n"
             "groups: {top: g2}\n"
             "initial_velocity: [{group: top, value: [%g, -50]}]\n"
             "run: {end_time: 2.4e-4}\n",
             type, model_extra, 0.0115 + gap_y, 0.0175 + gap_y, 0.012 + gap_y, vx);
    return test_build(yaml);
}

#endif
