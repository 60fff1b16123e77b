/**
 * @file cases.c
 * @brief Registry of the built-in validation cases (`spall validate`).
 *        Adding a case = one row here; the CLI and the quick test iterate it.
 */
#include "validation/lattice_cases.h"
/* impact cases header */
#include "validation/impact_cases.h"
#include "validation/thermal_cases.h"

/* peridynamics cases header */
#include "validation/pd_cases.h"

/* macro-particle cases header */
#include "validation/macro_cases.h"

/* sph cases header */
#include "validation/sph_cases.h"

/* penetration cases header */
#include "validation/pen_cases.h"
#include "validation/pen_sph_setup.h"

#include "validation/validation.h"

#include <stddef.h>

/* Passes that hold at one resolution only: the checks pass at d/10, the
 * converged answer is elsewhere (pen-sph-gelatin-convergence,
 * pen-sph-sebs-convergence; docs/notes/validation-log.md). */
#define STATUS_PEN_SPH_GELATIN                                                                   \
    "PASS at d/10 only: the converged depth with the same material data is about 80 um "        \
    "(73-86 um, +19 % against the 67 um experiment; pen-sph-gelatin-convergence)"
#define STATUS_PEN_SPH_GELATIN_MODULUS                                                           \
    "PASS at d/10 only: at the converged resolution every depth is deeper (20 MPa: about 80 "   \
    "um, +19 %), so the modulus closest to 67 um is not 20 MPa (at d/15, 40 MPa is)"
#define STATUS_PEN_SPH_SEBS                                                                      \
    "PASS at d/10 only: d/15 deepens every shot by 22-27 % and 3 of the 5 E = 40 MPa shots "    \
    "then miss the 15 %; the converging form is pen-sph-sebs-convergence"

