/**
 * @file lattice_fixture.c
 * @brief The lattice model's body for the model contract test
 *        (tests/test_model_contract.c): a triangular lattice with nu = 0.25,
 *        so the alpha-beta angular springs (non-central forces, [Wang2010]
 *        Eq. 17) act besides the axial springs; unbreakable at the test's
 *        strains (~1e-3).
 */
#include "core/model.h"

const struct model_fixture lattice_fixtures[] = {
    {.label = "lattice-triangular-angular",
     .deck = "model: {type: lattice}\n"
             "materials:\n  m: {density: 2000, youngs_modulus: 1.0e9, poisson_ratio: 0.25, "
             "failure_strain: 0.5}\n",
     .lattice = "triangular",
     .spacing = 1.0e-3},
    {.label = NULL}};
