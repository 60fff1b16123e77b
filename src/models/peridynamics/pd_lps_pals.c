/**
 * @file pd_lps_pals.c
 * @brief Position-aware linear solid (PALS, [Mitchell2015]): deck
 *        `model.surface_correction: position_aware` with `formulation: lps`,
 *        2D (plane stress and plane strain) and 3D.
 *
 * Each particle i has two influence functions on its own half-bonds, omega_i
 * for the dilatation and sigma_i for the deviatoric energy, each the default
 * LPS influence times a polynomial in the bond whose coefficients are the
 * Lagrange multipliers of that particle: the least change, in the norm
 * sum (w - w0)^2 / w0 V over the family, that meets linear constraints on
 * the DISCRETE family as it is (free surfaces, edges, corners and the
 * lattice's own anisotropy alike) ([Mitchell2015] sec. 3).  With ob = omega
 * beta of pd_lps.c (cubic factor included), m_i = sum ob |xi|^2 V_j, u =
 * xi / delta and d the dimension:
 *   omega_ij = omega0 (1 + sum_b lw_b c_b(u)),  omega0 = d ob / m_i,
 *              c_b = u_k u_l (k <= l: 3 in 2D, 6 in 3D),
 *     constraints sum_j omega_ij xi (x) xi V_j = I   (dilatation exact);
 *   sigma_ij = sigma0 (1 + sum_a ls_a h_a(u)),  sigma0 = d (d + 2) ob / (2 m_i),
 *     constraints sum_j sigma_ij |xi|^2 psi_a(n)^2 V_j = D_a : D_a
 *     (h_a = |u|^2 psi_a(n)^2) for the deviatoric modes psi_a(n) = n . D_a . n
 *     listed below, and in 2D also their cross products.
 * The stationarity of the least change gives these forms (the gradient of
 * each constraint times w0), so each set of multipliers solves one small
 * symmetric system.  For a homogeneous strain eps, |xi| e = xi . eps . xi,
 * so theta_i = sum omega |xi| e V = tr eps for every eps, and e^d = e -
 * theta |xi| / d = |xi| n . eps^d . n, so sum sigma (e^d)^2 V is the
 * quadratic form the sigma constraints fix:
 *   2D: D_1 = (e_x e_x - e_y e_y) / sqrt 2, D_2 = (e_x e_y + e_y e_x) /
 *       sqrt 2 and every product psi_p psi_q (p <= q, targets delta_pq: 3
 *       multipliers), so sum sigma (e^d)^2 V = eps^d : eps^d for EVERY
 *       deviatoric eps.
 *   3D: the deviatoric parts of the six coordinate strains, D = dev(e_k e_k)
 *       (psi = n_k^2 - 1/3, target 2/3) and (e_k e_l + e_l e_k) / sqrt 2
 *       (k < l, psi = sqrt 2 n_k n_l, target 1), their energies only, as
 *       [Mitchell2015] and Peridigm's Pals: 6 multipliers.  Exact for every
 *       diagonal strain (the three normal modes' energies fix the whole
 *       quadratic form on the 2-dimensional space they span) and for each
 *       simple shear; the cross terms of two shears, or of a shear and a
 *       diagonal strain, are free: exact in a complete family (its cubic
 *       symmetry makes them vanish), off by up to 75 % of the deviatoric
 *       energy of a random strain at the corners of sc and fcc cubes
 *       (tests/test_pd_lps_pals.c).  Imposing them too (all 15 products of
 *       an orthonormal basis, as 2D does) admits no non-negative sigma at an
 *       edge or corner: for an octant family (x, y, z >= 0) the targets 0 on
 *       (x^2 + y^2 - 2 z^2) x y and on x^2 y z leave sigma > 0 only on bonds
 *       with x y = 0, where the target 1 on x^2 y^2 fails (measured: 6 % of
 *       a 7^3 sc cube's half-bonds negative, sc and fcc cubes blowing up
 *       within 150 steps).
 * The energy of particle i
 *   W_i = k theta_i^2 / 2 + mu sum_j sigma_ij (e^d_ij)^2 V_j
 * is then k (tr eps)^2 / 2 + mu eps^d : eps^d for those strains, k the bulk
 * modulus of the dimension (mt->kd: K in 3D, K + mu / 3 in plane strain,
 * E / (2 (1 - nu)) in plane stress, [Le2014]) and mu the shear modulus.
 * Force state t = dW / de ([Silling2007]'s Frechet derivative, dW = sum t
 * de V):
 *   t_ij = omega_ij |xi| P_i + 2 mu sigma_ij e^d_ij,
 *   P_i  = k theta_i - (2 mu / d) gamma_i,  gamma_i = sum_l sigma_il |xi| e^d_il V_l
 * (gamma_i, the term from theta inside e^d, vanishes in the default LPS
 * where sigma is proportional to omega); the force F_i = V_i sum_j (t_ij +
 * t_ji) V_j M_ij, so a bond needs both ends' (omega, sigma), which set-up
 * stores per half-bond with the reverse half's (4 doubles).  The collapsed
 * stress of a homogeneous strain is k tr eps I + 2 mu eps^d exactly in 2D.
 * In 3D a particle's stress needs the free cross terms too: the body-mean
 * stress of a cube under uniaxial strain and simple shear gives E, nu and G
 * to 1e-7 (pd-lps-surface), but a random strain's stress at the edges and
 * corners of the test bodies is off by up to 36 % of |sigma| (the default
 * LPS: 84 %).
 * The influences are set up on the intact family, again after each
 * pre-crack (a pre-cut face is a free surface like the others; the default
 * LPS weighted volume is recomputed there too), and then fixed: bonds
 * broken during the run leave them as they are.  Formulation eps is
 * refused (its return map assumes sigma proportional to omega).
 *
 * Stability needs sigma >= 0 (then W_i >= 0; omega's sign does not matter,
 * k theta^2 / 2 >= 0): set-up refuses a particle whose sigma comes out
 * negative.  Measured at delta = 3.015 dx, the smallest sigma / sigma0 over
 * the half-bonds: 2D plates, discs and rotated plates non-negative, corners
 * included, and strips of 4 rows or more; strips of 2 rows (3 on the
 * triangular lattice) negative.  3D: sc cube 7^3 and plate of 4 layers
 * 0.112, fcc cubes 0.119, sc and fcc spheres 0.56 / 0.32, fcc plates of 7
 * layers (4.2 dx) and more 0.119; plates thinner than about delta negative
 * in their middle layers (sc 2 and 3 layers: -1.9, -1.2; fcc 4 and 5
 * layers: -1.0, -0.69) and refused.
 */
