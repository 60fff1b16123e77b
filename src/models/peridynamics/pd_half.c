/**
 * @file pd_half.c
 * @brief The bond-based PMB kernel with each bond evaluated once (issue 25
 *        item 2), bit for bit the results of the split kernel of
 *        pd_forces.c, which evaluates every bond from both of its rows.
 *
 * Only the row of the lower index i evaluates the bond i-j (j > i) and
 * hands j the negated term, as lattice_half.c does for the lattice:
 * x_i - x_j = -(x_j - x_i) exactly (round to nearest is symmetric), so the
 * length l, the elongation l - r, g = coef (l - r) / l, the pre-test and
 * the exact test (l - r) / r > s0 are the same bits from both ends (the
 * rest length, coefficient, type and state of both halves are checked to
 * be equal), and g (x_i - x_j) = -(g (x_j - x_i)).  So is the energy a
 * breaking bond releases (pd_break_energy: its x_n difference is negated
 * as a whole).  Half the square roots and divisions, which bound the
 * split kernel (one of each per half-bond, ~6 cycles: docs/performance.md),
 * and half the gathers.
 *
 * The order of each row's sum is kept.  The rows of the family list are
 * sorted (core/neighbor.h): the partners below i ascending, then those
 * above.  Row i's sum 0 + t_1 + t_2 + ... (slot order) is started in a
 * per-thread ring of accumulators, ring[i mod W], by the pushes of its
 * lower partners, which arrive in ascending order since the rows are swept
 * in order; row i then adds its upper terms in slot order, and f_i += the
 * entry, which is cleared for row i + W.  W, a power of two, exceeds the
 * largest index distance of a bond.  A thread's range [lo, hi) first
 * evaluates, from the rows' own side, the bonds to partners below lo (the
 * thread below evaluates them too: the same bits), and pushes nothing to
 * rows at or past hi, nor to ghosts: every row is summed by its thread
 * alone, in its order, for any thread count.  A broken half-bond's term is
 * an exact zero, as in the split kernel; a partial sum is never -0.0 (it
 * starts at +0.0), so adding its negation changes nothing.
 *
 * The released energy is summed the same way (the ring's fourth column):
 * a bond that breaks now marks both halves when the partner's row is the
 * thread's, and each row adds the energy in its slot order.
 *
 * Each row's upper part goes through the split kernel's passes in chunks
 * of PD_CHUNK half-bonds: pass 0 gathers lengths, coefficients and
 * pre-test bounds, pass 1 (pd_chunkD, vectorised) the terms, and a chunk
 * with no half-bond near breaking is summed and pushed inside the next
 * chunk's pass 0, where the chain of dependent additions of the row sum
 * overlaps the loads; a chunk with one is settled at once, in slot order.
 */
#include "models/peridynamics/pd_internal.h"
#include "models/peridynamics/pd_kernel.h"

#include "core/bond_list.h"
#include "core/particles.h"
#include "core/sim.h"

#include <stdlib.h>
#include <string.h>
#ifdef _OPENMP
#include <omp.h>
#endif

/* Largest ring [entries per thread]: a list whose bonds join particles
 * further apart in index takes the split kernel. */
#define HALF_RING_MAX ((size_t)1 << 16)
/* Entries past the ring that take the pushes to rows of other threads and
 * ghosts (never read): several, so that those pushes form no chain. */
#define HALF_TRASH 8
/* doubles per ring entry: fx, fy, fz, released energy */
#define HALF_COLS 4

/* First slot of row @p i whose partner is not below @p b (the partners
 * below i are a sorted prefix of the row). */
static size_t first_not_below(const size_t *off, const int32_t *partner, size_t i, size_t b)
{
    /* halve the candidates [first, first + count) until one is left */
    size_t first = off[i], count = off[i + 1] - off[i];
    while (count > 0) {
        const size_t half = count / 2;
        if ((size_t)partner[first + half] >= b) {
            count = half;
        } else {
            first += half + 1;
            count -= half + 1;
        }
    }
    return first;
}

