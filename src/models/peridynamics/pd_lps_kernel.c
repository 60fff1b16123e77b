/**
 * @file pd_lps_kernel.c
 * @brief The force passes of formulations lps and eps (the model and its
 *        formulas: pd_lps.c, pd_eps.c) as split row kernels.
 *
 * Each pass takes a particle's row in three steps, as the PMB kernel of
 * pd_forces.c takes its chunks: pass 0 gathers each half-bond's rest
 * length, omega beta and breaking pre-test bound (NaN: broken) from the
 * kind table or the arrays; a vector loop (PD_CLONES: four doubles a
 * vector where the CPU has them) computes every half-bond with no
 * dependence between them, an exact +0.0 for a broken one; then the terms
 * are summed in row order.  A row where some intact half-bond passes the
 * pre-test e > s0 |xi| PD_PRE (which misses none of the exact test e / |xi|
 * > s0) settles those one at a time with the exact test.  Every operation
 * that reaches a result, its operands and the order of every sum are those
 * of the loops it replaces (a +0.0 term leaves a sum that starts at +0.0 as
 * it was), so the results are bit for bit the same for any thread count.
 *
 * eps keeps no per-half-bond force state: pass 2 computes t_ji from j's
 * dilatation, return-map scale and isotropic coefficient (per particle,
 * hs) and the plastic extension e^dp_ji of j's half (through the 8- or
 * 16-bit reverse slot, pd_eps_rev, or distributed i's copy epr), the operations j's own
 * pass 1 used to do, so the same bits.  Since j reads e^dp_ji of the step's
 * start, the new plastic extensions (and the next_step breaking, which
 * reads them) are written in a pass 3 over the rows that yielded or have a
 * half-bond past the pre-test.
 */
#include "models/peridynamics/pd_internal.h"

#include "core/bond_list.h"
#include "core/parallel/decomp.h"
#include "core/particles.h"
#include "core/sim.h"
#include "spall/error.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* What the passes read besides the row's own buffers. */
struct lps_ctx {
    const size_t *off;
    const int32_t *partner;
    uint8_t *st;
    const uint16_t *kind;        /* NULL: the arrays rest, ob, type */
    const struct pd_kind_row *ktab; /* per call: thr with the thresholds of now */
    const double *rest, *ob;
    const uint8_t *type;
    const double *s0tab;
    double *const *x;
    const double *vol;
};

/* One thread's buffers, each as long as the longest row. */
struct lps_buf {
    double *rb, *ob, *tb, *el, *gx, *gy, *gz, *ej;
};

static int lps_buf_alloc(struct lps_buf *b, size_t len)
{
    const size_t L = len ? len : 1;
    double *a = malloc(8 * L * sizeof *a);
    *b = a ? (struct lps_buf){a, a + L, a + 2 * L, a + 3 * L, a + 4 * L, a + 5 * L, a + 6 * L,
                              a + 7 * L}
           : (struct lps_buf){NULL, NULL, NULL, NULL, NULL, NULL, NULL, NULL};
    return a != NULL;
}

/* A row whose terms wait to be summed (LPS_PEND) */
struct lps_pend {
    const struct lps_buf *b; /* NULL: none */
    size_t i, nb;
};

/* Pass 0: rest length, omega beta and pre-test bound (NaN: broken) of the
 * half-bonds [s0, s0 + nb); and in the same loop the row-order sums of the
 * ncomp term columns (gx, gy, gz) of the pending row p into acc.  A sum is
 * a chain of dependent additions that would wait on the adder's latency
 * alone; next to the loads of pass 0 it costs little (as pd_chunk_gather
 * of pd_forces.c). */