#include "models/peridynamics/pd_internal.h"

#include "core/bond_list.h"
#include "core/fields.h"
#include "core/options.h"
#include "core/parallel/decomp.h"
#include "core/parallel/setup_dist.h"
#include "core/particles.h"
#include "core/sim.h"
#include "spall/error.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

int pd_surface_opts(struct model *m, const struct deck_node *params, struct spall_error *err)
{
    const char *v = NULL;
    bool on = false, pals = false;
    struct spall_error e2 = {0};
    if (params && deck_string(params, "surface_correction", false, &v, &e2) == SPALL_OK && v &&
        !strcmp(v, "position_aware"))
        pals = true;
    else if (params && deck_bool(params, "surface_correction", false, &on, &e2))
        return deck_error_key(err, params, "surface_correction", "surface_correction is "
                              "true, false or position_aware (got %s)", v ? v : "a non-scalar");
    if (pals && (!m->opt.lps || m->opt.eps))
        return deck_error_key(err, params, "surface_correction", "surface_correction "
                              "position_aware is for formulation lps (eps: its return map "
                              "assumes one influence function)");
    if (m->opt.lps) { /* lps/eps: their own surface correction (pd_lps_surface.c) */
        m->lps.surface = on;
        m->lps.pals = pals;
    } else {
        m->opt.surface_correction = on;
    }
    return SPALL_OK;
}

#define PALS_NW 6 /* dilatation multipliers (3 in 2D, 6 in 3D) */
#define PALS_NS 6 /* deviatoric multipliers (3 in 2D, 6 in 3D), >= PALS_NW */

