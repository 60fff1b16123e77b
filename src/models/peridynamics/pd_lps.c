/**
 * @file pd_lps.c
 * @brief Linear peridynamic solid (LPS, ordinary state-based PD,
 *        [Silling2007]) in 2D and 3D, deck `model.formulation: lps`.
 *
 * With omega the influence function, beta the partial volume (the linear
 * rule of pd_forces.c, or the cut cell fraction of partial_volume_rule
 * cell, pd_cellvol.c) and d the dimension (in 2D the in-plane dilatation,
 * [Le2014] uses the 3D one; both give the same energy for a homogeneous
 * deformation):
 *   m_i     = sum_j omega beta |xi|^2 V_j                 (weighted volume)
 *   theta_i = (d / m_i) sum_j omega beta |xi| e_ij V_j,   e = |Y| - |xi|
 *   W_i     = k theta^2 / 2 + alpha / 2 sum_j omega beta (e^d)^2 V_j,
 *             e^d = e - theta |xi| / d,  alpha = d (d + 2) mu / m_i
 *   t_ij    = dW_i / de_ij / V_j = omega (d k theta |xi| / m_i + alpha e^d)
 *   F_i     = V_i sum_j (t_ij + t_ji) beta V_j M_ij  (M: unit deformed bond)
 * k is the bulk modulus of the dimension: K in 3D, K + mu/3 in plane strain,
 * E / (2 (1 - nu)) in plane stress.  The force state follows from W (the
 * deviatoric sum of omega |xi| e^d vanishes by the definition of theta), so
 * any nu is reproduced; m_i is each particle's own (pre-cracks excluded),
 * which normalises a surface particle's dilatation (surface_correction:
 * pd_lps_surface.c).  A bond breaks, irreversibly, when its stretch passes
 * s0 (pd_model.c), decided from both ends from the same length so that
 * threads agree: before the forces (break_order immediate) or after them
 * (next_step, pd_lps_break_late: the order of LAMMPS pair peri/lps, with
 * which influence inverse and partial_volume_rule lammps give the same
 * forces, bench/pd_lps_vs_lammps.sh).
 */
#include "models/peridynamics/pd_internal.h"
#include "models/peridynamics/pd_cellvol.h"

#include "core/bond_list.h"
#include "core/distinct.h"
#include "core/fields.h"
#include "core/lattice_gen.h"
#include "core/parallel/comm.h"
#include "core/parallel/decomp.h"
#include "core/parallel/setup_dist.h"
#include "core/particles.h"
#include "core/sim.h"
#include "spall/error.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* Partial volume, the linear rule of pd_forces.c ([MadenciOterkus2014] sec. 2.4). */
static double lps_beta(const struct model *m, double xi)
{
    if (!m->opt.partial_volume || xi <= m->delta - 0.5 * m->dx)
        return 1.0;
    if (xi >= m->delta + 0.5 * m->dx)
        return 0.0;
    return (m->delta + 0.5 * m->dx - xi) / m->dx;
}

/* omega beta of a bond of length xi and reference offset e without the
 * cubic factor; beta of the cell rule from the cut cell (pd_cellvol.c) */
static int lps_ob0(const struct model *m, double xi, const double *e, double *ob,
                   struct spall_error *err)
{
    double om = m->lps.influence == PD_OMEGA_INVERSE ? m->delta / xi : 1.0, beta;
    if (m->lps.cell) {
        int rc = pd_cellvol_beta(m->lps.cell, e, m->dx, &beta, err);
        if (rc)
            return rc;
    } else {
        beta = lps_beta(m, xi);
    }
    *ob = om * beta;
    return SPALL_OK;
}

void pd_lps_free(struct pd_lps *L)
{
    free(L->wvol);
    free(L->theta);
    free(L->alpha);
    free(L->bcoef);
    free(L->ob);
    free(L->afac);
    free(L->ep);
    free(L->rloc);
    free(L->rloc8);
    free(L->epr);
    free(L->hs);
    free(L->pw);
    free(L->pp);
}

/* Cubic harmonic of the unit bond n in the lattice frame (2D: rotated by the
 * lattice angle): P = sum_a n_a^4 - 3 / (d + 2), whose isotropic mean is 0,
 * and Q = n_x^4 - 3 n_x^2 n_y^2, whose family sum A - 3B vanishes exactly
 * when the fourth moment is isotropic. */
