/**
 * @file lattice_half.c
 * @brief The linear lattice loop with each bond evaluated once (issue 25
 *        item 1), bit for bit the sums of the row loop of lattice_forces.c.
 *
 * The row loop evaluates every bond twice, once from each of its rows.  Here
 * only the row of the lower index j evaluates the bond j-i (i > j) and hands
 * i the negated term: x_j - x_i = -(x_i - x_j) exactly (round to nearest is
 * symmetric), so |dx|^2, r, the coefficient c and the breaking decision are
 * the same bits from both ends (the rest length and type are checked to be
 * symmetric), and c (x_j - x_i) = -(c (x_i - x_j)).  Half the square roots
 * and divisions, half the gathers and coefficient work.
 *
 * The order of each row's sum is kept.  The rows of a lattice's list are
 * sorted (core/neighbor.h): first the partners below i, ascending, then
 * those above.  Row i's sum fi = 0 + t_1 + t_2 + ... (slot order) is started
 * in a per-thread ring of accumulators, ring[i mod W], by the pushes of its
 * lower partners, which arrive in ascending order because the rows are
 * swept in order; row i then adds the terms of its upper partners in slot
 * order and f_i += the ring entry, which is cleared for row i + W.  W, a
 * power of two, exceeds the largest index distance of a bond (1 024 entries,
 * 16 kB, on lattice2d: the ring stays in L1).  A second ring counts each
 * row's lower partners as they record their bonds, which gives the row's
 * first upper slot without a scan.  A thread's range [lo, hi)
 * first evaluates, from the rows' own side, the bonds to partners below lo
 * (evaluated again by the thread below: the same bits), and pushes nothing
 * to rows at or past hi, nor to ghosts: every row is summed by its thread
 * alone, in its order, for any thread count.
 *
 * Breaking is booked as the row loop books it: a bond that breaks now marks
 * both of its halves and books each half's energy on its row; a row's
 * bookings come in slot order (its lower partners' rows are swept first,
 * ascending), so diss[] sums in the same order too.
 *
 * Angular springs (2D): each row's sum adds, after the axial term of each
 * slot, the angle forces buffered for it (lattice_forces.c, pass 1); the
 * pushed term carries its slot's buffer along (push_angles).
 *
 * Used for the linear law of one material, when the rows pass
 * lattice_half_ring's check (sorted as above, symmetric); otherwise,
 * e.g. on a rank of a distributed run whose rows list ghosts before lower
 * owned partners, the row loop runs.
 */
#include "models/lattice/lattice_kernels.h"

#include "core/bond_list.h"
#include "core/particles.h"
#include "core/sim.h"

#include <math.h>
#include <stdlib.h>

/* Largest ring [entries per thread]: a list whose bonds join particles
 * further apart in index takes the row loop. */
#define HALF_RING_MAX ((size_t)1 << 20)

/* Slot of partner @p j in the lower part of row @p i, or SIZE_MAX. */
static size_t lower_slot(const size_t *offset, const int32_t *partner, size_t i, size_t j)
{
    for (size_t s = offset[i]; s < offset[i + 1] && (size_t)partner[s] < i; s++)
        if ((size_t)partner[s] == j)
            return s;
    return SIZE_MAX;
}

/* Whether the owned rows [0, n) suit the once-per-bond loop; *span: the
 * largest index distance of a bond between owned particles. */
static int rows_suit(const struct bond_list *bl, size_t n, size_t *span)
{
    size_t n_lower = 0, n_upper = 0;
    *span = 0;
    if (bl->n < n)
        return 0;
    for (size_t i = 0; i < n; i++) {
        const size_t e = bl->offset[i + 1];
        size_t s = bl->offset[i], last = 0;
        int any = 0;
        /* the lower part: ascending, no duplicates, counted in 16 bits */
        if (e - s > UINT16_MAX)
            return 0;
        for (; s < e && (size_t)bl->partner[s] < i; s++, n_lower++) {
            if (any && (size_t)bl->partner[s] <= last)
                return 0;
            last = (size_t)bl->partner[s];
            any = 1;
        }
        /* the upper part: owned partners ascending (ghosts anywhere), each
         * with its twin in the partner's lower part, same length and type */
        for (; s < e; s++) {
            const size_t j = (size_t)bl->partner[s];
            if (j <= i)
                return 0;
            if (j >= n)
                continue;
            if (any && j <= last)
                return 0;
            last = j;
            any = 1;
            n_upper++;
            const size_t t = lower_slot(bl->offset, bl->partner, j, i);
            if (t == SIZE_MAX || bond_rest(bl, s) != bond_rest(bl, t) ||
                (bl->type && bl->type[s] != bl->type[t]) || bl->state[s] != bl->state[t])
                return 0;
            if (j - i > *span)
                *span = j - i;
        }
    }
    /* every upper half has a distinct lower twin: equal counts make it a
     * one-to-one map, so no lower half is left without its push */
    return n_lower == n_upper;
}