/* Slot of partner @p i in the lower part of row @p j (i < j), or SIZE_MAX. */
static size_t lower_slot(const size_t *off, const int32_t *partner, size_t j, size_t i)
{
    const size_t s = first_not_below(off, partner, j, i);
    return s < off[j + 1] && (size_t)partner[s] == i ? s : SIZE_MAX;
}

/* Whether the two halves s and t of one bond have the same length,
 * coefficient, type and state. */
static bool halves_equal(const struct model *m, size_t s, size_t t)
{
    const struct bond_list *bl = m->bl;
    if (bl->state[s] != bl->state[t])
        return false;
    if (m->kind)
        return m->kind[s] == m->kind[t];
    return bl->rest[s] == bl->rest[t] && m->coef[s] == m->coef[t] && bl->type[s] == bl->type[t];
}

/* Row flags (m->half_flags): an irregular row evaluates all its slots
 * itself and takes no pushes; a clean row's upper partners are all owned
 * and regular (its chunks push straight, half_segment). */
#define HALF_IRREGULAR 1u
#define HALF_CLEAN 2u

/* Whether row @p i is regular: its owned partners below i ascending, then
 * the partners above i, owned ascending, ghosts anywhere.  A distributed
 * run's rows near the rank's boundary list ghosts among the partners
 * below i (the rows keep the serial slot order, core/bond_list.h). */
static bool row_regular(const struct bond_list *bl, size_t n, size_t i)
{
    const size_t e = bl->offset[i + 1];
    size_t s = bl->offset[i], last = 0;
    bool any = false;
    for (; s < e && (size_t)bl->partner[s] < i; s++) {
        if (any && (size_t)bl->partner[s] <= last)
            return false;
        last = (size_t)bl->partner[s];
        any = true;
    }
    for (; s < e; s++) {
        const size_t j = (size_t)bl->partner[s];
        if (j <= i)
            return false;
        if (j >= n)
            continue;
        if (any && j <= last)
            return false;
        last = j;
        any = true;
    }
    return true;
}

/* Slot of partner @p i (< j) in row @p j: in a regular row the next slot
 * of its lower part (cnt[j] counts those found: the rows i are visited in
 * ascending order, as the lower part lists them), else by a scan; SIZE_MAX
 * when absent. */
static size_t twin_slot(const struct bond_list *bl, const uint8_t *flags, uint32_t *cnt, size_t j,
                        size_t i)
{
    if (!(flags[j] & HALF_IRREGULAR)) {
        const size_t t = bl->offset[j] + cnt[j]++;
        return t < bl->offset[j + 1] && (size_t)bl->partner[t] == i ? t : SIZE_MAX;
    }
    for (size_t t = bl->offset[j]; t < bl->offset[j + 1]; t++)
        if ((size_t)bl->partner[t] == i)
            return t;
    return SIZE_MAX;
}

/* Whether the owned rows [0, n) suit the loop, with each row's flags;
 * *span: the largest index distance of a bond between owned particles. */
