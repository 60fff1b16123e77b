/**
 * @file sph_plate.h
 * @brief Driver of the SPH oscillating-plate runs (validation/sph_plate.c):
 *        Gray, Monaghan & Swift (2001) plate, clamped or free-free.
 */
#ifndef SPALL_VALIDATION_SPH_PLATE_H
#define SPALL_VALIDATION_SPH_PLATE_H

#include <stdbool.h>
#include <stddef.h>

struct spall_error;

/** How the plate is held. */
enum sph_plate_clamp {
    SPH_PLATE_FREE,   /**< free-free plate of length L, no clamp */
    SPH_PLATE_FIXED,  /**< L/4 of fixed particles behind x = 0 (Gray et al.) */
    SPH_PLATE_MIRROR  /**< the same particles as a mirrored clamp (model.clamp) */
};

/** Outcome of one run. */
struct sph_plate_result {
    double period;  /**< time of the tip's first up-crossing after a down-crossing [s] */
    double half;    /**< 2 x the time of the first down-crossing [s] */
    size_t np;      /**< particles */
    long steps;     /**< steps run */
    double balance; /**< energy balance at the end [J] */
    double energy0; /**< initial kinetic energy [J] */
};

/** First-mode period of the plate with @p rows particles over H; with
 *  @p half_only stop at the first down-crossing (period = NaN).
 *  @p model: the model keys besides "plane: strain", the type among them
 *  (flow-mapping text, e.g. "type: sph, kernel: cubic_spline, h_factor: 1.5,
 *  cspm: true, time_integration: leapfrog, viscosity: [0.1, 0.1]"). */
int sph_plate_run(int rows, const char *model, enum sph_plate_clamp clamp, bool half_only,
                  struct sph_plate_result *out, struct spall_error *err);

/** Thin-plate (plane strain) first-mode period: cantilever (kL = 1.875104)
 *  or free-free (kL = 4.730041) [s]. */
double sph_plate_theory_period(enum sph_plate_clamp clamp);

#endif