static void cubic_harmonics(const struct sim *sim, const double *e, double xi, double *P,
                            double *Q)
{
    double n[3] = {e[0] / xi, e[1] / xi, sim->dim == 3 ? e[2] / xi : 0.0};
    if (sim->dim == 2) {
        const double c = cos(sim->lattice.angle), s = sin(sim->lattice.angle);
        const double nx = c * n[0] + s * n[1], ny = -s * n[0] + c * n[1];
        n[0] = nx;
        n[1] = ny;
    }
    double s4 = 0.0;
    for (int a = 0; a < sim->dim; a++)
        s4 += n[a] * n[a] * n[a] * n[a];
    *P = s4 - 3.0 / (sim->dim + 2.0);
    *Q = n[0] * n[0] * n[0] * n[0] - 3.0 * n[0] * n[0] * n[1] * n[1];
}

/* influence_correction cubic: omega -> omega (1 + gamma P(n)).  On a cubic
 * lattice (square, sc, fcc) the family's fourth moment M = sum omega beta
 * |xi|^2 n n n n V has cubic symmetry, so the deviatoric energy alpha/2 eps^d
 * : M : eps^d gives two shear moduli (docs/decks.md); gamma is chosen so that
 * M of the fullest family is isotropic (M_1111 = 3 M_1122), the second
 * moment staying isotropic by the same symmetry.  One gamma for the run,
 * from its fullest family, in the frame of the deck's lattice. */
static int cubic_gamma(struct model *m, const struct sim *sim, struct spall_error *err)
{
    struct pd_lps *L = &m->lps;
    const struct particles *p = sim->p;
    const struct bond_list *bl = m->bl;
    const enum lattice_kind k = sim->lattice.kind;
    if (k != LATTICE_SQUARE && k != LATTICE_SC && k != LATTICE_FCC)
        return spall_error_set_key(err, SPALL_ERR_INPUT, "model.influence_correction",
                                   "influence_correction cubic is for the square, sc and fcc "
                                   "lattices (got %s)", lattice_kind_name(k));
    /* the first particle (lowest index) with the most bonds; in a window of
     * the distributed set-up among the block's particles only (a halo
     * family may be cut short), then over the ranks below */
    const struct par_setup *ps = par_setup_window(sim);
    size_t best = SIZE_MAX, most = 0;
    for (size_t i = 0; i < p->n; i++)
        if ((!ps || par_setup_in_block(ps, i)) &&
            (best == SIZE_MAX || bl->offset[i + 1] - bl->offset[i] > most)) {
            best = i;
            most = bl->offset[i + 1] - bl->offset[i];
        }
    double s0 = 0.0, s1 = 0.0;
    int rc = SPALL_OK;
    for (size_t s = best != SIZE_MAX ? bl->offset[best] : 0;
         !rc && best != SIZE_MAX && s < bl->offset[best + 1]; s++) {
        size_t j = (size_t)bl->partner[s];
        const double xi = bond_rest(bl, s);
        double e[3] = {0, 0, 0}, P, Q;
        for (int c = 0; c < sim->dim; c++)
            e[c] = p->x0[c][j] - p->x0[c][best];
        cubic_harmonics(sim, e, xi, &P, &Q);
        double ob = 0.0;
        rc = lps_ob0(m, xi, e, &ob, err);
        const double w = ob * xi * xi * p->volume[j];
        s0 += w * Q;
        s1 += w * P * Q;
    }
    if (ps) /* before the collective choice below: every window or none */
        rc = par_agree(rc, err);
    if (rc)
        return rc;
    L->gamma = s1 != 0.0 ? -s0 / s1 : 0.0;
    if (ps) { /* the serial choice: the most bonds, then the lowest global id */
        const bool have = best != SIZE_MAX;
        const int64_t top = -par_min_i64(have ? -(int64_t)most : 1);
        const bool cand = have && (int64_t)most == top;
        const int64_t g = par_min_i64(cand ? p->gid[best] : INT64_MAX);
        L->gamma = par_min_double(cand && p->gid[best] == g ? L->gamma : INFINITY);
    }
    return SPALL_OK;
}