/* phi_p(v) = v . E_p . v over the orthonormal deviatoric basis of 2D,
 * E_1 = (e_x e_x - e_y e_y) / sqrt 2, E_2 = (e_x e_y + e_y e_x) / sqrt 2
 * (unnormalised v: homogeneous of degree 2); returns the count. */
static int pals_phi(const double *v, double *phi)
{
    const double r2 = sqrt(2.0), x = v[0], y = v[1];
    phi[0] = (x * x - y * y) / r2;
    phi[1] = r2 * x * y;
    return 2;
}

/* c_b(u) = u_k u_l, k <= l; returns the count */
static int pals_cb(int dim, const double *u, double *c)
{
    int q = 0;
    for (int k = 0; k < dim; k++)
        c[q++] = u[k] * u[k];
    for (int k = 0; k < dim; k++)
        for (int l = k + 1; l < dim; l++)
            c[q++] = u[k] * u[l];
    return q;
}

/* 2D: h_a(u) = |u|^2 phi_p(n) phi_q(n) = phi_p(u) phi_q(u) / |u|^2, p <= q,
 * target delta_pq (every deviatoric strain).  3D: h_a = psi_a(u)^2 / |u|^2
 * over the six coordinate strains' deviatoric modes psi_a(n) = n . D_a . n,
 * D_a = dev(e_k e_k) (k = x, y, z: psi = n_k^2 - 1 / 3, target D : D = 2 / 3)
 * and (e_k e_l + e_l e_k) / sqrt 2 (k < l: psi = sqrt 2 n_k n_l, target 1):
 * their energies only, as Peridigm's Pals ([Mitchell2015]); *tgt the targets */
static int pals_ha(int dim, const double *u, double *h, double *tgt)
{
    double u2 = 0.0;
    for (int k = 0; k < dim; k++)
        u2 += u[k] * u[k];
    int q = 0;
    if (dim == 3) {
        const double r2 = sqrt(2.0);
        double psi[6];
        for (int k = 0; k < 3; k++)
            psi[k] = u[k] * u[k] - u2 / 3.0;
        psi[3] = r2 * u[0] * u[1];
        psi[4] = r2 * u[1] * u[2];
        psi[5] = r2 * u[0] * u[2];
        for (; q < 6; q++) {
            if (tgt)
                tgt[q] = q < 3 ? 2.0 / 3.0 : 1.0;
            h[q] = psi[q] * psi[q] / u2;
        }
        return q;
    }
    double phi[2];
    const int np = pals_phi(u, phi);
    for (int a = 0; a < np; a++)
        for (int b = a; b < np; b++) {
            if (tgt)
                tgt[q] = a == b ? 1.0 : 0.0;
            h[q++] = phi[a] * phi[b] / u2;
        }
    return q;
}

/* Solve A x = r for the symmetric positive semi-definite A (n x n,
 * row-major, destroyed) by its eigen-decomposition (cyclic Jacobi): the
 * least-norm solution over the eigenvalues above 1e-12 of the largest, so
 * that a family on which some basis function vanishes for every bond still
 * gets the multipliers its other constraints fix (that constraint is then
 * met, or the family refused).  1 when the system has no solution
 * (residual above 1e-9 of |r|: e.g. all bonds on one line). */
