/**
 * @file pd_forces.c
 * @brief Hot loops of the peridynamics model: PMB bond forces with fused
 *        irreversible breaking, the stable time step, the per-half-bond
 *        coefficients (partial volume, surface correction) and the adaptive
 *        dynamic relaxation damping.
 *
 * Force on particle i ([PDLM2019] digest; Silling & Askari 2005 Eq. 2):
 *   F_i = V_i sum_j c_ij s_ij mu_ij beta_ij G_ij V_j e_ij,  s = (l - xi)/xi,
 * stored per half-bond as coef = c V_i V_j beta G / xi so that
 * F = coef (l - xi) e.  Each half-bond is decided (s > s0 -> broken, forever)
 * by its own particle's thread from |x_j - x_i|, which is bit-identical from
 * both ends, so the result does not depend on the thread count.
 */
#include "models/peridynamics/pd_internal.h"
#include "models/peridynamics/pd_kernel.h"

#include "core/bond_list.h"
#include "core/exact_sum.h"
#include "core/parallel/decomp.h"
#include "core/parallel/psum.h"
#include "core/parallel/setup_dist.h"
#include "core/particles.h"
#include "core/sim.h"
#include "spall/error.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* One kernel per dimension: the loop over j is the hot path (the mixed-mode
 * threshold; pd_kernel_block below for the others). */
#define PD_KERNEL(DIM, MIXED)                                                                   \
    _Pragma("omp parallel for schedule(dynamic, 256)")                                          \
    for (size_t i = 0; i < n; i++) {                                                            \
        double fx = 0.0, fy = 0.0, fz = 0.0, dd = 0.0;                                          \
        const double xi0 = x[0][i];                                                             \
        const double yi0 = DIM > 1 ? x[1][i] : 0.0;                                             \
        const double zi0 = DIM > 2 ? x[2][i] : 0.0;                                             \
        for (size_t s = off[i]; s < off[i + 1]; s++) {                                          \
            if (st[s] & BOND_BROKEN)                                                            \
                continue;                                                                       \
            const size_t j = (size_t)partner[s];                                                \
            const double ex = x[0][j] - xi0;                                                    \
            const double ey = DIM > 1 ? x[1][j] - yi0 : 0.0;                                    \
            const double ez = DIM > 2 ? x[2][j] - zi0 : 0.0;                                    \
            const double l = sqrt(ex * ex + ey * ey + ez * ez);                                 \
            const double r = rest[s];                                                           \
            const double stretch = (l - r) / r;                                                 \
            double thr = s0tab[type[s]];                                                        \
            if (MIXED && mmt[type[s]])                                                          \
                thr *= 0.5 * (mmg[i] + mmg[j]);                                                 \
            if (stretch > thr) {                                                                \
                st[s] |= BOND_BROKEN;                                                           \
                if (fresh && !(type[s] & 1u))                                                   \
                    fresh[s] = 1;                                                               \
                dd += pd_break_energy(DIM, ex, ey, ez, r, l - r, coef[s], dt, u, i, j, late);   \
                if (!late)                                                                      \
                    continue;                                                                   \
            }                                                                                   \
            const double g = coef[s] * (l - r) / l;                                             \
            fx += g * ex;                                                                       \
            if (DIM > 1)                                                                        \
                fy += g * ey;                                                                   \
            if (DIM > 2)                                                                        \
                fz += g * ez;                                                                   \
        }                                                                                       \
        f[0][i] += fx;                                                                          \
        if (DIM > 1)                                                                            \
            f[1][i] += fy;                                                                      \
        if (DIM > 2)                                                                            \
            f[2][i] += fz;                                                                      \
        diss[i] += dd;                                                                          \
    }

/* Pass 1 for half-bond k of a chunk of particle i's row (partner, rest,
 * coef and thr start at the chunk) at (xi0, yi0, zi0): the force
 * components g e into gx, gy, gz, exact zeros for a broken half-bond, and
 * the elongation l - r into el.  thr holds the pre-test bound s0 r (1 -
 * 1e-12) of an intact half-bond and NaN for a broken one (INFINITY is a
 * bond that never breaks), so one array says both.  Returns whether the
 * half-bond is intact and passes the pre-test into any. */