/* omega beta of half-bond s of particle i: lps_ob0, with the cubic
 * correction its factor 1 + gamma P(n) */
static int lps_ob(const struct model *m, const struct sim *sim, size_t i, size_t s, double *ob,
                  struct spall_error *err)
{
    const struct bond_list *bl = m->bl;
    const double xi = bond_rest(bl, s);
    const size_t j = (size_t)bl->partner[s];
    double e[3] = {0, 0, 0}, P, Q;
    for (int c = 0; c < sim->dim; c++)
        e[c] = sim->p->x0[c][j] - sim->p->x0[c][i];
    int rc = lps_ob0(m, xi, e, ob, err);
    if (rc || !m->lps.cubic)
        return rc;
    cubic_harmonics(sim, e, xi, &P, &Q);
    const double f = 1.0 + m->lps.gamma * P;
    if (!(f > 0.0))
        return spall_error_set_key(err, SPALL_ERR_PHYSICS, "model.influence_correction",
                                   "influence_correction cubic: gamma = %g makes the influence "
                                   "of some bonds non-positive", m->lps.gamma);
    *ob *= f;
    return SPALL_OK;
}

/* Bond type of half-bond s of particle i (isotropic materials: no fiber
 * bit), as pd_init sets it for the arrays. */
static uint8_t lps_type(const struct model *m, const struct sim *sim, size_t i, size_t s)
{
    const struct particles *p = sim->p;
    const size_t j = (size_t)m->bl->partner[s];
    return (uint8_t)(((size_t)p->material[i] * m->n_mat + (size_t)p->material[j]) * 2);
}

/* Compact set-up (pd_init built the list with bond_list_build_compact and
 * no types): each half-bond's (length, omega beta, type) indexed at once
 * in slot order into the kind table, never holding the 8-byte lengths or
 * omega beta (set-up peak memory: partner, state, rest index, row).  The
 * keys are the doubles the arrays would hold, so the run is the same bit
 * for bit.  More than PD_KIND_MAX distinct triples: the arrays (lengths,
 * types), which the caller then fills as without the table. */
static int lps_build_kinds(struct model *m, struct sim *sim, struct spall_error *err)
{
    struct bond_list *bl = m->bl;
    const size_t n = bl->n, nh = bl->offset[n];
    struct distinct16 *d = NULL;
    int rc = distinct16_create(&d, PD_KIND_KEY, 65535u, err);
    /* A compact list's rest indices (16 bits, one per half-bond) become the
     * kinds in place, each read before its slot is overwritten: the
     * window's set-up peak (partners, states, rest indices and kinds at
     * once) loses one 2-byte array.  back[] maps a kind to the rest index
     * it replaced, so an overflow can give the list its indices back. */
    uint16_t *back = NULL, *kind = NULL;
    if (!rc && bl->rest_idx) {
        kind = bl->rest_idx;
        if (!(back = malloc(65535u * sizeof *back)))
            rc = spall_error_set(err, SPALL_ERR_NOMEM, "out of memory for peridynamic bonds");
    } else if (!rc && !(kind = malloc((nh ? nh : 1) * sizeof *kind)))
        rc = spall_error_set(err, SPALL_ERR_NOMEM, "out of memory for peridynamic bonds");
    bool fits = nh > 0; /* no bonds: the (empty) arrays, no table */
    size_t done = 0; /* slots holding a kind */
    for (size_t i = 0; !rc && i < n && fits; i++)
        for (size_t s = bl->offset[i]; !rc && s < bl->offset[i + 1] && fits; s++) {
            const double rest = bond_rest(bl, s);
            double ob = 0.0;
            rc = lps_ob(m, sim, i, s, &ob, err);
            unsigned char key[PD_KIND_KEY];
            memcpy(key, &rest, sizeof rest);
            memcpy(key + sizeof rest, &ob, sizeof ob);
            key[2 * sizeof(double)] = lps_type(m, sim, i, s);
            const int32_t row = distinct16_add(d, key);
            fits = row >= 0;
            if (!fits)
                break;
            if (back)
                back[row] = bl->rest_idx[s];
            kind[s] = (uint16_t)row;
            done = s + 1;
        }
    size_t nk = 0;
    unsigned char *tab = (!rc && fits) ? distinct16_take_table(d, &nk) : NULL;
    distinct16_destroy(&d);
    if (!rc && tab)
        rc = pd_kinds_from_table(m, tab, nk, err); /* frees tab */
    if (!rc && tab) {
        if (kind == bl->rest_idx)
            bl->rest_idx = NULL; /* the kinds now: m->kind owns them */
        m->kind = kind;
    } else if (back) { /* the list's rest indices back, as they were */
        for (size_t s = 0; s < done; s++)
            kind[s] = back[kind[s]];
    } else
        free(kind);
    free(back);
    if (rc)
        return rc;
    if (!m->kind) {
        /* the arrays, as pd_init builds them without the table */
        if ((rc = bond_list_expand_rest(bl, err)))
            return rc;
        if (!(bl->type = malloc((nh ? nh : 1) * sizeof *bl->type)))
            return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory for peridynamic bonds");
        for (size_t i = 0; i < n; i++)
            for (size_t s = bl->offset[i]; s < bl->offset[i + 1]; s++)
                bl->type[s] = lps_type(m, sim, i, s);
        return SPALL_OK;
    }
    /* the table holds the lengths (k_rest): the list keeps none */
    bond_list_drop_rest(bl);
    return SPALL_OK;
}