static int pals_solve(int n, double *A, double *r)
{
    double Q[PALS_NS * PALS_NS], A0[PALS_NS * PALS_NS], x[PALS_NS], rn = 0.0;
    memcpy(A0, A, (size_t)(n * n) * sizeof *A);
    for (int k = 0; k < n * n; k++)
        Q[k] = k % (n + 1) == 0 ? 1.0 : 0.0;
    for (int sweep = 0; sweep < 60; sweep++) {
        double off = 0.0, dia = 0.0;
        for (int p = 0; p < n; p++)
            for (int q = 0; q < n; q++)
                *(p == q ? &dia : &off) += A[p * n + q] * A[p * n + q];
        if (!(off > 1e-30 * dia))
            break;
        for (int p = 0; p < n - 1; p++)
            for (int q = p + 1; q < n; q++) {
                const double apq = A[p * n + q];
                if (apq == 0.0)
                    continue;
                const double th = 0.5 * (A[q * n + q] - A[p * n + p]) / apq;
                const double t = (th >= 0.0 ? 1.0 : -1.0) / (fabs(th) + sqrt(th * th + 1.0));
                const double c = 1.0 / sqrt(t * t + 1.0), sn = t * c;
                for (int k = 0; k < n; k++) { /* A <- A J */
                    const double akp = A[k * n + p], akq = A[k * n + q];
                    A[k * n + p] = c * akp - sn * akq;
                    A[k * n + q] = sn * akp + c * akq;
                }
                for (int k = 0; k < n; k++) { /* A <- J^T A */
                    const double apk = A[p * n + k], aqk = A[q * n + k];
                    A[p * n + k] = c * apk - sn * aqk;
                    A[q * n + k] = sn * apk + c * aqk;
                }
                for (int k = 0; k < n; k++) { /* Q <- Q J */
                    const double qkp = Q[k * n + p], qkq = Q[k * n + q];
                    Q[k * n + p] = c * qkp - sn * qkq;
                    Q[k * n + q] = sn * qkp + c * qkq;
                }
            }
    }
    double big = 0.0;
    for (int k = 0; k < n; k++) {
        big = fmax(big, A[k * n + k]);
        x[k] = 0.0;
        rn += r[k] * r[k];
    }
    for (int k = 0; k < n; k++) {
        const double lam = A[k * n + k];
        if (!(lam > 1e-12 * big))
            continue;
        double pr = 0.0;
        for (int l = 0; l < n; l++)
            pr += Q[l * n + k] * r[l];
        for (int l = 0; l < n; l++)
            x[l] += pr / lam * Q[l * n + k];
    }
    double res = 0.0;
    for (int k = 0; k < n; k++) {
        double ax = 0.0;
        for (int l = 0; l < n; l++)
            ax += A0[k * n + l] * x[l];
        res += (ax - r[k]) * (ax - r[k]);
    }
    memcpy(r, x, (size_t)n * sizeof *r);
    return !(res <= 1e-18 * rn);
}

/* Bond offset xi of half-bond s of particle i, and u = xi / delta */
static void pals_bond(const struct model *m, const struct sim *sim, size_t i, size_t s,
                      double *xi, double *u)
{
    const size_t j = (size_t)m->bl->partner[s];
    for (int a = 0; a < 3; a++) {
        xi[a] = a < sim->dim ? sim->p->x0[a][j] - sim->p->x0[a][i] : 0.0;
        u[a] = xi[a] / m->delta;
    }
}

/* The influences of row i into pw (omega_ij, sigma_ij of each half-bond s
 * at pw[4 s], pw[4 s + 1]).  1 when a system has no solution (the family's
 * bond directions do not determine them), 2 when some sigma_ij < 0 (W_i
 * indefinite: see the file comment). */