#define PD_BOND(k)                                                                              \
    do {                                                                                        \
        const size_t j = (size_t)partner[k];                                                    \
        const double ex = x0[j] - xi0;                                                          \
        const double ey = dim > 1 ? x1[j] - yi0 : 0.0;                                          \
        const double ez = dim > 2 ? x2[j] - zi0 : 0.0;                                          \
        const double l = sqrt(ex * ex + ey * ey + ez * ez);                                     \
        const double e = l - rest[k];                                                           \
        const double g = coef[k] * e / l;                                                       \
        const double hx = g * ex, hy = g * ey, hz = g * ez;                                     \
        const int live = thr[k] == thr[k]; /* NaN: broken */                                    \
        gx[k] = live ? hx : 0.0;                                                                \
        gy[k] = live ? hy : 0.0;                                                                \
        gz[k] = live ? hz : 0.0;                                                                \
        el[k] = e;                                                                              \
        any |= (int64_t)(e > thr[k]);                                                           \
    } while (0)

/* Pass 1 over the nb half-bonds of a chunk (PD_BOND), with no dependence
 * between half-bonds.  Returns whether some intact half-bond of the chunk
 * passes the pre-test, i.e. whether its pass 2 must look at it one
 * half-bond at a time.  Only 64-bit data, so that the vectoriser keeps to
 * one element size. */
static inline __attribute__((always_inline)) int64_t
pd_chunk(int dim, size_t nb, double xi0, double yi0, double zi0, double *const *restrict x,
         const int32_t *restrict partner, const double *restrict rest,
         const double *restrict coef, const double *restrict thr, double *restrict gx,
         double *restrict gy, double *restrict gz, double *restrict el)
{
    const double *restrict x0 = x[0], *restrict x1 = x[1], *restrict x2 = x[2];
    int64_t any = 0;
    for (size_t k = 0; k < nb; k++)
        PD_BOND(k);
    return any;
}

/* pd_chunk per dimension in two versions picked once at load time by the
 * CPU (PD_CLONES, pd_internal.h). */
#define PD_CHUNK_DIM(DIM)                                                                       \
    PD_CLONES PD_CHUNK_DECL(DIM)                                                                \
    {                                                                                           \
        return pd_chunk(DIM, nb, xi0, yi0, zi0, x, partner, rest, coef, thr, gx, gy, gz, el);   \
    }
PD_CHUNK_DIM(1)
PD_CHUNK_DIM(2)
PD_CHUNK_DIM(3)

/* Rows per block of the split kernel: a block is one thread's, its rows in
 * turn, so that the plain sum of one chunk goes into pass 1 of the next
 * one, across row ends. */
#define PD_BLOCK 64

/* Pass 0 of chunk b: its lengths and coefficients (compact families: from
 * the table) and its pre-test bounds, NaN for a broken half-bond; and in
 * the same loop the plain row-order sum of the components of chunk p
 * (NULL: none) into its row's sums.  The sum is a chain of dependent
 * additions that would wait on the adder's latency alone; next to the
 * loads of pass 0 it costs little. */
static inline __attribute__((always_inline)) void
pd_chunk_gather(int dim, const struct pd_kctx *c, struct pd_chunk_buf *b,
                const struct pd_chunk_buf *p, double (*sum)[3])
{
    const size_t np = p ? p->nb : 0;
    double dummy[3] = {0.0, 0.0, 0.0};
    double *ps = p ? sum[p->r] : dummy;
    double sx = ps[0], sy = ps[1], sz = ps[2];
    /* half-bond k of b, then term k of p */
#define PD_PSUM(k) PD_ADD_TERM(dim, p, k, sx, sy, sz)
#define PD_NONE(k) ((void)0)
    PD_PASS0(c, b, np, PD_PSUM, PD_NONE);
#undef PD_PSUM
#undef PD_NONE
    ps[0] = sx;
    ps[1] = sy;
    ps[2] = sz;
}

/* Pass 2 of a chunk with a half-bond past the pre-test, in the row order:
 * each such half-bond settled with the exact test (l - r) / r > s0; the
 * sums into sum[0..2] and the released energy into *dd. */
static inline __attribute__((always_inline)) void
pd_chunk_settle(int dim, const struct pd_kctx *c, const struct pd_chunk_buf *b, double *sum,
                double *dd)
{
    double sx = sum[0], sy = sum[1], sz = sum[2];
    for (size_t k = 0; k < b->nb; k++) {
        const unsigned ty = pd_kc_type(c, b->s + k);
        if (pd_breaks_now(c, b, k, ty)) {
            *dd += pd_break_half(dim, c, b, k, ty);
            if (!c->late)
                continue;
        }
        PD_ADD_TERM(dim, b, k, sx, sy, sz);
    }
    sum[0] = sx;
    sum[1] = sy;
    sum[2] = sz;
}