static const struct vcase cases[] = {
    {"lattice-patch", "lattice patch test: E and nu of every calibrated lattice",
     VKIND_VERIFICATION, VGATE_QUICK, NULL, lattice_case_patch},
    {"lattice-waves", "[Wang2010] sec. 4.1 wave speeds, 1D chain and 2D strip",
     VKIND_VERIFICATION, VGATE_FULL, NULL, lattice_case_waves},
    {"lattice-energy", "energy conservation of an elastic alpha-beta plate (Verlet, dt^2)",
     VKIND_VERIFICATION, VGATE_QUICK, NULL, lattice_case_energy},
    {"lattice-chain-break", "slowly pulled chain breaks at eps_max = sigma_TS / E",
     VKIND_VERIFICATION, VGATE_QUICK, NULL, lattice_case_chain_break},
    {"lattice-threads", "1 and 2 OpenMP threads: bitwise identical fracture run",
     VKIND_VERIFICATION, VGATE_FULL, NULL, lattice_case_threads},
    {"abg-patch", "triple honeycomb (alpha-beta-gamma), nu > 1/3: patch, clamped block, P wave",
     VKIND_VERIFICATION, VGATE_FULL, NULL, lattice_case_abg},
    /* impact, fragments, thermal lattice (issue 3) */
    {"impact-nylon", "[Wang2010] sec. 3.2.1 nylon-6,6 drop-weight indentation, no-slip tup",
     VKIND_VALIDATION, VGATE_FULL, NULL, impact_case_nylon},
    {"impact-vinylester", "[Wang2010] sec. 3.2.2 vinyl ester drop-weight indentation",
     VKIND_VALIDATION, VGATE_FULL, NULL, impact_case_vinylester},
    {"impact-spall", "[Wang2010] sec. 4.2 flyer-plate spall at 260 m/s, long and short flyer",
     VKIND_VALIDATION, VGATE_FULL, NULL, impact_case_spall},
    {"impact-epoxy", "[Wang2010] sec. 3.1 epoxy plate with holes in tension: cracks link holes",
     VKIND_VALIDATION, VGATE_FULL, NULL, impact_case_epoxy},
    {"impact-punch", "[Wang2010] sec. 3.2.3 3D vinyl ester punch-shear, no-slip and friction",
     VKIND_VALIDATION, VGATE_OFF, NULL, impact_case_punch},
    {"thermal-conduction", "thermal lattice: 1D conduction from a fixed-temperature end vs erfc",
     VKIND_VERIFICATION, VGATE_QUICK, NULL, thermal_case_conduction},
    {"thermal-expansion", "thermal lattice: free expansion strain alpha dT of a heated plate",
     VKIND_VERIFICATION, VGATE_QUICK, NULL, thermal_case_expansion},

    /* peridynamics (issue 4) */
    {"pd-waves", "PMB wave speeds: 1D bar and 2D plate vs analytical",
     VKIND_VERIFICATION, VGATE_FULL, NULL, pd_case_waves},
    {"pd-lamina-elastic", "0 deg T700 lamina in tension (ADR): centreline displacement",
     VKIND_VERIFICATION, VGATE_FULL, NULL, pd_case_lamina_elastic},
    {"pd-branching", "Ha & Bobaru 2010 glass plate: branching, tip speed < c_R",
     VKIND_VALIDATION, VGATE_FULL, NULL, pd_case_branching},
    {"pd-kalthoff", "Kalthoff-Winkler plate: crack angle 65-72 deg",
     VKIND_VALIDATION, VGATE_FULL, NULL, pd_case_kalthoff},
    {"pd-lamina-a", "T700 open-hole laminae A-0/45/90: crack along fibers, start",
     VKIND_VALIDATION, VGATE_QUICK, NULL, pd_case_lamina_a},
    {"pd-lamina-b", "T700 line-crack laminae B-theta-alpha (mixed mode): crack along fibers",
     VKIND_VALIDATION, VGATE_QUICK, NULL, pd_case_lamina_b},
    {"pd-lps-patch", "LPS patch test: E and nu for nu = 0.1, 0.3, 0.45, 2D and 3D",
     VKIND_VERIFICATION, VGATE_FULL, NULL, pd_case_lps_patch},
    {"pd-lps-surface", "LPS surface correction: E and nu of small bodies with free surfaces",
     VKIND_VERIFICATION, VGATE_FULL, NULL, pd_case_lps_surface},
    {"pd-interface-crack", "LPS plate of two materials: the crack runs along the weaker "
     "interface (45 deg)",
     VKIND_VERIFICATION, VGATE_FULL, NULL, pd_case_interface_crack},
    {"pd-lps-waves", "LPS P-wave speed in a 2D plate (nu = 0.3) vs analytical",
     VKIND_VERIFICATION, VGATE_FULL, NULL, pd_case_lps_waves},
    {"pd-kalthoff-lps", "Kalthoff-Winkler plate with LPS (plane strain, nu = 0.3): crack angle "
     "65-72 deg",
     VKIND_VALIDATION, VGATE_OFF, NULL, pd_case_kalthoff_lps},
    {"pd-bimaterial-bar", "1D PMB bar of two materials: wave transmission and reflection vs "
     "the impedance formula",
     VKIND_VERIFICATION, VGATE_FULL, NULL, pd_case_bimaterial},
    {"pd-eps-bar", "EPS bar: uniaxial yield, unloading and reverse yield vs the elastic-"
     "perfectly plastic bar",
     VKIND_VERIFICATION, VGATE_FULL, NULL, pd_case_eps_bar},

    /* macro-particle (issue 5) */
    {"macro-calibration", "[Saitoh] Table 1: E from Eq. 15 for Al and Cu",
     VKIND_VERIFICATION, VGATE_FULL, NULL, macro_case_calibration},
    {"macro-rod-elastic", "[Saitoh] sec. 2.6 rod: E and nu vs n_phi and n_h/n_phi",
     VKIND_VERIFICATION, VGATE_QUICK, NULL, macro_case_rod_elastic},
    {"macro-thermostat", "[Saitoh] Langevin forces: free block settles to T (absolute, pairwise)",
     VKIND_VERIFICATION, VGATE_QUICK, NULL, macro_case_thermostat},
    {"macro-rod-large", "[Saitoh] sec. 2.6 rod: tension vs compression, compressive collapse",
     VKIND_VALIDATION, VGATE_QUICK, NULL, macro_case_rod_large},
    {"macro-rod-plastic", "[Saitoh] sec. 2.6 rod with Eq. 16 plasticity: yield, hardening, loop",
     VKIND_VALIDATION, VGATE_QUICK, NULL, macro_case_rod_plastic},

    /* SPH (issue 6) */
    {"sph-gradient", "SPH: CSPM velocity gradient exact for linear fields (2D, 3D)",
     VKIND_VERIFICATION, VGATE_QUICK, NULL, sph_case_gradient},
    {"sph-plate", "SPH: oscillating plate period vs thin-plate theory (Gray et al. 2001)",
     VKIND_VALIDATION, VGATE_OFF, NULL, sph_case_plate},
    {"sph-beam", "SPH: cantilever beam 1.75 kN, six kernels vs 33.59 mm ([Meng2021] Table 3.4)",
     VKIND_VALIDATION, VGATE_OFF, NULL, sph_case_beam},
    {"sph-beam-large", "SPH: cantilever 17.5 kN, six kernels + TLSPH vs 81.1 mm, cracking",
     VKIND_VALIDATION, VGATE_OFF, NULL, sph_case_beam_large},
    {"sph-leapfrog", "SPH: leapfrog keeps an undamped plate's energy (PC does not)",
     VKIND_VERIFICATION, VGATE_QUICK, NULL, sph_case_leapfrog},
    {"sph-taylor-3d", "SPH: 4340 steel Taylor bar 181 m/s, Johnson-Cook ([Meng2021] Table 3.6); "
     "power-law bar against FE",
     VKIND_VALIDATION, VGATE_QUICK, NULL, sph_case_taylor3d},
    {"sph-taylor-2d", "SPH: iron rod on a wall, Mie-Grueneisen, perfectly plastic ([Meng2021] "
     "Table 3.5), axisymmetric, against FE",
     VKIND_VALIDATION, VGATE_QUICK, NULL, sph_case_taylor2d},
    {"sph-rings", "SPH: two rubber rings collide and rebound, energy balance (Gray et al. 2001)",
     VKIND_VERIFICATION, VGATE_FULL, NULL, sph_case_rings},
    {"sph-debris-cloud", "SPH: Al sphere 10 mm on a 4 mm Al plate at 6.18 km/s, debris-cloud "
     "length / width, hole (axisymmetric)",
     VKIND_VALIDATION, VGATE_QUICK, NULL, sph_case_debris},

    /* penetration (issue 7) */
    {"pen-sph-sebs", "axisymmetric SPH: steel 12-22 um into SEBS (E = 40, 50 MPa) vs Modified-CG",
     VKIND_VALIDATION, VGATE_OFF, STATUS_PEN_SPH_SEBS, pen_case_sph_sebs},
    {"pen-sph-sebs-convergence", "axisymmetric SPH: two SEBS shots at d/10-d/20 (fixed AV "
     "length, contact offset) vs Modified-CG",
     VKIND_VALIDATION, VGATE_OFF, NULL, pen_case_sph_sebs_convergence},
    {"pen-check-value", "[Meng2021] Eq. 4.6/4.7: silica 7.38 um into gelatin at 1290 m/s",
     VKIND_REGRESSION, VGATE_QUICK, NULL, pen_case_check_value},
    {"pen-ode", "GSL-integrated P(t) vs closed forms (Poncelet, Liu) and quadrature (MCG)",
     VKIND_VERIFICATION, VGATE_QUICK, NULL, pen_case_ode},
    {"pen-fit-synthetic", "fits (a) and (b) recover known Poncelet/Liu/MCG coefficients",
     VKIND_VERIFICATION, VGATE_QUICK, NULL, pen_case_fit_synthetic},
    {"pen-thesis-refs", "thesis data files vs Poncelet / Modified-CG; SPH reference tables",
     VKIND_REGRESSION, VGATE_QUICK, NULL, pen_case_thesis_refs},
    {"pen-gelatin-time", "Poncelet T_f vs the 200-250 ns of the gelatin experiment (known gap)",
     VKIND_VALIDATION, VGATE_FULL, NULL, pen_case_gelatin_time},
    {"pen-sph-gelatin", "axisymmetric SPH: silica 7.38 um into gelatin at 1290 m/s (P_max, time)",
     VKIND_VALIDATION, VGATE_OFF, STATUS_PEN_SPH_GELATIN, pen_case_sph_gelatin},
    {"pen-sph-gelatin-sweep", "axisymmetric SPH: P_max/d at 200-1420 m/s vs Poncelet + d/2",
     VKIND_VALIDATION, VGATE_OFF, NULL, pen_case_sph_sweep},
    {"pen-sph-gelatin-modulus", "axisymmetric SPH: E = 1-40 MPa at 1290 m/s (trend of P_max)",
     VKIND_VALIDATION, VGATE_OFF, STATUS_PEN_SPH_GELATIN_MODULUS, pen_case_sph_modulus},
    {"pen-sph-gelatin-convergence",
     "axisymmetric SPH: d/10-d/25 and width, 1290 m/s (fixed AV length, contact offset)",
     VKIND_VALIDATION, VGATE_OFF, NULL, pen_case_sph_convergence},
    {"pen-sph-gelatin-av", "axisymmetric SPH: fixed-length AV and Balsara switch, d/10-d/20",
     VKIND_VALIDATION, VGATE_OFF, NULL, pen_case_sph_av_forms},

};

const struct vcase *validation_cases(size_t *n)
{
    *n = sizeof cases / sizeof cases[0];
    return cases;
}