static int pals_row(const struct model *m, const struct sim *sim, size_t i, double *pw)
{
    const struct bond_list *bl = m->bl;
    const double *V = sim->p->volume, *ob = m->lps.ob;
    const int dim = sim->dim;
    const double d = (double)dim, d2 = m->delta * m->delta;
    const size_t s0 = bl->offset[i], nb = bl->offset[i + 1] - s0;
    const uint8_t *st = bl->state;
    double mi = 0.0;
    for (size_t s = s0; s < s0 + nb; s++) {
        pw[4 * s] = pw[4 * s + 1] = 0.0;
        if (!(st[s] & BOND_BROKEN))
            mi += ob[s] * bl->rest[s] * bl->rest[s] * V[bl->partner[s]];
    }
    if (!(mi > 0.0))
        return 0; /* no family: no force */
    double Aw[PALS_NW * PALS_NW] = {0}, rw[PALS_NW] = {0};
    double xi[3], u[3], c[PALS_NW], h[PALS_NS], tgt[PALS_NS];
    int nw = 0, ns = 0;
    for (size_t s = s0; s < s0 + nb; s++) {
        if (st[s] & BOND_BROKEN)
            continue;
        pals_bond(m, sim, i, s, xi, u);
        nw = pals_cb(dim, u, c);
        /* w0 delta^2 V: the constraints scaled to order one */
        const double ww = d * ob[s] / mi * d2 * V[bl->partner[s]];
        for (int a = 0; a < nw; a++) {
            rw[a] -= ww * c[a];
            for (int b = 0; b < nw; b++)
                Aw[a * nw + b] += ww * c[a] * c[b];
        }
    }
    for (int a = 0; a < dim; a++)
        rw[a] += 1.0; /* the diagonal of I (c_b lists u_k u_k first) */
    if (pals_solve(nw, Aw, rw))
        return 1;
    for (size_t s = s0; s < s0 + nb; s++) {
        if (st[s] & BOND_BROKEN)
            continue;
        pals_bond(m, sim, i, s, xi, u);
        pals_cb(dim, u, c);
        double f = 1.0;
        for (int a = 0; a < nw; a++)
            f += rw[a] * c[a];
        pw[4 * s] = d * ob[s] / mi * f;
    }
    double As[PALS_NS * PALS_NS] = {0}, rs[PALS_NS] = {0};
    for (size_t s = s0; s < s0 + nb; s++) {
        if (st[s] & BOND_BROKEN)
            continue;
        pals_bond(m, sim, i, s, xi, u);
        ns = pals_ha(dim, u, h, tgt);
        const double ws = 0.5 * d * (d + 2.0) * ob[s] / mi * d2 * V[bl->partner[s]];
        for (int a = 0; a < ns; a++) {
            rs[a] -= ws * h[a];
            for (int b = 0; b < ns; b++)
                As[a * ns + b] += ws * h[a] * h[b];
        }
    }
    for (int a = 0; a < ns; a++)
        rs[a] += tgt[a];
    if (pals_solve(ns, As, rs))
        return 1;
    int neg = 0;
    for (size_t s = s0; s < s0 + nb; s++) {
        if (st[s] & BOND_BROKEN)
            continue;
        pals_bond(m, sim, i, s, xi, u);
        pals_ha(dim, u, h, NULL);
        double f = 1.0;
        for (int a = 0; a < ns; a++)
            f += rs[a] * h[a];
        pw[4 * s + 1] = 0.5 * d * (d + 2.0) * ob[s] / mi * f;
        neg |= pw[4 * s + 1] < 0.0;
    }
    return neg ? 2 : 0;
}

int pd_lps_pals_init(struct model *m, struct sim *sim, struct spall_error *err)
{
    struct pd_lps *L = &m->lps;
    const struct particles *p = sim->p;
    const struct bond_list *bl = m->bl;
    const size_t n = p->n, nh = bl->offset[n];
    const struct par_setup *ps = par_setup_window(sim);
    int rc = SPALL_OK;
    /* again after each pre-crack (pd_precrack): the arrays are kept */
    if ((!L->pw && !(L->pw = malloc((nh ? nh : 1) * 4 * sizeof(double)))) ||
        (!L->pp && !(L->pp = calloc(2 * (n ? n : 1), sizeof(double)))))
        rc = spall_error_set(err, SPALL_ERR_NOMEM, "out of memory for the position-aware LPS");
    /* A window of the distributed set-up: the block's rows and their
     * partners' are whole (two ranges of halo), and a bond reads only its
     * two ends' rows, so no exchange; a row cut by the window's edge may be
     * singular or negative and is read by no block row. */
    int64_t bad = -1;
    int why = 0;
    for (size_t i = 0; !rc && i < n; i++) {
        const int q = pals_row(m, sim, i, L->pw);
        if (q && (!ps || par_setup_in_block(ps, i)) && bad < 0) {
            bad = p->gid[i];
            why = q;
        }
    }
    if (!rc && why == 1)
        rc = spall_error_set_key(err, SPALL_ERR_PHYSICS, "model.surface_correction",
                                 "surface_correction position_aware: the bond directions of "
                                 "particle %lld's family do not determine its influence "
                                 "functions (are they all on one line?)",
                                 (long long)bad);
    if (!rc && why == 2)
        rc = spall_error_set_key(err, SPALL_ERR_PHYSICS, "model.surface_correction",
                                 "surface_correction position_aware: the deviatoric influence of "
                                 "particle %lld comes out negative on some bonds, which makes "
                                 "its energy indefinite and the run unstable (a part of the "
                                 "body a few rows thick, or a sharp corner?)",
                                 (long long)bad);
    /* the reverse half's (omega_ji, sigma_ji) as j set them */
    for (size_t i = 0; !rc && i < n; i++)
        for (size_t s = bl->offset[i]; s < bl->offset[i + 1]; s++) {
            const size_t j = (size_t)bl->partner[s];
            size_t r = bl->offset[j];
            while (r < bl->offset[j + 1] && (size_t)bl->partner[r] != i)
                r++;
            /* j's row cut by a window's edge (no reverse half): read by no block row */
            const bool has = r < bl->offset[j + 1];
            L->pw[4 * s + 2] = has ? L->pw[4 * r] : 0.0;
            L->pw[4 * s + 3] = has ? L->pw[4 * r + 1] : 0.0;
        }
    return rc; /* no collective step: sim_prepare agrees the windows' outcome */
}

