/**
 * @file lattice_forces.c
 * @brief Force loops of the lattice model ([Wang2010] Eqs. 1, 15, 17).
 *
 * Race-free gather: every bond i-j is stored in both rows (half-bonds), and
 * each particle sums its own row, so each bond is evaluated twice and no two
 * threads write the same memory.  Bond breaking is fused into this loop: the
 * thread of particle i decides for its own half-bond only, and both halves of
 * a bond decide identically because |x_j - x_i| and the rest length are
 * bitwise symmetric and the pair constants are stored symmetric.  The same
 * holds for the energy the break releases, which each half books as one half
 * on its own particle (diss[i]), so the sum is independent of the thread count.
 *
 * Angular springs (alpha-beta model, 2D triangular lattice, Eq. 17 with the
 * energy k_phi dphi^2 / 2 per angle between adjacent first-shell bonds):
 * pass 1 evaluates every angle where it is centred, adds the centre's force
 * directly and writes the forces on the two arm particles into per-slot
 * buffers of the centre's row; pass 2 (the axial loop) lets each particle
 * gather the buffers of the slots that point at it through the reverse index.
 * Angles see the bond states of the previous step (breaking is decided in
 * pass 2), a one-step lag that only delays the de-activation of an angle;
 * at de-activation the angle (and its area-spring share, one third
 * of a lattice triangle's area energy) books the energy it held into diss.
 *
 * The hot loop (linear law, one material) is specialised by dimension and
 * whether the list has more than one bond type; the general loop covers
 * several materials (pair table) and the non-linear laws with the law a
 * compile-time constant inside each specialisation.
 */
#include "core/fields.h"
#include "models/lattice/lattice_kernels.h"
#include "models/lattice/lattice_softening.h"

#include "core/bond_list.h"
#include "core/parallel/bhalo.h"
#include "core/particles.h"
#include "core/sim.h"
#include "spall/error.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>
#ifdef _OPENMP
#include <omp.h>
#endif

/** Rare path: half-bond s of particle i breaks now (length r, stretch st;
 *  dr = r - r_n over the step).  Books half the released energy on i as the
 *  Verlet kicks left it and returns the post-fracture force coefficient.
 *  The intact force acted only at x_n, half a step, and the broken law's
 *  from x_{n+1}: the energy the kicks took out differs from the intact
 *  energy at x_{n+1} by (f_i - f_b) dr / 2, which booking U_i - U_b at the
 *  break would leave in the account (first order in dt). */
#if defined(__GNUC__)
__attribute__((noinline))
#endif
double lattice_break_half(struct model *m, size_t i, size_t s, const struct lattice_bond_law *bw,
                          double rest, double r, double dr)
{
    const double st = r / rest;
    m->bl->state[s] |= BOND_BROKEN;
    double ui = lattice_energy(&m->lp, bw->curve, bw->k, rest, st, 0);
    double ub = lattice_energy(&m->lp, bw->curve, bw->k, rest, st, 1);
    double ci = lattice_coef(&m->lp, bw->curve, bw->k, st, 0);
    double cb = lattice_coef(&m->lp, bw->curve, bw->k, st, 1);
    m->diss[i] += 0.5 * (ui - ub) - 0.25 * (ci - cb) * r * dr;
    return cb;
}

struct lattice_view lattice_make_view(const struct model *m, struct sim *sim)
{
    struct lattice_view v;
    const struct bond_list *bl = m->bl;
    struct particles *p = sim->p;
    v.offset = bl->offset;
    v.partner = bl->partner;
    v.rest = bl->rest;
    v.rest_idx = bl->rest_idx;
    v.rest_tab = bl->rest_tab;
    v.state = bl->state;
    v.type = bl->type;
    v.reverse = bl->reverse;
    v.ang_buf = m->ang_buf;
    v.kscale = m->kscale;
    v.mat = p->material;
    v.x0 = p->x[0];
    v.x1 = p->dim > 1 ? p->x[1] : NULL;
    v.x2 = p->dim > 2 ? p->x[2] : NULL;
    v.f0 = p->f[0];
    v.f1 = p->dim > 1 ? p->f[1] : NULL;
    v.f2 = p->dim > 2 ? p->f[2] : NULL;
    v.u = (const double *const *)sim_drift_velocities(sim, &v.dt_drift);
    v.set_forces = 0;
    return v;
}

