/**
 * @file macro_half_rows.c
 * @brief Pass 2 of the once-per-pair macro-particle loop (macro_half.c):
 *        every owned row summed over all its slots in list order, with the
 *        full loop's operations, so the same bits for any thread and rank
 *        count.
 *
 * In 3D the rows go four at a time, a row a vector lane: step k takes slot
 * k of each of the four rows, so each lane runs the one-row operations on
 * its row in the same order, with no shuffles between lanes.  The slots of
 * a group of four rows (rows 4g .. 4g + 3) are laid out step by step after
 * each list change (macro_half_groups): per step the four partners, then the
 * four pairs, contiguous, so that a step loads them as two vectors; a row
 * that has ended points at itself (x_j - x_i = 0) and at a zero pair whose c
 * and phi are +0, so it adds +0 terms, which change no sum (they start at +0
 * and never become -0 in round-to-nearest), without an end test.  (The
 * positions and pair values of a step by AVX2 gathers instead of element
 * loads: as many cycles on the machines measured, docs/performance.md.)
 * The groups sum the force, and the virial only on the steps whose stress
 * something reads (sim.stress_skip); the energy is left to its readers
 * (macro_half_epot: the same sum from the pair values pass 1 stored).
 */
#include "models/macroparticle/macro_half.h"

#include "core/neighbor.h"
#include "core/particles.h"
#include "core/sim.h"

#include <stdlib.h>
#include <string.h>

#if defined(__GNUC__)
/* Lane-wise sums: each lane is its own scalar sum, in the same order (a
 * vector add rounds every lane as the scalar add does). */
typedef double half_v4 __attribute__((vector_size(32)));
typedef double half_v2 __attribute__((vector_size(16)));
typedef long long half_m4 __attribute__((vector_size(32)));
#endif

/* A row's sums, in this order: force x y z, energy, virial xx yy zz xy yz zx. */
enum { HALF_SUMS = 10 };

/* The sums of row i over all its slots in list order. */
static inline void half_row_sums(const struct half_ctx *h, size_t i, double out[HALF_SUMS])
{
    const struct neighbor_list *nl = h->nl;
    const int dim = h->dim;
    const double *x0 = h->x[0], *x1 = dim > 1 ? h->x[1] : h->x[0];
    const double *x2 = dim > 2 ? h->x[2] : h->x[0];
    const double *pc = h->m->pc, *pphi = h->m->pphi;
    const uint32_t *pid = h->m->pid;
    const double xi0 = x0[i], xi1 = dim > 1 ? x1[i] : 0.0, xi2 = dim > 2 ? x2[i] : 0.0;
#if defined(__GNUC__)
    /* lanes: A = force xyz and energy, B = virial xx yy zz xy, C = yz zx */
    half_v4 A = {0, 0, 0, 0}, B = {0, 0, 0, 0};
    half_v2 C = {0, 0};
    for (size_t s = nl->offset[i]; s < nl->offset[i + 1]; s++) {
        const size_t q = pid[s], j = (size_t)nl->idx[s];
        if (pc[q] == 0.0 && pphi[q] == 0.0)
            continue; /* does not count, or adds +-0 only */
        const double dx = x0[j] - xi0, dy = dim > 1 ? x1[j] - xi1 : 0.0;
        const double dz = dim > 2 ? x2[j] - xi2 : 0.0;
        const double c = pc[q], hc = 0.5 * c;
        A += (half_v4){c, c, c, 1.0} * (half_v4){dx, dy, dz, pphi[q]}; /* pphi: 0.5 phi */
        B += (half_v4){hc, hc, hc, hc} * (half_v4){dx, dy, dz, dx} * (half_v4){dx, dy, dz, dy};
        C += (half_v2){hc, hc} * (half_v2){dy, dz} * (half_v2){dz, dx};
    }
    for (int k = 0; k < 4; k++) {
        out[k] = A[k];
        out[4 + k] = B[k];
    }
    out[8] = C[0];
    out[9] = C[1];
#else
    for (int k = 0; k < HALF_SUMS; k++)
        out[k] = 0.0;
    for (size_t s = nl->offset[i]; s < nl->offset[i + 1]; s++) {
        const size_t q = pid[s], j = (size_t)nl->idx[s];
        if (pc[q] == 0.0 && pphi[q] == 0.0)
            continue; /* does not count, or adds +-0 only */
        const double dx[3] = {x0[j] - xi0, dim > 1 ? x1[j] - xi1 : 0.0,
                              dim > 2 ? x2[j] - xi2 : 0.0};
        const double c = pc[q];
        for (int d = 0; d < 3; d++)
            out[d] += c * dx[d];
        out[3] += pphi[q]; /* 0.5 phi */
        for (int d = 0; d < 3; d++)
            out[4 + d] += 0.5 * c * dx[d] * dx[d];
        out[7] += 0.5 * c * dx[0] * dx[1];
        out[8] += 0.5 * c * dx[1] * dx[2];
        out[9] += 0.5 * c * dx[2] * dx[0];
    }
#endif
}

