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
 * in a per-thread ring of accumulators, ring[i mod W] (one array per
 * component), by the pushes of its lower partners, which arrive in
 * ascending order because the rows are swept in order; row i then adds the
 * terms of its upper partners in slot order and f_i += the ring entry,
 * which is cleared for row i + W.  W, a power of two, exceeds the largest
 * index distance of a bond plus a stencil block (STENCIL_ROWS): 2 048
 * entries on lattice2d, 32 kB, of which only the few windows the sweep
 * touches are hot.  A thread's range [lo, hi)
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
 * Stencil runs (issue 25 item 1, round 3).  On a regular lattice most rows
 * repeat one pattern: n_l lower partners, then upper ones at i + o_1 <
 * i + o_2 < ... (on lattice2d two patterns, one per row parity, over runs
 * of a thousand rows; the rest lengths differ in their last bits along a
 * row and stay per half-bond).  lattice_half_ring finds these runs once per
 * list; the loop then takes STENCIL_ROWS rows of a run at a time without
 * reading the partners: per offset o_k, contiguously in t, the bond
 * i+t -> i+t+o_k (x[i+t+o_k] - x[i+t], its rest length from every
 * (n_l + n_u)-th slot, coefficient, term); then the pushes, offset by
 * offset from the largest to the smallest (a ring entry's lower partners
 * i+t-o_k then arrive in ascending order, as in the row sweep), and the
 * rows' sums: the ring entry plus the terms in offset order.  The same
 * operations on the same values as the blocks below, so the same bits.  A
 * block whose rows hold a broken half-bond or a bond that breaks now is
 * left to the general blocks (the states of its rows' slots are
 * contiguous: one OR over them), as is the end of a thread's range, whose
 * pushes would pass hi.
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

/* Rows per block of a stencil run: the block's terms (LATTICE_STENCIL_MAX
 * offsets x 3 components x 8 B a row, 12 kB) stay in L1. */
#define STENCIL_ROWS 64

/* Shortest run worth a stencil; most distinct stencils kept per list (a
 * regular lattice has a handful: its interior patterns and those of its
 * boundary rows; further ones leave their rows to the general blocks). */
#define STENCIL_MIN_RUN 8
#define STENCIL_MAX_KINDS 64

/* Slot of partner @p j in the lower part of row @p i, or SIZE_MAX. */
static size_t lower_slot(const size_t *offset, const int32_t *partner, size_t i, size_t j)
{
    for (size_t s = offset[i]; s < offset[i + 1] && (size_t)partner[s] < i; s++)
        if ((size_t)partner[s] == j)
            return s;
    return SIZE_MAX;
}