/** r - r_n: the bond's length change over this step (x_n = x - dt u). */
double lattice_bond_dr(const struct lattice_view *v, size_t i, size_t j, int dim,
                       const double dx[3], double r)
{
    double r2 = 0.0;
    for (int d = 0; d < dim; d++) {
        const double e = dx[d] - v->dt_drift * (v->u[d][j] - v->u[d][i]);
        r2 += e * e;
    }
    return r - sqrt(r2);
}

/** Linear law, one material: f_i += k (1 - r_rest / r) dx, one sqrt and one
 *  division per half-bond.  @p multi_type: read the bond type (two shells). */
LATTICE_INLINE void row_linear(struct model *m, const struct lattice_view *v,
                               const struct lattice_bond_law *pw, size_t i, const int dim,
                               const int multi_type, const int gather)
{
    const double k0 = pw[0].k, tl0 = pw[0].t_lim, cl0 = pw[0].c_lim;
    double fi[3] = {0, 0, 0};
    const size_t s1 = v->offset[i + 1];
    for (size_t s = v->offset[i]; s < s1; s++) {
        const size_t j = (size_t)v->partner[s];
        double dx[3] = {0, 0, 0};
        const double r = sqrt(bond_vec(v, i, j, dim, dx));
        const double r_rest = view_rest(v, s);
        double k = k0, tl = tl0, cl = cl0;
        if (multi_type) {
            const struct lattice_bond_law *b = &pw[v->type[s]];
            k = b->k;
            tl = b->t_lim;
            cl = b->c_lim;
        }
        double c = k - k * r_rest / r;
        if (LATTICE_UNLIKELY(v->state[s])) {
            c = c < 0.0 ? c : 0.0;
        } else if (LATTICE_UNLIKELY(r > r_rest * tl || r < r_rest * cl)) {
            c = lattice_break_half(m, i, s, &pw[multi_type ? v->type[s] : 0], r_rest, r,
                                   lattice_bond_dr(v, i, j, dim, dx, r));
        }
        for (int d = 0; d < dim; d++)
            fi[d] += c * dx[d];
        if (gather) {
            const double *ab = v->ang_buf + 2 * v->reverse[s];
            fi[0] += ab[0];
            fi[1] += ab[1];
        }
    }
    add_force(v, i, dim, fi);
}

/** Any law, any number of materials (pair table lookup per half-bond). */
LATTICE_INLINE void row_general(struct model *m, const struct lattice_view *v, size_t i,
                                const int dim, const enum lattice_law law, const int gather)
{
    struct lattice_law_params lp = m->lp;
    lp.law = law; /* constant: the switch inside the law functions folds */
    const size_t nm = m->n_mat;
    const struct lattice_bond_law *prow = m->pair + (size_t)v->mat[i] * nm * LATTICE_MAX_TYPES;
    double fi[3] = {0, 0, 0};
    const size_t s1 = v->offset[i + 1];
    for (size_t s = v->offset[i]; s < s1; s++) {
        const size_t j = (size_t)v->partner[s];
        double dx[3] = {0, 0, 0};
        const double r = sqrt(bond_vec(v, i, j, dim, dx));
        const double r_rest = view_rest(v, s);
        const struct lattice_bond_law *bw =
            &prow[(size_t)v->mat[j] * LATTICE_MAX_TYPES + v->type[s]];
        const double st = r / r_rest;
        /* temperature-dependent stiffness (youngs_modulus_table): the
         * thermal pass writes the factor per half-bond */
        const double k = v->kscale ? bw->k * v->kscale[s] : bw->k;
        double c;
        if (LATTICE_UNLIKELY(v->state[s])) {
            c = lattice_coef(&lp, bw->curve, k, st, 1);
        } else if (law == LATTICE_LAW_SOFT && !(r < r_rest * bw->c_lim)) {
            /* cohesive softening: history per half-bond (lattice_softening.h) */
            c = lattice_soft_coef(bw->e0, bw->t_lim - 1.0, k, r_rest, st, &m->kappa[s],
                                  &m->bl->state[s], &m->diss[i], BOND_BROKEN);
        } else if (LATTICE_UNLIKELY(r > r_rest * bw->t_lim || r < r_rest * bw->c_lim)) {
            struct lattice_bond_law bk = *bw;
            bk.k = k;
            c = lattice_break_half(m, i, s, &bk, r_rest, r,
                                   lattice_bond_dr(v, i, j, dim, dx, r));
        } else {
            c = lattice_coef(&lp, bw->curve, k, st, 0);
        }
        for (int d = 0; d < dim; d++)
            fi[d] += c * dx[d];
        if (gather) {
            const double *ab = v->ang_buf + 2 * v->reverse[s];
            fi[0] += ab[0];
            fi[1] += ab[1];
        }
    }
    add_force(v, i, dim, fi);
}

