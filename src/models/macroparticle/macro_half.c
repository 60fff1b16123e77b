/**
 * @file macro_half.c
 * @brief The macro-particle pair loop evaluating each pair once, with every
 *        particle's sums in the order of the full loop (macro_forces.c), so
 *        the results are the same bits for any thread and rank count.
 *
 * The neighbour list stays full (each pair in both rows, rows ascending in
 * the partner's key: the index on one rank, the global id on a distributed
 * run).  The end with the smaller key computes a pair, and so does an owned
 * particle whose partner is a ghost (the ghost's row is not summed here).
 * After each list change a flat pair list is made from it: per pair the
 * computing end and the partner, per slot of the owned rows the pair it
 * holds.  Pass 1 runs over the pairs (long vectorisable chunks): distance,
 * plastic update, pairwise Langevin force, the Mie law, and stores c = -f/r
 * and phi / 2 (+0 both when the pair does not count).  Pass 2 sums every row
 * over all its slots in list order, as the full loop does, reading its
 * pairs' values; in 3D four rows at a time, a row a vector lane (each lane
 * the same operations in the same order as one row alone), through a slot
 * layout by groups of four rows made with the pair list (macro_half_rows.c).
 *
 * Why the bits agree: x_i - x_j is exactly -(x_j - x_i) (IEEE subtraction),
 * so both ends of a pair compute the same r, re, phi and c; each end forms
 * its force term c (x_j - x_i) and virial terms 0.5 c dx dx from its own dx
 * with the full loop's operations; the pairwise Langevin term of the other
 * end is the exact negation (mu (v_i - v_j) and -sgn sp xi), subtracted; the
 * plastic update runs once and both slots take its state (the full loop
 * evolved them identically).  A pair that adds no Langevin force or plastic
 * work stores +0.0 where the full loop added nothing: sums that start at
 * +0.0 are never -0.0 in round-to-nearest, so adding a zero changes no bit.
 * For the same reason a pair that does not count (c = phi = +0 stored),
 * and a row of a four-row group that has ended (padded with the zero
 * pair), add +-0 terms instead of being skipped.
 *
 * One rank: rows in blocks, pass 1 of the block's pairs then pass 2 of its
 * rows (a row's other pairs belong to rows with smaller indices, done in
 * this block or an earlier one), so the pair values are read back while in
 * cache.  Threads split the rows into consecutive ranges; each first
 * computes (pass 1) the pairs of its last rows that the next range's rows
 * read and those of its first rows that read the previous range's, then,
 * after a barrier, sums its first rows (pass 2) and runs the rest of its
 * range block by block as one thread does.  A distributed run (or a list
 * whose pairs span more than a range): pass 1 over all pairs, then pass 2.
 */
#include "models/macroparticle/macro_half.h"

#include "core/neighbor.h"
#include "core/particles.h"
#include "core/sim.h"
#include "spall/error.h"

#include <stdlib.h>
#include <string.h>
#ifdef _OPENMP
#include <omp.h>
#endif

/* Rows per block of the fused one-thread loop: the block's pair values
 * (about 150 B a row) stay in L2 between the passes. */
#define HALF_BLOCK 512
#define NO_SLOT SIZE_MAX

void macro_half_free(struct model *m)
{
    free(m->hoff);
    free(m->hpi);
    free(m->hpj);
    free(m->hps);
    free(m->hprs);
    free(m->pid);
    free(m->pc);
    free(m->pphi);
    free(m->pwp);
    free(m->pfl);
    free(m->hreach);
    free(m->goff);
    free(m->gidx);
    free(m->gpid);
    m->hreach = NULL;
    m->hoff = m->hps = m->hprs = m->goff = NULL;
    m->pid = m->gpid = NULL;
    m->hpi = m->hpj = m->gidx = NULL;
    m->g_cap = 0;
    m->pc = m->pphi = m->pwp = m->pfl = NULL;
    m->half_pairs = m->half_pair_cap = 0;
    m->epot_lazy = 0; /* its pair values are gone (an error or the end) */
    macro_half_invalidate(m, NULL);
}