/* The PMB kernel without the mixed-mode threshold, split so that the
 * compiler vectorises the costly part (gathers, sqrt, division) of each
 * chunk of a row: pass 0 gathers the chunk's lengths, coefficients and
 * pre-test bounds (NaN: broken); pass 1 (pd_chunk) computes every
 * half-bond with no dependence between half-bonds; pass 2 adds the
 * components in the row order.  A chunk where no intact half-bond passes
 * the cheap pre-test l - r > s0 r (1 - 1e-12) (it misses none: (l - r) / r
 * > s0 in floating point needs l - r > s0 r (1 - 2^-53)) is a plain sum,
 * done in the loop of the next chunk's pass 1; otherwise its pass 2
 * settles each half-bond that passes with the exact test (l - r) / r > s0
 * right after its pass 1 (the chunks before it in the row are summed by
 * then).  A broken half-bond adds an exact +0.0, which leaves every
 * partial sum as it was (it starts at +0.0, and a sum in round-to-nearest
 * is -0.0 only when both terms are).  Every operation that reaches a
 * particle's result and the order of its sums are those of PD_KERNEL, so
 * the result is bit for bit the same, for any thread count and blocking.
 * One block of PD_BLOCK rows, its row sums in sum and dd. */
static inline __attribute__((always_inline)) void
pd_kernel_block(int dim, const struct pd_kctx *c, size_t n, size_t q, struct pd_chunk_buf *buf,
                double (*sum)[3], double *dd, double *const *f, double *diss)
{
    const size_t i0 = q * PD_BLOCK, i1 = i0 + PD_BLOCK < n ? i0 + PD_BLOCK : n;
    struct pd_chunk_buf *p = NULL; /* the chunk whose plain sum is pending */
    int next = 0;
    for (size_t i = i0; i < i1; i++) {
        const size_t r = i - i0;
        sum[r][0] = sum[r][1] = sum[r][2] = dd[r] = 0.0;
        for (size_t s0 = c->off[i]; s0 < c->off[i + 1]; s0 += PD_CHUNK) {
            struct pd_chunk_buf *b = &buf[next];
            next ^= 1;
            b->i = i;
            b->r = r;
            b->s = s0;
            b->nb = c->off[i + 1] - s0 < PD_CHUNK ? c->off[i + 1] - s0 : PD_CHUNK;
            b->xi0 = c->x[0][i];
            b->yi0 = dim > 1 ? c->x[1][i] : 0.0;
            b->zi0 = dim > 2 ? c->x[2][i] : 0.0;
            pd_chunk_gather(dim, c, b, p, sum);
            const int64_t any = pd_pass1(dim, c, b);
            p = NULL;
            if (any)
                pd_chunk_settle(dim, c, b, sum[r], &dd[r]);
            else
                p = b;
        }
    }
    if (p) { /* the block's last plain sum */
        double *ps = sum[p->r];
        for (size_t k = 0; k < p->nb; k++) {
            ps[0] += p->gx[k];
            if (dim > 1)
                ps[1] += p->gy[k];
            if (dim > 2)
                ps[2] += p->gz[k];
        }
    }
    for (size_t i = i0; i < i1; i++) {
        const size_t r = i - i0;
        f[0][i] += sum[r][0];
        if (dim > 1)
            f[1][i] += sum[r][1];
        if (dim > 2)
            f[2][i] += sum[r][2];
        diss[i] += dd[r];
    }
}

/* The kernel per dimension, so that the dimension is a constant in the
 * threads' code. */
#define PD_KERNEL_SPLIT_DIM(DIM)                                                                \
    static void pd_kernel_split##DIM(const struct pd_kctx *c, size_t n, double *const *f,      \
                                     double *diss)                                              \
    {                                                                                           \
        const size_t nblk = (n + PD_BLOCK - 1) / PD_BLOCK;                                      \
        _Pragma("omp parallel")                                                                 \
        {                                                                                       \
            struct pd_chunk_buf buf[2];                                                         \
            double sum[PD_BLOCK][3], dd[PD_BLOCK];                                              \
            _Pragma("omp for schedule(dynamic, 4)")                                             \
            for (size_t q = 0; q < nblk; q++)                                                   \
                pd_kernel_block(DIM, c, n, q, buf, sum, dd, f, diss);                           \
        }                                                                                       \
    }
