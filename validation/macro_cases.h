/**
 * @file macro_cases.h
 * @brief Validation cases of the macro-particle model ([Saitoh], issue 5).
 */
#ifndef SPALL_VALIDATION_MACRO_CASES_H
#define SPALL_VALIDATION_MACRO_CASES_H

#include "models/macroparticle/macro_calib.h"
#include "models/macroparticle/macro_slip.h"

#include <stdbool.h>
#include <stddef.h>

struct spall_error;
struct vreport;

/** "macro-calibration": Eq. 15 against Table 1 of [Saitoh]. */
int macro_case_calibration(struct vreport *r, struct spall_error *err);
/** "macro-rod-elastic": E and nu of the 14 mm rod over n_phi and n_h/n_phi. */
int macro_case_rod_elastic(struct vreport *r, struct spall_error *err);
/** "macro-rod-large": tension vs compression to 3.5 %, compressive collapse. */
int macro_case_rod_large(struct vreport *r, struct spall_error *err);
/** "macro-rod-plastic": tension with pair plasticity, load-unload-reload. */
int macro_case_rod_plastic(struct vreport *r, struct spall_error *err);
/** "macro-thermostat": a free block held at T by Langevin forces. */
int macro_case_thermostat(struct vreport *r, struct spall_error *err);

/** One rod run of [Saitoh] section 2.6 (see macro_rod.c). */
struct macro_rod {
    int n_phi;          /**< cubic cells across the 14 mm diameter */
    double n_h;         /**< cubic cells along the length (multiple of 1/2) */
    int sign;           /**< +1 tension, -1 compression */
    double eps_end;     /**< final |strain| */
    double transits;    /**< loading time in longitudinal wave transits */
    double yield_strain;/**< pair yield stretch / r0 (0: elastic) */
    const double (*table)[2]; /**< optional velocity table [t/T, f] (NULL: ramp) */
    int n_table;
    enum macro_calibration calibration; /**< eq15 (default) or lattice */
    double cutoff, taper; /**< r_c / r0, r_on / r0 (0: the model's 1.35, 1.2) */
    bool clamp;         /**< end layers also held in x, y (default: free laterally) */
    /* results */
    size_t n;           /**< samples */
    double *strain, *stress, *lateral; /**< owned, n samples; stress: nominal (engineering) */
    size_t particles;
    double r0, E_eq15, E_fcc100; /**< E_fcc100: lattice E_[100] of the pairs used */
    double end_time;
    /** original nearest-neighbour pairs stretched beyond 1.2 r0 at the end,
     *  by <110> family: (110) (1-10) (101) (10-1) (011) (01-1) */
    size_t broken[6];
    size_t bonds0;
    struct macro_slip_stats slip; /**< slip analysis at the end (threshold 0.25 r0, 10 deg) */
};

/** Builds and runs the rod; under mpirun (r's vpar) distributed, its
 *  measurements read the particles by global id (the serial values). */
int macro_rod_run(struct vreport *r, struct macro_rod *rod, struct spall_error *err);
void macro_rod_free(struct macro_rod *rod);
/** Least-squares slope of y(x) over samples with lo <= |x| <= hi. */
double macro_fit_slope(const double *x, const double *y, size_t n, double lo, double hi);

#endif
