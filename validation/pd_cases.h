/**
 * @file pd_cases.h
 * @brief Validation cases of the peridynamics model (issue 4), run by
 *        `spall validate` through validation/cases.c.  Numbers are
 *        tabulated in docs/notes/validation-log.md (peridynamics section).
 */
#ifndef SPALL_VALIDATION_PD_CASES_H
#define SPALL_VALIDATION_PD_CASES_H

struct spall_error;
struct vreport;

/** "pd-waves": 1D bar and 2D plate wave speeds vs sqrt(E/rho) and the
 *  plane-stress P speed. */
int pd_case_waves(struct vreport *r, struct spall_error *err);
/** "pd-lamina-elastic": 0 deg lamina in tension, centreline displacement. */
int pd_case_lamina_elastic(struct vreport *r, struct spall_error *err);
/** "pd-calibrate": PMB / PDLM / lamina patch tests (achieved moduli). */
int pd_case_patch(struct vreport *r, struct spall_error *err);

/** "pd-lamina-a": open-hole T700 laminae, A-90 ([PDLM2019] sec. 5.3). */
int pd_case_lamina_a(struct vreport *r, struct spall_error *err);
/** "pd-lamina-b": line-crack laminae B-theta-alpha incl. mixed mode (sec. 5.3-5.4). */
int pd_case_lamina_b(struct vreport *r, struct spall_error *err);

/** "pd-branching": Ha & Bobaru 2010 glass plate, branching and tip speed. */
int pd_case_branching(struct vreport *r, struct spall_error *err);
/** "pd-kalthoff": Kalthoff-Winkler crack angle. */
int pd_case_kalthoff(struct vreport *r, struct spall_error *err);

/** "pd-lps-patch": LPS E and nu for nu = 0.1, 0.3, 0.45, 2D and 3D (pd_lps_cases.c). */
int pd_case_lps_patch(struct vreport *r, struct spall_error *err);
/** "pd-lps-surface": E and nu of small bodies with the LPS surface correction (pd_lps_surface.c). */
int pd_case_lps_surface(struct vreport *r, struct spall_error *err);
/** "pd-interface-crack": a crack along the weaker interface (pd_interface_crack.c). */
int pd_case_interface_crack(struct vreport *r, struct spall_error *err);
/** "pd-lps-waves": LPS P-wave speed in a 2D plate (pd_lps_cases.c). */
int pd_case_lps_waves(struct vreport *r, struct spall_error *err);
/** "pd-bimaterial-bar": 1D two-material bar, T and R against the impedance formula. */
int pd_case_bimaterial(struct vreport *r, struct spall_error *err);
/** "pd-kalthoff-lps": Kalthoff-Winkler crack angle with LPS (pd_kalthoff_lps.c). */
int pd_case_kalthoff_lps(struct vreport *r, struct spall_error *err);
/** "pd-eps-bar": EPS bar pulled past yield and unloaded (pd_eps_bar.c). */
int pd_case_eps_bar(struct vreport *r, struct spall_error *err);

/** The Kalthoff-Winkler plate of pd-kalthoff and pd-kalthoff-lps, after
 *  the model, material and lattice lines: 200 x 100 mm, two notches from
 *  the impact edge at +-25.5 mm to 50.5 mm, the 50 mm between them struck
 *  at 32 m/s, 90 us ([Silling2003] set-up). */
#define PD_KALTHOFF_PLATE_YAML                                                                    \
    "geometry:\n  plate: {box: {min: [-1e-5, -0.05001], max: [0.20001, 0.05001]}}\n"             \
    "body: {geometry: plate, material: steel}\n"                                                  \
    "precracks:\n  - {from: [-0.001, 0.0255], to: [0.0505, 0.0255]}\n"                          \
    "  - {from: [-0.001, -0.0255], to: [0.0505, -0.0255]}\n"                                     \
    "groups:\n  impact: {box: {min: [-1, -0.025], max: [0.0025, 0.025]}}\n"                     \
    "boundary_conditions:\n"                                                                      \
    "  - {group: impact, type: velocity, components: [x], value: 32.0}\n"                         \
    "run: {end_time: 90.0e-6}\n"

#endif
