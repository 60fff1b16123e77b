/**
 * @file pd_fixture.c
 * @brief The peridynamics model's bodies for the model contract test
 *        (tests/test_model_contract.c): PMB, and PMB with the surface
 *        correction (whose pair factor, the mean of the two particles'
 *        factors, is then part of what Newton's third law checks);
 *        unbreakable at the test's strains (~1e-3).
 */
#include "core/model.h"

const struct model_fixture pd_fixtures[] = {
    {.label = "peridynamics-pmb",
     .deck = "model: {type: peridynamics}\n"
             "materials:\n  m: {density: 2000, youngs_modulus: 1.0e9, critical_stretch: 0.5}\n",
     .lattice = "square",
     .spacing = 1.0e-3},
    {.label = "peridynamics-pmb-surface",
     .deck = "model: {type: peridynamics, surface_correction: true}\n"
             "materials:\n  m: {density: 2000, youngs_modulus: 1.0e9, critical_stretch: 0.5}\n",
     .lattice = "square",
     .spacing = 1.0e-3,
     .rotation_deg = 90.0,
     .why = "the surface factors are the family energies under stretches along the global x "
            "and y axes ([MadenciOterkus2014] Eq. 4.31), so the corrected body is invariant "
            "only under the lattice's own rotations; at 37 degrees the runs differ by 0.55 of "
            "the displacement"},
    {.label = "peridynamics-lps",
     .deck = "model: {type: peridynamics, formulation: lps}\n"
             "materials:\n  m: {density: 2000, youngs_modulus: 1.0e9, poisson_ratio: 0.4, "
             "critical_stretch: 0.5}\n",
     .lattice = "square",
     .spacing = 1.0e-3},
    {.label = "peridynamics-lps-3d",
     .deck = "model: {type: peridynamics, formulation: lps, influence: inverse}\n"
             "materials:\n  m: {density: 2000, youngs_modulus: 1.0e9, poisson_ratio: 0.1, "
             "critical_stretch: 0.5}\n",
     .lattice = "sc",
     .spacing = 1.0e-3},
    /* the cubic influence correction follows the deck's lattice angle */
    {.label = "peridynamics-lps-cubic",
     .deck = "model: {type: peridynamics, formulation: lps, influence_correction: cubic}\n"
             "materials:\n  m: {density: 2000, youngs_modulus: 1.0e9, poisson_ratio: 0.2, "
             "critical_stretch: 0.5}\n",
     .lattice = "square",
     .spacing = 1.0e-3},
    /* yield stress low enough that the perturbation (strains ~1e-3) flows */
    {.label = "peridynamics-eps",
     .deck = "model: {type: peridynamics, formulation: eps}\n"
             "materials:\n  m: {density: 2000, youngs_modulus: 1.0e9, poisson_ratio: 0.3, "
             "critical_stretch: 0.5, yield_stress: 2.0e5}\n",
     .lattice = "triangular",
     .spacing = 1.0e-3},
    {.label = NULL}};