static inline __attribute__((always_inline)) void
lps_gather(int ncomp, const struct lps_ctx *c, size_t s0, size_t nb, struct lps_buf *b,
           const struct lps_pend *p, double *acc)
{
    const size_t np = p && p->b ? p->nb : 0, m = nb < np ? nb : np;
    const struct lps_buf *q = np ? p->b : NULL;
    double a0 = 0.0, a1 = 0.0, a2 = 0.0;
#define LPS_PSUM(k)                                                                             \
    do {                                                                                        \
        a0 += q->gx[k];                                                                         \
        if (ncomp > 1)                                                                          \
            a1 += q->gy[k];                                                                     \
        if (ncomp > 2)                                                                          \
            a2 += q->gz[k];                                                                     \
    } while (0)
#define LPS_GATHER_KIND(k)                                                                      \
    do {                                                                                        \
        const struct pd_kind_row *r = &c->ktab[c->kind[s0 + (k)]];                              \
        b->rb[k] = r->rest;                                                                     \
        b->ob[k] = r->coef;                                                                     \
        b->tb[k] = pd_thr_or_nan(r->thr, c->st[s0 + (k)]);                                      \
    } while (0)
#define LPS_GATHER_FULL(k)                                                                      \
    do {                                                                                        \
        b->rb[k] = c->rest[s0 + (k)];                                                           \
        b->ob[k] = c->ob[s0 + (k)];                                                             \
        b->tb[k] =                                                                              \
            pd_thr_or_nan(c->s0tab[c->type[s0 + (k)]] * b->rb[k] * PD_PRE, c->st[s0 + (k)]);    \
    } while (0)
    if (c->kind) {
        for (size_t k = 0; k < m; k++) {
            LPS_GATHER_KIND(k);
            LPS_PSUM(k);
        }
        for (size_t k = m; k < nb; k++)
            LPS_GATHER_KIND(k);
    } else {
        for (size_t k = 0; k < m; k++) {
            LPS_GATHER_FULL(k);
            LPS_PSUM(k);
        }
        for (size_t k = m; k < nb; k++)
            LPS_GATHER_FULL(k);
    }
    for (size_t k = m; k < np; k++)
        LPS_PSUM(k);
#undef LPS_PSUM
#undef LPS_GATHER_KIND
#undef LPS_GATHER_FULL
    acc[0] = a0;
    acc[1] = a1;
    acc[2] = a2;
}

static inline unsigned lps_type_of(const struct lps_ctx *c, size_t s)
{
    return c->kind ? c->ktab[c->kind[s]].type : c->type[s];
}

/* v where mask is all ones, +0.0 where it is zero: a select on the bits,
 * which keeps the loads that only the force reads (alpha_j, theta_j, ...)
 * unconditional; with a ?: GCC would make them masked gathers, which the
 * vectoriser leaves scalar. */
static inline double lps_keep(double v, uint64_t mask)
{
    uint64_t b;
    memcpy(&b, &v, sizeof b);
    b &= mask;
    memcpy(&v, &b, sizeof v);
    return v;
}

/* The force term g (x_j - x_i) of half-bond k into gx, gy, gz (+0.0 when
 * broken: thr is NaN), its extension e into el; whether it passes the
 * pre-test (a macro: as an inline function GCC no longer vectorised the
 * loops). */
#define LPS_PUT(k, g, ex, ey, ez, e, thr)                                                       \
    do {                                                                                        \
        const uint64_t live_ = (uint64_t)0 - (uint64_t)((thr) == (thr));                        \
        gx[k] = lps_keep((g) * (ex), live_);                                                    \
        gy[k] = lps_keep((g) * (ey), live_);                                                    \
        gz[k] = lps_keep((g) * (ez), live_);                                                    \
        el[k] = (e);                                                                            \
        any |= (int64_t)((e) > (thr));                                                          \
    } while (0)

/* Dilatation terms of a row's nb half-bonds seen from (xi0, yi0, zi0):
 * term = omega beta |xi| e V_j (+0.0 when broken) and the extension e =
 * l - |xi|; whether an intact one passes the pre-test. */
static inline __attribute__((always_inline)) int64_t
lps_dil(int dim, size_t nb, double xi0, double yi0, double zi0, double *const *restrict x,
        const int32_t *restrict partner, const double *restrict vol, const double *restrict rb,
        const double *restrict ob, const double *restrict tb, double *restrict term,
        double *restrict el)
{
    const double *restrict x0 = x[0], *restrict x1 = x[1], *restrict x2 = x[2];
    int64_t any = 0;
    for (size_t k = 0; k < nb; k++) {
        const size_t j = (size_t)partner[k];
        const double ex = x0[j] - xi0, ey = x1[j] - yi0;
        const double ez = dim > 2 ? x2[j] - zi0 : 0.0;
        const double e = sqrt(ex * ex + ey * ey + ez * ez) - rb[k];
        const double t = ob[k] * rb[k] * e * vol[j];
        term[k] = tb[k] == tb[k] ? t : 0.0;
        el[k] = e;
        any |= (int64_t)(e > tb[k]);
    }
    return any;
}

