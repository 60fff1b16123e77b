/**
 * @file pen_cases.h
 * @brief Validation cases of the analytical penetration models ([Meng2021]
 *        sec. 4.2, include/spall/penetration.h), registered under the
 *        penetration marker of validation/cases.c; numbers in
 *        docs/notes/validation-log.md.
 */
#ifndef SPALL_VALIDATION_PEN_CASES_H
#define SPALL_VALIDATION_PEN_CASES_H

#include <stddef.h>

struct spall_error;
struct vreport;

/** "pen-check-value": the digest's check value, Eq. 4.6 / 4.7. */
int pen_case_check_value(struct vreport *r, struct spall_error *err);
/** "pen-ode": GSL-integrated P(t) against the closed forms (Poncelet, Liu)
 *  and the ODE end point against an independent quadrature (MCG). */
int pen_case_ode(struct vreport *r, struct spall_error *err);
/** "pen-fit-synthetic": fits (approaches a and b, all three models) recover
 *  the coefficients that generated synthetic data. */
int pen_case_fit_synthetic(struct vreport *r, struct spall_error *err);
/** "pen-thesis-refs": the data files of data/penetration against the
 *  library (recorded references for the SPH cases, Re < 1e5, gelatin P_max). */
int pen_case_thesis_refs(struct vreport *r, struct spall_error *err);
/** "pen-gelatin-time": Poncelet stopping time against the experiment's
 *  200-250 ns (known gap, explained). */
int pen_case_gelatin_time(struct vreport *r, struct spall_error *err);
/** The gelatin deck of validation/pen_sph.c (= examples/pen_sph_gelatin at
 *  dx1 = d/10, width 1): silica 7.38 um at @p v0 [m/s] into gelatin of
 *  modulus @p E [Pa], finest spacing @p dx1 [m], outer levels scaled by
 *  @p width, run to @p t_end [s]; YAML into @p buf (also used by the bench). */
void pen_sph_deck(char *buf, size_t len, double v0, double E, double dx1, double width,
                  double t_end);
/** "pen-sph-gelatin": axisymmetric SPH, silica 7.38 um into gelatin at
 *  1290 m/s (validation/pen_sph.c): P_max, its time, cavity diameters. */
int pen_case_sph_gelatin(struct vreport *r, struct spall_error *err);
/** "pen-sph-gelatin-sweep": P_max/d at 200-1420 m/s vs Poncelet + d/2. */
int pen_case_sph_sweep(struct vreport *r, struct spall_error *err);
/** "pen-sph-gelatin-modulus": E = 1, 10, 20, 40 MPa at 1290 m/s (trend). */
int pen_case_sph_modulus(struct vreport *r, struct spall_error *err);
/** "pen-sph-gelatin-convergence": resolution and target width at 1290 m/s in
 *  the converging form (fixed AV length, contact offset dx1/2). */
int pen_case_sph_convergence(struct vreport *r, struct spall_error *err);
/** "pen-sph-gelatin-av": fixed-length AV and Balsara switch, d/10-d/20. */
int pen_case_sph_av_forms(struct vreport *r, struct spall_error *err);

#endif
