/**
 * @file sph_cases.h
 * @brief Validation cases of the SPH model (seed 004 chapter 3), run by
 *        `spall validate` through validation/cases.c.  Numbers are
 *        tabulated in docs/validation.md.
 */
#ifndef SPALL_VALIDATION_SPH_CASES_H
#define SPALL_VALIDATION_SPH_CASES_H

struct vreport;
struct spall_error;

/** "sph-gradient": CSPM reproduces a linear velocity field's gradient
 *  exactly, free surfaces included (fast, quick suite). */
int sph_case_gradient(struct vreport *r, struct spall_error *err);
/** "sph-beam": cantilever, 1.75 kN, six kernels vs 33.59 mm (Table 3.4). */
int sph_case_beam(struct vreport *r, struct spall_error *err);
/** "sph-beam-large": cantilever, 17.5 kN, six kernels and TLSPH vs 81.1 mm,
 *  which kernels crack (seed 004 sec. 3.4.1). */
int sph_case_beam_large(struct vreport *r, struct spall_error *err);
/** "sph-leapfrog": the leapfrog keeps an undamped plate's energy (quick). */
int sph_case_leapfrog(struct vreport *r, struct spall_error *err);
/** "sph-plate": oscillating plate period vs thin-plate theory (Gray et al. 2001). */
int sph_case_plate(struct vreport *r, struct spall_error *err);
/** "sph-taylor-3d": 4340 steel Taylor bar, 181 m/s, Johnson-Cook (Table 3.6). */
int sph_case_taylor3d(struct vreport *r, struct spall_error *err);

#endif
