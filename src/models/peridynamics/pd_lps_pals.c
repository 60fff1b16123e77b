/**
 * @file pd_lps_pals.c
 * @brief Position-aware linear solid (PALS, [Mitchell2015]): deck
 *        `model.surface_correction: position_aware` with `formulation: lps`.
 *
 * Each particle i has two influence functions on its own half-bonds, omega_i
 * for the dilatation and sigma_i for the deviatoric energy, each the default
 * LPS influence times a polynomial in the bond whose coefficients are the
 * Lagrange multipliers of that particle: the least change, in the norm
 * sum (w - w0)^2 / w0 V over the family, that meets linear constraints on
 * the DISCRETE family as it is (free surfaces, edges, corners and the
 * lattice's own anisotropy alike) ([Mitchell2015] sec. 3).  With ob = omega
 * beta of pd_lps.c (cubic factor included), m_i = sum ob |xi|^2 V_j, u =
 * xi / delta and phi_p(n) = n . E_p . n over an orthonormal basis E_p of
 * the deviatoric tensors (5 in 3D, 2 in 2D):
 *   omega_ij = omega0 (1 + sum_b lw_b c_b(u)),  omega0 = d ob / m_i,
 *              c_b = u_k u_l (k <= l: 6 in 3D, 3 in 2D),
 *     constraints sum_j omega_ij xi (x) xi V_j = I   (dilatation exact);
 *   sigma_ij = sigma0 (1 + sum_a ls_a h_a(u)),  sigma0 = d (d + 2) ob / (2 m_i),
 *              h_a = |u|^2 phi_p phi_q (p <= q: 15 in 3D, 3 in 2D),
 *     constraints sum_j sigma_ij |xi|^2 phi_p phi_q V_j = delta_pq.
 * The stationarity of the least change gives these forms (the gradient of
 * each constraint times w0), so each set of multipliers solves one small
 * symmetric system.  For a homogeneous strain eps, |xi| e = xi . eps . xi,
 * so theta_i = sum omega |xi| e V = tr eps, e^d = e - theta |xi| / d = |xi|
 * phi(eps^d), and sum sigma (e^d)^2 V = eps^d : eps^d for EVERY deviatoric
 * eps (shears and mixed strains included; [Mitchell2015] and Peridigm's Pals
 * material match the energy of the d(d+1)/2 coordinate strains only, which
 * leaves the cross terms free).  The energy of particle i
 *   W_i = k theta_i^2 / 2 + mu sum_j sigma_ij (e^d_ij)^2 V_j
 * is then k (tr eps)^2 / 2 + mu eps^d : eps^d exactly; k is the bulk
 * modulus of the dimension (mt->kd: K in 3D, K + mu / 3 in plane strain,
 * E / (2 (1 - nu)) in plane stress, [Le2014]; mu the shear modulus, the 2D
 * energies being those of the in-plane strain).  Force state t = dW / de:
 *   t_ij = omega_ij |xi| P_i + 2 mu sigma_ij e^d_ij,
 *   P_i  = k theta_i - (2 mu / d) gamma_i,  gamma_i = sum_l sigma_il |xi| e^d_il V_l
 * (gamma_i, the term from theta inside e^d, vanishes in the default LPS
 * where sigma is proportional to omega); the force F_i = V_i sum_j (t_ij +
 * t_ji) V_j M_ij, so a bond needs both ends' (omega, sigma), which set-up
 * stores per half-bond with the reverse half's (4 doubles).  The collapsed
 * stress of a homogeneous strain is k tr eps I + 2 mu eps^d exactly.
 * The influences are fixed at set-up on the whole family (before pre-cracks
 * and breaking, as the default LPS weighted volume is). Formulation eps is
 * refused (its return map assumes sigma proportional to omega).
 */
#include "models/peridynamics/pd_internal.h"

#include "core/bond_list.h"
#include "core/options.h"
#include "core/parallel/comm.h"
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

#define PALS_NW 6  /* dilatation multipliers (3D) */
#define PALS_NS 15 /* deviatoric multipliers (3D) */
#define PALS_REC (1 + PALS_NW + PALS_NS)

/* phi_p(v) = v . E_p . v over the orthonormal deviatoric basis (unnormalised
 * v: homogeneous of degree 2); returns the count. */