/** Wrap an angle difference into (-pi, pi]. */
static inline double wrap_angle(double a)
{
    if (a > SPALL_PI)
        a -= 2.0 * SPALL_PI;
    else if (a <= -SPALL_PI)
        a += 2.0 * SPALL_PI;
    return a;
}

/** One angle between arms a and b of particle i (2D).  Returns dphi and
 *  the forces on the arm particles (Fa, Fb); the centre gets -(Fa + Fb).
 *  phi = atan2(a x b, a . b) grows when b turns counter-clockwise, so
 *  dphi/d(x_b) = (-b_y, b_x)/|b|^2 and dphi/d(x_a) = (a_y, -a_x)/|a|^2;
 *  F = -k_phi dphi grad(phi). */
static inline double angle_forces(double k_phi, double phi0, const double a[2],
                                  const double b[2], double Fa[2], double Fb[2])
{
    const double cr = a[0] * b[1] - a[1] * b[0];
    const double dt = a[0] * b[0] + a[1] * b[1];
    const double dphi = wrap_angle(atan2(cr, dt) - phi0);
    const double T = k_phi * dphi;
    const double ia = T / (a[0] * a[0] + a[1] * a[1]);
    const double ib = T / (b[0] * b[0] + b[1] * b[1]);
    Fa[0] = -a[1] * ia;
    Fa[1] = a[0] * ia;
    Fb[0] = b[1] * ib;
    Fb[1] = -b[0] * ib;
    return dphi;
}

/** Rest area of the triangle spanned by the arms of angle s (arm b in slot sb). */
static inline double area_rest(const struct bond_list *bl, size_t s, size_t sb, double phi0)
{
    return 0.5 * bond_rest(bl, s) * bond_rest(bl, sb) * sin(phi0);
}

/** Alpha-beta-gamma area share (lattice_calib.c): energy k_s (A/A0 - 1)^2 / 2
 *  with A = (a x b) / 2, so dA/da = (b_y, -b_x)/2 and dA/db = (-a_y, a_x)/2;
 *  ADDS F = -k_s (A/A0 - 1)/A0 grad A to Fa, Fb.  Returns the share's energy. */
static inline double area_forces(double k_s, double A0, const double a[2], const double b[2],
                                 double Fa[2], double Fb[2])
{
    const double dA = 0.5 * (a[0] * b[1] - a[1] * b[0]) / A0 - 1.0;
    const double P = 0.5 * k_s * dA / A0;
    Fa[0] -= P * b[1];
    Fa[1] += P * b[0];
    Fb[0] += P * a[1];
    Fb[1] -= P * a[0];
    return 0.5 * k_s * dA * dA;
}

/** Pass 1 for particle i: angles centred at i (writes only row i's buffers,
 *  row i's angle states, diss[i] and the centre's force). */