/* t_ij of half-bond s (row i) with extension e, from i's (theta, P) */
static inline double pals_t(const struct pd_material *mt, const double *pw, const double *pp,
                            double d, double xi, double e)
{
    const double om = pw[0], sg = pw[1], th = pp[0], P = pp[1];
    return 2.0 * mt->mu * sg * (e - th * xi / d) + om * xi * P;
}

/* t_ji of half-bond s (row i), from j's (omega, sigma) stored in the row and
 * j's (theta, P) */
static inline double pals_trev(const struct pd_material *mt, const double *pw, const double *pp,
                               double d, double xi, double e)
{
    const double om = pw[2], sg = pw[3], th = pp[0], P = pp[1];
    return 2.0 * mt->mu * sg * (e - th * xi / d) + om * xi * P;
}

static double pals_len(const struct particles *p, int dim, size_t i, size_t j, double *r)
{
    double l2 = 0.0;
    for (int c = 0; c < 3; c++) {
        r[c] = c < dim ? p->x[c][j] - p->x[c][i] : 0.0;
        l2 += r[c] * r[c];
    }
    return sqrt(l2);
}

/* Half-bond s of row i past s0: broken, the energy t e / 2 of its state at
 * i's (theta, P) of pp booked as dissipated (as pd_lps_break_rows) */
static void pals_break(struct model *m, const struct sim *sim, size_t i, size_t s, double xi,
                       double e)
{
    const struct particles *p = sim->p;
    const struct pd_material *mt = &m->mat[p->material[i]];
    m->bl->state[s] |= BOND_BROKEN;
    m->diss[i] += 0.5 * pals_t(mt, m->lps.pw + 4 * s, m->lps.pp + 2 * i, (double)sim->dim, xi, e) *
                  e * p->volume[i] * p->volume[m->bl->partner[s]];
}

/* theta, gamma and P of row i from the current positions (intact half-bonds);
 * immediate: the half-bonds past s0 broken first, the energy t e / 2 of their
 * state at the last (theta, P) booked as dissipated. */
static void pals_row_state(struct model *m, const struct sim *sim, size_t i, bool brk,
                           double *out)
{
    const struct particles *p = sim->p;
    struct bond_list *bl = m->bl;
    const struct pd_lps *L = &m->lps;
    const int dim = sim->dim;
    const double d = (double)dim;
    const struct pd_material *mt = &m->mat[p->material[i]];
    double th = 0.0, g1 = 0.0, q = 0.0;
    for (size_t s = bl->offset[i]; s < bl->offset[i + 1]; s++) {
        if (bl->state[s] & BOND_BROKEN)
            continue;
        const size_t j = (size_t)bl->partner[s];
        double r[3];
        const double xi = bl->rest[s], e = pals_len(p, dim, i, j, r) - xi;
        const double *pw = L->pw + 4 * s;
        if (brk && e / xi > m->s0_tab[bl->type[s]]) {
            pals_break(m, sim, i, s, xi, e);
            continue;
        }
        th += pw[0] * xi * e * p->volume[j];
        g1 += pw[1] * xi * e * p->volume[j];
        q += pw[1] * xi * xi * p->volume[j];
    }
    const double gam = g1 - th * q / d;
    out[0] = th;
    out[1] = mt->kd * th - 2.0 * mt->mu / d * gam;
}

/* break_order next_step: rows [i0, i1), the half-bonds past s0 after this
 * step's forces, with the energy of this step's state (pd_lps_break_rows) */