#if defined(__GNUC__)
/* half_row_finish of the four rows i .. i + 3 of a run without plasticity
 * and damping, a row a lane: the same operations on the zero Langevin
 * force and plastic work (f += sum + 0, wdiss += 0 - (0 v) dt: kept, they
 * are not no-ops for -0 and non-finite values), so the same bits, with
 * vector loads and stores of the consecutive rows (about 100 instructions
 * a row less than four calls of half_row_finish); the energy is left to
 * macro_half_epot (m->epot_lazy). */
__attribute__((always_inline)) static inline void half_finish4(const struct half_ctx *h, size_t i,
                                                               const half_v4 acc[HALF_SUMS],
                                                               bool stress)
{
    struct model *m = h->m;
    const half_v4 z = {0, 0, 0, 0};
    half_v4 pw = z, t;
    for (int d = 0; d < 3; d++) {
        memcpy(&t, h->f[d] + i, sizeof t);
        t += acc[d] + z;
        memcpy(h->f[d] + i, &t, sizeof t);
        memcpy(&t, h->v[d] + i, sizeof t);
        pw += z * t;
    }
    if (stress)
        for (int l = 0; l < 4; l++)
            for (int k = 0; k < 6; k++)
                m->sig[6 * (i + (size_t)l) + (size_t)k] = acc[4 + k][l];
    memcpy(&t, m->wdiss + i, sizeof t);
    t += z - pw * h->dt;
    memcpy(m->wdiss + i, &t, sizeof t);
}
#endif

/* Row i's outputs from its sums: plastic work and Langevin forces (in list
 * order), force, energy (when @p energy), virial (when @p stress),
 * dissipation. */
static inline void half_row_finish(const struct half_ctx *h, size_t i,
                                   const double sum[HALF_SUMS], bool energy, bool stress)
{
    struct model *m = h->m;
    const struct neighbor_list *nl = h->nl;
    const int dim = h->dim;
    double vi[3] = {0, 0, 0}, fl[3] = {0, 0, 0};
    for (int d = 0; d < dim; d++)
        vi[d] = h->v[d][i];
    double wplast = 0.0;
    if (h->plastic)
        for (size_t s = nl->offset[i]; s < nl->offset[i + 1]; s++)
            wplast += m->pwp[m->pid[s]];
    if (h->mu > 0.0)
        for (size_t s = nl->offset[i]; s < nl->offset[i + 1]; s++) {
            const size_t q = m->pid[s];
            const bool own = (size_t)m->hpi[q] == i; /* else the partner's term, negated */
            for (int d = 0; d < dim; d++)
                fl[d] = own ? fl[d] + m->pfl[3 * q + (size_t)d]
                            : fl[d] - m->pfl[3 * q + (size_t)d];
        }
    if (h->g > 0.0) {
        double xr[3] = {0, 0, 0};
        if (h->sg > 0.0)
            macro_gauss3(h->seed, h->step, (uint64_t)h->gid[i], UINT64_MAX, xr);
        for (int d = 0; d < dim; d++)
            fl[d] += -h->g * vi[d] + h->sg * xr[d];
    }
    double pw = 0.0;
    for (int d = 0; d < dim; d++) {
        h->f[d][i] += sum[d] + fl[d];
        pw += fl[d] * vi[d];
    }
    if (energy)
        m->epot[i] = sum[3];
    if (stress)
        for (int k = 0; k < 6; k++)
            m->sig[6 * i + k] = sum[4 + k];
    m->wdiss[i] += wplast - pw * h->dt;
}

#if defined(__GNUC__)
/* Step k of a group: the four lanes' partner positions xj, yj, zj and pair
 * values c added to the force sums and, with @p stress, the virial's (the
 * operations of half_row_sums in its order; the energy sum is left to
 * macro_half_epot, which adds the same values in the same order).  c = +-0: the force and virial terms are +-0,
 * which change no sum (they start at +0 and never become -0); @p mask: dx
 * is then replaced by +0, for the run whose positions may be huge or not
 * finite (x_j - x_i infinite or NaN, where 0 dx would not be 0). */
