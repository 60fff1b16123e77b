/**
 * @file step_passes.c
 * @brief The integrator's per-particle passes, in two versions picked once
 *        at load time by the CPU (x86-64-v3: four lanes; the build's
 *        baseline: two), as the models' hot loops are.  Every operation is
 *        a single IEEE rounding (ISO C mode: no FP contraction), done the
 *        same way per lane, so both versions give the same bits on any
 *        thread count.
 *
 * The passes sweep all components of a chunk of particles at once (the
 * chunk's masses read from memory once, then from L1).  The
 * first kick of a step and the drift are one pass over m, f, v and x
 * (step_kick_drift; the integrator redoes the drift of the particles a
 * velocity condition sets in between), which also clears the forces the
 * force call is about to fill: one pass over the particle arrays instead
 * of three (issue 25 item 1, round 3; docs/performance.md).
 */
#include "core/step_passes.h"

#include <string.h>

#ifdef _OPENMP
#include <omp.h>
#endif

#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__) && defined(__linux__) &&     \
    !defined(SPALL_NO_CLONES)
#define STEP_CLONES __attribute__((target_clones("arch=x86-64-v3", "default")))
#else
#define STEP_CLONES
#endif

/* What a pass does: kick; kick and drift; kick, drift and clear f. */
enum pass_kind { PASS_KICK, PASS_KICK_DRIFT, PASS_KICK_DRIFT_ZERO };

/* Particles per chunk of a pass: the chunk's masses (16 kB) stay in the caches while its
 * components are swept one after the other. */
#define PASS_CHUNK 2048

/* The mass of particle i: m[i], or with @p uni (particles.mass_uniform) the
 * one mass m0 of every particle, the same double, so the same bits. */
static inline double mass_at(const double *restrict m, double m0, size_t i, const bool uni)
{
    return uni ? m0 : m[i];
}

/* One component over [lo, hi): the kick, then the drift with the new
 * velocity and the clearing, as @p kind asks. */
static inline void pass_comp(const double *restrict m, double m0, double *restrict x,
                             double *restrict v, double *restrict f, size_t lo, size_t hi,
                             double half_dt, double dt, const enum pass_kind kind, const bool uni)
{
    for (size_t i = lo; i < hi; i++) {
        const double vi = v[i] + half_dt * f[i] / mass_at(m, m0, i, uni);
        v[i] = vi;
        if (kind != PASS_KICK)
            x[i] += dt * vi;
        if (kind == PASS_KICK_DRIFT_ZERO)
            f[i] = 0.0;
    }
}

static inline void pass_kind(const struct particles *p, size_t lo, size_t hi, double half_dt,
                             double dt, const enum pass_kind kind, const bool uni)
{
    for (size_t c = lo; c < hi; c += PASS_CHUNK) {
        const size_t e = hi - c < PASS_CHUNK ? hi : c + PASS_CHUNK;
        for (int d = 0; d < p->dim; d++)
            pass_comp(p->mass, p->mass_uniform, p->x[d], p->v[d], p->f[d], c, e, half_dt, dt,
                      kind, uni);
    }
}

STEP_CLONES static void pass_range(const struct particles *p, size_t lo, size_t hi,
                                   double half_dt, double dt, int kind)
{
    const bool uni = p->mass_uniform > 0.0;
    if (kind == PASS_KICK && uni)
        pass_kind(p, lo, hi, half_dt, dt, PASS_KICK, true);
    else if (kind == PASS_KICK)
        pass_kind(p, lo, hi, half_dt, dt, PASS_KICK, false);
    else if (kind == PASS_KICK_DRIFT && uni)
        pass_kind(p, lo, hi, half_dt, dt, PASS_KICK_DRIFT, true);
    else if (kind == PASS_KICK_DRIFT)
        pass_kind(p, lo, hi, half_dt, dt, PASS_KICK_DRIFT, false);
    else if (uni)
        pass_kind(p, lo, hi, half_dt, dt, PASS_KICK_DRIFT_ZERO, true);
    else
        pass_kind(p, lo, hi, half_dt, dt, PASS_KICK_DRIFT_ZERO, false);
}

STEP_CLONES static void drift_range(const struct particles *p, size_t lo, size_t hi, double dt)
{
    for (int d = 0; d < p->dim; d++) {
        double *restrict x = p->x[d];
        const double *restrict v = p->v[d];
        for (size_t i = lo; i < hi; i++)
            x[i] += dt * v[i];
    }
}

/* The calling thread's static share of [0, n) (as schedule(static) and
 * particles_zero_forces split it). */