/* Pass 2 terms: the force g (x_j - x_i) of each half-bond, g = omega beta
 * (t_ij + t_ji) V_i V_j / l; e as lps_dil.  lps (eps false): own = (x_i,
 * alpha_i, bcoef_i, theta_i, V_i), t_ji from alpha_j, bcoef_j (q) and
 * theta_j.  eps: own = (x_i, iso_i, alpha_i, theta_i, scale_i, V_i), t_ij
 * with e^dp of the step's start es, t_ji from j's theta, scale and iso (q
 * = hs, three per particle) and ej, the e^dp of j's half; tau = alpha (e^d
 * - e^dp) times the scale (1: exact, no yield). */
static inline __attribute__((always_inline)) int64_t
lps_frc(int dim, bool eps, size_t nb, const double *own, double d, double *const *restrict x,
        const int32_t *restrict partner, const double *restrict vol, const double *restrict al,
        const double *restrict q, const double *restrict th, const double *restrict rb,
        const double *restrict ob, const double *restrict tb, const double *restrict es,
        const double *restrict ej, double *restrict gx, double *restrict gy, double *restrict gz,
        double *restrict el)
{
    const double *restrict x0 = x[0], *restrict x1 = x[1], *restrict x2 = x[2];
    const double xi0 = own[0], yi0 = own[1], zi0 = own[2];
    int64_t any = 0;
    for (size_t k = 0; k < nb; k++) {
        const size_t j = (size_t)partner[k];
        const double ex = x0[j] - xi0, ey = x1[j] - yi0;
        const double ez = dim > 2 ? x2[j] - zi0 : 0.0;
        const double l = sqrt(ex * ex + ey * ey + ez * ez), xi = rb[k], e = l - xi;
        double tij, tji;
        if (eps) {
            tij = own[3] * xi + own[4] * (e - own[5] * xi / d - es[k]) * own[6];
            tji = q[3 * j + 2] * xi + al[j] * (e - q[3 * j] * xi / d - ej[k]) * q[3 * j + 1];
        } else {
            tij = own[3] * e + own[4] * xi * own[5];
            tji = al[j] * e + q[j] * xi * th[j];
        }
        const double g = ob[k] * (tij + tji) * (own[eps ? 7 : 6] * vol[j]) / l;
        LPS_PUT(k, g, ex, ey, ez, e, tb[k]);
    }
    return any;
}

/* eps pass 1: each term of the norm ||tau||^2 = sum omega beta tau^2 V_j,
 * tau = alpha (e - theta |xi| / d - e^dp) (+0.0 when broken). */
PD_CLONES static void eps_norm(size_t nb, double th, double al, double d,
                               const int32_t *restrict partner, const double *restrict vol,
                               const double *restrict ep, const double *restrict rb,
                               const double *restrict ob, const double *restrict tb,
                               const double *restrict el, double *restrict q)
{
    for (size_t k = 0; k < nb; k++) {
        const double tau = al * (el[k] - th * rb[k] / d - ep[k]);
        const double v = ob[k] * tau * tau * vol[partner[k]];
        q[k] = tb[k] == tb[k] ? v : 0.0;
    }
}

/* The vector loops per dimension (2D, 3D), the dimension a constant. */
#define LPS_DIM(DIM)                                                                            \
    PD_CLONES static int64_t lps_dil##DIM(                                                      \
        size_t nb, double xi0, double yi0, double zi0, double *const *restrict x,              \
        const int32_t *restrict partner, const double *restrict vol, const double *restrict rb, \
        const double *restrict ob, const double *restrict tb, double *restrict term,            \
        double *restrict el)                                                                    \
    {                                                                                           \
        return lps_dil(DIM, nb, xi0, yi0, zi0, x, partner, vol, rb, ob, tb, term, el);          \
    }                                                                                           \
    PD_CLONES static int64_t lps_frc##DIM(                                                      \
        size_t nb, const double *own, double *const *restrict x,                               \
        const int32_t *restrict partner, const double *restrict vol, const double *restrict al, \
        const double *restrict bc, const double *restrict th, const double *restrict rb,        \
        const double *restrict ob, const double *restrict tb, double *restrict gx,              \
        double *restrict gy, double *restrict gz, double *restrict el)                          \
    {                                                                                           \
        return lps_frc(DIM, false, nb, own, 0.0, x, partner, vol, al, bc, th, rb, ob, tb, NULL, \
                       NULL, gx, gy, gz, el);                                                   \
    }                                                                                           \
    PD_CLONES static int64_t eps_frc##DIM(                                                      \
        size_t nb, const double *own, double d, double *const *restrict x,                     \
        const int32_t *restrict partner, const double *restrict vol, const double *restrict al, \
        const double *restrict hs, const double *restrict rb, const double *restrict ob,        \
        const double *restrict tb, const double *restrict es, const double *restrict ej,        \
        double *restrict gx, double *restrict gy, double *restrict gz, double *restrict el)     \
    {                                                                                           \
        return lps_frc(DIM, true, nb, own, d, x, partner, vol, al, hs, NULL, rb, ob, tb, es, ej, \
                       gx, gy, gz, el);                                                         \
    }