PD_KERNEL_SPLIT_DIM(1)
PD_KERNEL_SPLIT_DIM(2)
PD_KERNEL_SPLIT_DIM(3)

/* The kernel's table of the compact families for this step (NULL when
 * the model keeps the arrays): thr = s0 r (1 - 1e-12) with the
 * thresholds of now; the LPS kernel reads the same rows. */
int pd_kind_rows(const struct model *m, struct pd_kind_row **out, struct spall_error *err)
{
    *out = NULL;
    if (!m->kind)
        return SPALL_OK;
    struct pd_kind_row *t = malloc((m->n_kind ? m->n_kind : 1) * sizeof *t);
    if (!t)
        return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory for peridynamic bonds");
    for (size_t q = 0; q < m->n_kind; q++) {
        t[q].rest = m->k_rest[q];
        t[q].coef = m->k_coef[q];
        t[q].type = m->k_type[q];
        t[q].thr = m->s0_tab[t[q].type] * t[q].rest * PD_PRE;
    }
    *out = t;
    return SPALL_OK;
}

int pd_compute_forces(struct model *m, struct sim *sim, struct spall_error *err)
{
    struct particles *p = sim->p;
    struct bond_list *bl = m->bl;
    const size_t n = p->n_owned;
    const size_t *off = bl->offset;
    const int32_t *partner = bl->partner;
    const double *rest = bl->rest;
    const uint8_t *type = bl->type;
    uint8_t *st = bl->state;
    const double *coef = m->coef;
    /* compact families (pd_compact.c): rest, type and coef are NULL */
    const uint16_t *kind = m->kind;
    const double *s0tab = m->s0_tab;
    double *diss = m->diss;
    double *const *x = p->x;
    double *const *f = p->f;
    /* x_n = x_{n+1} - dt u for the energy of a bond that breaks in this step */
    double dt;
    double *const *u = sim_drift_velocities(sim, &dt);
    /* break_order next_step: a bond past s0 still pulls in this step
     * (PDLAMMPS pair peri/pmb order); immediate: it is dropped at once */
    const bool late = m->opt.break_late;
    /* mixed-mode matrix bonds (pd_mixed.c): threshold s0_m (g_i + g_j) / 2 */
    const uint8_t *mmt = m->mm_type;
    const double *mmg = m->mm_g;
    /* fiber-parallel matrix cracks (pd_plane.c): flag stretch-broken matrix bonds */
    uint8_t *fresh = m->fresh;
    if (m->opt.lps) {
        int rc = pd_lps_forces(m, sim, err);
        if (!rc && m->opt.quasi == PD_QS_ADR)
            pd_adr_update(m, sim);
        return rc;
    }
    struct pd_kind_row *ktab;
    int rc = pd_kind_rows(m, &ktab, err);
    if (rc)
        return rc;
    const struct pd_kctx kc = {off, partner, rest, coef, type, st, kind, ktab, s0tab,
                               x, u, dt, late, fresh};
    switch (p->dim) {
    case 1:
        if (!pd_half_forces(m, sim, &kc, n, f, diss))
            pd_kernel_split1(&kc, n, f, diss);
        break;
    case 2:
        if (m->mixed) {
            pd_mixed_update(m, sim);
            /* distributed: a ghost's family is on its owner, and so is its
             * factor, which the thresholds of its bonds read */
            if (sim->par)
                par_halo_values(sim, m->mm_g, 1);
            PD_KERNEL(2, 1)
        } else if (!pd_half_forces(m, sim, &kc, n, f, diss)) {
            pd_kernel_split2(&kc, n, f, diss);
        }
        break;
    default:
        if (!pd_half_forces(m, sim, &kc, n, f, diss))
            pd_kernel_split3(&kc, n, f, diss);
        break;
    }
    free(ktab);
    if (m->opt.quasi == PD_QS_ADR)
        pd_adr_update(m, sim);
    return SPALL_OK;
}

/* Kilic & Madenci 2010 (Eqs. 17-19) with the physical masses as the
 * (diagonal) density matrix: local stiffness
 *   K_ii = -(F_i^n - F_i^{n-1}) / (m_i dt v_i^{n-1/2}),
 * damping coefficient c_n = 2 sqrt(u^T K u / u^T u) (1/s), which the engine
 * takes (pd_damping, model_ops.damping) for its mass-proportional damping
 * F = -c m v.  Model forces only (loads
 * and grips are not part of the stiffness).  The two sums are exact
 * (core/exact_sum.h; over all ranks when distributed, parallel/psum.h), so
 * every rank takes the same coefficient, the serial one. */