static void angles_row(struct model *m, const int32_t *mat, double *const *x, size_t i,
                       double fi[2])
{
    const struct bond_list *bl = m->bl;
    const size_t s0 = bl->offset[i], s1 = bl->offset[i + 1];
    double *buf = m->ang_buf;
    for (size_t s = s0; s < s1; s++) {
        buf[2 * s] = 0.0;
        buf[2 * s + 1] = 0.0;
    }
    const double k_phi = m->mat_k_phi[mat[i]];
    const double k_s = m->mat_k_area[mat[i]] / 3.0; /* one vertex share of a triangle */
    if (k_phi == 0.0 && k_s == 0.0)
        return;
    const double lim_c = m->mat_dphi_c[mat[i]], lim_t = m->mat_dphi_t[mat[i]];
    for (size_t s = s0; s < s1; s++) {
        const unsigned lb = m->ang_b[s];
        if (lb == LATTICE_NO_ANGLE)
            continue;
        const size_t sb = s0 + lb;
        if (m->ang_state[s])
            continue;
        const size_t ja = (size_t)bl->partner[s], jb = (size_t)bl->partner[sb];
        const double a[2] = {x[0][ja] - x[0][i], x[1][ja] - x[1][i]};
        const double b[2] = {x[0][jb] - x[0][i], x[1][jb] - x[1][i]};
        double Fa[2], Fb[2];
        const double dphi = angle_forces(k_phi, m->ang_phi0[s], a, b, Fa, Fb);
        if (LATTICE_UNLIKELY(bl->state[s] || bl->state[sb])) {
            /* an arm broke (last step's axial pass): the angle and its area
             * share switch off for good; book the energy they held so the
             * energy balance stays closed */
            m->ang_state[s] = 1;
            m->diss[i] += 0.5 * k_phi * dphi * dphi;
            if (k_s != 0.0)
                m->diss[i] += area_forces(k_s, area_rest(bl, s, sb, m->ang_phi0[s]), a, b, Fa,
                                          Fb);
            continue;
        }
        if (LATTICE_UNLIKELY(dphi < -lim_c || dphi > lim_t)) {
            m->ang_state[s] = 1;
            m->diss[i] += 0.5 * k_phi * dphi * dphi;
            if (k_s != 0.0)
                m->diss[i] += area_forces(k_s, area_rest(bl, s, sb, m->ang_phi0[s]), a, b, Fa,
                                          Fb);
            continue;
        }
        if (k_s != 0.0)
            area_forces(k_s, area_rest(bl, s, sb, m->ang_phi0[s]), a, b, Fa, Fb);
        buf[2 * s] += Fa[0];
        buf[2 * s + 1] += Fa[1];
        buf[2 * sb] += Fb[0];
        buf[2 * sb + 1] += Fb[1];
        fi[0] -= Fa[0] + Fb[0];
        fi[1] -= Fa[1] + Fb[1];
    }
}

/* ---- specialised ranges ------------------------------------------------------
 * OpenMP outlines a parallel region before inlining, so constants passed into
 * a region do not reach the kernels.  The region therefore only splits the
 * particles into static per-thread ranges, and these functions (called from
 * inside it) switch once per range to a loop whose dimension, law and
 * variant are literal constants. */


/** Pass 2 of block_linear over the block's @p nt half-bonds from slot @p sb:
 *  the force coefficients into cb; returns nonzero when a bond breaks now.
 *  @p tab: the rest lengths are compacted (bond_list_compact_rest). */
LATTICE_INLINE int block_coefs(const struct lattice_view *v, const struct lattice_bond_law *pw,
                               size_t sb, size_t nt, double dxb[3][LATTICE_BLOCK],
                               double *restrict cb, const int dim, const int multi,
                               const int tab)
{
    const double *restrict rest = tab ? NULL : v->rest + sb;
    const uint16_t *restrict ridx = tab ? v->rest_idx + sb : NULL;
    const double *restrict rtab = v->rest_tab;
    const uint8_t *restrict state = v->state + sb;
    const uint8_t *restrict type = v->type + sb;
    const double k0 = pw[0].k, tl0 = pw[0].t_lim, cl0 = pw[0].c_lim;
    int breaks = 0;
    for (size_t t = 0; t < nt; t++) {
        double r2 = dxb[0][t] * dxb[0][t];
        if (dim > 1)
            r2 += dxb[1][t] * dxb[1][t];
        if (dim > 2)
            r2 += dxb[2][t] * dxb[2][t];
        const double r = sqrt(r2), r_rest = tab ? rtab[ridx[t]] : rest[t];
        double k = k0, tl = tl0, cl = cl0;
        if (multi) {
            k = pw[type[t]].k;
            tl = pw[type[t]].t_lim;
            cl = pw[type[t]].c_lim;
        }
        const double c = k - k * r_rest / r;
        const double cmin = c < 0.0 ? c : 0.0;
        const int intact = state[t] == 0;
        breaks |= intact & ((r > r_rest * tl) | (r < r_rest * cl));
        cb[t] = intact ? c : cmin;
    }
    return breaks;
}

