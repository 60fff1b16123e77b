/**
 * @file sph_beam.h
 * @brief Shared driver of the SPH cantilever cases (validation/sph_beam_plate.c,
 *        validation/sph_beam_large.c): [Meng2021] sec. 3.4.1 beam, dx = 1 mm,
 *        plane stress, quadratic 1.5 ms load ramp; clamp = 3 fixed columns
 *        behind x = 0 (the thesis' form), 1 fixed column (the thesis' "left
 *        edge fixed" read literally) or the mirrored clamp
 *        (src/models/sph/sph_clamp.c) on 5 columns, symmetric about x = 0.
 */
#ifndef SPALL_VALIDATION_SPH_BEAM_H
#define SPALL_VALIDATION_SPH_BEAM_H

#include <stddef.h>

struct vreport;
struct spall_error;

/** Kernel names of [Meng2021] Fig. 3.1, types 1-6. */
extern const char *const SPH_BEAM_KERNELS[6];

/** Outcome of one beam run (deflections downwards positive) [m]. */
struct sph_beam_result {
    double mean;     /**< time mean of the tip deflection over 1.5-3.0 ms */
    double final;    /**< at 3 ms */
    double max;      /**< largest */
    double stretch;  /**< largest stretch of an initially adjacent pair (crack: >> 1) */
    double balance;  /**< energy balance at the end [J] */
    double external; /**< work of the load [J] */
};

/** Clamp forms of the beam. */
enum sph_beam_clamp {
    SPH_BEAM_FIXED = 0, /**< 3 columns of fixed particles behind x = 0 ([Meng2021]) */
    SPH_BEAM_MIRROR = 1, /**< model.clamp on 5 fixed columns: ghosts mirror the beam */
    SPH_BEAM_EDGE = 2    /**< 1 column of fixed particles behind x = 0 (the edge only) */
};

/** The beam's deck text (into @p deck, @p len bytes) for sph_beam_run. */
void sph_beam_deck(const char *kernel, double force, double hfac, const char *extra,
                   enum sph_beam_clamp clamp, char *deck, size_t len);
/** Run the beam with @p kernel, end load @p force [N], h = @p hfac dx,
 *  extra model keys @p extra (flow-mapping text; the model is type: sph
 *  unless @p extra starts with its own type, e.g. "type: tlsph, ") and
 *  clamp form @p clamp. */
int sph_beam_run(const char *kernel, double force, double hfac, const char *extra,
                 enum sph_beam_clamp clamp, struct sph_beam_result *out,
                 struct spall_error *err);
/** sph_beam_run, an unstable run noted in @p r and returned as mean = NaN;
 *  the outcome is printed as an info line. */
int sph_beam_run_or_note(struct vreport *r, const char *what, const char *kernel, double force,
                         double hfac, const char *extra, enum sph_beam_clamp clamp,
                         struct sph_beam_result *res, struct spall_error *err);

#endif