void pd_adr_update(struct model *m, const struct sim *sim)
{
    const struct particles *p = sim->p;
    const size_t n = p->n_owned;
    struct xsum acc[2]; /* num, den */
    xsum_init(&acc[0]);
    xsum_init(&acc[1]);
    for (int d = 0; d < p->dim; d++) {
        double *fc = m->f_prev[d]; /* [2 i]: current, stored; [2 i + 1]: previous */
        for (size_t i = 0; i < n; i++) {
            /* step n-1's force becomes the previous one here, for every
             * formulation (LPS/EPS return before the bond-based kernel) */
            fc[2 * i + 1] = fc[2 * i];
            double fi = p->f[d][i];
            double u = p->x[d][i] - p->x0[d][i];
            double v = p->v[d][i];
            const double h = sim_step_dt(sim); /* the position change is v h */
            if (sim->step > 0 && h > 0.0 && fabs(v) * h > 1e-9 * fabs(u)) {
                double k = -(fi - fc[2 * i + 1]) / (p->mass[i] * h * v);
                xsum_add(&acc[0], u * k * u);
            }
            xsum_add(&acc[1], u * u);
            fc[2 * i] = fi;
        }
    }
    double sums[2];
    par_xsum_finish(sim, acc, 2, sums);
    const double num = sums[0], den = sums[1];
    /* Near convergence v and the force change are round-off and the estimate
     * is noise: keep the previous coefficient when it is not positive, and
     * never exceed 0.2 / dt (explicit damping stays far below its 2 / dt
     * stability bound). */
    if (!(den > 0.0 && num > 0.0))
        return;
    double c = 2.0 * sqrt(num / den);
    if (sim->dt > 0.0 && c > 0.2 / sim->dt)
        c = 0.2 / sim->dt;
    m->adr_damping = c;
    m->adr_estimated = true;
}

/* Silling & Askari 2005 Eq. 15 with the particle's row sum of bond
 * stiffnesses: dt < sqrt(2 m_i / sum_j coef_ij).  In a window of the
 * distributed set-up the block's rows only: a halo particle cut by the
 * window's edge lost bonds, but with the surface correction its remaining
 * ones are stiffer (its factors see a surface there), so its row sum is
 * not bounded by its serial one. */
double pd_stable_dt(const struct model *m, const struct sim *sim)
{
    const struct particles *p = sim->p;
    const struct bond_list *bl = m->bl;
    const struct par_setup *ps = par_setup_window(sim);
    double w2 = 0.0;
    for (size_t i = 0; i < p->n_owned; i++) {
        if (ps && !par_setup_in_block(ps, i))
            continue;
        double k = 0.0;
        for (size_t s = bl->offset[i]; s < bl->offset[i + 1]; s++)
            if (!(bl->state[s] & BOND_BROKEN))
                k += pd_coef(m, s);
        w2 = fmax(w2, k / p->mass[i]);
    }
    return w2 > 0.0 ? sqrt(2.0 / w2) : INFINITY;
}

/* Partial volume of a neighbour cut by the horizon (linear rule, Madenci &
 * Oterkus 2014 sec. 2.4 / Hu et al.): 1 inside delta - dx/2, 0 beyond
 * delta + dx/2, linear between. */
static inline double pd_beta(double xi, double delta, double dx)
{
    if (xi <= delta - 0.5 * dx)
        return 1.0;
    if (xi >= delta + 0.5 * dx)
        return 0.0;
    return (delta + 0.5 * dx - xi) / dx;
}

/* Micromodulus of half-bond s of particle i (per unit V_i V_j, per xi). */
static double bond_c(const struct model *m, const struct sim *sim, size_t i, size_t s)
{
    const struct particles *p = sim->p;
    const struct bond_list *bl = m->bl;
    size_t j = (size_t)bl->partner[s];
    const struct pd_material *a = &m->mat[p->material[i]], *b = &m->mat[p->material[j]];
    if (!a->ortho && !b->ortho)
        return 2.0 * a->c * b->c / (a->c + b->c); /* springs in series */
    const struct pd_material *o = a->ortho ? a : b;
    double ex = p->x0[0][j] - p->x0[0][i], ey = sim->dim > 1 ? p->x0[1][j] - p->x0[1][i] : 0.0;
    double cphi = fabs(ex * cos(o->fiber_angle) + ey * sin(o->fiber_angle)) / bond_rest(bl, s);
    if (m->opt.fiber_model == PD_FIBER_ANGULAR)
        return o->c_m + o->c_f * pow(cphi * cphi, (double)m->opt.fiber_power);
    return cphi > 0.9999 ? o->c_f : o->c_m;
}