size_t lattice_half_ring(struct model *m, const struct sim *sim)
{
    const struct bond_list *bl = m->bl;
    const size_t n = sim->p->n_owned;
    if (m->half_known && m->half_gen == bl->gen && m->half_n == n)
        return m->half_ring;
    size_t span = 0, w = 1;
    const int ok = rows_suit(bl, n, &span);
    while (w <= span)
        w <<= 1;
    m->half_ring = ok && w <= HALF_RING_MAX ? w : 0;
    m->half_known = true;
    m->half_gen = bl->gen;
    m->half_n = n;
    return m->half_ring;
}

/* Coefficient of half-bond @p s of row @p i (partner @p j, bond vector dx,
 * r2 = |dx|^2), the row loop's arithmetic (lattice_forces.c, row_linear),
 * booking a break on i alone. */
LATTICE_INLINE double slot_coef(struct model *m, const struct lattice_view *v,
                                const struct lattice_bond_law *pw, size_t i, size_t s, size_t j,
                                const double dx[3], double r2, const int dim, const int multi)
{
    const double r = sqrt(r2), r_rest = view_rest(v, s);
    const struct lattice_bond_law *b = &pw[multi ? v->type[s] : 0];
    double c = b->k - b->k * r_rest / r;
    if (LATTICE_UNLIKELY(v->state[s]))
        c = c < 0.0 ? c : 0.0;
    else if (LATTICE_UNLIKELY(r > r_rest * b->t_lim || r < r_rest * b->c_lim))
        c = lattice_break_half(m, i, s, b, r_rest, r, lattice_bond_dr(v, i, j, dim, dx, r));
    return c;
}

/* Bond i-j (j > i, slot s in row i, length r) breaks now: both halves as
 * the row loop breaks them, j's only when row j is this thread's (j < hi;
 * else j's thread books it in its first pass). Returns the coefficient. */
static double break_both(struct model *m, const struct lattice_view *v,
                         const struct lattice_bond_law *b, size_t i, size_t s, size_t j,
                         size_t hi, const double dx[3], double r_rest, double r, int dim)
{
    const double c =
        lattice_break_half(m, i, s, b, r_rest, r, lattice_bond_dr(v, i, j, dim, dx, r));
    if (j < hi) {
        const double dn[3] = {-dx[0], -dx[1], -dx[2]};
        lattice_break_half(m, j, lower_slot(v->offset, v->partner, j, i), b, r_rest, r,
                           lattice_bond_dr(v, j, i, dim, dn, r));
    }
    return c;
}

/* Ring entry of row i (stride dim). */
#define RING(i) (ring + ((i) & mask) * (size_t)dim)

/* Angular springs (2D): after the axial term of the upper half-bond s, its
 * row adds the angle forces on its partner's side of s (the buffer slot of
 * s's twin, reverse[s]) and the partner's entry those of the twin's side,
 * the buffer at s (reverse[twin] = s): each row's sum interleaves axial and
 * angle terms in slot order, as the row loop adds them. */
LATTICE_INLINE void push_angles(const struct lattice_view *v, size_t s, double a[3],
                                double *restrict rj)
{
    const double *ab = v->ang_buf + 2 * v->reverse[s];
    a[0] += ab[0];
    a[1] += ab[1];
    if (rj) {
        const double *aj = v->ang_buf + 2 * s;
        rj[0] += aj[0];
        rj[1] += aj[1];
    }
}

/* First pass of a thread's range [lo, hi): the rows' bonds to partners
 * below lo, evaluated from the rows' side into their ring entries. */