void pd_lps_pals_break_rows(struct model *m, const struct sim *sim, size_t i0, size_t i1)
{
    const struct particles *p = sim->p;
    const struct bond_list *bl = m->bl;
    const int dim = sim->dim;
#pragma omp parallel for schedule(dynamic, 256)
    for (size_t i = i0; i < i1; i++)
        for (size_t s = bl->offset[i]; s < bl->offset[i + 1]; s++) {
            if (bl->state[s] & BOND_BROKEN)
                continue;
            double r[3];
            const double xi = bl->rest[s];
            const double e = pals_len(p, dim, i, (size_t)bl->partner[s], r) - xi;
            if (e / xi > m->s0_tab[bl->type[s]])
                pals_break(m, sim, i, s, xi, e);
        }
}

int pd_lps_pals_forces(struct model *m, struct sim *sim, struct spall_error *err)
{
    (void)err;
    struct particles *p = sim->p;
    const struct bond_list *bl = m->bl;
    struct pd_lps *L = &m->lps;
    const size_t n = p->n, no = p->n_owned;
    const int dim = sim->dim;
    const double d = (double)dim;
    const bool late = m->opt.break_late;
    /* pass 1: every row (a ghost's is empty when distributed): breaking
     * (immediate), theta and P; rows are independent, each sum in row order */
#pragma omp parallel for schedule(dynamic, 256)
    for (size_t i = 0; i < n; i++) {
        double st[2];
        pals_row_state(m, sim, i, !late, st);
        L->pp[2 * i] = st[0];
        L->pp[2 * i + 1] = st[1];
        L->theta[i] = st[0];
    }
    if (sim->par) /* a ghost's (theta, P) from its owner, for t_ji */
        par_halo_values(sim, L->pp, 2);
    /* pass 2: F_i = V_i sum_j (t_ij + t_ji) V_j M_ij over the owned rows */
#pragma omp parallel for schedule(dynamic, 256)
    for (size_t i = 0; i < no; i++) {
        const struct pd_material *mi = &m->mat[p->material[i]];
        double f[3] = {0.0, 0.0, 0.0};
        for (size_t s = bl->offset[i]; s < bl->offset[i + 1]; s++) {
            if (bl->state[s] & BOND_BROKEN)
                continue;
            const size_t j = (size_t)bl->partner[s];
            double r[3];
            const double l = pals_len(p, dim, i, j, r), xi = bl->rest[s], e = l - xi;
            const double *pw = L->pw + 4 * s;
            const double t = pals_t(mi, pw, L->pp + 2 * i, d, xi, e) +
                             pals_trev(&m->mat[p->material[j]], pw, L->pp + 2 * j, d, xi, e);
            const double g = t * p->volume[i] * p->volume[j] / l;
            for (int c = 0; c < dim; c++)
                f[c] += g * r[c];
        }
        for (int c = 0; c < dim; c++)
            p->f[c][i] += f[c];
    }
    if (late)
        pd_lps_pals_break_rows(m, sim, 0, n);
    return SPALL_OK;
}

void pd_lps_pals_particle_eval(const struct model *m, const struct sim *sim, size_t i,
                               double *energy, double *stress)
{
    const struct particles *p = sim->p;
    const struct bond_list *bl = m->bl;
    const struct pd_lps *L = &m->lps;
    const int dim = sim->dim;
    const double d = (double)dim;
    const struct pd_material *mt = &m->mat[p->material[i]];
    double st[2];
    pals_row_state((struct model *)m, sim, i, false, st);
    double w = 0.5 * mt->kd * st[0] * st[0], sg[6] = {0, 0, 0, 0, 0, 0};
    for (size_t s = bl->offset[i]; s < bl->offset[i + 1]; s++) {
        if (bl->state[s] & BOND_BROKEN)
            continue;
        const size_t j = (size_t)bl->partner[s];
        double r[3], r0[3] = {0, 0, 0};
        const double l = pals_len(p, dim, i, j, r), xi = bl->rest[s], e = l - xi;
        for (int c = 0; c < dim; c++)
            r0[c] = p->x0[c][j] - p->x0[c][i];
        const double ed = e - st[0] * xi / d;
        w += mt->mu * L->pw[4 * s + 1] * ed * ed * p->volume[j];
        /* collapsed stress sum_j t_ij M (x) xi V_j ([Silling2007]) */
        pd_add_bond_virial(sg, dim, pals_t(mt, L->pw + 4 * s, st, d, xi, e) * p->volume[j] / l,
                           r, r0);
    }
    if (energy)
        *energy = w * p->volume[i];
    if (stress)
        for (int c = 0; c < field_symtensor_ncomp(dim); c++)
            stress[c] = sg[c];
}

