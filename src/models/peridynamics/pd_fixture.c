/**
 * @file pd_fixture.c
 * @brief The peridynamics model's body for the model contract test
 *        (tests/test_model_contract.c): PMB with the surface correction on,
 *        so the pair factor (the mean of the two particles' factors) is part
 *        of what Newton's third law checks; unbreakable at the test's strains.
 */
#include "models/model.h"

const struct model_fixture pd_fixtures[] = {
    {"peridynamics-pmb-surface",
     "model: {type: peridynamics, surface_correction: true}\n"
     "materials:\n  m: {density: 2000, youngs_modulus: 1.0e9, critical_stretch: 0.5}\n",
     "square", 1.0e-3},
    {NULL, NULL, NULL, 0.0}};