int pd_lps_init(struct model *m, struct sim *sim, struct spall_error *err)
{
    struct pd_lps *L = &m->lps;
    const size_t n = sim->p->n, nh = m->bl->offset[n];
    int rc = SPALL_OK;
    if (!(L->wvol = calloc(n ? n : 1, sizeof(double))) ||
        !(L->theta = calloc(n ? n : 1, sizeof(double))) ||
        !(L->alpha = calloc(n ? n : 1, sizeof(double))) ||
        !(L->bcoef = calloc(n ? n : 1, sizeof(double))))
        rc = spall_error_set(err, SPALL_ERR_NOMEM, "out of memory for the LPS state");
    /* partial_volume_rule cell: the cut cells' fractions, met while the
     * influence is set up below (the cache lives for this call only) */
    struct pd_cellvol cv = {0};
    if (!rc && m->opt.cell_volumes &&
        !(rc = pd_cellvol_init(&cv, sim->lattice.kind, sim->dim, m->delta / m->dx,
                               sim->lattice.angle, err)))
        L->cell = &cv;
    if (L->cubic && par_setup_window(sim)) /* its choice is collective there */
        rc = par_agree(rc, err);
    if (!rc && L->cubic)
        rc = cubic_gamma(m, sim, err);
    /* compact families (pd_compact_predicted): the table, built directly */
    if (!rc && !m->bl->type)
        rc = lps_build_kinds(m, sim, err);
    if (!rc && !m->kind) {
        if (!(L->ob = calloc(nh ? nh : 1, sizeof(double))))
            rc = spall_error_set(err, SPALL_ERR_NOMEM, "out of memory for the LPS state");
        for (size_t i = 0; !rc && i < n; i++)
            for (size_t s = m->bl->offset[i]; !rc && s < m->bl->offset[i + 1]; s++)
                rc = lps_ob(m, sim, i, s, &L->ob[s], err);
    }
    L->cell = NULL;
    pd_cellvol_free(&cv);
    if (rc)
        return rc;
    if (L->surface) { /* after the cubic factors: it corrects the family as weighted */
        if ((rc = pd_lps_surface_init(m, sim, err)))
            return rc;
    }
    if (L->pals && (rc = pd_lps_pals_init(m, sim, err))) /* position_aware: the same */
        return rc;
    pd_lps_weights(m, sim);
    return SPALL_OK;
}