__attribute__((always_inline)) static inline void
half_step4(half_v4 acc[HALF_SUMS], const half_v4 xi[3], half_v4 xj, half_v4 yj, half_v4 zj,
           half_v4 c, bool mask, bool stress)
{
    half_v4 dx = xj - xi[0], dy = yj - xi[1], dz = zj - xi[2];
    if (mask) {
        const half_m4 ok = c != 0.0;
        dx = (half_v4)((half_m4)dx & ok);
        dy = (half_v4)((half_m4)dy & ok);
        dz = (half_v4)((half_m4)dz & ok);
    }
    acc[0] += c * dx;
    acc[1] += c * dy;
    acc[2] += c * dz;
    if (!stress)
        return; /* the force sums do not depend on the virial's */
    const half_v4 hc = 0.5 * c;
    acc[4] += hc * dx * dx;
    acc[5] += hc * dy * dy;
    acc[6] += hc * dz * dz;
    acc[7] += hc * dx * dy;
    acc[8] += hc * dy * dz;
    acc[9] += hc * dz * dx;
}

/* The group's rows i .. i + 3 from their sums: the vector finish of a
 * plain run, else each row's own. */
__attribute__((always_inline)) static inline void
half_group_finish(const struct half_ctx *h, size_t i, bool plain, bool stress,
                  const half_v4 acc[HALF_SUMS])
{
    if (plain) {
        half_finish4(h, i, acc, stress);
        return;
    }
    for (size_t l = 0; l < 4; l++) {
        double sum[HALF_SUMS];
        for (int k = 0; k < HALF_SUMS; k++)
            sum[k] = stress || k < 3 ? acc[k][l] : 0.0;
        half_row_finish(h, i + l, sum, false, stress);
    }
}

/* Pass 2 of the groups [g0, g1): the steps' partners and pairs loaded as
 * vectors, their positions and values element by element (AVX2 gathers
 * instead: as many cycles or more on the machine measured). */
__attribute__((always_inline)) static inline void
half_groups_k(const struct half_ctx *h, size_t g0, size_t g1, bool plain, bool mask,
              bool stress)
{
    const struct model *m = h->m;
    const double *x0 = h->x[0], *x1 = h->x[1], *x2 = h->x[2], *pc = m->pc;
    for (size_t g = g0; g < g1; g++) {
        const size_t i = 4 * g;
        /* the running sums in a local array that nothing else sees, so that
         * they stay in registers; copied out after the steps */
        half_v4 a[HALF_SUMS], acc[HALF_SUMS], xi[3];
        for (int d = 0; d < 3; d++)
            memcpy(&xi[d], h->x[d] + i, sizeof xi[d]);
        for (int k = 0; k < HALF_SUMS; k++)
            a[k] = (half_v4){0, 0, 0, 0};
        for (size_t k = m->goff[g]; k < m->goff[g + 1]; k++) {
            const int32_t *j = m->gidx + 4 * k;
            const uint32_t *q = m->gpid + 4 * k;
            const half_v4 xj = {x0[j[0]], x0[j[1]], x0[j[2]], x0[j[3]]};
            const half_v4 yj = {x1[j[0]], x1[j[1]], x1[j[2]], x1[j[3]]};
            const half_v4 zj = {x2[j[0]], x2[j[1]], x2[j[2]], x2[j[3]]};
            const half_v4 c = {pc[q[0]], pc[q[1]], pc[q[2]], pc[q[3]]};
            half_step4(a, xi, xj, yj, zj, c, mask, stress);
        }
        memcpy(acc, a, sizeof acc);
        half_group_finish(h, i, plain, stress, acc);
    }
}

/* ... with the mask of dx only where a position is huge or not finite
 * (@p bounded false): four vector operations a step fewer; without the
 * virial's six sums on the steps whose stress nothing reads (@p stress
 * false): 13 vector operations a step fewer and no spilled sums. */
MACRO_CLONES static void half_groups(const struct half_ctx *h, size_t g0, size_t g1, bool plain,
                                     bool bounded, bool stress)
{
    if (bounded && stress)
        half_groups_k(h, g0, g1, plain, false, true);
    else if (bounded)
        half_groups_k(h, g0, g1, plain, false, false);
    else if (stress)
        half_groups_k(h, g0, g1, plain, true, true);
    else
        half_groups_k(h, g0, g1, plain, true, false);
}

/* Whether every coordinate of the n particles is within +-1e300: then every
 * x_j - x_i is finite (no NaN, no overflow), and c dx = +-0 where c = +-0. */