LPS_DIM(2)
LPS_DIM(3)

/* Pass 1 of row i (both formulations), its vector loop on the gathered
 * row: the dilatation terms into b->gx; whether a half-bond passes the
 * pre-test. */
static int64_t lps_row_dil(const struct model *m, const struct lps_ctx *c, size_t i,
                           struct lps_buf *b)
{
    const size_t s0 = c->off[i], nb = c->off[i + 1] - s0;
    double *const *x = c->x;
    return m->dim == 3 ? lps_dil3(nb, x[0][i], x[1][i], x[2][i], x, c->partner + s0, c->vol,
                                  b->rb, b->ob, b->tb, b->gx, b->el)
                       : lps_dil2(nb, x[0][i], x[1][i], 0.0, x, c->partner + s0, c->vol, b->rb,
                                  b->ob, b->tb, b->gx, b->el);
}

/* break_order immediate, a row with a half-bond past the pre-test: the
 * sum of its dilatation terms with the half-bonds past s0 broken and left
 * out (their bound set to NaN in b->tb, so that later loops of the row skip
 * them).  ep: eps' plastic extensions (the energy of a breaking half-bond
 * is of its elastic part), NULL for lps. */
static double lps_row_settle(struct model *m, const struct lps_ctx *c, size_t i,
                             const double *ep, struct lps_buf *b)
{
    const struct pd_lps *L = &m->lps;
    const size_t s0 = c->off[i], nb = c->off[i + 1] - s0;
    double sum = 0.0;
    for (size_t k = 0; k < nb; k++) {
        const size_t s = s0 + k;
        const double xi = b->rb[k], e = b->el[k];
        if (e > b->tb[k] && e / xi > c->s0tab[lps_type_of(c, s)]) {
            c->st[s] |= BOND_BROKEN;
            b->tb[k] = NAN;
            /* energy of the half-bond at the last dilatation: t e / 2 (the
             * state energy is homogeneous of degree 2 in e); eps: of the
             * elastic part e - e^dp */
            const size_t j = (size_t)c->partner[s];
            const double ee = e - (ep ? ep[s] : 0.0);
            const double t = L->alpha[i] * ee + L->bcoef[i] * xi * L->theta[i];
            m->diss[i] += 0.5 * b->ob[k] * t * ee * c->vol[i] * c->vol[j];
            continue;
        }
        sum += b->gx[k];
    }
    return sum;
}

/* The longest row of particles [0, n) */
static size_t lps_max_row(const struct bond_list *bl, size_t n)
{
    size_t r = 0;
    for (size_t i = 0; i < n; i++)
        r = bl->offset[i + 1] - bl->offset[i] > r ? bl->offset[i + 1] - bl->offset[i] : r;
    return r;
}

/* The context of a call, with the kind table's pre-test bounds of now
 * (*ktab: free it; omega beta in its coef column). */
static int lps_ctx_make(const struct model *m, const struct sim *sim, struct lps_ctx *c,
                        struct pd_kind_row **ktab, struct spall_error *err)
{
    const struct bond_list *bl = m->bl;
    int rc = pd_kind_rows(m, ktab, err);
    if (rc)
        return rc;
    *c = (struct lps_ctx){bl->offset, bl->partner, bl->state, m->kind, *ktab, bl->rest,
                          m->lps.ob, bl->type, m->s0_tab, sim->p->x, sim->p->volume};
    return SPALL_OK;
}

/* break_order next_step: the half-bonds of row i past s0 broken, the
 * energy of their state t_ij e / 2 (lps; eps: eps_row_pass3). */