LATTICE_INLINE void half_first(struct model *m, const struct lattice_view *v,
                               const struct lattice_bond_law *pw, size_t lo, size_t hi,
                               double *restrict ring, uint16_t *restrict cnt, size_t mask,
                               const int dim, const int multi, const int gather)
{
    const size_t end = hi - lo > mask ? lo + mask + 1 : hi;
    for (size_t i = lo; i < end; i++) {
        double *ri = RING(i);
        for (size_t s = v->offset[i]; s < v->offset[i + 1] && (size_t)v->partner[s] < lo; s++) {
            cnt[i & mask]++;
            const size_t j = (size_t)v->partner[s];
            double dx[3] = {0, 0, 0};
            const double r2 = bond_vec(v, i, j, dim, dx);
            const double c = slot_coef(m, v, pw, i, s, j, dx, r2, dim, multi);
            for (int d = 0; d < dim; d++)
                ri[d] += c * dx[d];
            if (gather) {
                const double *ab = v->ang_buf + 2 * v->reverse[s];
                ri[0] += ab[0];
                ri[1] += ab[1];
            }
        }
    }
}

/* Row i alone (more than a block's half-bonds): its upper half-bonds. */
LATTICE_INLINE void half_row(struct model *m, const struct lattice_view *v,
                             const struct lattice_bond_law *pw, size_t i, size_t hi,
                             double *restrict ring, uint16_t *restrict cnt, size_t mask,
                             const int dim, const int multi, const int gather)
{
    double *ri = RING(i);
    double a[3] = {ri[0], dim > 1 ? ri[1] : 0.0, dim > 2 ? ri[2] : 0.0};
    for (size_t s = v->offset[i]; s < v->offset[i + 1]; s++) {
        const size_t j = (size_t)v->partner[s];
        if (j < i)
            continue;
        double dx[3] = {0, 0, 0};
        const double r2 = bond_vec(v, i, j, dim, dx), r = sqrt(r2);
        const double r_rest = view_rest(v, s);
        const struct lattice_bond_law *b = &pw[multi ? v->type[s] : 0];
        double c = b->k - b->k * r_rest / r;
        if (LATTICE_UNLIKELY(v->state[s]))
            c = c < 0.0 ? c : 0.0;
        else if (LATTICE_UNLIKELY(r > r_rest * b->t_lim || r < r_rest * b->c_lim))
            c = break_both(m, v, b, i, s, j, hi, dx, r_rest, r, dim);
        double *rj = j < hi ? RING(j) : NULL;
        if (rj)
            cnt[j & mask]++;
        for (int d = 0; d < dim; d++) {
            const double g = c * dx[d];
            a[d] += g;
            if (rj)
                rj[d] -= g;
        }
        if (gather)
            push_angles(v, s, a, rj);
    }
    double fi[3] = {a[0], a[1], a[2]};
    add_force(v, i, dim, fi);
    for (int d = 0; d < dim; d++)
        ri[d] = 0.0;
    cnt[i & mask] = 0;
}

/* Pass 3 of half_block (rare): the upper half-bonds of the rows [i0, i1)
 * (nu[] each, the last of their rows) that break now, in row order; their
 * terms (sc[0..dim)) again from the new coefficient.  sc[3]: signed rest
 * lengths, jb partners, tb types. */
static void half_breaks(struct model *m, const struct lattice_view *v,
                        const struct lattice_bond_law *pw, size_t i0, size_t i1, size_t hi,
                        const uint16_t *nu, double sc[][LATTICE_BLOCK], const int32_t *jb,
                        const uint8_t *tb, int dim, int multi)
{
    size_t t = 0;
    for (size_t i = i0; i < i1; i++) {
        const size_t e = v->offset[i + 1];
        for (size_t s = e - nu[i - i0]; s < e; s++, t++) {
            if (!(sc[3][t] > 0.0)) /* broken before */
                continue;
            const size_t j = (size_t)jb[t];
            double dx[3] = {0, 0, 0}; /* again: pass 2 replaced them by the terms */
            const double r = sqrt(bond_vec(v, i, j, dim, dx)), r_rest = sc[3][t];
            const struct lattice_bond_law *b = &pw[multi ? tb[t] : 0];
            if (r > r_rest * b->t_lim || r < r_rest * b->c_lim) {
                const double c = break_both(m, v, b, i, s, j, hi, dx, r_rest, r, dim);
                for (int d = 0; d < dim; d++)
                    sc[d][t] = c * dx[d];
            }
        }
    }
}