void pd_lps_weights(struct model *m, const struct sim *sim)
{
    const struct pd_lps_bonds B = pd_lps_bonds(m);
    struct pd_lps *L = &m->lps;
    const struct particles *p = sim->p;
    const struct bond_list *bl = m->bl;
    const double d = (double)sim->dim;
    for (size_t i = 0; i < p->n; i++) {
        double w = 0.0;
        for (size_t s = bl->offset[i]; s < bl->offset[i + 1]; s++)
            if (!(bl->state[s] & BOND_BROKEN)) {
                const size_t row = pd_lps_row(&B, s);
                w += B.ob[row] * B.rest[row] * B.rest[row] * p->volume[bl->partner[s]];
            }
        const struct pd_material *mt = &m->mat[p->material[i]];
        L->wvol[i] = w;
        L->alpha[i] = w > 0.0 ? d * (d + 2.0) * mt->mu / w * (L->afac ? L->afac[i] : 1.0) : 0.0;
        L->bcoef[i] = w > 0.0 ? d * mt->kd / w - L->alpha[i] / d : 0.0;
    }
}

/* Dilatation of particle i from the current positions (intact bonds). */
static double lps_theta(const struct model *m, const struct sim *sim, size_t i)
{
    const struct pd_lps_bonds B = pd_lps_bonds(m);
    const struct particles *p = sim->p;
    const struct bond_list *bl = m->bl;
    const int dim = sim->dim;
    if (!(m->lps.wvol[i] > 0.0))
        return 0.0;
    double sum = 0.0;
    for (size_t s = bl->offset[i]; s < bl->offset[i + 1]; s++) {
        if (bl->state[s] & BOND_BROKEN)
            continue;
        size_t j = (size_t)bl->partner[s];
        const size_t row = pd_lps_row(&B, s);
        double l2 = 0.0;
        for (int c = 0; c < dim; c++) {
            double r = p->x[c][j] - p->x[c][i];
            l2 += r * r;
        }
        double xi = B.rest[row];
        sum += B.ob[row] * xi * (sqrt(l2) - xi) * p->volume[j];
    }
    return (double)dim * sum / m->lps.wvol[i];
}

/* break_order next_step (PDLAMMPS order, pair peri/lps and peri/eps): a bond
 * past s0 has pulled with its full force state in this step and is dropped
 * after it, each half-bond by its own particle from the same length (so the
 * two ends agree).  Its stored elastic energy goes to the dissipated energy
 * as in the immediate order, from this step's state (e^dp: eps). */
void pd_lps_break_rows(struct model *m, const struct sim *sim, size_t i0, size_t i1)
{
    const struct pd_lps_bonds B = pd_lps_bonds(m);
    const struct particles *p = sim->p;
    struct bond_list *bl = m->bl;
    const struct pd_lps *L = &m->lps;
    const int dim = p->dim;
    if (L->pw) {
        pd_lps_pals_break_rows(m, sim, i0, i1);
        return;
    }
#pragma omp parallel for schedule(dynamic, 256)
    for (size_t i = i0; i < i1; i++)
        for (size_t s = bl->offset[i]; s < bl->offset[i + 1]; s++) {
            if (bl->state[s] & BOND_BROKEN)
                continue;
            size_t j = (size_t)bl->partner[s];
            const size_t row = pd_lps_row(&B, s);
            double l2 = 0.0;
            for (int c = 0; c < dim; c++) {
                double r = p->x[c][j] - p->x[c][i];
                l2 += r * r;
            }
            const double xi = B.rest[row], e = sqrt(l2) - xi;
            if (!(e / xi > m->s0_tab[B.type[row]]))
                continue;
            bl->state[s] |= BOND_BROKEN;
            const double ee = e - (L->ep ? L->ep[s] : 0.0);
            const double t = L->alpha[i] * ee + L->bcoef[i] * xi * L->theta[i];
            m->diss[i] += 0.5 * B.ob[row] * t * ee * p->volume[i] * p->volume[j];
        }
}

void pd_lps_break_late(struct model *m, const struct sim *sim)
{
    pd_lps_break_rows(m, sim, 0, sim->p->n);
}

/* Row sum of the linearised stiffness of particle i (each |n . u| <= |u|):
 * direct terms (alpha_i + alpha_j), i's own dilatation and its neighbours'. */
