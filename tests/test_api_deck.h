/* The deck of the public C API's tests (test_api.c, test_api_setup.c): a 2D
 * lattice strip, left edge driven at 0.6 m/s, right edge fixed. */
#ifndef SPALL_TEST_API_DECK_H
#define SPALL_TEST_API_DECK_H

static const char *DECK =
    "model: {type: lattice, law: linear}\n"
    "materials:\n"
    "  polymer: {density: 1140, youngs_modulus: 3.0e9, poisson_ratio: 0.3333333333333333,\n"
    "            failure_strain: 1.0}\n"
    "lattice: {type: triangular, spacing: 1.0e-3}\n"
    "geometry:\n"
    "  strip: {box: {min: [-0.0004, -0.0001], max: [0.0195, 0.0052]}}\n"
    "body: {geometry: strip, material: polymer}\n"
    "groups:\n"
    "  left: {box: {min: [-0.001, -1], max: [0.0006, 1]}}\n"
    "  right: {box: {min: [0.0188, -1], max: [0.021, 1]}}\n"
    "boundary_conditions:\n"
    "  - {group: left, type: velocity, components: [x], value: 0.6}\n"
    "  - {group: right, type: fixed}\n"
    "run: {end_time: 4.0e-6}\n"
    "output: {field_interval: 1.0e-6, fields: [position, velocity]}\n";

#endif