static void share(size_t n, size_t *lo, size_t *hi)
{
#ifdef _OPENMP
    const size_t nt = (size_t)omp_get_num_threads(), t = (size_t)omp_get_thread_num();
#else
    const size_t nt = 1, t = 0;
#endif
    *lo = n * t / nt;
    *hi = n * (t + 1) / nt;
}

static void run_pass(struct particles *p, double half_dt, double dt, int kind)
{
    const size_t n = p->n_owned;
#pragma omp parallel if (n > SPALL_OMP_MIN_PARTICLES)
    {
        size_t lo, hi;
        share(n, &lo, &hi);
        pass_range(p, lo, hi, half_dt, dt, kind);
    }
}

void step_kick(struct particles *p, double half_dt)
{
    run_pass(p, half_dt, 0.0, PASS_KICK);
}

void step_kick_drift(struct particles *p, double half_dt, double dt, bool zero_forces)
{
    run_pass(p, half_dt, dt, zero_forces ? PASS_KICK_DRIFT_ZERO : PASS_KICK_DRIFT);
}

void step_drift(struct particles *p, double dt)
{
    const size_t n = p->n_owned;
#pragma omp parallel if (n > SPALL_OMP_MIN_PARTICLES)
    {
        size_t lo, hi;
        share(n, &lo, &hi);
        drift_range(p, lo, hi, dt);
    }
}

#if defined(__GNUC__)
/* Four lanes as one vector: each lane is its own sequence of roundings,
 * as the four scalars below (a vector multiply or add rounds every lane as
 * the scalar operation does); GCC does not vectorise the scalar form. */
typedef double step_v4 __attribute__((vector_size(4 * sizeof(double))));
#endif

STEP_CLONES double step_block_mv2(const double *restrict m, const double *restrict v, size_t lo,
                                  size_t hi)
{
    /* four lanes a[l] += m v v over i = lo + l (mod 4) */
    double a[4] = {0.0, 0.0, 0.0, 0.0};
    size_t i = lo;
#if defined(__GNUC__)
    step_v4 acc = {0.0, 0.0, 0.0, 0.0};
    for (; i + 4 <= hi; i += 4) {
        step_v4 mm, vv;
        memcpy(&mm, m + i, sizeof mm);
        memcpy(&vv, v + i, sizeof vv);
        acc += mm * vv * vv;
    }
    memcpy(a, &acc, sizeof a);
#else
    for (; i + 4 <= hi; i += 4)
        for (int l = 0; l < 4; l++)
            a[l] += m[i + l] * v[i + l] * v[i + l];
#endif
    double sum = (a[0] + a[1]) + (a[2] + a[3]);
    for (; i < hi; i++)
        sum += m[i] * v[i] * v[i];
    return sum;
}

/* One block and component of step_kick_sum: v += half_dt f / m over
 * [lo, hi), and the sum of m v^2 with the new velocities formed as
 * step_block_mv2 forms it (the same lanes, combination and order). */
static inline double kick_sum_comp(const double *restrict m, double m0, double *restrict v,
                                   const double *restrict f, size_t lo, size_t hi,
                                   double half_dt, const bool uni)
{
    double a[4] = {0.0, 0.0, 0.0, 0.0};
    size_t i = lo;
#if defined(__GNUC__)
    step_v4 acc = {0.0, 0.0, 0.0, 0.0};
    const step_v4 mu = {m0, m0, m0, m0};
    for (; i + 4 <= hi; i += 4) {
        step_v4 mm = mu, vv, ff;
        if (!uni)
            memcpy(&mm, m + i, sizeof mm);
        memcpy(&vv, v + i, sizeof vv);
        memcpy(&ff, f + i, sizeof ff);
        vv = vv + half_dt * ff / mm;
        memcpy(v + i, &vv, sizeof vv);
        acc += mm * vv * vv;
    }
    memcpy(a, &acc, sizeof a);
#else
    for (; i + 4 <= hi; i += 4)
        for (size_t l = 0; l < 4; l++) {
            const double mi = mass_at(m, m0, i + l, uni);
            const double vi = v[i + l] + half_dt * f[i + l] / mi;
            v[i + l] = vi;
            a[l] += mi * vi * vi;
        }
#endif
    double sum = (a[0] + a[1]) + (a[2] + a[3]);
    for (; i < hi; i++) {
        const double mi = mass_at(m, m0, i, uni);
        const double vi = v[i] + half_dt * f[i] / mi;
        v[i] = vi;
        sum += mi * vi * vi;
    }
    return sum;
}