static bool rows_suit(const struct model *m, size_t n, size_t *span, uint8_t *flags,
                      uint32_t *cnt)
{
    const struct bond_list *bl = m->bl;
    size_t n_lower = 0, n_upper = 0;
    *span = 0;
    if (bl->n < n || !bl->state || (!m->kind && !(bl->rest && m->coef && bl->type)))
        return false;
    for (size_t i = 0; i < n; i++)
        flags[i] = row_regular(bl, n, i) ? 0 : HALF_IRREGULAR;
    /* each owned bond with its twin in the partner's row, both halves equal */
    for (size_t i = 0; i < n; i++) {
        for (size_t s = bl->offset[i]; s < bl->offset[i + 1]; s++) {
            const size_t j = (size_t)bl->partner[s];
            if (j == i)
                return false;
            if (j >= n)
                continue;
            if (j < i) {
                n_lower++;
                continue;
            }
            n_upper++;
            const size_t t = twin_slot(bl, flags, cnt, j, i);
            if (t == SIZE_MAX || !halves_equal(m, s, t))
                return false;
            if (j - i > *span)
                *span = j - i;
        }
    }
    for (size_t i = 0; i < n; i++) {
        if (flags[i] & HALF_IRREGULAR)
            continue;
        bool clean = true;
        for (size_t s = bl->offset[i]; s < bl->offset[i + 1]; s++) {
            const size_t j = (size_t)bl->partner[s];
            if (j > i && (j >= n || (flags[j] & HALF_IRREGULAR)))
                clean = false;
        }
        flags[i] |= clean ? HALF_CLEAN : 0u;
    }
    /* every upper half has a distinct twin: equal counts make it a
     * one-to-one map, so no lower half is left without its push */
    return n_lower == n_upper;
}

/* The ring width W for the owned rows [0, n) (with each row's flags): a
 * power of two above the largest index distance of a bond, 0 when the
 * rows do not suit the loop. */
static size_t half_width(struct model *m, size_t n)
{
    free(m->half_flags);
    m->half_flags = malloc(n ? n : 1);
    uint32_t *cnt = calloc(n ? n : 1, sizeof *cnt);
    size_t span = 0, w = 1;
    const bool ok = m->half_flags && cnt && rows_suit(m, n, &span, m->half_flags, cnt);
    free(cnt);
    if (!ok || span >= HALF_RING_MAX)
        return 0;
    while (w <= span)
        w *= 2;
    return w;
}

/* half_width, checked again only for a new list (generation) or owned
 * count. */
static size_t pd_half_ring(struct model *m, const struct sim *sim)
{
    const struct bond_list *bl = m->bl;
    const size_t n = sim->p->n_owned;
    if (!m->half_known || m->half_gen != bl->gen || m->half_n != n) {
        m->half_ring = half_width(m, n);
        m->half_known = true;
        m->half_gen = bl->gen;
        m->half_n = n;
    }
    return m->half_ring;
}

/* A chunk of the loop: the split kernel's buffers, where each term goes
 * (ring entry of the partner's row, or a trash entry), and whether it
 * ends its row's main part. */
struct half_buf {
    struct pd_chunk_buf b;
    uint32_t pi[PD_CHUNK]; /* unless direct */
    bool last;
    bool direct; /* every partner's row is the thread's: entry partner mod W */
};

/* What one thread's sweep works with. */
struct half_ctx {
    const struct pd_kctx *c;
    double *ring;    /* (mask + 1 + HALF_TRASH) entries of HALF_COLS */
    size_t mask;
    const uint8_t *flags; /* per owned row: HALF_IRREGULAR, HALF_CLEAN */
    size_t hi_push;  /* pushes go to the rows below (0: none) */
    double *const *f;
    double *diss;
};

/* Pass 0 of chunk b, and in the same loop the plain sum of chunk p (NULL:
 * none) into its row's entry and the negated terms into its partners'
 * entries.  Pushes only when @p push (a constant: the first pass has
 * none). */
