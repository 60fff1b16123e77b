/**
 * @file sph_fixture.c
 * @brief The SPH model's bodies for the model contract test
 *        (tests/test_model_contract.c), one per formulation: updated
 *        Lagrangian (seed 004) and total Lagrangian (sph_tlsph.c), elastic,
 *        without artificial viscosity (an elastic free body conserves energy).
 */
#include "models/model.h"

const struct model_fixture sph_fixtures[] = {
    {"sph-updated",
     "model: {type: sph, formulation: updated, viscosity: [0, 0]}\n"
     "materials:\n  m: {density: 1000, youngs_modulus: 1.0e7, poisson_ratio: 0.3}\n",
     "square", 1.0e-3},
    {"sph-total",
     "model: {type: sph, formulation: total, viscosity: [0, 0]}\n"
     "materials:\n  m: {density: 1000, youngs_modulus: 1.0e7, poisson_ratio: 0.3}\n",
     "square", 1.0e-3},
    {NULL, NULL, NULL, 0.0}};