/** The linear loop over the particles [i0, i1), whose rows hold at most
 *  LATTICE_BLOCK half-bonds together, in three passes so that the
 *  arithmetic of a row is the same, bit for bit, as row_linear's (same
 *  operations in the same order; -ffp-contract=off) while the costly part
 *  vectorises: (1) bond vectors dx = x_j - x_i (the partner gathers),
 *  (2) over the block's half-bonds, contiguous and without branches: one
 *  sqrt and one division each, the broken-bond clamp and a flag for a
 *  bond that breaks now, (3) per particle the force sum in row order.
 *  A breaking bond takes the rare path of row_linear (break_half), in row
 *  order, so diss[i] sums in the same order too. */
LATTICE_INLINE void block_linear(struct model *m, const struct lattice_view *v,
                                 const struct lattice_bond_law *pw, size_t i0, size_t i1,
                                 const int dim, const int multi, const int gather)
{
    double dxb[3][LATTICE_BLOCK], cb[LATTICE_BLOCK];
    const size_t sb = v->offset[i0], nt = v->offset[i1] - sb;
    for (size_t i = i0; i < i1; i++) {
        const double xi = v->x0[i], yi = dim > 1 ? v->x1[i] : 0.0,
                     zi = dim > 2 ? v->x2[i] : 0.0;
        for (size_t s = v->offset[i]; s < v->offset[i + 1]; s++) {
            const size_t j = (size_t)v->partner[s], t = s - sb;
            dxb[0][t] = v->x0[j] - xi;
            if (dim > 1)
                dxb[1][t] = v->x1[j] - yi;
            if (dim > 2)
                dxb[2][t] = v->x2[j] - zi;
        }
    }
    const int breaks = v->rest_idx ? block_coefs(v, pw, sb, nt, dxb, cb, dim, multi, 1)
                                   : block_coefs(v, pw, sb, nt, dxb, cb, dim, multi, 0);
    if (LATTICE_UNLIKELY(breaks)) {
        for (size_t i = i0; i < i1; i++)
            for (size_t s = v->offset[i]; s < v->offset[i + 1]; s++) {
                const size_t t = s - sb;
                if (v->state[s])
                    continue;
                double dx[3] = {dxb[0][t], dim > 1 ? dxb[1][t] : 0.0, dim > 2 ? dxb[2][t] : 0.0};
                double r2 = dx[0] * dx[0];
                if (dim > 1)
                    r2 += dx[1] * dx[1];
                if (dim > 2)
                    r2 += dx[2] * dx[2];
                const double r = sqrt(r2), r_rest = view_rest(v, s);
                const struct lattice_bond_law *b = &pw[multi ? v->type[s] : 0];
                if (r > r_rest * b->t_lim || r < r_rest * b->c_lim)
                    cb[t] = lattice_break_half(
                        m, i, s, b, r_rest, r,
                        lattice_bond_dr(v, i, (size_t)v->partner[s], dim, dx, r));
            }
    }
    for (size_t i = i0; i < i1; i++) {
        double fi[3] = {0, 0, 0};
        for (size_t s = v->offset[i]; s < v->offset[i + 1]; s++) {
            const size_t t = s - sb;
            for (int d = 0; d < dim; d++)
                fi[d] += cb[t] * dxb[d][t];
            if (gather) {
                const double *ab = v->ang_buf + 2 * v->reverse[s];
                fi[0] += ab[0];
                fi[1] += ab[1];
            }
        }
        add_force(v, i, dim, fi);
    }
}

LATTICE_INLINE void loop_linear(struct model *m, const struct lattice_view *v, size_t lo,
                                size_t hi, const int dim, const int multi, const int gather)
{
    const struct lattice_bond_law *pw = m->pair; /* material 0 with itself: types 0..1 */
    size_t i = lo;
    while (i < hi) {
        const size_t sb = v->offset[i];
        size_t e = i;
        while (e < hi && v->offset[e + 1] - sb <= LATTICE_BLOCK)
            e++;
        if (e == i) { /* one row longer than a block */
            row_linear(m, v, pw, i, dim, multi, gather);
            i++;
        } else {
            block_linear(m, v, pw, i, e, dim, multi, gather);
            i = e;
        }
    }
}