void macro_half_invalidate(struct model *m, struct neighbor_pairs *pairs)
{
    m->half_ok = false;
    if (m->hnew) {
        neighbor_pairs_free(m->hnew);
        free(m->hnew);
    }
    m->hnew = pairs;
}

/* *a holds @p count elements of @p size bytes: (re)allocated when it
 * grows or is missing (contents not kept). */
static bool need(void **a, size_t count, size_t size, bool grows)
{
    if (*a && !grows)
        return true;
    free(*a);
    *a = malloc((count ? count : 1) * size);
    return *a != NULL;
}

/* First slot of row i whose partner's key exceeds the particle's own. */
static size_t half_start(const struct neighbor_list *nl, const int64_t *pg, const int64_t *gid,
                         size_t i)
{
    const int64_t ki = pg ? gid[i] : (int64_t)i;
    size_t h = nl->offset[i];
    while (h < nl->offset[i + 1] && (pg ? pg[h] : (int64_t)nl->idx[h]) < ki)
        h++;
    return h;
}

/* The pairs row i computes: its suffix and its ghost partners before it. */
static size_t half_count(const struct neighbor_list *nl, size_t h, size_t i, size_t n)
{
    size_t c = nl->offset[i + 1] - h;
    for (size_t s = nl->offset[i]; s < h; s++)
        c += (size_t)nl->idx[s] >= n;
    return c;
}

/* Fill the pair list; returns the gid of a particle that a partner does
 * not list back (an asymmetric list), or -1. */
static int64_t half_fill(struct model *m, const struct particles *p, size_t n)
{
    const struct neighbor_list *nl = m->nl;
    const size_t *off = nl->offset;
    const int32_t *idx = nl->idx;
    int64_t bad = -1;
#pragma omp parallel for schedule(static) if (n >= MACRO_OMP_MIN)
    for (size_t i = 0; i < n; i++) {
        const size_t h = half_start(nl, m->pgid, p->gid, i);
        size_t q = m->hoff[i];
        for (size_t s = off[i]; s < off[i + 1]; s++) {
            const size_t j = (size_t)idx[s];
            if (s < h && j < n)
                continue; /* the partner computes this pair */
            size_t t = NO_SLOT;
            if (j < n) {
                t = off[j];
                while (t < off[j + 1] && (size_t)idx[t] != i)
                    t++;
                if (t == off[j + 1]) {
#pragma omp critical(macro_half_fill)
                    bad = p->gid[i];
                    continue;
                }
                m->pid[t] = (uint32_t)q;
            }
            m->pid[s] = (uint32_t)q;
            m->hpi[q] = (int32_t)i;
            m->hpj[q] = (int32_t)j;
            if (m->hps) {
                m->hps[q] = s;
                m->hprs[q] = t;
            }
            q++;
        }
    }
    return bad;
}

/* The arrays of the pair table @p t of the one-rank build (neighbor_pairs.c:
 * the same pairs, numbered as half_fill numbers them: by the computing end,
 * the smaller index, then the partner ascending), taken over. */
static void half_take(struct model *m, struct neighbor_pairs *t, size_t n)
{
    free(m->hoff);
    free(m->hpj);
    free(m->pid);
    m->hoff = t->first;
    m->hpj = t->partner;
    m->pid = t->slot_pair;
    t->first = NULL;
    t->slot_pair = NULL;
    t->partner = NULL;
    const struct neighbor_list *nl = m->nl;
#pragma omp parallel for schedule(static) if (n >= MACRO_OMP_MIN)
    for (size_t i = 0; i < n; i++)
        for (size_t q = m->hoff[i]; q < m->hoff[i + 1]; q++)
            m->hpi[q] = (int32_t)i;
    if (m->hps)
        for (size_t i = 0; i < n; i++)
            for (size_t s = nl->offset[i]; s < nl->offset[i + 1]; s++) {
                if ((size_t)nl->idx[s] > i)
                    m->hps[m->pid[s]] = s;
                else
                    m->hprs[m->pid[s]] = s;
            }
}

