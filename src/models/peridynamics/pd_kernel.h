/**
 * @file pd_kernel.h
 * @brief What the two bond-based PMB kernels share: the split kernel of
 *        pd_forces.c (every half-bond from its own row) and the
 *        once-per-bond loop of pd_half.c.  Internal to the peridynamics
 *        model.
 */
#ifndef SPALL_PD_KERNEL_H
#define SPALL_PD_KERNEL_H

#include "models/peridynamics/pd_internal.h"

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

/* Type of half-bond @p s in either storage. */
static inline unsigned pd_kc_type(const struct pd_kctx *c, size_t s)
{
    return c->kind ? c->ktab[c->kind[s]].type : c->type[s];
}

/* Term k of chunk b added to the row's running sums sx, sy, sz. */
#define PD_ADD_TERM(dim, b, k, sx, sy, sz)                                                      \
    do {                                                                                        \
        (sx) += (b)->gx[k];                                                                     \
        if ((dim) > 1)                                                                          \
            (sy) += (b)->gy[k];                                                                 \
        if ((dim) > 2)                                                                          \
            (sz) += (b)->gz[k];                                                                 \
    } while (0)

/* Pass 0 of half-bond k of chunk b, compact families: its length and
 * coefficient from the table, its pre-test bound, NaN when broken. */
static inline __attribute__((always_inline)) void
pd_gather_kind(const struct pd_kctx *c, struct pd_chunk_buf *b, size_t k)
{
    const struct pd_kind_row *q = &c->ktab[c->kind[b->s + k]];
    b->rb[k] = q->rest;
    b->cb[k] = q->coef;
    b->tb[k] = pd_thr_or_nan(q->thr, c->st[b->s + k]);
}

/* The same with the arrays (b->rr points into them): the bound only. */
static inline __attribute__((always_inline)) void
pd_gather_full(const struct pd_kctx *c, struct pd_chunk_buf *b, size_t k)
{
    b->tb[k] = pd_thr_or_nan(c->s0tab[c->type[b->s + k]] * b->rr[k] * PD_PRE, c->st[b->s + k]);
}

/* Pass 0 of chunk b (pointer, its nb half-bonds) with, in the same loop,
 * TERM(k) for the np terms of the chunk before (its row-order sum: a
 * chain of dependent additions that would wait on the adder's latency
 * alone; next to the loads of pass 0 it costs little), and EXTRA(k) for
 * each half-bond of b.  One loop per storage. */
#define PD_PASS0(c, b, np, TERM, EXTRA)                                                         \
    do {                                                                                        \
        const size_t nb_ = (b)->nb, m_ = nb_ < (np) ? nb_ : (np);                               \
        (b)->rr = (c)->rest ? (c)->rest + (b)->s : (b)->rb;                                     \
        (b)->cc = (c)->coef ? (c)->coef + (b)->s : (b)->cb;                                     \
        if ((c)->kind)                                                                          \
            PD_PASS0_LOOPS(pd_gather_kind, c, b, m_, nb_, TERM, EXTRA);                         \
        else                                                                                    \
            PD_PASS0_LOOPS(pd_gather_full, c, b, m_, nb_, TERM, EXTRA);                         \
        for (size_t k = m_; k < (np); k++)                                                      \
            TERM(k);                                                                            \
    } while (0)
/* PD_PASS0's loops for one storage (GATHER): the terms with the first m
 * half-bonds, then the other half-bonds alone. */
#define PD_PASS0_LOOPS(GATHER, c, b, m, nb, TERM, EXTRA)                                        \
    do {                                                                                        \
        for (size_t k = 0; k < (m); k++) {                                                      \
            GATHER(c, b, k);                                                                    \
            EXTRA(k);                                                                           \
            TERM(k);                                                                            \
        }                                                                                       \
        for (size_t k = (m); k < (nb); k++) {                                                   \
            GATHER(c, b, k);                                                                    \
            EXTRA(k);                                                                           \
        }                                                                                       \
    } while (0)

/* Whether half-bond k of chunk b (type @p ty) breaks now: past the
 * pre-test, then the exact test (l - r) / r > s0. */
static inline bool pd_breaks_now(const struct pd_kctx *c, const struct pd_chunk_buf *b, size_t k,
                                 unsigned ty)
{
    return b->el[k] > b->tb[k] && b->el[k] / b->rr[k] > c->s0tab[ty];
}

/* Half-bond k of chunk b (type @p ty) breaks: marked broken, and fresh
 * when a matrix bond (pd_plane.c); returns the energy it releases. */
static inline double pd_break_half(int dim, const struct pd_kctx *c, const struct pd_chunk_buf *b,
                                   size_t k, unsigned ty)
{
    const size_t s = b->s + k, j = (size_t)c->partner[s];
    const double ex = c->x[0][j] - b->xi0;
    const double ey = dim > 1 ? c->x[1][j] - b->yi0 : 0.0;
    const double ez = dim > 2 ? c->x[2][j] - b->zi0 : 0.0;
    c->st[s] |= BOND_BROKEN;
    if (c->fresh && !(ty & 1u))
        c->fresh[s] = 1;
    return pd_break_energy(dim, ex, ey, ez, b->rr[k], b->el[k], b->cc[k], c->dt, c->u, b->i, j,
                           c->late);
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

/* Pass 1 of chunk b (pd_chunkD). */
static inline __attribute__((always_inline)) int64_t pd_pass1(int dim, const struct pd_kctx *c,
                                                              struct pd_chunk_buf *b)
{
    switch (dim) {
    case 1:
        return pd_chunk1(b->nb, b->xi0, b->yi0, b->zi0, c->x, c->partner + b->s, b->rr, b->cc,
                         b->tb, b->gx, b->gy, b->gz, b->el);
    case 2:
        return pd_chunk2(b->nb, b->xi0, b->yi0, b->zi0, c->x, c->partner + b->s, b->rr, b->cc,
                         b->tb, b->gx, b->gy, b->gz, b->el);
    default:
        return pd_chunk3(b->nb, b->xi0, b->yi0, b->zi0, c->x, c->partner + b->s, b->rr, b->cc,
                         b->tb, b->gx, b->gy, b->gz, b->el);
    }
}

/* pd_half.c: the once-per-bond loop.  Computes the forces and released
 * energies of the owned particles, as the split kernel would, bit for
 * bit, and returns true; false (nothing done) where the rows do not suit
 * it (pd_half_ring) or memory is short, and the split kernel runs. */
bool pd_half_forces(struct model *m, const struct sim *sim, const struct pd_kctx *c, size_t n,
                    double *const *f, double *diss);

#endif