LATTICE_CLONES static void range_linear(struct model *m, const struct lattice_view *v, size_t lo, size_t hi,
                         int dim, int multi, int gather)
{
    if (dim == 1)
        loop_linear(m, v, lo, hi, 1, 0, 0);
    else if (dim == 2 && gather && multi)
        loop_linear(m, v, lo, hi, 2, 1, 1);
    else if (dim == 2 && gather)
        loop_linear(m, v, lo, hi, 2, 0, 1);
    else if (dim == 2 && multi)
        loop_linear(m, v, lo, hi, 2, 1, 0);
    else if (dim == 2)
        loop_linear(m, v, lo, hi, 2, 0, 0);
    else if (multi)
        loop_linear(m, v, lo, hi, 3, 1, 0);
    else
        loop_linear(m, v, lo, hi, 3, 0, 0);
}

LATTICE_INLINE void loop_general(struct model *m, const struct lattice_view *v, size_t lo,
                                 size_t hi, const int dim, const enum lattice_law law,
                                 const int gather)
{
    for (size_t i = lo; i < hi; i++)
        row_general(m, v, i, dim, law, gather);
}

static void range_general_law(struct model *m, const struct lattice_view *v, size_t lo,
                              size_t hi, int dim, const enum lattice_law law, int gather)
{
    if (dim == 1)
        loop_general(m, v, lo, hi, 1, law, 0);
    else if (dim == 2 && gather)
        loop_general(m, v, lo, hi, 2, law, 1);
    else if (dim == 2)
        loop_general(m, v, lo, hi, 2, law, 0);
    else
        loop_general(m, v, lo, hi, 3, law, 0);
}

static void range_general(struct model *m, const struct lattice_view *v, size_t lo, size_t hi,
                          int dim, int gather)
{
    switch (m->lp.law) {
    case LATTICE_LAW_LJ: range_general_law(m, v, lo, hi, dim, LATTICE_LAW_LJ, gather); break;
    case LATTICE_LAW_PWL: range_general_law(m, v, lo, hi, dim, LATTICE_LAW_PWL, gather); break;
    case LATTICE_LAW_SOFT: range_general_law(m, v, lo, hi, dim, LATTICE_LAW_SOFT, gather); break;
    case LATTICE_LAW_LINEAR:
    default: range_general_law(m, v, lo, hi, dim, LATTICE_LAW_LINEAR, gather); break;
    }
}

/** Static split of [0, n) over the threads of the current team; *tid:
 *  the calling thread's number. */
static void thread_range(size_t n, size_t *lo, size_t *hi, size_t *tid)
{
#ifdef _OPENMP
    size_t nt = (size_t)omp_get_num_threads(), t = (size_t)omp_get_thread_num();
#else
    size_t nt = 1, t = 0;
#endif
    size_t q = n / nt, r = n % nt;
    *lo = t * q + (t < r ? t : r);
    *hi = *lo + q + (t < r ? 1 : 0);
    *tid = t;
}

/* ---- loop drivers: the only place with OpenMP pragmas ----------------------- */

/* The threads' rings of the once-per-bond loop (lattice_half.c): dim
 * arrays of W entries each for up to the team's size, kept by the model
 * (all zero between calls).  0 when that loop does not apply, is switched
 * off (lattice_set_row_loop) or memory is short: the row loop then gives
 * the same bits. */
static size_t half_rings(struct model *m, struct sim *sim, int dim)
{
    if (m->half_off)
        return 0;
    const size_t w = lattice_half_ring(m, sim);
#ifdef _OPENMP
    const size_t nt = (size_t)omp_get_max_threads();
#else
    const size_t nt = 1;
#endif
    const size_t need = nt * w * (size_t)dim;
    if (w && m->half_buf_len < need) {
        free(m->half_buf);
        m->half_buf = calloc(need, sizeof *m->half_buf);
        m->half_buf_len = m->half_buf ? need : 0;
    }
    return m->half_buf ? w : 0;
}