static int half_prepare(struct model *m, const struct particles *p, size_t n, int dim,
                        bool plastic, bool pairwise, struct spall_error *err)
{
    const struct neighbor_list *nl = m->nl;
    /* the build's table describes this list only when no ghosts follow
     * (one rank: n owned = all particles) */
    struct neighbor_pairs *t = m->hnew && nl->n == n ? m->hnew : NULL;
    size_t *cnt = NULL, np;
    if (t) {
        np = t->n_pairs;
    } else {
        cnt = malloc((n + 1) * sizeof *cnt);
        if (!cnt)
            return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory (macro-particle pairs)");
#pragma omp parallel for schedule(static) if (n >= MACRO_OMP_MIN)
        for (size_t i = 0; i < n; i++)
            cnt[i] = half_count(nl, half_start(nl, m->pgid, p->gid, i), i, n);
        np = 0;
        for (size_t i = 0; i < n; i++) {
            size_t c = cnt[i];
            cnt[i] = np;
            np += c;
        }
        cnt[n] = np;
        if (np > UINT32_MAX) {
            free(cnt);
            return spall_error_set(err, SPALL_ERR_INPUT, "%zu macro-particle pairs on a rank "
                                   "exceed the 32-bit pair index", np);
        }
    }
    const size_t ns = nl->offset[n];
    const bool pg = np > m->half_pair_cap;
    const size_t pn = pg ? np : m->half_pair_cap;
    bool ok = need((void **)&m->hpi, pn, sizeof *m->hpi, pg) &&
              need((void **)&m->pc, pn + 1, sizeof *m->pc, pg) &&
              need((void **)&m->pphi, pn + 1, sizeof *m->pphi, pg) &&
              (!plastic || (need((void **)&m->hps, pn, sizeof *m->hps, pg) &&
                            need((void **)&m->hprs, pn, sizeof *m->hprs, pg) &&
                            need((void **)&m->pwp, pn, sizeof *m->pwp, pg))) &&
              (!pairwise || need((void **)&m->pfl, 3 * pn, sizeof *m->pfl, pg));
    if (!t) { /* made here: the exact sizes of this list */
        free(m->hoff);
        free(m->hpj);
        free(m->pid);
        m->hoff = cnt;
        m->hpj = malloc((np ? np : 1) * sizeof *m->hpj);
        m->pid = malloc((ns ? ns : 1) * sizeof *m->pid);
        ok = ok && m->hpj && m->pid;
    }
    if (!ok) {
        macro_half_free(m);
        return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory for the macro-particle "
                               "pair loop (%zu pairs)", np);
    }
    m->half_pair_cap = pn;
    m->half_pairs = np;
    m->pc[np] = m->pphi[np] = 0.0; /* the zero pair of pass 2's group layout */
    if (t) {
        half_take(m, t, n);
        macro_half_invalidate(m, NULL);
    } else {
        int64_t bad = half_fill(m, p, n);
        if (bad >= 0) {
            macro_half_free(m);
            return spall_error_set(err, SPALL_ERR_INTERNAL, "macro-particle pair list not "
                                   "symmetric (a partner of particle %lld does not list it)",
                                   (long long)bad);
        }
    }
    if (!m->pgid) { /* one rank: every partner an owned row */
        free(m->hreach);
        m->hreach = malloc((n ? 2 * n : 1) * sizeof *m->hreach);
        if (!m->hreach) {
            macro_half_free(m);
            return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory (macro-particle pairs)");
        }
        int32_t r = -1;
        for (size_t i = 0; i < n; i++) {
            /* partners ascend in a row: its last pair has the largest */
            if (m->hoff[i + 1] > m->hoff[i] && m->hpj[m->hoff[i + 1] - 1] > r)
                r = m->hpj[m->hoff[i + 1] - 1];
            m->hreach[i] = r;
        }
        const size_t *off = m->nl->offset;
        r = INT32_MAX;
        for (size_t i = n; i-- > 0;) {
            if (off[i + 1] > off[i] && m->nl->idx[off[i]] < r)
                r = m->nl->idx[off[i]]; /* full rows ascend: the first is the smallest */
            m->hreach[n + i] = r;
        }
    }
    if (dim == 3 && !macro_half_groups(m, n)) {
        macro_half_free(m);
        return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory (macro-particle pairs)");
    }
    m->half_ok = true;
    return SPALL_OK;
}