static int pals_phi(int dim, const double *v, double *phi)
{
    const double r2 = sqrt(2.0), r6 = sqrt(6.0);
    const double x = v[0], y = v[1];
    if (dim == 2) {
        phi[0] = (x * x - y * y) / r2;
        phi[1] = r2 * x * y;
        return 2;
    }
    const double z = v[2];
    phi[0] = (x * x - y * y) / r2;
    phi[1] = (x * x + y * y - 2.0 * z * z) / r6;
    phi[2] = r2 * x * y;
    phi[3] = r2 * x * z;
    phi[4] = r2 * y * z;
    return 5;
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

/* h_a(u) = |u|^2 phi_p(n) phi_q(n) = phi_p(u) phi_q(u) / |u|^2, p <= q;
 * *diag: which of them are p == q (their constraint target is 1) */
static int pals_ha(int dim, const double *u, double *h, int *diag)
{
    double phi[5], u2 = 0.0;
    const int np = pals_phi(dim, u, phi);
    for (int k = 0; k < dim; k++)
        u2 += u[k] * u[k];
    int q = 0;
    for (int a = 0; a < np; a++)
        for (int b = a; b < np; b++) {
            if (diag)
                diag[q] = a == b;
            h[q++] = phi[a] * phi[b] / u2;
        }
    return q;
}

/* Solve A x = r (n x n, row-major, destroyed) by Gaussian elimination with
 * partial pivoting; 1 when a pivot is below tol times the largest diagonal
 * (the family's bond directions do not determine the multipliers). */
static int pals_solve(int n, double *A, double *r)
{
    double big = 0.0;
    for (int k = 0; k < n; k++)
        big = fmax(big, fabs(A[k * n + k]));
    for (int c = 0; c < n; c++) {
        int piv = c;
        for (int k = c + 1; k < n; k++)
            if (fabs(A[k * n + c]) > fabs(A[piv * n + c]))
                piv = k;
        if (!(fabs(A[piv * n + c]) > 1e-12 * big))
            return 1;
        if (piv != c) {
            for (int k = 0; k < n; k++) {
                const double t = A[c * n + k];
                A[c * n + k] = A[piv * n + k];
                A[piv * n + k] = t;
            }
            const double t = r[c];
            r[c] = r[piv];
            r[piv] = t;
        }
        for (int k = c + 1; k < n; k++) {
            const double f = A[k * n + c] / A[c * n + c];
            for (int l = c; l < n; l++)
                A[k * n + l] -= f * A[c * n + l];
            r[k] -= f * r[c];
        }
    }
    for (int c = n - 1; c >= 0; c--) {
        double s = r[c];
        for (int l = c + 1; l < n; l++)
            s -= A[c * n + l] * r[l];
        r[c] = s / A[c * n + c];
    }
    return 0;
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

/* The record of particle i: m_i, the dilatation multipliers lw, the
 * deviatoric ones ls.  1 when a system is singular. */
static int pals_record(const struct model *m, const struct sim *sim, size_t i, double *rec)
{
    const struct bond_list *bl = m->bl;
    const double *V = sim->p->volume, *ob = m->lps.ob;
    const int dim = sim->dim;
    const double d = (double)dim;
    memset(rec, 0, PALS_REC * sizeof *rec);
    double mi = 0.0;
    for (size_t s = bl->offset[i]; s < bl->offset[i + 1]; s++)
        mi += ob[s] * bl->rest[s] * bl->rest[s] * V[bl->partner[s]];
    rec[0] = mi;
    if (!(mi > 0.0))
        return 0; /* no family: no force */
    double Aw[PALS_NW * PALS_NW] = {0}, rw[PALS_NW] = {0};
    double As[PALS_NS * PALS_NS] = {0}, rs[PALS_NS] = {0};
    int diag[PALS_NS], nw = 0, ns = 0;
    const double d2 = m->delta * m->delta;
    for (size_t s = bl->offset[i]; s < bl->offset[i + 1]; s++) {
        double xi[3], u[3], c[PALS_NW], h[PALS_NS];
        pals_bond(m, sim, i, s, xi, u);
        nw = pals_cb(dim, u, c);
        ns = pals_ha(dim, u, h, diag);
        /* w0 delta^2 V: the constraints scaled to order one */
        const double ww = d * ob[s] / mi * d2 * V[bl->partner[s]];
        const double ws = 0.5 * d * (d + 2.0) * ob[s] / mi * d2 * V[bl->partner[s]];
        for (int a = 0; a < nw; a++) {
            rw[a] -= ww * c[a];
            for (int b = 0; b < nw; b++)
                Aw[a * nw + b] += ww * c[a] * c[b];
        }
        for (int a = 0; a < ns; a++) {
            rs[a] -= ws * h[a];
            for (int b = 0; b < ns; b++)
                As[a * ns + b] += ws * h[a] * h[b];
        }
    }
    for (int a = 0; a < dim; a++)
        rw[a] += 1.0; /* the diagonal of I (c_b lists u_k u_k first) */
    for (int a = 0; a < ns; a++)
        rs[a] += diag[a] ? 1.0 : 0.0;
    if (pals_solve(nw, Aw, rw) || pals_solve(ns, As, rs))
        return 1;
    memcpy(rec + 1, rw, (size_t)nw * sizeof *rw);
    memcpy(rec + 1 + PALS_NW, rs, (size_t)ns * sizeof *rs);
    return 0;
}

/* omega and sigma of half-bond s of the particle whose record is rec */
static void pals_eval(const struct model *m, const struct sim *sim, const double *rec,
                      size_t i, size_t s, double *om, double *sg)
{
    const double d = (double)sim->dim, ob = m->lps.ob[s];
    double xi[3], u[3], c[PALS_NW], h[PALS_NS];
    *om = *sg = 0.0;
    if (!(rec[0] > 0.0))
        return;
    pals_bond(m, sim, i, s, xi, u);
    const int nw = pals_cb(sim->dim, u, c), ns = pals_ha(sim->dim, u, h, NULL);
    double fw = 1.0, fs = 1.0;
    for (int a = 0; a < nw; a++)
        fw += rec[1 + a] * c[a];
    for (int a = 0; a < ns; a++)
        fs += rec[1 + PALS_NW + a] * h[a];
    *om = d * ob / rec[0] * fw;
    *sg = 0.5 * d * (d + 2.0) * ob / rec[0] * fs;
}

int pd_lps_pals_init(struct model *m, struct sim *sim, struct spall_error *err)
{
    struct pd_lps *L = &m->lps;
    const struct particles *p = sim->p;
    const struct bond_list *bl = m->bl;
    const size_t n = p->n, nh = bl->offset[n];
    const struct par_setup *ps = par_setup_window(sim);
    double *rec = malloc((n ? n : 1) * PALS_REC * sizeof *rec);
    int rc = SPALL_OK;
    if (!rec || !(L->pw = malloc((nh ? nh : 1) * 4 * sizeof(double))) ||
        !(L->pp = calloc(2 * (n ? n : 1), sizeof(double))))
        rc = spall_error_set(err, SPALL_ERR_NOMEM, "out of memory for the position-aware LPS");
    /* A window of the distributed set-up: the block's rows and their
     * partners' are whole (two ranges of halo), and a bond reads only its
     * two ends' records, so no exchange; a row cut by the window's edge may
     * be singular and is read by no block row. */
    int64_t bad = -1;
    for (size_t i = 0; !rc && i < n; i++)
        if (pals_record(m, sim, i, rec + i * PALS_REC)) {
            memset(rec + i * PALS_REC, 0, PALS_REC * sizeof *rec);
            if ((!ps || par_setup_in_block(ps, i)) && bad < 0)
                bad = p->gid[i];
        }
    if (!rc && bad >= 0)
        rc = spall_error_set_key(err, SPALL_ERR_PHYSICS, "model.surface_correction",
                                 "surface_correction position_aware: the bond directions of "
                                 "particle %lld's family do not determine its influence "
                                 "functions (too few bonds: raise horizon_factor)",
                                 (long long)bad);
    /* own half (omega_ij, sigma_ij), then the reverse half's as j set it */
    for (size_t i = 0; !rc && i < n; i++)
        for (size_t s = bl->offset[i]; s < bl->offset[i + 1]; s++)
            pals_eval(m, sim, rec + i * PALS_REC, i, s, &L->pw[4 * s], &L->pw[4 * s + 1]);
    for (size_t i = 0; !rc && i < n; i++)
        for (size_t s = bl->offset[i]; s < bl->offset[i + 1]; s++) {
            const size_t j = (size_t)bl->partner[s];
            size_t r = bl->offset[j];
            while (r < bl->offset[j + 1] && (size_t)bl->partner[r] != i)
                r++;
            if (r < bl->offset[j + 1]) {
                L->pw[4 * s + 2] = L->pw[4 * r];
                L->pw[4 * s + 3] = L->pw[4 * r + 1];
            } else { /* j's row cut by a window's edge: read by no block row */
                pals_eval(m, sim, rec + j * PALS_REC, i, s, &L->pw[4 * s + 2],
                          &L->pw[4 * s + 3]);
            }
        }
    free(rec);
    if (ps) /* every window agrees before the set-up's next collective step */
        rc = par_agree(rc, err);
    return rc;
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
            bl->state[s] |= BOND_BROKEN;
            m->diss[i] += 0.5 * pals_t(mt, pw, L->pp + 2 * i, d, xi, e) * e * p->volume[i] *
                          p->volume[j];
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
    struct bond_list *bl = m->bl;
    const struct pd_lps *L = &m->lps;
    const int dim = sim->dim;
#pragma omp parallel for schedule(dynamic, 256)
    for (size_t i = i0; i < i1; i++) {
        const struct pd_material *mt = &m->mat[p->material[i]];
        for (size_t s = bl->offset[i]; s < bl->offset[i + 1]; s++) {
            if (bl->state[s] & BOND_BROKEN)
                continue;
            const size_t j = (size_t)bl->partner[s];
            double r[3];
            const double xi = bl->rest[s], e = pals_len(p, dim, i, j, r) - xi;
            if (!(e / xi > m->s0_tab[bl->type[s]]))
                continue;
            bl->state[s] |= BOND_BROKEN;
            m->diss[i] += 0.5 * pals_t(mt, L->pw + 4 * s, L->pp + 2 * i, (double)dim, xi, e) *
                          e * p->volume[i] * p->volume[j];
        }
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
        for (int c = 0; c < (dim == 3 ? 6 : 3); c++)
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