static inline __attribute__((always_inline)) void
half_gather_v(int dim, int push, int fast, const struct half_ctx *h, struct half_buf *hb,
              const struct half_buf *hp)
{
    const struct pd_kctx *c = h->c;
    struct pd_chunk_buf *b = &hb->b;
    const struct pd_chunk_buf *p = hp ? &hp->b : NULL;
    const size_t np = p ? p->nb : 0;
    const size_t trash = h->mask + 1, hi = h->hi_push, mask = h->mask;
    /* a direct chunk (most of them) finds its partners' entries from the
     * partner indices, without the table pi (fast: b and p both direct) */
    const bool bdir = fast || hb->direct, pdir = fast || (hp && hp->direct);
    double *restrict ring = h->ring;
    double dummy[HALF_COLS] = {0.0, 0.0, 0.0, 0.0};
    double *ps = p ? ring + HALF_COLS * (p->i & h->mask) : dummy;
    double sx = ps[0], sy = ps[1], sz = ps[2];
#define HALF_PSUM(k)                                                                            \
    do {                                                                                        \
        PD_ADD_TERM(dim, p, k, sx, sy, sz);                                                     \
        if (push) {                                                                             \
            const size_t e = pdir ? (size_t)c->partner[p->s + (k)] & mask : (size_t)hp->pi[k];  \
            double *q = ring + HALF_COLS * e;                                                   \
            q[0] -= p->gx[k];                                                                   \
            if (dim > 1)                                                                        \
                q[1] -= p->gy[k];                                                               \
            if (dim > 2)                                                                        \
                q[2] -= p->gz[k];                                                               \
        }                                                                                       \
    } while (0)
#define HALF_PI(k)                                                                              \
    do {                                                                                        \
        if (push && !bdir) {                                                                    \
            const size_t j = (size_t)c->partner[b->s + (k)];                                    \
            const bool to = j > b->i && j < hi && !(h->flags[j] & HALF_IRREGULAR);              \
            hb->pi[k] = (uint32_t)(to ? (j & mask) : trash + ((k) & (HALF_TRASH - 1)));         \
        }                                                                                       \
    } while (0)
    PD_PASS0(c, b, np, HALF_PSUM, HALF_PI);
    ps[0] = sx;
    ps[1] = sy;
    ps[2] = sz;
#undef HALF_PSUM
#undef HALF_PI
}

/* half_gather_v with the common case, both chunks direct, in a loop of its
 * own. */
static inline __attribute__((always_inline)) void
half_gather(int dim, int push, const struct half_ctx *h, struct half_buf *hb,
            const struct half_buf *hp)
{
    if (push && hb->direct && (!hp || hp->direct))
        half_gather_v(dim, push, 1, h, hb, hp);
    else
        half_gather_v(dim, push, 0, h, hb, hp);
}

/* Pass 2 of a chunk with a half-bond past the pre-test, in slot order:
 * each such half-bond settled with the exact test (l - r) / r > s0 (both
 * halves marked when the partner's row is this thread's, with the energy
 * pushed to it); the sums and pushes as half_gather's. */
static inline __attribute__((always_inline)) void
half_settle(int dim, int push, const struct half_ctx *h, const struct half_buf *hb)
{
    const struct pd_kctx *c = h->c;
    const struct pd_chunk_buf *b = &hb->b;
    double *ring = h->ring;
    double *ps = ring + HALF_COLS * (b->i & h->mask);
    double sx = ps[0], sy = ps[1], sz = ps[2], dd = ps[3];
    for (size_t k = 0; k < b->nb; k++) {
        const size_t s = b->s + k;
        double *q = NULL;
        if (push)
            q = ring + HALF_COLS * (hb->direct ? (size_t)c->partner[s] & h->mask
                                               : (size_t)hb->pi[k]);
        const unsigned ty = pd_kc_type(c, s);
        if (pd_breaks_now(c, b, k, ty)) {
            const size_t i = b->i, j = (size_t)c->partner[s];
            const double e = pd_break_half(dim, c, b, k, ty);
            dd += e;
            if (push && (hb->direct || hb->pi[k] <= h->mask)) {
                const size_t t = lower_slot(c->off, c->partner, j, i);
                c->st[t] |= BOND_BROKEN;
                if (c->fresh && !(ty & 1u))
                    c->fresh[t] = 1;
                q[3] += e;
            }
            if (!c->late)
                continue;
        }
        PD_ADD_TERM(dim, b, k, sx, sy, sz);
        if (push) {
            q[0] -= b->gx[k];
            if (dim > 1)
                q[1] -= b->gy[k];
            if (dim > 2)
                q[2] -= b->gz[k];
        }
    }
    ps[0] = sx;
    ps[1] = sy;
    ps[2] = sz;
    ps[3] = dd;
}