static void lps_row_break(struct model *m, const struct lps_ctx *c, size_t i,
                          const struct lps_buf *b)
{
    const struct pd_lps *L = &m->lps;
    const size_t s0 = c->off[i], nb = c->off[i + 1] - s0;
    for (size_t k = 0; k < nb; k++) {
        const size_t s = s0 + k;
        const double xi = b->rb[k], e = b->el[k];
        if (!(e > b->tb[k] && e / xi > c->s0tab[lps_type_of(c, s)]))
            continue;
        c->st[s] |= BOND_BROKEN;
        const size_t j = (size_t)c->partner[s];
        const double tij = L->alpha[i] * e + L->bcoef[i] * xi * L->theta[i];
        m->diss[i] += 0.5 * b->ob[k] * tij * e * c->vol[i] * c->vol[j];
    }
}

/* The force sums of a pending row (acc) into f. */
static inline void lps_add_force(int dim, const struct lps_pend *p, const double *acc,
                                 double *const *f)
{
    if (!p->b)
        return;
    f[0][p->i] += acc[0];
    f[1][p->i] += acc[1];
    if (dim > 2)
        f[2][p->i] += acc[2];
}

/* Two row buffers for one thread; 0 when out of memory (both freed). */
static int lps_bufs_alloc(struct lps_buf b[2], size_t len)
{
    const int ok = lps_buf_alloc(&b[0], len) && lps_buf_alloc(&b[1], len);
    if (!ok) {
        free(b[0].rb);
        b[0].rb = b[1].rb = NULL;
    }
    return ok;
}

/* What a row function (lps_rows) returns: its sums wait for the next row
 * (LPS_PENDING), it has a half-bond past the breaking pre-test (LPS_ANY). */
enum { LPS_PENDING = 1, LPS_ANY = 2 };

/* theta of the pending row of pass 1 from its sum acc[0] */
static void lps_fin_theta(struct model *m, const struct lps_pend *p, const double *acc)
{
    struct pd_lps *L = &m->lps;
    if (p->b)
        L->theta[p->i] = L->wvol[p->i] > 0.0 ? m->dim * acc[0] / L->wvol[p->i] : 0.0;
}

/* lps pass 1 of row i (the sum of the pending row first): dilatation terms;
 * break_order immediate with a half-bond past the pre-test: settled, the
 * theta of the row at once. */
static int lps_row_pass1(struct model *m, const struct sim *sim, const struct lps_ctx *c,
                         size_t i, struct lps_buf *b, const struct lps_pend *pend)
{
    (void)sim;
    struct pd_lps *L = &m->lps;
    const size_t s0 = c->off[i], nb = c->off[i + 1] - s0;
    double acc[3];
    lps_gather(1, c, s0, nb, b, pend, acc);
    lps_fin_theta(m, pend, acc);
    if (lps_row_dil(m, c, i, b) && !m->opt.break_late) {
        const double sum = lps_row_settle(m, c, i, NULL, b);
        L->theta[i] = L->wvol[i] > 0.0 ? m->dim * sum / L->wvol[i] : 0.0;
        return 0;
    }
    return LPS_PENDING;
}

/* lps pass 2 of owned row i (the sums of the pending row first): the
 * forces, and next_step the breaking. */
static int lps_row_pass2(struct model *m, const struct sim *sim, const struct lps_ctx *c,
                         size_t i, struct lps_buf *b, const struct lps_pend *pend)
{
    const struct particles *p = sim->p;
    const struct pd_lps *L = &m->lps;
    const size_t s0 = c->off[i], nb = c->off[i + 1] - s0;
    double acc[3];
    lps_gather(m->dim, c, s0, nb, b, pend, acc);
    lps_add_force(m->dim, pend, acc, p->f);
    const double own[7] = {p->x[0][i], p->x[1][i], m->dim > 2 ? p->x[2][i] : 0.0,
                           L->alpha[i], L->bcoef[i], L->theta[i], p->volume[i]};
    const int64_t any =
        (m->dim == 3 ? lps_frc3 : lps_frc2)(nb, own, p->x, c->partner + s0, c->vol, L->alpha,
                                            L->bcoef, L->theta, b->rb, b->ob, b->tb, b->gx,
                                            b->gy, b->gz, b->el);
    if (m->opt.break_late && any)
        lps_row_break(m, c, i, b);
    return LPS_PENDING;
}

