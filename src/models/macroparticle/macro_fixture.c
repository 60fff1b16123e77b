/**
 * @file macro_fixture.c
 * @brief The macro-particle model's body for the model contract test
 *        (tests/test_model_contract.c): aluminium Mie pairs on FCC ([Saitoh]),
 *        no Langevin bath (a free elastic body: random forces would break the
 *        energy and frame checks by design).
 */
#include "core/model.h"

const struct model_fixture macro_fixtures[] = {
    {.label = "macroparticle-fcc",
     .deck = "model: {type: macroparticle}\n"
             "materials:\n  m: {density: 2700, atomic_mass_u: 26.98, cohesive_energy_ev: 3.39, "
             "exponents: [4, 9]}\n",
     .lattice = "fcc",
     .spacing = 1.0e-3},
    {.label = NULL}};