static void drive_axial(struct model *m, struct sim *sim, int fast, int dim, int multi,
                        int gather, const size_t *reverse, int set)
{
    struct lattice_view v = lattice_make_view(m, sim);
    v.reverse = reverse;
    v.set_forces = set;
    const size_t n = sim->p->n_owned;
    const size_t w = fast ? half_rings(m, sim, dim) : 0;
    m->half_used = w > 0;
    const size_t per = w * (size_t)dim, n_rings = per ? m->half_buf_len / per : 0;
    size_t stencil_rows = 0;
#pragma omp parallel reduction(+ : stencil_rows)
    {
        const struct lattice_view lv = v; /* thread-local copy */
        size_t lo, hi, t = 0;
        thread_range(n, &lo, &hi, &t);
        if (t < n_rings)
            stencil_rows += lattice_half_range(m, &lv, lo, hi, m->half_buf + t * per, w - 1,
                                               dim, multi, gather);
        else if (fast)
            range_linear(m, &lv, lo, hi, dim, multi, gather);
        else
            range_general(m, &lv, lo, hi, dim, gather);
    }
    m->half_stencil_rows = stencil_rows;
}

static void drive_angles(struct model *m, struct sim *sim, int set)
{
    struct particles *p = sim->p;
    double *const *x = p->x;
    double *const *f = p->f;
    const int32_t *mat = p->material;
    const size_t n = p->n; /* ghost rows too: their buffers feed owned particles */
    const size_t n_owned = p->n_owned;
#pragma omp parallel for schedule(static)
    for (size_t i = 0; i < n; i++) {
        double fi[2] = {0.0, 0.0};
        angles_row(m, mat, x, i, fi);
        if (i < n_owned && set) { /* the first write of the call (add_force) */
            f[0][i] = 0.0 + fi[0];
            f[1][i] = 0.0 + fi[1];
        } else if (i < n_owned) {
            f[0][i] += fi[0];
            f[1][i] += fi[1];
        }
    }
}

/* The forces of the bonds and angles: added to the owned forces, or with
 * @p set written over them (each owned row is written once per pass). */
static int compute_forces(struct model *m, struct sim *sim, int set, struct spall_error *err)
{
    const int dim = m->dim;
    const int gather = m->angular && dim == 2;
    const size_t *reverse = m->bl->reverse;
    size_t nr = 0;
    /* distributed: the angles centred on a ghost j are evaluated by j's
     * owner; the forces they put on i (j's buffer slot j->i) come through
     * the per-bond halo into ang_buf past the local slots, where reverse
     * points (core/parallel/bhalo.h; lattice_localize.c sizes ang_buf) */
    if (gather && sim->par && !(reverse = par_bhalo_reverse(sim, m->bl, &nr, err)))
        return err->code;
    if (gather) {
        drive_angles(m, sim, set);
        if (sim->par) {
            const size_t nh = m->bl->offset[m->bl->n];
            const double *rb = par_bhalo_exchange(sim, m->ang_buf, 2);
            memcpy(m->ang_buf + 2 * nh, rb, 2 * nr * sizeof *rb);
        }
    }
    const int fast = m->lp.law == LATTICE_LAW_LINEAR && m->n_mat == 1 && !m->kscale;
    drive_axial(m, sim, fast, dim, m->layers > 1 || m->honeycomb, gather, reverse,
                set && !gather);
    return 0;
}

int lattice_compute_forces(struct model *m, struct sim *sim, struct spall_error *err)
{
    return compute_forces(m, sim, 0, err);
}

int lattice_set_forces(struct model *m, struct sim *sim, struct spall_error *err)
{
    return compute_forces(m, sim, 1, err);
}

void lattice_set_row_loop(struct model *m, bool rows)
{
    m->half_off = rows;
}

bool lattice_used_half_loop(const struct model *m)
{
    return m->half_used;
}

size_t lattice_stencil_rows(const struct model *m)
{
    return m->half_used ? m->half_stencil_rows : 0;
}

/* ---- per-particle diagnostics (no state change) ------------------------- */

static void add_outer(int dim, double *sig, const double *u, const double *v, double w)
{
    /* symmetric part of w u (x) v in the component order of the stress field */
    if (dim == 1) {
        sig[0] += w * u[0] * v[0];
    } else if (dim == 2) {
        sig[0] += w * u[0] * v[0];
        sig[1] += w * u[1] * v[1];
        sig[2] += 0.5 * w * (u[0] * v[1] + u[1] * v[0]);
    } else {
        sig[0] += w * u[0] * v[0];
        sig[1] += w * u[1] * v[1];
        sig[2] += w * u[2] * v[2];
        sig[3] += 0.5 * w * (u[0] * v[1] + u[1] * v[0]);
        sig[4] += 0.5 * w * (u[1] * v[2] + u[2] * v[1]);
        sig[5] += 0.5 * w * (u[0] * v[2] + u[2] * v[0]);
    }
}