/* The rows from i0 on, as many as fit a block (at most LATTICE_BLOCK rows
 * and half-bonds, at least one row; returns the end): (1) the upper
 * half-bonds' vectors and rest lengths, compacted, a broken bond's length
 * negated (lengths are positive: the sign carries the state, fabs gives the
 * length back exactly); (2) their coefficients and terms c dx, contiguous
 * and without branches (vectorised: the sqrt and division); (3) rare: the
 * bonds that break now, in row order; (4) per row in order: the ring entry
 * plus the terms in slot order, each term pushed negated to the partner's
 * entry.  A first row of more than a block's half-bonds goes alone
 * (half_row). */
LATTICE_INLINE size_t half_block(struct model *m, const struct lattice_view *v,
                                 const struct lattice_bond_law *pw, size_t i0, size_t hi,
                                 double *restrict ring, uint16_t *restrict cnt, size_t mask,
                                 const int dim, const int multi, const int gather,
                                 const int tab)
{
    /* sc[0..dim): bond vectors, then terms; sc[3]: signed rest lengths */
    double sc[4][LATTICE_BLOCK];
    int32_t jb[LATTICE_BLOCK];
    uint8_t tb[LATTICE_BLOCK];
    uint16_t nu[LATTICE_BLOCK];
    const size_t sb = v->offset[i0];
    if (v->offset[i0 + 1] - sb > LATTICE_BLOCK) {
        half_row(m, v, pw, i0, hi, ring, cnt, mask, dim, multi, gather);
        return i0 + 1;
    }
    /* the block's end: the last row whose slots still fit (offset is
     * sorted: a binary search, not a test per row) */
    size_t lo_end = i0 + 1, hi_end = hi - i0 < LATTICE_BLOCK ? hi : i0 + LATTICE_BLOCK;
    while (lo_end < hi_end) {
        const size_t mid = lo_end + (hi_end - lo_end + 1) / 2;
        if (v->offset[mid] - sb <= LATTICE_BLOCK)
            lo_end = mid;
        else
            hi_end = mid - 1;
    }
    const size_t i1 = lo_end;
    size_t nt = 0, s = sb;
    for (size_t i = i0; i < i1; i++) {
        const double xi = v->x0[i], yi = dim > 1 ? v->x1[i] : 0.0,
                     zi = dim > 2 ? v->x2[i] : 0.0;
        const size_t e = v->offset[i + 1];
        s = v->offset[i] + cnt[i & mask]; /* past the lower partners */
        cnt[i & mask] = 0;
        const size_t t0 = nt;
        /* (nt < LATTICE_BLOCK always holds: the second exit keeps GCC from
         * vectorising a loop of three or so with gathers and checks) */
        for (; s < e && nt < LATTICE_BLOCK; s++, nt++) {
            const int32_t j = v->partner[s];
            sc[0][nt] = v->x0[j] - xi;
            if (dim > 1)
                sc[1][nt] = v->x1[j] - yi;
            if (dim > 2)
                sc[2][nt] = v->x2[j] - zi;
            const double r_rest = tab ? v->rest_tab[v->rest_idx[s]] : v->rest[s];
            sc[3][nt] = v->state[s] ? -r_rest : r_rest;
            if (multi)
                tb[nt] = v->type[s];
            jb[nt] = j;
            if ((size_t)j < hi)
                cnt[j & mask]++;
        }
        nu[i - i0] = (uint16_t)(nt - t0);
    }
    const double k0 = pw[0].k, tl0 = pw[0].t_lim, cl0 = pw[0].c_lim;
    int64_t breaks = 0;
    for (size_t t = 0; t < nt; t++) {
        double r2 = sc[0][t] * sc[0][t];
        if (dim > 1)
            r2 += sc[1][t] * sc[1][t];
        if (dim > 2)
            r2 += sc[2][t] * sc[2][t];
        const double r = sqrt(r2), r_rest = fabs(sc[3][t]);
        double k = k0, tl = tl0, cl = cl0;
        if (multi) {
            k = pw[tb[t]].k;
            tl = pw[tb[t]].t_lim;
            cl = pw[tb[t]].c_lim;
        }
        const double c = k - k * r_rest / r;
        const double cmin = c < 0.0 ? c : 0.0;
        const int64_t intact = sc[3][t] > 0.0;
        breaks |= intact & ((int64_t)(r > r_rest * tl) | (int64_t)(r < r_rest * cl));
        const double cb = intact ? c : cmin;
        for (int d = 0; d < dim; d++)
            sc[d][t] = cb * sc[d][t];
    }
    if (LATTICE_UNLIKELY(breaks))
        half_breaks(m, v, pw, i0, i1, hi, nu, sc, jb, tb, dim, multi);
    size_t t = 0;
    for (size_t r = i0; r < i1; r++) {
        double *ri = RING(r);
        double a0 = ri[0], a1 = dim > 1 ? ri[1] : 0.0, a2 = dim > 2 ? ri[2] : 0.0;
        size_t sl = gather ? v->offset[r + 1] - nu[r - i0] : 0; /* slot of entry t */
        for (const size_t te = t + nu[r - i0]; t < te; t++, sl++) {
            const size_t j = (size_t)jb[t];
            const double g0 = sc[0][t], g1 = dim > 1 ? sc[1][t] : 0.0,
                         g2 = dim > 2 ? sc[2][t] : 0.0;
            a0 += g0;
            if (dim > 1)
                a1 += g1;
            if (dim > 2)
                a2 += g2;
            double *rj = LATTICE_UNLIKELY(j >= hi) ? NULL : RING(j);
            if (gather) {
                double a[3] = {a0, a1, 0.0};
                if (rj) {
                    rj[0] -= g0;
                    rj[1] -= g1;
                }
                push_angles(v, sl, a, rj);
                a0 = a[0];
                a1 = a[1];
                continue;
            }
            if (!rj)
                continue;
            rj[0] -= g0;
            if (dim > 1)
                rj[1] -= g1;
            if (dim > 2)
                rj[2] -= g2;
        }
        const double fi[3] = {a0, a1, a2};
        add_force(v, r, dim, fi);
        ri[0] = 0.0;
        if (dim > 1)
            ri[1] = 0.0;
        if (dim > 2)
            ri[2] = 0.0;
    }
    return i1;
}