STEP_CLONES static void kick_sum_range(const struct particles *p, size_t blo, size_t bhi,
                                       double half_dt, double *part)
{
    const size_t n = p->n_owned;
    const bool uni = p->mass_uniform > 0.0;
    for (size_t b = blo; b < bhi; b++) {
        const size_t lo = b * STEP_SUM_BLOCK, hi = n - lo < STEP_SUM_BLOCK ? n : lo + STEP_SUM_BLOCK;
        for (int d = 0; d < p->dim; d++)
            part[3 * b + (size_t)d] =
                uni ? kick_sum_comp(p->mass, p->mass_uniform, p->v[d], p->f[d], lo, hi, half_dt, true)
                    : kick_sum_comp(p->mass, 0.0, p->v[d], p->f[d], lo, hi, half_dt, false);
    }
}

void step_kick_sum(struct particles *p, double half_dt, double *part)
{
    const size_t n = p->n_owned, nb = (n + STEP_SUM_BLOCK - 1) / STEP_SUM_BLOCK;
#pragma omp parallel if (n > SPALL_OMP_MIN_PARTICLES)
    {
        size_t blo, bhi; /* whole blocks: a block's sum is one thread's */
        share(nb, &blo, &bhi);
        kick_sum_range(p, blo, bhi, half_dt, part);
    }
}

/* The largest squared displacement since the build of particles [i0, i1)
 * (a maximum, exact in any order: the loops vectorise, the decision is the
 * one of a serial scan; a NaN is never the maximum, as in the scan it
 * replaces). */
STEP_CLONES static double max_shift2(int dim, size_t i0, size_t i1, double *const x[3],
                                     double *const xb[3])
{
    double d2max = 0.0;
    if (dim == 3) {
        const double *x0 = x[0], *x1 = x[1], *x2 = x[2];
        const double *b0 = xb[0], *b1 = xb[1], *b2 = xb[2];
        size_t i = i0;
#if defined(__GNUC__)
        /* four running maxima, a vector lane each (GCC does not vectorise a
         * maximum reduction of doubles without fast-math), combined by the
         * same test: a NaN never becomes one, as in the scan */
        typedef long long m4 __attribute__((vector_size(32)));
        step_v4 mx = {0.0, 0.0, 0.0, 0.0};
        for (; i + 4 <= i1; i += 4) {
            step_v4 p0, p1, p2, q0, q1, q2;
            memcpy(&p0, x0 + i, sizeof p0);
            memcpy(&p1, x1 + i, sizeof p1);
            memcpy(&p2, x2 + i, sizeof p2);
            memcpy(&q0, b0 + i, sizeof q0);
            memcpy(&q1, b1 + i, sizeof q1);
            memcpy(&q2, b2 + i, sizeof q2);
            const step_v4 u0 = p0 - q0, u1 = p1 - q1, u2 = p2 - q2;
            const step_v4 d2 = u0 * u0 + u1 * u1 + u2 * u2;
            const m4 gt = d2 > mx;
            mx = (step_v4)(((m4)d2 & gt) | ((m4)mx & ~gt));
        }
        for (int l = 0; l < 4; l++)
            d2max = mx[l] > d2max ? mx[l] : d2max;
#endif
        for (; i < i1; i++) {
            const double u0 = x0[i] - b0[i], u1 = x1[i] - b1[i], u2 = x2[i] - b2[i];
            const double d2 = u0 * u0 + u1 * u1 + u2 * u2;
            d2max = d2 > d2max ? d2 : d2max;
        }
        return d2max;
    }
    for (size_t i = i0; i < i1; i++) {
        double d2 = 0.0;
        for (int d = 0; d < dim; d++) {
            double u = x[d][i] - xb[d][i];
            d2 += u * u;
        }
        d2max = d2 > d2max ? d2 : d2max;
    }
    return d2max;
}

double step_max_shift2(int dim, size_t n, double *const x[3], double *const xb[3])
{
    double d2max = 0.0;
#pragma omp parallel if (n > SPALL_OMP_MIN_PARTICLES)
    {
        size_t i0 = 0, i1 = n;
#ifdef _OPENMP
        const size_t nt = (size_t)omp_get_num_threads(), t = (size_t)omp_get_thread_num();
        i0 = n * t / nt;
        i1 = n * (t + 1) / nt;
#endif
        const double d = max_shift2(dim, i0, i1, x, xb);
#pragma omp critical(step_max_shift)
        d2max = d > d2max ? d : d2max;
    }
    return d2max;
}
