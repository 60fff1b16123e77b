/**
 * @file cases.c
 * @brief Registry of the built-in validation cases (`spall validate`).
 *        Adding a case = one row here; the CLI and the quick test iterate it.
 */
#include "validation/lattice_cases.h"
/* impact cases header */
#include "validation/thermal_cases.h"

/* peridynamics cases header */

/* macro-particle cases header */

/* sph cases header */

/* penetration cases header */

#include "validation/validation.h"

static const struct vcase cases[] = {
    {"lattice-patch", "lattice patch test: E and nu of every calibrated lattice", true,
     lattice_case_patch},
    {"lattice-waves", "seed 000 sec. 4.1 wave speeds, 1D chain and 2D strip", true,
     lattice_case_waves},
    {"lattice-energy", "energy conservation of an elastic alpha-beta plate (Verlet, dt^2)", true,
     lattice_case_energy},
    {"lattice-chain-break", "slowly pulled chain breaks at eps_max = sigma_TS / E", true,
     lattice_case_chain_break},
    {"lattice-threads", "1 and 2 OpenMP threads: bitwise identical fracture run", true,
     lattice_case_threads},
    /* impact, fragments, thermal lattice (issue 3) */
    {"thermal-conduction", "thermal lattice: 1D conduction from a fixed-temperature end vs erfc",
     true, thermal_case_conduction},
    {"thermal-expansion", "thermal lattice: free expansion strain alpha dT of a heated plate", true,
     thermal_case_expansion},

    /* peridynamics (issue 4) */

    /* macro-particle (issue 5) */

    /* SPH (issue 6) */

    /* penetration (issue 7) */

};

const struct vcase *validation_cases(size_t *n)
{
    *n = sizeof cases / sizeof cases[0];
    return cases;
}