/*
 * Virial stress of particle i (tension positive).  For a pair the virial
 * sum_k x_k (x) f_k = (x_i - x_j) (x) f_i = -dx (x) (c dx), and the stress is
 * sigma = -(1/V) sum_k x_k (x) f_k; each particle takes half of each of its
 * bonds: sigma_i = (1 / (2 V_i)) sum_j c_ij dx_ij (x) dx_ij.  An angle centred
 * at i contributes -(1/V_i) (a (x) F_a + b (x) F_b) (relative arms; its net
 * torque vanishes, so the symmetric part is the whole).
 */
void lattice_particle_eval(const struct model *m, const struct sim *sim, size_t i,
                           double *energy, double *stress)
{
    const struct particles *p = sim->p;
    const struct bond_list *bl = m->bl;
    const int dim = m->dim;
    const int32_t *mat = p->material;
    const size_t nm = m->n_mat;
    double e = 0.0, sig[6] = {0, 0, 0, 0, 0, 0};
    for (size_t s = bl->offset[i]; s < bl->offset[i + 1]; s++) {
        const size_t j = (size_t)bl->partner[s];
        double dx[3] = {0, 0, 0}, r2 = 0.0;
        for (int d = 0; d < dim; d++) {
            dx[d] = p->x[d][j] - p->x[d][i];
            r2 += dx[d] * dx[d];
        }
        const double r_rest = bond_rest(bl, s), st = sqrt(r2) / r_rest;
        const struct lattice_bond_law *bw =
            &m->pair[((size_t)mat[i] * nm + (size_t)mat[j]) * LATTICE_MAX_TYPES + bl->type[s]];
        const int broken = bl->state[s] != 0;
        const double k = m->kscale ? bw->k * m->kscale[s] : bw->k;
        /* the energy alone (every history row) skips the stress's law call */
        double c = stress ? lattice_coef(&m->lp, bw->curve, k, st, broken) : 0.0;
        if (m->lp.law == LATTICE_LAW_SOFT && !broken) {
            /* damaged bond in tension: secant stiffness (lattice_softening.h) */
            const double ef = bw->t_lim - 1.0, kap = m->kappa[s];
            if (stress && st > 1.0)
                c *= lattice_soft_secant(bw->e0, ef, kap);
            e += 0.5 * lattice_soft_energy(bw->e0, ef, k, r_rest, st, kap);
        } else {
            e += 0.5 * lattice_energy(&m->lp, bw->curve, k, r_rest, st, broken);
        }
        if (stress)
            add_outer(dim, sig, dx, dx, 0.5 * c);
    }
    if (m->angular && dim == 2) {
        const double k_phi = m->mat_k_phi[mat[i]];
        const double k_s = m->mat_k_area[mat[i]] / 3.0;
        const size_t s0 = bl->offset[i];
        for (size_t s = s0; s < bl->offset[i + 1] && (k_phi != 0.0 || k_s != 0.0); s++) {
            if (m->ang_b[s] == LATTICE_NO_ANGLE)
                continue;
            const size_t sb = s0 + m->ang_b[s];
            if (m->ang_state[s] || bl->state[s] || bl->state[sb])
                continue;
            const size_t ja = (size_t)bl->partner[s], jb = (size_t)bl->partner[sb];
            const double a[2] = {p->x[0][ja] - p->x[0][i], p->x[1][ja] - p->x[1][i]};
            const double b[2] = {p->x[0][jb] - p->x[0][i], p->x[1][jb] - p->x[1][i]};
            double Fa[2], Fb[2];
            const double dphi = angle_forces(k_phi, m->ang_phi0[s], a, b, Fa, Fb);
            e += 0.5 * k_phi * dphi * dphi;
            if (k_s != 0.0)
                e += area_forces(k_s, area_rest(bl, s, sb, m->ang_phi0[s]), a, b, Fa, Fb);
            add_outer(dim, sig, a, Fa, -1.0);
            add_outer(dim, sig, b, Fb, -1.0);
        }
    }
    if (energy)
        *energy = e;
    if (stress) {
        const int nc = field_symtensor_ncomp(dim);
        const double v = p->volume[i];
        for (int c = 0; c < nc; c++)
            stress[c] = sig[c] / v;
    }
}