#if defined(__GNUC__)
typedef double half_d4 __attribute__((vector_size(32)));
#endif

/** Distances of the nb pairs (pi[k], pj[k]): r^2 and r, with x_j - x_i as
 *  the computing end forms it. */
MACRO_CLONES static void half_chunk_dist(size_t nb, int dim, double *const *restrict x,
                                         const int32_t *restrict pi,
                                         const int32_t *restrict pj, double *restrict r2,
                                         double *restrict r)
{
    const double *restrict x0 = x[0], *restrict x1 = dim > 1 ? x[1] : x[0];
    const double *restrict x2 = dim > 2 ? x[2] : x[0];
    size_t k = 0;
#if defined(__GNUC__)
    /* 3D: four pairs a vector, each lane the scalar loop's operations in its
     * order (the same bits).  Left to the vectoriser, the loop below runs
     * eight pairs an iteration (the 32-bit indices set its width) and
     * spills their sixteen indices: about 4 instructions a pair more. */
    if (dim == 3)
        for (; k + 4 <= nb; k += 4) {
            const int32_t *a = pi + k, *b = pj + k;
            const half_d4 ex = (half_d4){x0[b[0]], x0[b[1]], x0[b[2]], x0[b[3]]} -
                               (half_d4){x0[a[0]], x0[a[1]], x0[a[2]], x0[a[3]]};
            const half_d4 ey = (half_d4){x1[b[0]], x1[b[1]], x1[b[2]], x1[b[3]]} -
                               (half_d4){x1[a[0]], x1[a[1]], x1[a[2]], x1[a[3]]};
            const half_d4 ez = (half_d4){x2[b[0]], x2[b[1]], x2[b[2]], x2[b[3]]} -
                               (half_d4){x2[a[0]], x2[a[1]], x2[a[2]], x2[a[3]]};
            const half_d4 q = ex * ex + ey * ey + ez * ez;
            memcpy(r2 + k, &q, sizeof q);
        }
#endif
    /* the loads are unconditional (x1, x2 name x[0] below 2D, 3D) so that
     * the loop vectorises; the unused components are then replaced by 0 */
    for (; k < nb; k++) {
        const size_t i = (size_t)pi[k], j = (size_t)pj[k];
        const double ex = x0[j] - x0[i], fy = x1[j] - x1[i], fz = x2[j] - x2[i];
        const double ey = dim > 1 ? fy : 0.0, ez = dim > 2 ? fz : 0.0;
        r2[k] = ex * ex + ey * ey + ez * ez;
    }
    for (k = 0; k < nb; k++)
        r[k] = sqrt(r2[k]);
}

/** Pair law of nb pairs at distances rd (squared r2) and elastic distances
 *  re: phi / 2 and c = -f/r, both +0 where the pair does not count
 *  (macro_mie_pairs).  A pair with c = +-0 and phi = 0 adds only +-0 terms
 *  to the sums of pass 2, which change no sum (they start at +0 and never
 *  become -0), so pass 2 may skip it: that is the skip of a pair that does
 *  not count. */
MACRO_CLONES static void half_chunk_law(const struct macro_pair *w, size_t nb,
                                        const double *restrict r2, const double *restrict rd,
                                        const double *restrict re, double rlist2,
                                        double *restrict ph, double *restrict c)
{
    macro_mie_pairs(w, nb, r2, rd, re, rlist2, ph, c);
}