LATTICE_INLINE void half_loop(struct model *m, const struct lattice_view *v, size_t lo, size_t hi,
                              double *restrict ring, uint16_t *restrict cnt, size_t mask,
                              const int dim, const int multi, const int gather)
{
    const struct lattice_bond_law *pw = m->pair; /* material 0 with itself */
    half_first(m, v, pw, lo, hi, ring, cnt, mask, dim, multi, gather);
    for (size_t i = lo; i < hi;)
        i = v->rest_idx ? half_block(m, v, pw, i, hi, ring, cnt, mask, dim, multi, gather, 1)
                        : half_block(m, v, pw, i, hi, ring, cnt, mask, dim, multi, gather, 0);
}

LATTICE_CLONES void lattice_half_range(struct model *m, const struct lattice_view *v, size_t lo,
                                       size_t hi, double *ring, uint16_t *cnt, size_t mask,
                                       int dim, int multi, int gather)
{
    if (dim == 1)
        half_loop(m, v, lo, hi, ring, cnt, mask, 1, 0, 0);
    else if (dim == 2 && gather && multi)
        half_loop(m, v, lo, hi, ring, cnt, mask, 2, 1, 1);
    else if (dim == 2 && gather)
        half_loop(m, v, lo, hi, ring, cnt, mask, 2, 0, 1);
    else if (dim == 2 && multi)
        half_loop(m, v, lo, hi, ring, cnt, mask, 2, 1, 0);
    else if (dim == 2)
        half_loop(m, v, lo, hi, ring, cnt, mask, 2, 0, 0);
    else if (multi)
        half_loop(m, v, lo, hi, ring, cnt, mask, 3, 1, 0);
    else
        half_loop(m, v, lo, hi, ring, cnt, mask, 3, 0, 0);
}