typedef int (*lps_row_fn)(struct model *m, const struct sim *sim, const struct lps_ctx *c,
                          size_t i, struct lps_buf *b, const struct lps_pend *pend);

/* Rows [0, nrows) by row(), two buffers a thread: a row's sums wait for
 * the next row's pass 0 (lps_gather), the last one's for the end (ncomp
 * sums: 1, pass 1's theta; dim, pass 2's forces).  brk: the rows where
 * row() found a half-bond past the pre-test.  Returns 1 when out of
 * memory. */
static int lps_rows(struct model *m, struct sim *sim, const struct lps_ctx *c, size_t len,
                    size_t nrows, int ncomp, lps_row_fn row, uint8_t *brk)
{
    int bad = 0;
#pragma omp parallel reduction(| : bad)
    {
        struct lps_buf b[2];
        const int ok = lps_bufs_alloc(b, len);
        bad |= !ok;
        struct lps_pend pend = {NULL, 0, 0};
        int cur = 0;
#pragma omp for schedule(dynamic, 256) nowait
        for (size_t i = 0; i < nrows; i++) {
            if (!ok)
                continue;
            const int r = row(m, sim, c, i, &b[cur], &pend);
            if ((r & LPS_ANY) && brk)
                brk[i] = 1;
            pend = (struct lps_pend){(r & LPS_PENDING) ? &b[cur] : NULL, i,
                                     c->off[i + 1] - c->off[i]};
            cur ^= (r & LPS_PENDING) ? 1 : 0;
        }
        double acc[3];
        if (pend.b)
            lps_gather(ncomp, c, 0, 0, &b[cur], &pend, acc);
        if (pend.b && ncomp == 1)
            lps_fin_theta(m, &pend, acc);
        else if (pend.b)
            lps_add_force(m->dim, &pend, acc, sim->p->f);
        free(b[0].rb);
        free(b[1].rb);
    }
    return bad;
}

/* lps: passes 1 and 2; 1 when out of memory */
static int lps_forces(struct model *m, struct sim *sim, const struct lps_ctx *c, size_t len)
{
    /* pass 1: breaking (immediate) and dilatation; each half-bond decided by
     * its own particle from a length that is bit-identical from both ends */
    int bad = lps_rows(m, sim, c, len, sim->p->n, 1, lps_row_pass1, NULL);
    /* distributed: a ghost's row is empty here; its owner's dilatation,
     * which t_ji needs, comes with the halo */
    if (!bad && sim->par)
        par_halo_values(sim, m->lps.theta, 1);
    /* pass 2: forces, t_ij from i's state and t_ji from j's; next_step:
     * pd_lps_break_rows' rule on the same lengths, in row order */
    if (!bad)
        bad = lps_rows(m, sim, c, len, sim->p->n_owned, m->dim, lps_row_pass2, NULL);
    return bad;
}

/* eps pass 1 of row i (pd_eps.c has the formulas): dilatation, the norm of
 * the trial deviatoric force state, the return map's scale, the plastic
 * work of a yielding row; theta, scale and the isotropic coefficient d k
 * theta / m_i into hs.  The plastic extensions themselves are written by
 * pass 3. */