/* First upper slot of row @p i (its lower partners come first). */
static inline size_t upper_slot(const size_t *offset, const int32_t *partner, size_t i)
{
    size_t s = offset[i];
    while (s < offset[i + 1] && (size_t)partner[s] < i)
        s++;
    return s;
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
        /* the lower part: ascending, no duplicates */
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

/* Stencil of owned row @p i into @p st: 0 when its upper partners are too
 * many or include a ghost. */
static int row_stencil(const struct bond_list *bl, size_t n, size_t i, struct lattice_stencil *st)
{
    const size_t e = bl->offset[i + 1];
    size_t s = upper_slot(bl->offset, bl->partner, i);
    if (e - s > LATTICE_STENCIL_MAX)
        return 0;
    st->nl = s - bl->offset[i];
    st->nu = 0;
    for (; s < e; s++) {
        const size_t j = (size_t)bl->partner[s];
        if (j >= n)
            return 0;
        st->off[st->nu++] = j - i;
    }
    return 1;
}

static int same_stencil(const struct lattice_stencil *a, const struct lattice_stencil *b)
{
    if (a->nl != b->nl || a->nu != b->nu)
        return 0;
    for (size_t k = 0; k < a->nu; k++)
        if (a->off[k] != b->off[k])
            return 0;
    return 1;
}

/* The runs of at least STENCIL_MIN_RUN consecutive owned rows of one
 * stencil.  No memory: no runs, the general blocks give the same bits. */
static void find_runs(struct model *m, const struct bond_list *bl, size_t n)
{
    free(m->half_st);
    free(m->half_runs);
    m->half_st = malloc(STENCIL_MAX_KINDS * sizeof *m->half_st);
    m->half_runs = NULL;
    m->half_n_st = m->half_n_runs = 0;
    size_t cap = 0, a = 0, cur = SIZE_MAX;
    for (size_t i = 0; m->half_st && i <= n; i++) {
        struct lattice_stencil st;
        size_t k = SIZE_MAX;
        if (i < n && row_stencil(bl, n, i, &st)) {
            for (k = 0; k < m->half_n_st && !same_stencil(&m->half_st[k], &st); k++)
                ;
            if (k == m->half_n_st && k < STENCIL_MAX_KINDS)
                m->half_st[m->half_n_st++] = st;
            else if (k == m->half_n_st)
                k = SIZE_MAX;
        }
        if (k == cur)
            continue;
        if (cur != SIZE_MAX && i - a >= STENCIL_MIN_RUN) {
            if (m->half_n_runs == cap) {
                cap = cap ? 2 * cap : 256;
                struct lattice_run *r = realloc(m->half_runs, cap * sizeof *r);
                if (!r) {
                    m->half_n_runs = 0;
                    return;
                }
                m->half_runs = r;
            }
            m->half_runs[m->half_n_runs++] = (struct lattice_run){a, i, cur};
        }
        a = i;
        cur = k;
    }
}

size_t lattice_half_ring(struct model *m, const struct sim *sim)
{
    const struct bond_list *bl = m->bl;
    const size_t n = sim->p->n_owned;
    if (m->half_known && m->half_gen == bl->gen && m->half_n == n)
        return m->half_ring;
    size_t span = 0, w = 1;
    const int ok = rows_suit(bl, n, &span);
    while (w < span + STENCIL_ROWS)
        w <<= 1;
    m->half_ring = ok && w <= HALF_RING_MAX ? w : 0;
    m->half_n_runs = 0;
    /* fixed rest lengths only (the thermal lattice rewrites its doubles) */
    if (m->half_ring && bl->rest_idx)
        find_runs(m, bl, n);
    m->half_known = true;
    m->half_gen = bl->gen;
    m->half_n = n;
    return m->half_ring;
}

/* Whether the stencil runs apply on the view @p v: found (compact rest
 * lengths), one bond type, no angular springs. */
static bool half_stencils(const struct model *m, const struct lattice_view *v, int multi,
                          int gather)
{
    return m->half_n_runs > 0 && v->rest_idx && !multi && !gather;
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

/* Ring entry of row i, component d. */
#define RING(i, d) ring[(size_t)(d) * (mask + 1) + ((i) & mask)]

/* Angular springs (2D): after the axial term of the upper half-bond s, its
 * row adds the angle forces on its partner's side of s (the buffer slot of
 * s's twin, reverse[s]) and the partner's entry (row j, when @p to_j) those
 * of the twin's side, the buffer at s (reverse[twin] = s): each row's sum
 * interleaves axial and angle terms in slot order, as the row loop adds
 * them. */
LATTICE_INLINE void push_angles(const struct lattice_view *v, size_t s, double a[3],
                                double *restrict ring, size_t mask, size_t j, int to_j)
{
    const double *ab = v->ang_buf + 2 * v->reverse[s];
    a[0] += ab[0];
    a[1] += ab[1];
    if (to_j) {
        const double *aj = v->ang_buf + 2 * s;
        RING(j, 0) += aj[0];
        RING(j, 1) += aj[1];
    }
}

/* First pass of a thread's range [lo, hi): the rows' bonds to partners
 * below lo, evaluated from the rows' side into their ring entries. */
LATTICE_INLINE void half_first(struct model *m, const struct lattice_view *v,
                               const struct lattice_bond_law *pw, size_t lo, size_t hi,
                               double *restrict ring, size_t mask, const int dim,
                               const int multi, const int gather)
{
    const size_t end = hi - lo > mask ? lo + mask + 1 : hi;
    for (size_t i = lo; i < end; i++) {
        for (size_t s = v->offset[i]; s < v->offset[i + 1] && (size_t)v->partner[s] < lo; s++) {
            const size_t j = (size_t)v->partner[s];
            double dx[3] = {0, 0, 0};
            const double r2 = bond_vec(v, i, j, dim, dx);
            const double c = slot_coef(m, v, pw, i, s, j, dx, r2, dim, multi);
            for (int d = 0; d < dim; d++)
                RING(i, d) += c * dx[d];
            if (gather) {
                const double *ab = v->ang_buf + 2 * v->reverse[s];
                RING(i, 0) += ab[0];
                RING(i, 1) += ab[1];
            }
        }
    }
}

/* Row i alone (more than a block's half-bonds): its upper half-bonds. */
LATTICE_INLINE void half_row(struct model *m, const struct lattice_view *v,
                             const struct lattice_bond_law *pw, size_t i, size_t hi,
                             double *restrict ring, size_t mask, const int dim, const int multi,
                             const int gather)
{
    double a[3] = {RING(i, 0), dim > 1 ? RING(i, 1) : 0.0, dim > 2 ? RING(i, 2) : 0.0};
    for (size_t s = upper_slot(v->offset, v->partner, i); s < v->offset[i + 1]; s++) {
        const size_t j = (size_t)v->partner[s];
        double dx[3] = {0, 0, 0};
        const double r2 = bond_vec(v, i, j, dim, dx), r = sqrt(r2);
        const double r_rest = view_rest(v, s);
        const struct lattice_bond_law *b = &pw[multi ? v->type[s] : 0];
        double c = b->k - b->k * r_rest / r;
        if (LATTICE_UNLIKELY(v->state[s]))
            c = c < 0.0 ? c : 0.0;
        else if (LATTICE_UNLIKELY(r > r_rest * b->t_lim || r < r_rest * b->c_lim))
            c = break_both(m, v, b, i, s, j, hi, dx, r_rest, r, dim);
        const int to_j = j < hi;
        for (int d = 0; d < dim; d++) {
            const double g = c * dx[d];
            a[d] += g;
            if (to_j)
                RING(j, d) -= g;
        }
        if (gather)
            push_angles(v, s, a, ring, mask, j, to_j);
    }
    double fi[3] = {a[0], a[1], a[2]};
    add_force(v, i, dim, fi);
    for (int d = 0; d < dim; d++)
        RING(i, d) = 0.0;
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

/* The rows from i0 on, before @p stop, as many as fit a block (at most
 * LATTICE_BLOCK rows and half-bonds, at least one row; returns the end):
 * (1) the upper half-bonds' vectors and rest lengths, compacted, a broken
 * bond's length negated (lengths are positive: the sign carries the state,
 * fabs gives the length back exactly); (2) their coefficients and terms
 * c dx, contiguous and without branches (vectorised: the sqrt and
 * division); (3) rare: the bonds that break now, in row order; (4) per row
 * in order: the ring entry plus the terms in slot order, each term pushed
 * negated to the partner's entry.  A first row of more than a block's
 * half-bonds goes alone (half_row). */
LATTICE_INLINE size_t half_block(struct model *m, const struct lattice_view *v,
                                 const struct lattice_bond_law *pw, size_t i0, size_t hi,
                                 size_t stop, double *restrict ring, size_t mask,
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
        half_row(m, v, pw, i0, hi, ring, mask, dim, multi, gather);
        return i0 + 1;
    }
    /* the block's end: the last row whose slots still fit (offset is
     * sorted: a binary search, not a test per row) */
    size_t lo_end = i0 + 1, hi_end = stop - i0 < LATTICE_BLOCK ? stop : i0 + LATTICE_BLOCK;
    while (lo_end < hi_end) {
        const size_t mid = lo_end + (hi_end - lo_end + 1) / 2;
        if (v->offset[mid] - sb <= LATTICE_BLOCK)
            lo_end = mid;
        else
            hi_end = mid - 1;
    }
    const size_t i1 = lo_end;
    size_t nt = 0;
    for (size_t i = i0; i < i1; i++) {
        const double xi = v->x0[i], yi = dim > 1 ? v->x1[i] : 0.0,
                     zi = dim > 2 ? v->x2[i] : 0.0;
        const size_t e = v->offset[i + 1];
        size_t s = upper_slot(v->offset, v->partner, i);
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
        double a0 = RING(r, 0), a1 = dim > 1 ? RING(r, 1) : 0.0, a2 = dim > 2 ? RING(r, 2) : 0.0;
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
            const int to_j = !LATTICE_UNLIKELY(j >= hi);
            if (gather) {
                double a[3] = {a0, a1, 0.0};
                if (to_j) {
                    RING(j, 0) -= g0;
                    RING(j, 1) -= g1;
                }
                push_angles(v, sl, a, ring, mask, j, to_j);
                a0 = a[0];
                a1 = a[1];
                continue;
            }
            if (!to_j)
                continue;
            RING(j, 0) -= g0;
            if (dim > 1)
                RING(j, 1) -= g1;
            if (dim > 2)
                RING(j, 2) -= g2;
        }
        const double fi[3] = {a0, a1, a2};
        add_force(v, r, dim, fi);
        RING(r, 0) = 0.0;
        if (dim > 1)
            RING(r, 1) = 0.0;
        if (dim > 2)
            RING(r, 2) = 0.0;
    }
    return i1;
}

/* One contiguous piece of a push: r_d[t - t0] -= g_d[t], t in [t0, t1),
 * r_d = r + d W. */
LATTICE_INLINE void push_piece(double *restrict r, size_t w, double g[][STENCIL_ROWS], size_t t0,
                               size_t t1, const int dim)
{
    double *restrict r0 = r, *restrict r1 = dim > 1 ? r + w : r,
                     *restrict r2 = dim > 2 ? r + 2 * w : r;
    const double *restrict g0 = g[0], *restrict g1 = g[1], *restrict g2 = g[2];
    for (size_t t = t0; t < t1; t++) {
        r0[t - t0] -= g0[t];
        if (dim > 1)
            r1[t - t0] -= g1[t];
        if (dim > 2)
            r2[t - t0] -= g2[t];
    }
}

/* Push of one offset: ring[(start + t) mod W] -= g[t] per component,
 * t < n, in the ring's contiguous pieces. */
LATTICE_INLINE void ring_push(double *restrict ring, size_t start, double g[][STENCIL_ROWS],
                              size_t n, size_t mask, const int dim)
{
    const size_t w = mask + 1, n1 = w - start < n ? w - start : n;
    push_piece(ring + start, w, g, 0, n1, dim);
    push_piece(ring, w, g, n1, n, dim);
}

/* Row sums of one component over t in [t0, t1): f[t] += (ring entry + the
 * nu terms in offset order), with @p set f[t] = 0 + (...) without reading
 * f (add_force), the entry (r[t - t0]) cleared. */
LATTICE_INLINE void row_sums(double *restrict r, double g[][3][STENCIL_ROWS], size_t nu, int d,
                             double *restrict f, size_t t0, size_t t1, int set)
{
    for (size_t t = t0; t < t1; t++) {
        double a = r[t - t0];
        r[t - t0] = 0.0;
        for (size_t k = 0; k < nu; k++)
            a += g[k][d][t];
        f[t] = (set ? 0.0 : f[t]) + a;
    }
}

/* Rows [i0, i0 + nb) of a run of stencil @p st (nb <= STENCIL_ROWS, every
 * push below the range's end), all bonds of law @p b: 0, changing nothing,
 * when a slot of these rows is broken or a bond breaks now (the general
 * blocks then take the rows).  Per offset the bonds' terms, as half_block's
 * pass 2 computes them; then the pushes from the largest offset down, and
 * each row's sum in offset order (module comment).  @p nu_lit, @p ns_lit:
 * the stencil's upper and all slots as literals (0: read from @p st). */
LATTICE_INLINE int stencil_block(const struct lattice_view *v, const struct lattice_stencil *st,
                                 const struct lattice_bond_law *b, size_t i0, size_t nb,
                                 double *restrict ring, size_t mask, const int dim,
                                 const size_t nu_lit, const size_t ns_lit)
{
    const uint8_t *restrict state = v->state + v->offset[i0];
    const size_t n_slots = v->offset[i0 + nb] - v->offset[i0];
    uint8_t any = 0;
    for (size_t q = 0; q < n_slots; q++)
        any |= state[q];
    if (any)
        return 0;
    double g[LATTICE_STENCIL_MAX][3][STENCIL_ROWS];
    /* the rest lengths of the upper slots, offset by offset (a row's upper
     * slots are its last nu of ns) */
    double rest[LATTICE_STENCIL_MAX][STENCIL_ROWS];
    const size_t nu = nu_lit ? nu_lit : st->nu, ns = ns_lit ? ns_lit : st->nl + st->nu;
    {
        const uint16_t *restrict ri = v->rest_idx + v->offset[i0] + (ns - nu);
        const double *restrict tab = v->rest_tab;
        for (size_t t = 0; t < nb; t++, ri += ns)
            for (size_t k = 0; k < nu; k++)
                rest[k][t] = tab[ri[k]];
    }
    const double kk = b->k, tl = b->t_lim, cl = b->c_lim;
    int64_t breaks = 0;
    for (size_t k = 0; k < nu; k++) {
        const size_t o = st->off[k];
        const double *restrict rk = rest[k];
        const double *restrict x = v->x0 + i0, *restrict y = dim > 1 ? v->x1 + i0 : x,
                               *restrict z = dim > 2 ? v->x2 + i0 : x;
        double *restrict g0 = g[k][0], *restrict g1 = g[k][1], *restrict g2 = g[k][2];
        for (size_t t = 0; t < nb; t++) {
            const double dx = x[t + o] - x[t];
            const double dy = dim > 1 ? y[t + o] - y[t] : 0.0;
            const double dz = dim > 2 ? z[t + o] - z[t] : 0.0;
            double r2 = dx * dx;
            if (dim > 1)
                r2 += dy * dy;
            if (dim > 2)
                r2 += dz * dz;
            const double r = sqrt(r2), r0 = rk[t];
            const double c = kk - kk * r0 / r;
            breaks |= (int64_t)(r > r0 * tl) | (int64_t)(r < r0 * cl);
            g0[t] = c * dx;
            if (dim > 1)
                g1[t] = c * dy;
            if (dim > 2)
                g2[t] = c * dz;
        }
    }
    if (LATTICE_UNLIKELY(breaks))
        return 0;
    for (size_t k = nu; k-- > 0;)
        ring_push(ring, (i0 + st->off[k]) & mask, g[k], nb, mask, dim);
    const size_t w = mask + 1, start = i0 & mask, n1 = w - start < nb ? w - start : nb;
    double *restrict fd[3] = {v->f0 + i0, dim > 1 ? v->f1 + i0 : NULL,
                              dim > 2 ? v->f2 + i0 : NULL};
    for (int d = 0; d < dim; d++) {
        double *rd = ring + (size_t)d * w;
        if (v->set_forces) { /* two copies: the loop then reads no f */
            row_sums(rd + start, g, nu, d, fd[d], 0, n1, 1);
            row_sums(rd, g, nu, d, fd[d], n1, nb, 1);
        } else {
            row_sums(rd + start, g, nu, d, fd[d], 0, n1, 0);
            row_sums(rd, g, nu, d, fd[d], n1, nb, 0);
        }
    }
    return 1;
}

/* Returns the rows the stencil blocks took. */
LATTICE_INLINE size_t half_loop(struct model *m, const struct lattice_view *v, size_t lo,
                                size_t hi, double *restrict ring, size_t mask, const int dim,
                                const int multi, const int gather)
{
    const struct lattice_bond_law *pw = m->pair; /* material 0 with itself */
    const struct lattice_run *run = m->half_runs;
    const size_t nr = half_stencils(m, v, multi, gather) ? m->half_n_runs : 0;
    const int tab = v->rest_idx != NULL;
    half_first(m, v, pw, lo, hi, ring, mask, dim, multi, gather);
    /* the first run that ends past lo */
    size_t q = 0, qe = nr;
    while (q < qe) {
        const size_t mid = q + (qe - q) / 2;
        if (run[mid].b <= lo)
            q = mid + 1;
        else
            qe = mid;
    }
    size_t done = 0;
    for (size_t i = lo; i < hi;) {
        while (q < nr && run[q].b <= i)
            q++;
        size_t stop = hi;
        if (q < nr && run[q].a <= i) {
            const struct lattice_stencil *st = &m->half_st[run[q].st];
            const size_t reach = st->nu ? st->off[st->nu - 1] : 0;
            /* rows whose pushes stay below hi: i + t + reach < hi */
            const size_t end = run[q].b + reach < hi ? run[q].b : (hi > reach ? hi - reach : 0);
            if (i < end) {
                const size_t nb = end - i < STENCIL_ROWS ? end - i : STENCIL_ROWS;
                /* the interior rows of a 2D alpha lattice as literals */
                const int ok = st->nl == 3 && st->nu == 3
                                   ? stencil_block(v, st, &pw[0], i, nb, ring, mask, dim, 3, 6)
                                   : stencil_block(v, st, &pw[0], i, nb, ring, mask, dim, 0, 0);
                if (ok)
                    done += nb;
                else
                    for (size_t r = i; r < i + nb;)
                        r = tab ? half_block(m, v, pw, r, hi, i + nb, ring, mask, dim, multi,
                                             gather, 1)
                                : half_block(m, v, pw, r, hi, i + nb, ring, mask, dim, multi,
                                             gather, 0);
                i += nb;
                continue;
            }
        } else if (q < nr && run[q].a < hi) {
            stop = run[q].a;
        }
        i = tab ? half_block(m, v, pw, i, hi, stop, ring, mask, dim, multi, gather, 1)
                : half_block(m, v, pw, i, hi, stop, ring, mask, dim, multi, gather, 0);
    }
    return done;
}

LATTICE_CLONES size_t lattice_half_range(struct model *m, const struct lattice_view *v,
                                         size_t lo, size_t hi, double *ring, size_t mask,
                                         int dim, int multi, int gather)
{
    if (dim == 1)
        return half_loop(m, v, lo, hi, ring, mask, 1, 0, 0);
    if (dim == 2 && gather && multi)
        return half_loop(m, v, lo, hi, ring, mask, 2, 1, 1);
    if (dim == 2 && gather)
        return half_loop(m, v, lo, hi, ring, mask, 2, 0, 1);
    if (dim == 2 && multi)
        return half_loop(m, v, lo, hi, ring, mask, 2, 1, 0);
    if (dim == 2)
        return half_loop(m, v, lo, hi, ring, mask, 2, 0, 0);
    if (multi)
        return half_loop(m, v, lo, hi, ring, mask, 3, 1, 0);
    return half_loop(m, v, lo, hi, ring, mask, 3, 0, 0);
}