/* Row i is complete: its sums onto f and diss, its entry cleared. */
static inline __attribute__((always_inline)) void half_finish(int dim, const struct half_ctx *h,
                                                              size_t i)
{
    double *e = h->ring + HALF_COLS * (i & h->mask);
    h->f[0][i] += e[0];
    if (dim > 1)
        h->f[1][i] += e[1];
    if (dim > 2)
        h->f[2][i] += e[2];
    h->diss[i] += e[3];
    e[0] = e[1] = e[2] = e[3] = 0.0;
}

/* The pending plain chunk (if any) summed, and its row finished when it
 * was the row's last. */
static inline __attribute__((always_inline)) void
half_flush(int dim, int push, const struct half_ctx *h, struct half_buf **pend)
{
    const struct half_buf *p = *pend;
    if (!p)
        return;
    struct half_buf none; /* an empty chunk: only its count and start are read */
    none.b.nb = 0;
    none.b.s = 0;
    none.direct = true;
    half_gather(dim, push, h, &none, p);
    if (push && p->last)
        half_finish(dim, h, p->b.i);
    *pend = NULL;
}

/* Slots [s, e) of row i through the passes, chunk by chunk (two buffers:
 * the one pending its plain sum, and the next); @p ends: these slots end
 * the row's main part, which is finished once summed. */
static inline __attribute__((always_inline)) void
half_segment(int dim, int push, const struct half_ctx *h, struct half_buf *buf, int *next,
             struct half_buf **pend, size_t i, size_t s, size_t e, bool ends)
{
    const struct pd_kctx *c = h->c;
    for (size_t s0 = s; s0 < e; s0 += PD_CHUNK) {
        struct half_buf *hb = &buf[*next];
        *next ^= 1;
        struct pd_chunk_buf *b = &hb->b;
        b->i = i;
        b->r = 0;
        b->s = s0;
        b->nb = e - s0 < PD_CHUNK ? e - s0 : PD_CHUNK;
        b->xi0 = c->x[0][i];
        b->yi0 = dim > 1 ? c->x[1][i] : 0.0;
        b->zi0 = dim > 2 ? c->x[2][i] : 0.0;
        hb->last = ends && s0 + b->nb == e;
        /* a clean row's upper part ascends: its last partner is its largest */
        hb->direct = push && (h->flags[i] & HALF_CLEAN) &&
                     (size_t)c->partner[s0 + b->nb - 1] < h->hi_push;
        const struct half_buf *p = *pend;
        half_gather(dim, push, h, hb, p);
        if (push && p && p->last)
            half_finish(dim, h, p->b.i);
        *pend = NULL;
        if (pd_pass1(dim, c, b)) {
            half_settle(dim, push, h, hb);
            if (push && hb->last)
                half_finish(dim, h, i);
        } else {
            *pend = hb;
        }
    }
}