static void eps_row_pass1(struct model *m, const struct sim *sim, const struct lps_ctx *c,
                          size_t i, bool late, struct lps_buf *b)
{
    struct pd_lps *L = &m->lps;
    const struct particles *p = sim->p;
    const double d = (double)m->dim, *ep = L->ep;
    const struct pd_material *mt = &m->mat[p->material[i]];
    const size_t s0 = c->off[i], nb = c->off[i + 1] - s0;
    double acc[3];
    lps_gather(1, c, s0, nb, b, NULL, acc);
    const int64_t any = lps_row_dil(m, c, i, b);
    double sum = 0.0;
    if (!late && any)
        sum = lps_row_settle(m, c, i, ep, b);
    else
        for (size_t k = 0; k < nb; k++)
            sum += b->gx[k];
    const double wv = L->wvol[i];
    const double th = wv > 0.0 ? d * sum / wv : 0.0;
    L->theta[i] = th;
    double *hs = L->hs + 3 * i;
    hs[0] = th;
    hs[1] = 1.0;
    hs[2] = 0.0;
    if (!(wv > 0.0))
        return;
    const double al = L->alpha[i];
    eps_norm(nb, th, al, d, c->partner + s0, c->vol, ep + s0, b->rb, b->ob, b->tb, b->el, b->gy);
    double nrm2 = 0.0;
    for (size_t k = 0; k < nb; k++)
        nrm2 += b->gy[k];
    /* with the surface correction's a_i on alpha_i (pd_lps_surface.c) the
     * homogeneous-state norm is ||tau||^2 = a_i alpha_i s : s / (2 mu) */
    const double lim2 = d * (d + 2.0) * pd_eps_cd(m->dim) * mt->yield_stress * mt->yield_stress / (2.0 * wv) *
                        (L->afac ? L->afac[i] : 1.0);
    const double scale = nrm2 > lim2 ? sqrt(lim2 / nrm2) : 1.0;
    hs[1] = scale;
    hs[2] = (d * mt->kd / wv) * th; /* d k theta / m_i, times |xi| in t */
    double work = 0.0;
    if (scale < 1.0)
        for (size_t k = 0; k < nb; k++) {
            if (!(b->tb[k] == b->tb[k]))
                continue;
            const size_t s = s0 + k;
            const double xi = b->rb[k], ed = b->el[k] - th * xi / d;
            double tau = al * (ed - ep[s]);
            tau *= scale;
            const double dep = ed - tau / al - ep[s];
            work += b->ob[k] * tau * dep * c->vol[c->partner[s]];
        }
    m->diss[i] += work * p->volume[i];
}

/* eps pass 2 of owned row i: the forces; distributed, i's copies e^dp_ji
 * (epr) updated as j's owner updates e^dp_ji.  LPS_ANY: some half-bond
 * passes the breaking pre-test. */
static int eps_row_pass2(struct model *m, const struct sim *sim, const struct lps_ctx *c,
                         size_t i, struct lps_buf *b, const struct lps_pend *pend)
{
    struct pd_lps *L = &m->lps;
    const struct particles *p = sim->p;
    const double d = (double)m->dim, *hs = L->hs;
    const size_t s0 = c->off[i], nb = c->off[i + 1] - s0;
    double *epr = L->epr;
    double acc[3];
    lps_gather(m->dim, c, s0, nb, b, pend, acc);
    lps_add_force(m->dim, pend, acc, p->f);
    if (epr)
        for (size_t k = 0; k < nb; k++)
            b->ej[k] = epr[s0 + k];
    else
        for (size_t k = 0; k < nb; k++)
            b->ej[k] = L->ep[pd_eps_rev(m, s0 + k)];
    const double own[8] = {p->x[0][i], p->x[1][i], m->dim > 2 ? p->x[2][i] : 0.0,
                           hs[3 * i + 2], L->alpha[i], hs[3 * i], hs[3 * i + 1], p->volume[i]};
    const int64_t any =
        (m->dim == 3 ? eps_frc3 : eps_frc2)(nb, own, d, p->x, c->partner + s0, c->vol, L->alpha,
                                            hs, b->rb, b->ob, b->tb, L->ep + s0, b->ej, b->gx,
                                            b->gy, b->gz, b->el);
    if (epr) /* pass 1 of j for this half-bond, as j's owner runs it */
        for (size_t k = 0; k < nb; k++) {
            const size_t s = s0 + k, j = (size_t)c->partner[s];
            const double scj = hs[3 * j + 1];
            if (!(b->tb[k] == b->tb[k]) || !(scj < 1.0))
                continue;
            const double xi = b->rb[k], alj = L->alpha[j];
            const double ed = b->el[k] - hs[3 * j] * xi / d;
            double tau = alj * (ed - epr[s]);
            tau *= scj;
            const double dep = ed - tau / alj - epr[s];
            epr[s] += dep;
        }
    return LPS_PENDING | (any ? LPS_ANY : 0);
}

/* eps pass 3 of row i: the plastic extensions of a yielding row (the
 * return map of pass 1 on the same lengths), then break_order next_step
 * (brk): pd_lps_break_rows' rule, in row order. */
