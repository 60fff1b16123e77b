/**
 * @file pd_kernel.h
 * @brief What the two bond-based PMB kernels share: the split kernel of
 *        pd_forces.c (every half-bond from its own row) and the
 *        once-per-bond loop of pd_half.c.  Internal to the peridynamics
 *        model.
 */
#ifndef SPALL_PD_KERNEL_H
#define SPALL_PD_KERNEL_H

#include "core/bond_list.h"

#include <math.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

struct model;
struct sim;

/* Energy released by a half-bond that breaks in this step: what the kicks
 * left of the bond's energy, not 1/4 coef e_{n+1}^2.  immediate: its force
 * at x_n acted half a step (1/4 coef e_{n+1} e_n, exact); next_step: its
 * force at x_{n+1} acts half a step more (1/4 coef e_{n+1} (e_{n+1} + de),
 * de ~ e_{n+1} - e_n).  x_n = x - dt u; (ex, ey, ez) = x_j - x_i, e0 = l - r. */
static inline double pd_break_energy(int dim, double ex, double ey, double ez, double r,
                                     double e0, double coef, double dt, double *const *u,
                                     size_t i, size_t j, bool late)
{
    const double px = ex - dt * (u[0][j] - u[0][i]);
    const double py = dim > 1 ? ey - dt * (u[1][j] - u[1][i]) : 0.0;
    const double pz = dim > 2 ? ez - dt * (u[2][j] - u[2][i]) : 0.0;
    const double en = sqrt(px * px + py * py + pz * pz) - r;
    return 0.25 * coef * e0 * (late ? 2.0 * e0 - en : en);
}

#define PD_CHUNK 64
#define PD_PRE (1.0 - 1e-12)

/* A row of the compact families' table as the kernel reads it: one cache
 * line for the three doubles of a half-bond, and its pre-test bound. */
struct pd_kind_row {
    double rest, coef, thr;
    unsigned type;
};

/* What the bond-based kernels (pd_forces.c, pd_half.c) read and write
 * besides the particle's row. */
struct pd_kctx {
    const size_t *off;
    const int32_t *partner;
    const double *rest, *coef; /* NULL: compact families (ktab) */
    const uint8_t *type;
    uint8_t *st;
    const uint16_t *kind;
    const struct pd_kind_row *ktab;
    const double *s0tab;
    double *const *x, *const *u;
    double dt;
    bool late;
    uint8_t *fresh;
};

/* One chunk of a row: half-bonds [s, s + nb) of particle i (row r of the
 * block) at (xi0, yi0, zi0), and the buffers of passes 0 and 1. */
struct pd_chunk_buf {
    size_t i, r, s, nb;
    double xi0, yi0, zi0;
    const double *rr, *cc;
    double gx[PD_CHUNK], gy[PD_CHUNK], gz[PD_CHUNK], el[PD_CHUNK];
    double rb[PD_CHUNK], cb[PD_CHUNK], tb[PD_CHUNK];
};

/* A pre-test bound, or NaN when the half-bond is broken (state bit 0),
 * without a branch: the bits of a quiet NaN or-ed into any double give a
 * NaN. */
static inline double pd_thr_or_nan(double thr, uint8_t state)
{
    uint64_t b;
    memcpy(&b, &thr, sizeof b);
    b |= ((uint64_t)0 - (uint64_t)(state & BOND_BROKEN)) & UINT64_C(0x7ff8000000000000);
    memcpy(&thr, &b, sizeof thr);
    return thr;
}

/* Pass 1 of a chunk (pd_forces.c, pd_chunk): for half-bonds k < nb of a row
 * at (xi0, yi0, zi0), partner, rest, coef and thr starting at the chunk,
 * the force components g e into gx, gy, gz (exact zeros for a broken
 * half-bond) and the elongations l - r into el.  Returns whether some
 * intact half-bond passes the pre-test. */
#define PD_CHUNK_DECL(DIM)                                                                      \
    int64_t pd_chunk##DIM(size_t nb, double xi0, double yi0, double zi0,                        \
                          double *const *restrict x, const int32_t *restrict partner,           \
                          const double *restrict rest, const double *restrict coef,             \
                          const double *restrict thr, double *restrict gx,                      \
                          double *restrict gy, double *restrict gz, double *restrict el)
PD_CHUNK_DECL(1);
PD_CHUNK_DECL(2);
PD_CHUNK_DECL(3);

/* pd_half.c: the once-per-bond loop.  Computes the forces and released
 * energies of the owned particles, as the split kernel would, bit for
 * bit, and returns true; false (nothing done) where the rows do not suit
 * it (pd_half_ring) or memory is short, and the split kernel runs. */
bool pd_half_forces(struct model *m, const struct sim *sim, const struct pd_kctx *c, size_t n,
                    double *const *f, double *diss);

#endif