MACRO_CLONES static bool half_bounded(const double *const *x, size_t n)
{
    const double big = 1e300;
    half_m4 in = {-1, -1, -1, -1};
    bool ok = true;
    for (int d = 0; d < 3; d++) {
        size_t i = 0;
        for (; i + 4 <= n; i += 4) {
            half_v4 v;
            memcpy(&v, x[d] + i, sizeof v);
            in &= (v <= big) & (v >= -big);
        }
        for (; i < n; i++)
            ok &= x[d][i] <= big && x[d][i] >= -big;
    }
    return ok && (in[0] & in[1] & in[2] & in[3]);
}
#endif

double macro_half_epot(const struct model *m, size_t i)
{
    /* pass 2's energy sum: from +0, each slot's 0.5 phi in list order (its
     * groups added +0 for the steps after a row's end and its single rows
     * skipped pairs of +-0: neither changes a sum that starts at +0) */
    const size_t *off = m->nl->offset;
    double e = 0.0;
    for (size_t s = off[i]; s < off[i + 1]; s++)
        e += m->pphi[m->pid[s]];
    return e;
}

void macro_half_epot_sync(struct model *m)
{
    const size_t n = m->epot_lazy;
#pragma omp parallel for schedule(static) if (n >= MACRO_OMP_MIN)
    for (size_t i = 0; i < n; i++)
        m->epot[i] = macro_half_epot(m, i);
    m->epot_lazy = 0;
}

bool macro_half_bounded(double *const *x, size_t i0, size_t i1)
{
#if defined(__GNUC__)
    const double *const y[3] = {x[0] + i0, x[1] + i0, x[2] + i0};
    return half_bounded(y, i1 - i0);
#else
    (void)x;
    (void)i0;
    (void)i1;
    return false;
#endif
}

bool macro_half_groups(struct model *m, size_t n)
{
    const size_t ng = n / 4, *off = m->nl->offset;
    size_t *goff = realloc(m->goff, (ng + 1) * sizeof *goff);
    if (!goff)
        return false;
    m->goff = goff;
    /* the steps of group g: its longest row's slots */
#pragma omp parallel for schedule(static) if (n >= MACRO_OMP_MIN)
    for (size_t g = 0; g < ng; g++) {
        size_t len = 0;
        for (size_t l = 4 * g; l < 4 * g + 4; l++)
            len = off[l + 1] - off[l] > len ? off[l + 1] - off[l] : len;
        goff[g + 1] = len;
    }
    goff[0] = 0;
    for (size_t g = 0; g < ng; g++)
        goff[g + 1] += goff[g];
    const size_t ne = 4 * goff[ng];
    if (ne > m->g_cap || !m->gidx || !m->gpid) {
        free(m->gidx);
        free(m->gpid);
        m->gidx = malloc((ne ? ne : 1) * sizeof *m->gidx);
        m->gpid = malloc((ne ? ne : 1) * sizeof *m->gpid);
        m->g_cap = m->gidx && m->gpid ? ne : 0;
        if (!m->g_cap)
            return false; /* the caller frees the loop's arrays */
    }
    const int32_t *idx = m->nl->idx;
    const uint32_t *pid = m->pid;
    /* the zero pair (pass 1 never writes it; <= 2^32 - 1, half_prepare) */
    const uint32_t zero = (uint32_t)m->half_pairs;
#pragma omp parallel for schedule(static) if (n >= MACRO_OMP_MIN)
    for (size_t g = 0; g < ng; g++)
        for (size_t l = 0; l < 4; l++) {
            const size_t i = 4 * g + l, len = off[i + 1] - off[i];
            size_t k = 0, e = 4 * goff[g] + l;
            for (; k < len; k++, e += 4) {
                m->gidx[e] = idx[off[i] + k];
                m->gpid[e] = pid[off[i] + k];
            }
            for (; k < goff[g + 1] - goff[g]; k++, e += 4) {
                m->gidx[e] = (int32_t)i;
                m->gpid[e] = zero;
            }
        }
    return true;
}

void macro_half_pass2(const struct half_ctx *h, size_t i0, size_t i1)
{
    const bool plain = !h->plastic && !(h->mu > 0.0) && !(h->g > 0.0);
    for (size_t i = i0; i < i1;) {
#if defined(__GNUC__)
        /* the whole groups from i on */
        const size_t ge = (i1 < h->n - h->n % 4 ? i1 : h->n - h->n % 4) / 4;
        if (h->dim == 3 && h->m->goff && i % 4 == 0 && i / 4 < ge) {
            half_groups(h, i / 4, ge, plain, h->bounded, h->stress);
            i = 4 * ge;
            continue;
        }
#endif
        double sum[HALF_SUMS];
        half_row_sums(h, i, sum);
        half_row_finish(h, i, sum, true, true);
        i++;
    }
}