/* Gershgorin bound of the linearised stiffness of row i (each |de| <= |du|):
 * dt_ij = 2 mu sigma de_ij + |xi| (omega_ij dP_i - (2 mu / d) sigma_ij
 * dtheta_i), dP_i = sum_l pc_il de_il, pc = ((k + 2 mu q_i / d^2) omega -
 * (2 mu / d) sigma) |xi| V; per particle A = sum |omega| |xi| V and Pa =
 * sum |pc|. */
double pd_lps_pals_stable_dt(const struct model *m, const struct sim *sim)
{
    const struct particles *p = sim->p;
    const struct bond_list *bl = m->bl;
    const struct pd_lps *L = &m->lps;
    const double d = (double)sim->dim;
    const size_t n = p->n;
    double *AP = malloc(2 * (n ? n : 1) * sizeof *AP);
    if (!AP)
        return 0.0; /* the engine refuses a non-positive step with a message */
    for (size_t i = 0; i < n; i++) {
        const struct pd_material *mt = &m->mat[p->material[i]];
        double q = 0.0, A = 0.0, Pa = 0.0;
        for (size_t s = bl->offset[i]; s < bl->offset[i + 1]; s++)
            if (!(bl->state[s] & BOND_BROKEN))
                q += L->pw[4 * s + 1] * bl->rest[s] * bl->rest[s] * p->volume[bl->partner[s]];
        for (size_t s = bl->offset[i]; s < bl->offset[i + 1]; s++) {
            if (bl->state[s] & BOND_BROKEN)
                continue;
            const double xv = bl->rest[s] * p->volume[bl->partner[s]];
            const double *pw = L->pw + 4 * s;
            A += fabs(pw[0]) * xv;
            Pa += fabs(((mt->kd + 2.0 * mt->mu * q / (d * d)) * pw[0] - 2.0 * mt->mu / d * pw[1]) *
                       xv);
        }
        AP[2 * i] = A;
        AP[2 * i + 1] = Pa;
    }
    /* a window of the distributed set-up: the block's particles only (as
     * pd_lps_stable_dt) */
    const struct par_setup *ps = par_setup_window(sim);
    double dt = INFINITY;
    for (size_t i = 0; i < p->n_owned; i++) {
        if (ps && !par_setup_in_block(ps, i))
            continue;
        const double mui = m->mat[p->material[i]].mu;
        double R = 0.0;
        for (size_t s = bl->offset[i]; s < bl->offset[i + 1]; s++) {
            if (bl->state[s] & BOND_BROKEN)
                continue;
            const size_t j = (size_t)bl->partner[s];
            const double muj = m->mat[p->material[j]].mu, xi = bl->rest[s];
            const double *pw = L->pw + 4 * s;
            R += p->volume[j] * 2.0 * (mui * fabs(pw[1]) + muj * fabs(pw[3]));
            R += p->volume[j] * xi *
                 (fabs(pw[0]) * AP[2 * i + 1] + 2.0 * mui / d * fabs(pw[1]) * AP[2 * i]);
            R += p->volume[j] * xi *
                 (fabs(pw[2]) * AP[2 * j + 1] + 2.0 * muj / d * fabs(pw[3]) * AP[2 * j]);
        }
        R *= 2.0 * p->volume[i];
        if (R > 0.0)
            dt = fmin(dt, 2.0 * sqrt(p->mass[i] / R));
    }
    free(AP);
    return dt;
}

bool pd_lps_pals_half(const struct model *m, size_t s, double *omega, double *sigma)
{
    if (!m->lps.pw)
        return false;
    *omega = m->lps.pw[4 * s];
    *sigma = m->lps.pw[4 * s + 1];
    return true;
}