static void eps_row_pass3(struct model *m, const struct sim *sim, const struct lps_ctx *c,
                          size_t i, bool brk)
{
    struct pd_lps *L = &m->lps;
    const struct particles *p = sim->p;
    const double d = (double)m->dim, th = L->theta[i], al = L->alpha[i];
    const double scale = L->hs[3 * i + 1];
    double *ep = L->ep;
    for (size_t s = c->off[i]; s < c->off[i + 1]; s++) {
        if (c->st[s] & BOND_BROKEN)
            continue;
        const size_t j = (size_t)c->partner[s];
        double l2 = 0.0;
        for (int q = 0; q < m->dim; q++) {
            const double r = p->x[q][j] - p->x[q][i];
            l2 += r * r;
        }
        const size_t row = c->kind ? c->kind[s] : s;
        const double xi = c->kind ? c->ktab[row].rest : c->rest[s], e = sqrt(l2) - xi;
        if (scale < 1.0) {
            const double ed = e - th * xi / d;
            double tau = al * (ed - ep[s]);
            tau *= scale;
            const double dep = ed - tau / al - ep[s];
            ep[s] += dep;
        }
        if (!brk || !(e / xi > c->s0tab[lps_type_of(c, s)]))
            continue;
        c->st[s] |= BOND_BROKEN;
        const double ob = c->kind ? c->ktab[row].coef : c->ob[s];
        const double ee = e - ep[s];
        const double t = L->alpha[i] * ee + L->bcoef[i] * xi * L->theta[i];
        m->diss[i] += 0.5 * ob * t * ee * p->volume[i] * p->volume[j];
    }
}

/* eps: passes 1 to 3; 1 when out of memory */
static int eps_forces(struct model *m, struct sim *sim, const struct lps_ctx *c, size_t len)
{
    struct pd_lps *L = &m->lps;
    const size_t n = sim->p->n;
    const bool late = m->opt.break_late;
    /* next_step: the rows with a half-bond past the pre-test in pass 2 */
    uint8_t *brk = late ? calloc(n ? n : 1, 1) : NULL;
    int bad = late && !brk;
    /* pass 1, per particle (its own half-bonds only): breaking (immediate),
     * dilatation, return map */
#pragma omp parallel reduction(| : bad)
    {
        struct lps_buf b;
        const int ok = lps_buf_alloc(&b, len);
        bad |= !ok;
#pragma omp for schedule(dynamic, 256)
        for (size_t i = 0; i < n; i++)
            if (ok)
                eps_row_pass1(m, sim, c, i, late, &b);
        free(b.rb);
    }
    /* distributed: the partner's half t_ji needs its whole family (the
     * return map's scale), which a ghost's owner has.  Rather than the
     * values t_ji themselves (one per bond that crosses ranks), its owner
     * sends theta_j, the scale and d k theta_j / m_j (three per ghost), and i
     * repeats j's update of e^dp_ji on its copy epr: the same operations on
     * the same operands (the length and rest length of a bond are bitwise
     * symmetric), so the same bits (docs/parallel.md, "Elastic-plastic
     * peridynamics") */
    if (!bad && sim->par)
        par_halo_values(sim, L->hs, 3);
    /* pass 2: F_i = V_i sum_j (t_ij + t_ji) beta V_j M_ij */
    if (!bad)
        bad = lps_rows(m, sim, c, len, sim->p->n_owned, m->dim, eps_row_pass2, brk);
    /* pass 3: once every row has read the plastic extensions of the step's
     * start */
    if (!bad) {
#pragma omp parallel for schedule(dynamic, 256)
        for (size_t i = 0; i < n; i++)
            if (L->hs[3 * i + 1] < 1.0 || (brk && brk[i]))
                eps_row_pass3(m, sim, c, i, brk && brk[i]);
    }
    free(brk);
    return bad;
}

int pd_lps_forces(struct model *m, struct sim *sim, struct spall_error *err)
{
    const size_t n = sim->p->n, no = sim->p->n_owned;
    if (m->lps.pw) /* surface_correction position_aware: its own passes */
        return pd_lps_pals_forces(m, sim, err);
    struct lps_ctx c;
    struct pd_kind_row *ktab;
    int rc = lps_ctx_make(m, sim, &c, &ktab, err);
    if (rc)
        return rc;
    const size_t len = lps_max_row(m->bl, n);
    /* formulation eps: with the plastic return map */
    const int bad = m->lps.ep ? eps_forces(m, sim, &c, len) : lps_forces(m, sim, &c, len);
    free(ktab);
    if (bad)
        return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory for the LPS row buffers");
    if (m->opt.break_late && n > no) /* distributed: the ghosts' rows (empty) */
        pd_lps_break_rows(m, sim, no, n);
    return SPALL_OK;
}
