/**
 * @file cases.c
 * @brief Registry of the built-in validation cases (`spall validate`).
 *        Adding a case = one row here; the CLI and the quick test iterate it.
 */
#include "validation/lattice_cases.h"
/* impact cases header */

/* peridynamics cases header */

/* macro-particle cases header */

/* sph cases header */
#include "validation/sph_cases.h"

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

    /* SPH (issue 6) */
    {"sph-gradient", "SPH: CSPM velocity gradient exact for linear fields (2D, 3D)", true,
     sph_case_gradient},
    {"sph-plate", "SPH: oscillating plate period vs thin-plate theory (Gray et al. 2001)", false,
     sph_case_plate},
    {"sph-beam", "SPH: cantilever beam 1.75 kN, six kernels vs 33.59 mm (seed 004 Table 3.4)",
     false, sph_case_beam},
    {"sph-taylor-3d", "SPH: 4340 steel Taylor bar 181 m/s, Johnson-Cook (seed 004 Table 3.6)",
     false, sph_case_taylor3d},

    /* penetration (issue 7) */

};

const struct vcase *validation_cases(size_t *n)
{
    *n = sizeof cases / sizeof cases[0];
    return cases;
}
