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

/* The tier columns of a row (validation.h, struct vcase): the whole case is
 * the standard tier; the standard tier is its working resolution and --full
 * adds levels (last full wall time in s, the full values with resolution);
 * a full-only case (last full wall time, why it is full-only). */
#define TIER_ALL VTIER_ALL, 0.0, NULL
#define TIER_REDUCED(wall_s, note) VTIER_REDUCED, (wall_s), (note)
#define TIER_FULL_ONLY(wall_s, note) VTIER_FULL_ONLY, (wall_s), (note)

static const struct vcase cases[] = {
    {"lattice-patch", "lattice patch test: E and nu of every calibrated lattice",
     VKIND_VERIFICATION, VGATE_QUICK, NULL, lattice_case_patch, TIER_ALL},
    {"lattice-waves", "[Wang2010] sec. 4.1 wave speeds, 1D chain and 2D strip",
     VKIND_VERIFICATION, VGATE_FULL, NULL, lattice_case_waves, TIER_ALL},
    {"lattice-energy", "energy conservation of an elastic alpha-beta plate (Verlet, dt^2)",
     VKIND_VERIFICATION, VGATE_QUICK, NULL, lattice_case_energy, TIER_ALL},
    {"lattice-chain-break", "slowly pulled chain breaks at eps_max = sigma_TS / E",
     VKIND_VERIFICATION, VGATE_QUICK, NULL, lattice_case_chain_break, TIER_ALL},
    {"lattice-threads", "1 and 2 OpenMP threads: bitwise identical fracture run",
     VKIND_VERIFICATION, VGATE_FULL, NULL, lattice_case_threads, TIER_ALL},
    {"abg-patch", "triple honeycomb (alpha-beta-gamma), nu > 1/3: patch, clamped block, P wave",
     VKIND_VERIFICATION, VGATE_FULL, NULL, lattice_case_abg, TIER_ALL},
    /* impact, fragments, thermal lattice (issue 3) */
    {"impact-nylon", "[Wang2010] sec. 3.2.1 nylon-6,6 drop-weight indentation, no-slip tup",
     VKIND_VALIDATION, VGATE_FULL, NULL, impact_case_nylon, TIER_ALL},
    {"impact-vinylester", "[Wang2010] sec. 3.2.2 vinyl ester drop-weight indentation",
     VKIND_VALIDATION, VGATE_FULL, NULL, impact_case_vinylester, TIER_ALL},
    {"impact-spall", "[Wang2010] sec. 4.2 flyer-plate spall at 260 m/s, long and short flyer",
     VKIND_VALIDATION, VGATE_FULL, NULL, impact_case_spall, TIER_ALL},
    {"impact-epoxy", "[Wang2010] sec. 3.1 epoxy plate with holes in tension: cracks link holes",
     VKIND_VALIDATION, VGATE_FULL, NULL, impact_case_epoxy, TIER_ALL},
    {"impact-punch", "[Wang2010] sec. 3.2.3 3D vinyl ester punch-shear, no-slip and friction",
     VKIND_VALIDATION, VGATE_OFF, NULL, impact_case_punch,
     TIER_ALL},
    {"thermal-conduction", "thermal lattice: 1D conduction from a fixed-temperature end vs erfc",
     VKIND_VERIFICATION, VGATE_QUICK, NULL, thermal_case_conduction, TIER_ALL},
    {"thermal-expansion", "thermal lattice: free expansion strain alpha dT of a heated plate",
     VKIND_VERIFICATION, VGATE_QUICK, NULL, thermal_case_expansion, TIER_ALL},

    /* peridynamics (issue 4) */
    {"pd-waves", "PMB wave speeds: 1D bar and 2D plate vs analytical",
     VKIND_VERIFICATION, VGATE_FULL, NULL, pd_case_waves, TIER_ALL},
    {"pd-lamina-elastic", "0 deg T700 lamina in tension (ADR): centreline displacement",
     VKIND_VERIFICATION, VGATE_FULL, NULL, pd_case_lamina_elastic, TIER_ALL},
    {"pd-branching", "Ha & Bobaru 2010 glass plate: branching, tip speed < c_R",
     VKIND_VALIDATION, VGATE_FULL, NULL, pd_case_branching, TIER_ALL},
    {"pd-kalthoff", "Kalthoff-Winkler plate: crack angle 65-72 deg",
     VKIND_VALIDATION, VGATE_FULL, NULL, pd_case_kalthoff, TIER_ALL},
    {"pd-lamina-a", "T700 open-hole laminae A-0/45/90: crack along fibers, start",
     VKIND_VALIDATION, VGATE_QUICK, NULL, pd_case_lamina_a,
     TIER_REDUCED(134.0,
         "all five open-hole laminae (A-0, A-45, A-90 and two option variants, dx = 0.5 mm, "
         "10-40 s each); last full values: angle 0.0 deg (A-0, A-90, A-45 with fiber_plane), "
         "60.0 deg (A-45; gap), starts 1.88 / 0.66 / 0.22 mm; 8 of 15 checks pass, 7 gaps "
         "(crack starts, the 45 deg hinge band, the G_IIc-off demonstration). Standard tier: "
         "A-0.")},
    {"pd-lamina-b", "T700 line-crack laminae B-theta-alpha (mixed mode): crack along fibers",
     VKIND_VALIDATION, VGATE_QUICK, NULL, pd_case_lamina_b,
     TIER_REDUCED(165.0,
         "all seven line-crack laminae (B-0-90, B-90-90, B-0-30/45/60, B-45-90, B-45-90 with "
         "fiber_plane; 10-40 s each); last full values: 0.0 deg except B-45-90 at 60.0 deg "
         "(gap; 0.0 deg with fiber_plane), starts 0.25-0.72 mm from the tip; 20 of 21 checks "
         "pass. Standard tier: B-0-45.")},
    {"pd-lps-patch", "LPS patch test: E and nu for nu = 0.1, 0.3, 0.45, 2D and 3D; at the "
     "default rule surface_correction position_aware meets 1 % in 2D and 3D",
     VKIND_VERIFICATION, VGATE_QUICK, NULL, pd_case_lps_patch, TIER_ALL},
    {"pd-lps-surface", "LPS surface correction: E, nu and G of small bodies with free "
     "surfaces (true; position_aware: G too)",
     VKIND_VERIFICATION, VGATE_FULL, NULL, pd_case_lps_surface, TIER_ALL},
    {"pd-interface-crack", "LPS plate of two materials: the crack runs along the weaker "
     "interface (45 deg)",
     VKIND_VERIFICATION, VGATE_FULL, NULL, pd_case_interface_crack, TIER_ALL},
    {"pd-lps-waves", "LPS P-wave speed in a 2D plate (nu = 0.3) vs analytical",
     VKIND_VERIFICATION, VGATE_FULL, NULL, pd_case_lps_waves, TIER_ALL},
    {"pd-kalthoff-lps", "Kalthoff-Winkler plate with LPS (plane strain, nu = 0.3, dx = 0.5 mm): "
     "crack angle 65-72 deg",
     VKIND_VALIDATION, VGATE_OFF, NULL, pd_case_kalthoff_lps, TIER_ALL},
    {"pd-bimaterial-bar", "1D PMB bar of two materials: wave transmission and reflection vs "
     "the impedance formula",
     VKIND_VERIFICATION, VGATE_FULL, NULL, pd_case_bimaterial, TIER_ALL},
    {"pd-eps-bar", "EPS bar: uniaxial yield, unloading and reverse yield vs the elastic-"
     "perfectly plastic bar",
     VKIND_VERIFICATION, VGATE_FULL, NULL, pd_case_eps_bar, TIER_ALL},

    /* macro-particle (issue 5) */
    {"macro-calibration", "[Saitoh] Table 1: E from Eq. 15 for Al and Cu",
     VKIND_VERIFICATION, VGATE_FULL, NULL, macro_case_calibration, TIER_ALL},
    {"macro-rod-elastic", "[Saitoh] sec. 2.6 rod: E and nu vs n_phi and n_h/n_phi",
     VKIND_VERIFICATION, VGATE_QUICK, NULL, macro_case_rod_elastic,
     TIER_REDUCED(205.0,
         "n_phi = 2-16 (eq15) and 2-32 (lattice), the finest-rod checks and the aspect-ratio "
         "sweeps up to the 51 413-particle rod; last full values (docs/notes/validation-"
         "log.md): lattice calibration n_phi = 32: 66.92 GPa (-3.7 %, PASS); eq15 n_phi = 16: "
         "120.9 GPa (gap); 51 413-particle rod 65.20 GPa (-6.2 %, gap); nu 0.343 / 0.351 / "
         "0.341 / 0.3345 at n_phi = 2 / 4 / 8 / 16 (the same in the full run of 2026-12-08: 376 "
         "CPU-s).")},
    {"macro-thermostat", "[Saitoh] Langevin forces: free block settles to T (absolute, pairwise)",
     VKIND_VERIFICATION, VGATE_QUICK, NULL, macro_case_thermostat, TIER_ALL},
    {"macro-rod-large", "[Saitoh] sec. 2.6 rod: tension vs compression, compressive collapse",
     VKIND_VALIDATION, VGATE_QUICK, NULL, macro_case_rod_large,
     TIER_ALL},
    {"macro-rod-plastic", "[Saitoh] sec. 2.6 rod with Eq. 16 plasticity: yield, hardening, loop",
     VKIND_VALIDATION, VGATE_QUICK, NULL, macro_case_rod_plastic,
     TIER_ALL},

    /* SPH (issue 6) */
    {"sph-gradient", "SPH: CSPM velocity gradient exact for linear fields (2D, 3D)",
     VKIND_VERIFICATION, VGATE_QUICK, NULL, sph_case_gradient, TIER_ALL},
    {"sph-plate", "SPH: oscillating plate period vs thin-plate theory (Gray et al. 2001)",
     VKIND_VALIDATION, VGATE_OFF, NULL, sph_case_plate,
     TIER_REDUCED(653.0,
         "TLSPH at 16 and 24 rows and the updated form at 10 rows; last full values: TLSPH 24 "
         "rows 0.25991 s (+2.31 %, PASS; 16 rows 0.26403 s), updated CSPM mirrored clamp 10 "
         "rows 0.27152 s (+6.88 %, gap). The standard tier (6 / 10 rows TLSPH, 6 rows updated)"
         " is too coarse for the 3 % on both rows: known gaps of that tier, with the cause in "
         "each note.")},
    {"sph-beam", "SPH: cantilever beam 1.75 kN, six kernels vs 33.59 mm ([Meng2021] Table 3.4)",
     VKIND_VALIDATION, VGATE_OFF, NULL, sph_case_beam,
     TIER_REDUCED(2261.0,
         "all 15 beam runs (six kernels, fixed and mirrored clamp, TLSPH) at dx = 1 mm; last "
         "full values: fixed clamp cubic 34.05, Gaussian 35.96, Wendland 35.56, double cosine "
         "34.83, hyperbolic 34.20 mm, quintic blows up (averaged AS 36.30 mm, gap), TLSPH "
         "32.69 mm; mirrored clamp 33.03-34.99 mm; 12 of 15 pass. Standard tier: the type 1 "
         "(cubic) and TLSPH rows with the fixed clamp at the same dx, so the same values as in"
         " the full run (34.05 mm, +1.37 %; 32.69 mm, -2.68 %).")},
    {"sph-beam-large", "SPH: cantilever 17.5 kN, six kernels + TLSPH vs 81.1 mm, cracking",
     VKIND_VALIDATION, VGATE_OFF, NULL, sph_case_beam_large,
     TIER_FULL_ONLY(3333.0,
         "dx = 1 mm is its working resolution and the 17.5 kN runs take minutes each (56 min "
         "wall, 64 CPU-min, 2026-12-08); last full values: TLSPH Wendland 83.70 mm "
         "(+3.2 %), edge clamp averaged AS 83.93 mm (+3.49 %); with the pointwise AS 0.9 every"
         " updated-form kernel cracks or blows up (gap); 3 of 5 pass.")},
    {"sph-leapfrog", "SPH: leapfrog keeps an undamped plate's energy (PC does not)",
     VKIND_VERIFICATION, VGATE_QUICK, NULL, sph_case_leapfrog, TIER_ALL},
    {"sph-taylor-3d", "SPH: 4340 steel Taylor bar 181 m/s, Johnson-Cook ([Meng2021] Table 3.6); "
     "power-law bar against FE",
     VKIND_VALIDATION, VGATE_QUICK, NULL, sph_case_taylor3d,
     TIER_ALL},
    {"sph-taylor-2d", "SPH: iron rod on a wall, Mie-Grueneisen, perfectly plastic ([Meng2021] "
     "Table 3.5), axisymmetric, against FE",
     VKIND_VALIDATION, VGATE_QUICK, NULL, sph_case_taylor2d,
     TIER_REDUCED(128.0,
         "n = 16, 32, 48 with the Richardson estimate, the FE checks and the AV forms; last "
         "full values: n = 48 (dx = 0.159 mm) L = 20.313 mm, R(0.5 mm) 6.409 mm, Richardson "
         "error 2.7 % (gap), thesis AV +3.27 % / -8.31 % against FE (gap), Balsara +1.44 % / "
         "-0.35 %, Taylor sigma 627 MPa (+4.4 %). Standard tier: n = 16 (dx = 0.476 mm), L = "
         "20.833 mm, Taylor sigma 708 MPa (+18 %) when recorded.")},
    {"sph-rings", "SPH: two rubber rings collide and rebound, energy balance (Gray et al. 2001)",
     VKIND_VERIFICATION, VGATE_FULL, NULL, sph_case_rings, TIER_ALL},
    {"sph-debris-cloud", "SPH: Al sphere 10 mm on a 4 mm Al plate at 6.18 km/s, debris-cloud "
     "length / width, hole (axisymmetric)",
     VKIND_VALIDATION, VGATE_QUICK, NULL, sph_case_debris,
     TIER_ALL},

    /* penetration (issue 7) */
    {"pen-sph-sebs", "axisymmetric SPH: steel 12-22 um into SEBS (E = 40, 50 MPa) vs Modified-CG",
     VKIND_VALIDATION, VGATE_OFF, STATUS_PEN_SPH_SEBS, pen_case_sph_sebs,
     TIER_REDUCED(1546.0,
         "the ten shots at d/10 (6031 particles each, 35-73 s CPU per shot, 554 s CPU for the "
         "ten); last full values: 66.92-176.34 um against MCG + d/2 73.90-159.79 um, -10.0 ..."
         " +10.4 %, 10 of 10 pass (at d/10 only, see status). Standard tier: E = 40 MPa, the "
         "20 um at 215 m/s and 12 um at 735 m/s shots at the same d/10, so the same values as "
         "in the full run (log: 67.33 um, -8.9 %; 175.09 um, +9.6 %).")},
    {"pen-sph-sebs-convergence", "axisymmetric SPH: two SEBS shots at d/10-d/20 (fixed AV "
     "length, contact offset) vs Modified-CG",
     VKIND_VALIDATION, VGATE_OFF, NULL, pen_case_sph_sebs_convergence,
     TIER_FULL_ONLY(3000.0,
         "a convergence study (d/10, d/15, d/20); last full values: 20 um shot 59.14 / 61.50 /"
         " 62.75 um, order 0.85; 12 um shot 156.25 / 162.10 / 163.13 um; d/20 -15.1 % (gap) "
         "and +2.1 % against MCG + d/2.")},
    {"pen-check-value", "[Meng2021] Eq. 4.6/4.7: silica 7.38 um into gelatin at 1290 m/s",
     VKIND_REGRESSION, VGATE_QUICK, NULL, pen_case_check_value, TIER_ALL},
    {"pen-ode", "GSL-integrated P(t) vs closed forms (Poncelet, Liu) and quadrature (MCG)",
     VKIND_VERIFICATION, VGATE_QUICK, NULL, pen_case_ode, TIER_ALL},
    {"pen-fit-synthetic", "fits (a) and (b) recover known Poncelet/Liu/MCG coefficients",
     VKIND_VERIFICATION, VGATE_QUICK, NULL, pen_case_fit_synthetic, TIER_ALL},
    {"pen-thesis-refs", "thesis data files vs Poncelet / Modified-CG; SPH reference tables",
     VKIND_REGRESSION, VGATE_QUICK, NULL, pen_case_thesis_refs, TIER_ALL},
    {"pen-gelatin-time", "Poncelet T_f vs the 200-250 ns of the gelatin experiment (known gap)",
     VKIND_VALIDATION, VGATE_FULL, NULL, pen_case_gelatin_time, TIER_ALL},
    {"pen-sph-gelatin", "axisymmetric SPH: silica 7.38 um into gelatin at 1290 m/s (P_max, time)",
     VKIND_VALIDATION, VGATE_OFF, STATUS_PEN_SPH_GELATIN, pen_case_sph_gelatin, TIER_ALL},
    {"pen-sph-gelatin-sweep", "axisymmetric SPH: P_max/d at 200-1420 m/s vs Poncelet + d/2",
     VKIND_VALIDATION, VGATE_OFF, NULL, pen_case_sph_sweep, TIER_ALL},
    {"pen-sph-gelatin-modulus", "axisymmetric SPH: E = 1-40 MPa at 1290 m/s (trend of P_max)",
     VKIND_VALIDATION, VGATE_OFF, STATUS_PEN_SPH_GELATIN_MODULUS, pen_case_sph_modulus, TIER_ALL},
    {"pen-sph-gelatin-convergence",
     "axisymmetric SPH: d/10-d/25 and width, 1290 m/s (fixed AV length, contact offset)",
     VKIND_VALIDATION, VGATE_OFF, NULL, pen_case_sph_convergence,
     TIER_FULL_ONLY(2400.0,
         "a convergence study (d/10-d/25 and 1.5x width); last full values: P_max 62.85 / "
         "66.90 / 69.27 / 70.99 um at d/10 / d/15 / d/20 / d/25, d/20 against d/25 -2.42 %, "
         "Richardson order 0.27 (gap), 1.5x width +0.02 %.")},
    {"pen-sph-gelatin-av", "axisymmetric SPH: fixed-length AV and Balsara switch, d/10-d/20",
     VKIND_VALIDATION, VGATE_OFF, NULL, pen_case_sph_av_forms,
     TIER_FULL_ONLY(4140.0,
         "a convergence study of two AV forms (d/10, d/15, d/20); last full values: fixed "
         "length 0.65 um 73.01 / 73.91 / 75.24 um, Balsara 77.32 / 84.63 / 90.13 um, no "
         "Richardson order (both gaps).")},

};

const struct vcase *validation_cases(size_t *n)
{
    *n = sizeof cases / sizeof cases[0];
    return cases;
}