/* Strain energy density of a particle's family under the uniaxial
 * displacement field u_d = eps x_d (only component d): sum over intact bonds
 * of 1/4 c s^2 xi V_j beta (Madenci & Oterkus 2014 Eq. 4.23 form). */
static double family_energy(const struct model *m, const struct sim *sim, size_t i, int d)
{
    const struct particles *p = sim->p;
    const struct bond_list *bl = m->bl;
    double w = 0.0;
    for (size_t s = bl->offset[i]; s < bl->offset[i + 1]; s++) {
        size_t j = (size_t)bl->partner[s];
        double xi = bond_rest(bl, s);
        double cd = (p->x0[d][j] - p->x0[d][i]) / xi;
        double st = cd * cd; /* stretch per unit eps */
        w += 0.25 * st * st * xi * p->volume[j] * pd_beta(xi, m->delta, m->dx);
    }
    return w;
}

/* Same integral for a complete continuous family: int cos^4 xi dV. */
static double family_energy_bulk(int dim, double delta, double thickness)
{
    switch (dim) {
    case 1: return 0.25 * thickness * delta * delta;                 /* A delta^2 */
    case 2: return 0.25 * thickness * SPALL_PI * delta * delta * delta / 4.0;
    default: return 0.25 * SPALL_PI * pow(delta, 4) / 5.0;
    }
}

int pd_surface_factors(const struct model *m, const struct sim *sim, double **out,
                       struct spall_error *err)
{
    *out = NULL;
    const size_t n = sim->p->n;
    const int dim = sim->dim;
    if (!m->opt.surface_correction || m->opt.variant == PD_PDLM)
        return SPALL_OK;
    double *g = malloc((n ? n : 1) * 3 * sizeof *g);
    if (!g)
        return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory for surface factors");
    const double wb = family_energy_bulk(dim, m->delta, sim->thickness);
    for (size_t i = 0; i < n; i++)
        for (int d = 0; d < 3; d++) {
            double w = d < dim ? family_energy(m, sim, i, d) : 0.0;
            g[3 * i + (size_t)d] = w > 0.0 ? wb / w : 1.0;
        }
    *out = g;
    return SPALL_OK;
}

double pd_bond_coef(const struct model *m, const struct sim *sim, const double *g, size_t i,
                    size_t s)
{
    const struct particles *p = sim->p;
    const struct bond_list *bl = m->bl;
    const bool pdlm = m->opt.variant == PD_PDLM;
    const size_t j = (size_t)bl->partner[s];
    const double xi = bond_rest(bl, s);
    double beta = (m->opt.partial_volume && !pdlm) ? pd_beta(xi, m->delta, m->dx) : 1.0;
    double corr = 1.0;
    if (g) {
        /* Madenci & Oterkus 2014 Eq. 4.31: ellipsoidal interpolation of the
         * directional factors, each the mean of both ends */
        double q = 0.0;
        for (int d = 0; d < sim->dim; d++) {
            double nd = (p->x0[d][j] - p->x0[d][i]) / xi;
            double gd = 0.5 * (g[3 * i + (size_t)d] + g[3 * j + (size_t)d]);
            q += (nd / gd) * (nd / gd);
        }
        corr = q > 0.0 ? 1.0 / sqrt(q) : 1.0;
    }
    return bond_c(m, sim, i, s) * (p->volume[i] * p->volume[j]) * beta * corr / xi;
}

int pd_build_coefficients(struct model *m, struct sim *sim, struct spall_error *err)
{
    const struct bond_list *bl = m->bl;
    const size_t n = sim->p->n, nh = bl->offset[n];
    free(m->coef);
    m->coef = malloc((nh ? nh : 1) * sizeof *m->coef);
    if (!m->coef)
        return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory for peridynamic bonds");
    double *g = NULL;
    int rc = pd_surface_factors(m, sim, &g, err);
    if (rc)
        return rc;
    for (size_t i = 0; i < n; i++)
        for (size_t s = bl->offset[i]; s < bl->offset[i + 1]; s++)
            m->coef[s] = pd_bond_coef(m, sim, g, i, s);
    free(g);
    return SPALL_OK;
}