/* Pass 1 over the pairs [q0, q0 + nb), nb <= MACRO_CHUNK. */
static void half_compute(const struct half_ctx *h, size_t q0, size_t nb)
{
    struct model *m = h->m;
    const struct macro_pair *w = h->w;
    double rr2[MACRO_CHUNK], rr[MACRO_CHUNK], rre[MACRO_CHUNK];
    half_chunk_dist(nb, h->dim, h->x, m->hpi + q0, m->hpj + q0, rr2, rr);
    const double *re_k = rr;
    if (h->plastic || h->mu > 0.0) {
        for (size_t k = 0; k < nb; k++) {
            const size_t q = q0 + k, i = (size_t)m->hpi[q], j = (size_t)m->hpj[q];
            const double r = rr[k];
            double wp = 0.0, fl[3] = {0, 0, 0};
            rre[k] = r;
            if (!(rr2[k] >= h->rlist2 || rr2[k] == 0.0)) {
                if (h->plastic) {
                    const size_t s = m->hps[q], rs = m->hprs[q];
                    rre[k] = macro_plastic_update(w, r, &m->dr0[s], &m->kappa[s],
                                                  &m->engaged[s], &wp);
                    if (rs != NO_SLOT) {
                        m->dr0[rs] = m->dr0[s];
                        m->kappa[rs] = m->kappa[s];
                        m->engaged[rs] = m->engaged[s];
                    }
                }
                if (h->mu > 0.0 && r < w->r_c) {
                    double xr[3] = {0, 0, 0};
                    uint64_t ga = (uint64_t)h->gid[i], gb = (uint64_t)h->gid[j];
                    double sgn = ga < gb ? 1.0 : -1.0;
                    if (h->sp > 0.0)
                        macro_gauss3(h->seed, h->step, ga < gb ? ga : gb, ga < gb ? gb : ga, xr);
                    for (int d = 0; d < h->dim; d++)
                        fl[d] = h->mu * (h->v[d][j] - h->v[d][i]) + sgn * h->sp * xr[d];
                }
            }
            if (h->plastic)
                m->pwp[q] = wp;
            if (h->mu > 0.0)
                for (int d = 0; d < 3; d++)
                    m->pfl[3 * q + (size_t)d] = fl[d];
        }
        re_k = rre;
    }
    half_chunk_law(w, nb, rr2, rr, re_k, h->rlist2, m->pphi + q0, m->pc + q0);
}

static void half_pass1(const struct half_ctx *h, size_t q0, size_t q1)
{
    for (size_t q = q0; q < q1; q += MACRO_CHUNK)
        half_compute(h, q, q1 - q < MACRO_CHUNK ? q1 - q : MACRO_CHUNK);
}

/* Rows [a, b) block by block: pass 1 of the block's pairs below pair qend
 * (those from qend on were computed before), then pass 2 of its rows. */
static void half_fused(const struct half_ctx *h, size_t a, size_t b, size_t qend)
{
    const size_t *hoff = h->m->hoff;
    /* blocks end at multiples of HALF_BLOCK, so that they hold whole groups
     * of four rows (pass 2) wherever the range starts */
    for (size_t r = a; r < b;) {
        const size_t nb = (r / HALF_BLOCK + 1) * HALF_BLOCK, re = b < nb ? b : nb;
        const size_t q1 = hoff[re] < qend ? hoff[re] : qend;
        if (hoff[r] < q1)
            half_pass1(h, hoff[r], q1);
        macro_half_pass2(h, r, re);
        r = re;
    }
}

/* The first row with a pair whose partner is row b or later (b if none):
 * a bisection of the running maximum hreach. */
static size_t half_reach(const struct model *m, size_t b)
{
    size_t lo = 0, hi = b; /* the answer is in [lo, hi] */
    while (lo < hi) {
        const size_t mid = lo + (hi - lo) / 2;
        if (m->hreach[mid] >= 0 && (size_t)m->hreach[mid] >= b)
            hi = mid;
        else
            lo = mid + 1;
    }
    return lo;
}

/* The first row of [a, b) from which on no row has a partner below row a (b
 * if none): a bisection of the rows' running smallest partner. */
static size_t half_head(const struct model *m, size_t n, size_t a, size_t b)
{
    const int32_t *low = m->hreach + n;
    size_t lo = a, hi = b;
    while (lo < hi) {
        const size_t mid = lo + (hi - lo) / 2;
        if ((size_t)low[mid] >= a)
            hi = mid;
        else
            lo = mid + 1;
    }
    return lo;
}