/* One thread's rows [lo, hi). */
static inline __attribute__((always_inline)) void half_range(int dim, struct half_ctx *h,
                                                             size_t lo, size_t hi)
{
    const struct pd_kctx *c = h->c;
    struct half_buf buf[2];
    struct half_buf *pend = NULL;
    int next = 0;
    /* first pass: the bonds to partners below lo, from the rows' side (the
     * leading slots of the rows within a ring of lo) */
    const size_t end = hi - lo > h->mask ? lo + h->mask + 1 : hi;
    h->hi_push = 0;
    for (size_t i = lo; i < end; i++) {
        if (h->flags[i] & HALF_IRREGULAR)
            continue;
        const size_t s = c->off[i], e = first_not_below(c->off, c->partner, i, lo);
        half_segment(dim, 0, h, buf, &next, &pend, i, s, e, false);
    }
    half_flush(dim, 0, h, &pend);
    /* the sweep: each row's upper part, its terms pushed to its partners */
    h->hi_push = hi;
    for (size_t i = lo; i < hi; i++) {
        /* an irregular row: all its slots in order, pushing to its regular
         * partners above i only */
        const size_t s = h->flags[i] & HALF_IRREGULAR
                             ? c->off[i]
                             : first_not_below(c->off, c->partner, i, i + 1);
        const size_t e = c->off[i + 1];
        if (s < e) {
            half_segment(dim, 1, h, buf, &next, &pend, i, s, e, true);
        } else {
            half_flush(dim, 1, h, &pend);
            half_finish(dim, h, i);
        }
    }
    half_flush(dim, 1, h, &pend);
    /* the trash too, so that the whole buffer is zero between calls, for
     * a later ring width (a list rebuilt by migration) */
    memset(h->ring + HALF_COLS * (h->mask + 1), 0, HALF_TRASH * HALF_COLS * sizeof *h->ring);
}

/* The loop per dimension, so that the dimension is a constant in the
 * threads' code. */
#define HALF_DIM(DIM)                                                                           \
    static void half_forces##DIM(const struct pd_kctx *c, size_t n, double *ring, size_t w,     \
                                 const uint8_t *flags, int nt_max, double *const *f,            \
                                 double *diss)                                                  \
    {                                                                                           \
        (void)nt_max;                                                                           \
        _Pragma("omp parallel num_threads(nt_max)")                                             \
        {                                                                                       \
            size_t t = 0, nt = 1;                                                               \
            HALF_THREAD_IDS(t, nt);                                                             \
            struct half_ctx h = {c, ring + t * (w + HALF_TRASH) * HALF_COLS, w - 1, flags, 0, f, \
                                 diss};                                                         \
            half_range(DIM, &h, n * t / nt, n * (t + 1) / nt);                                  \
        }                                                                                       \
    }
#ifdef _OPENMP
#define HALF_THREAD_IDS(t, nt)                                                                  \
    do {                                                                                        \
        t = (size_t)omp_get_thread_num();                                                       \
        nt = (size_t)omp_get_num_threads();                                                     \
    } while (0)
#else
#define HALF_THREAD_IDS(t, nt) ((void)0)
#endif
HALF_DIM(1)
HALF_DIM(2)
HALF_DIM(3)

bool pd_half_forces(struct model *m, const struct sim *sim, const struct pd_kctx *c, size_t n,
                    double *const *f, double *diss)
{
    m->half_used = false;
    if (m->half_off)
        return false;
    const size_t w = pd_half_ring(m, sim);
    if (!w)
        return false;
#ifdef _OPENMP
    const int nt = omp_get_max_threads();
#else
    const int nt = 1;
#endif
    /* the rings, all zero between calls (every row clears its entry) */
    const size_t len = (size_t)nt * (w + HALF_TRASH) * HALF_COLS;
    if (m->half_buf_len < len) {
        free(m->half_buf);
        m->half_buf = calloc(len, sizeof *m->half_buf);
        m->half_buf_len = m->half_buf ? len : 0;
        if (!m->half_buf)
            return false; /* memory is short: the split kernel */
    }
    switch (sim->dim) {
    case 1:
        half_forces1(c, n, m->half_buf, w, m->half_flags, nt, f, diss);
        break;
    case 2:
        half_forces2(c, n, m->half_buf, w, m->half_flags, nt, f, diss);
        break;
    default:
        half_forces3(c, n, m->half_buf, w, m->half_flags, nt, f, diss);
        break;
    }
    m->half_used = true;
    return true;
}

void pd_set_row_loop(struct model *m, bool rows)
{
    m->half_off = rows;
}

bool pd_used_half_loop(const struct model *m)
{
    return m->half_used;
}