double pd_lps_stable_dt(const struct model *m, const struct sim *sim)
{
    const struct pd_lps_bonds B = pd_lps_bonds(m);
    const struct particles *p = sim->p;
    const struct bond_list *bl = m->bl;
    const struct pd_lps *L = &m->lps;
    const double d = (double)sim->dim;
    const size_t n = p->n;
    if (L->pw)
        return pd_lps_pals_stable_dt(m, sim);
    double *S = malloc((n ? n : 1) * sizeof *S);
    if (!S)
        return 0.0; /* the engine refuses a non-positive step with a message */
    for (size_t i = 0; i < n; i++) {
        S[i] = 0.0;
        for (size_t s = bl->offset[i]; s < bl->offset[i + 1]; s++)
            if (!(bl->state[s] & BOND_BROKEN)) {
                const size_t row = pd_lps_row(&B, s);
                S[i] += B.ob[row] * B.rest[row] * p->volume[bl->partner[s]];
            }
    }
    /* In a window of the distributed set-up only the block's particles:
     * the bound reads the partners' weighted volumes and S, whose families
     * lie whole inside the two-range halo, where a halo particle's family
     * cut by the window's edge has a small m_j and so a large bound (the
     * minimum over the windows came out below the serial step). */
    const struct par_setup *ps = par_setup_window(sim);
    double dt = INFINITY;
    for (size_t i = 0; i < p->n_owned; i++) {
        if (ps && !par_setup_in_block(ps, i))
            continue;
        double R = L->wvol[i] > 0.0 ? fabs(L->bcoef[i]) * d * S[i] * S[i] / L->wvol[i] : 0.0;
        for (size_t s = bl->offset[i]; s < bl->offset[i + 1]; s++) {
            if (bl->state[s] & BOND_BROKEN)
                continue;
            size_t j = (size_t)bl->partner[s];
            const size_t row = pd_lps_row(&B, s);
            R += p->volume[j] * B.ob[row] * (L->alpha[i] + L->alpha[j]);
            if (L->wvol[j] > 0.0)
                R += p->volume[j] * B.ob[row] * B.rest[row] * fabs(L->bcoef[j]) * d * S[j] /
                     L->wvol[j];
        }
        R *= 2.0 * p->volume[i];
        if (R > 0.0)
            dt = fmin(dt, 2.0 * sqrt(p->mass[i] / R));
    }
    free(S);
    return dt;
}

void pd_lps_particle_eval(const struct model *m, const struct sim *sim, size_t i,
                          double *energy, double *stress)
{
    const struct pd_lps_bonds B = pd_lps_bonds(m);
    const struct particles *p = sim->p;
    const struct bond_list *bl = m->bl;
    const struct pd_lps *L = &m->lps;
    const int dim = sim->dim;
    if (L->pw) {
        pd_lps_pals_particle_eval(m, sim, i, energy, stress);
        return;
    }
    const double th = lps_theta(m, sim, i);
    const struct pd_material *mt = &m->mat[p->material[i]];
    double w = 0.5 * mt->kd * th * th, sg[6] = {0, 0, 0, 0, 0, 0};
    for (size_t s = bl->offset[i]; s < bl->offset[i + 1]; s++) {
        if (bl->state[s] & BOND_BROKEN)
            continue;
        size_t j = (size_t)bl->partner[s];
        double r[3] = {0, 0, 0}, r0[3] = {0, 0, 0}, l = 0.0;
        for (int c = 0; c < dim; c++) {
            r[c] = p->x[c][j] - p->x[c][i];
            r0[c] = p->x0[c][j] - p->x0[c][i];
            l += r[c] * r[c];
        }
        l = sqrt(l);
        /* formulation eps: only the elastic part e^d - e^dp stores energy (pd_eps.c) */
        const double ep = L->ep ? L->ep[s] : 0.0;
        const size_t row = pd_lps_row(&B, s);
        const double xi = B.rest[row], e = l - xi, ed = e - th * xi / (double)dim - ep;
        w += 0.5 * L->alpha[i] * B.ob[row] * ed * ed * p->volume[j];
        /* collapsed stress sum_j t_ij M (x) xi V_j ([Silling2007], homogeneous case) */
        const double g = B.ob[row] * (L->alpha[i] * (e - ep) + L->bcoef[i] * xi * th) *
                         p->volume[j] / l;
        pd_add_bond_virial(sg, dim, g, r, r0);
    }
    if (energy)
        *energy = w * p->volume[i];
    if (stress)
        for (int c = 0; c < field_symtensor_ncomp(dim); c++)
            stress[c] = sg[c];
}