int macro_forces_half(struct model *m, struct sim *sim, struct spall_error *err)
{
    struct particles *p = sim->p;
    const size_t n = p->n_owned;
    const struct macro_pair w = m->pp;
    const bool plastic = isfinite(w.e_y);
    const double dt = sim_step_dt(sim) > 0.0 ? sim_step_dt(sim) : 1.0; /* this step's noise */
    const double kT = MACRO_KB * m->temperature;
    const double g = m->damping == MACRO_DAMP_ABSOLUTE ? m->gamma_used : 0.0;
    const double mu = m->damping == MACRO_DAMP_PAIRWISE ? m->mu_used : 0.0;
    if (!m->half_ok) {
        int rc = half_prepare(m, p, n, sim->dim, plastic, mu > 0.0, err);
        if (rc)
            return rc;
    }
    const double rl = w.r_c + m->skin_ratio * w.r0;
    struct half_ctx h = {
        .m = m, .w = &w, .nl = m->nl, .x = p->x, .v = p->v, .f = p->f, .gid = p->gid,
        .dim = sim->dim, .n = n, .plastic = plastic, .mu = mu, .g = g, .dt = dt,
        .sp = m->eta_cg * sqrt(2.0 * mu * kT / dt), .sg = m->eta_cg * sqrt(2.0 * g * kT / dt),
        .rlist2 = rl * rl, .seed = sim->seed, .step = (uint64_t)m->n_calls,
        .stress = !sim->stress_skip};
    m->n_calls++;
    /* 3D: pass 2's groups leave epot to macro_half_epot (the pair values
     * stay until the next call) */
    m->epot_lazy = sim->dim == 3 ? n : 0;
    bool threads = false;
#ifdef _OPENMP
    threads = n >= MACRO_OMP_MIN && omp_get_max_threads() > 1;
#endif
    const size_t na = p->n; /* owned and ghosts: the positions pass 2 reads */
    if (!threads && !m->pgid) {
        h.bounded = sim->dim == 3 && macro_half_bounded(p->x, 0, na);
        half_fused(&h, 0, n, m->hoff[n]);
        return SPALL_OK;
    }
    const size_t nq = m->half_pairs, nc = (nq + MACRO_CHUNK - 1) / MACRO_CHUNK;
    const bool can = !m->pgid;
    int split = can; /* rows in ranges (cleared when a range cannot be) */
    int bounded = sim->dim == 3; /* cleared by a thread whose share is not */
#pragma omp parallel if (threads) firstprivate(h)
    {
        size_t t = 0, nt = 1;
#ifdef _OPENMP
        t = (size_t)omp_get_thread_num();
        nt = (size_t)omp_get_num_threads();
#endif
        /* the bounds scan, a share a thread, agreed at the barrier below */
        if (sim->dim == 3 && !macro_half_bounded(p->x, na * t / nt, na * (t + 1) / nt)) {
#pragma omp atomic write
            bounded = 0;
        }
        const size_t a = n * t / nt, b = n * (t + 1) / nt;
        /* rows [hb, b) have pairs that the next range reads; rows [a, lb)
         * may read the previous range's, and their own pairs are computed
         * before the barrier too, so that the work before it is about the
         * same on each thread */
        const size_t hb = can && t + 1 < nt ? half_reach(m, b) : b;
        const size_t lh = can && t > 0 ? half_head(m, n, a, b) : a;
        const size_t lb = lh < hb ? lh : hb;
        if (hb < a) {
#pragma omp atomic write
            split = 0;
        }
#pragma omp barrier
        int ranges, bd;
#pragma omp atomic read
        ranges = split;
#pragma omp atomic read
        bd = bounded;
        h.bounded = bd != 0;
        if (ranges) {
            half_pass1(&h, m->hoff[a], m->hoff[lb]);
            half_pass1(&h, m->hoff[hb], m->hoff[b]);
#pragma omp barrier
            macro_half_pass2(&h, a, lb);
            half_fused(&h, lb, b, m->hoff[hb]);
        } else {
#pragma omp for schedule(static)
            for (size_t k = 0; k < nc; k++)
                half_pass1(&h, k * MACRO_CHUNK, k * MACRO_CHUNK + MACRO_CHUNK < nq
                                                    ? k * MACRO_CHUNK + MACRO_CHUNK : nq);
#pragma omp for schedule(dynamic, 4)
            for (size_t r = 0; r < n; r += 64)
                macro_half_pass2(&h, r, n - r < 64 ? n : r + 64);
        }
    }
    return SPALL_OK;
}
