/**
 * @file cases.c
 * @brief Registry of the built-in validation cases (`spall validate`).
 *        Adding a case = one row here; the CLI and the quick test iterate it.
 */
#include "validation/lattice_cases.h"
/* impact cases header */

/* peridynamics cases header */

/* macro-particle cases header */
#include "validation/macro_cases.h"

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

    /* peridynamics (issue 4) */

    /* macro-particle (issue 5) */
    {"macro-calibration", "seed 001 Table 1: E from Eq. 15 for Al and Cu", false,
     macro_case_calibration},
    {"macro-rod-elastic", "seed 001 sec. 2.6 rod: E and nu vs n_phi and n_h/n_phi", true,
     macro_case_rod_elastic},
    {"macro-thermostat", "seed 001 Langevin forces: free block settles to T (absolute, pairwise)",
     true, macro_case_thermostat},
    {"macro-rod-large", "seed 001 sec. 2.6 rod: tension vs compression, compressive collapse",
     false, macro_case_rod_large},
    {"macro-rod-plastic", "seed 001 sec. 2.6 rod with Eq. 16 plasticity: yield, hardening, loop",
     true, macro_case_rod_plastic},

    /* SPH (issue 6) */

    /* penetration (issue 7) */

};

const struct vcase *validation_cases(size_t *n)
{
    *n = sizeof cases / sizeof cases[0];
    return cases;
}
