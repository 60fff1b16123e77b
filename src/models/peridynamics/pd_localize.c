/**
 * @file pd_localize.c
 * @brief model_ops.localize of the peridynamic model (distributed runs,
 *        core/parallel/decomp.h).  The bond-based kernel (PMB, PDLM) gathers over each owned
 *        particle's family; families keep their serial order (ascending
 *        partner gid) with the partners renumbered to local indices, so
 *        each force sum is the serial one bit for bit; a bond's two halves
 *        decide breaking from the same bitwise-symmetric stretch.
 */
#include "models/peridynamics/pd_internal.h"

#include "core/bond_list.h"
#include "core/model.h"
#include "core/parallel/decomp.h"
#include "core/parallel/migrate.h"
#include "core/particles.h"
#include "core/sim.h"
#include "spall/error.h"

#include <stdlib.h>

/* formulation lps: the per-particle state of owned particles and ghosts
 * (a ghost's alpha, bcoef and, refreshed by the halo each force call,
 * theta enter t_ji of pd_lps_forces) and the per-half-bond influence; eps
 * adds per half-bond the plastic extension state and the scalar force
 * state (scratch of each force call, kept the size of the rows) and the
 * copy of the reverse half's plastic extension; per particle the dilatation
 * return-map scale and d k theta / m its owner sends to the ghosts
 * (pd_lps_kernel.c). */
static int lps_localize(struct pd_lps *L, const size_t *keep, size_t n_keep,
                        const struct bond_rows *rows, struct spall_error *err)
{
    /* afac (surface correction) is NULL without it */
    double **pp[5] = {&L->wvol, &L->theta, &L->alpha, &L->bcoef, &L->afac};
    const int npp = L->afac ? 5 : 4;
    /* ob is NULL in compact storage (pd_lps_init: m->kind has the rows) */
    double **bb[4];
    size_t bsz[4] = {sizeof(double), sizeof(double), sizeof(double), sizeof(double)};
    int nbb = 0;
    if (L->ob)
        bb[nbb++] = &L->ob;
    if (L->ep) {
        bb[nbb++] = &L->ep;
        bb[nbb++] = &L->epr;
    }
    if (L->pw) { /* position_aware: omega, sigma of both halves per half-bond */
        bsz[nbb] = 4 * sizeof(double);
        bb[nbb++] = &L->pw;
    }
    double *np[5] = {NULL, NULL, NULL, NULL, NULL}, *nb[4] = {NULL, NULL, NULL, NULL};
    int bad = 0;
    for (int k = 0; k < npp; k++)
        bad |= !(np[k] = array_gather(*pp[k], sizeof(double), keep, n_keep));
    for (int k = 0; k < nbb; k++)
        bad |= !(nb[k] = bond_rows_gather(rows, *bb[k], bsz[k]));
    double *hs = NULL; /* eps: theta, scale, d k theta / m per particle, of each force call */
    if (L->ep)
        bad |= !(hs = calloc(3 * (n_keep ? n_keep : 1), sizeof *hs));
    /* position_aware: theta and P per particle of the last force call (restart
     * state: a restored run localises after reading its checkpoint) */
    double *ptp = NULL;
    if (L->pp)
        bad |= !(ptp = array_gather(L->pp, 2 * sizeof *ptp, keep, n_keep));
    if (bad) {
        for (int k = 0; k < npp; k++)
            free(np[k]);
        for (int k = 0; k < nbb; k++)
            free(nb[k]);
        free(hs);
        free(ptp);
        return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory localising the LPS state");
    }
    free(L->hs);
    L->hs = hs;
    if (L->pp) {
        free(L->pp);
        L->pp = ptp;
    }
    free(L->rloc); /* the reverse slots of the whole body's rows: epr takes over */
    free(L->rloc8);
    L->rloc = NULL;
    L->rloc8 = NULL;
    for (int k = 0; k < npp; k++) {
        free(*pp[k]);
        *pp[k] = np[k];
    }
    for (int k = 0; k < nbb; k++) {
        free(*bb[k]);
        *bb[k] = nb[k];
    }
    return SPALL_OK;
}

/* quasi_static adr: each owned particle's model force of this and of the
 * previous step (pd_adr_update) */
static int adr_localize(struct model *m, int dim, const size_t *keep, size_t n_keep,
                        struct spall_error *err)
{
    double *nf[3] = {NULL, NULL, NULL};
    int bad = 0;
    for (int d = 0; d < dim; d++)
        bad |= !(nf[d] = array_gather(m->f_prev[d], 2 * sizeof(double), keep, n_keep));
    if (bad) {
        for (int d = 0; d < dim; d++)
            free(nf[d]);
        return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory localising the ADR forces");
    }
    for (int d = 0; d < dim; d++) {
        free(m->f_prev[d]);
        m->f_prev[d] = nf[d];
    }
    return SPALL_OK;
}

/* laminae, mixed mode: each particle's factor on the matrix critical
 * stretch and its mode mix (a ghost's factor, refreshed by the halo after
 * each update, enters the threshold of its bonds to owned particles) */
static int mixed_localize(struct model *m, const size_t *keep, size_t n_keep,
                          struct spall_error *err)
{
    double *g = array_gather(m->mm_g, sizeof *g, keep, n_keep);
    double *b = array_gather(m->mm_beta, sizeof *b, keep, n_keep);
    if (!g || !b) {
        free(g);
        free(b);
        return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory localising the mode mix");
    }
    free(m->mm_g);
    m->mm_g = g;
    free(m->mm_beta);
    m->mm_beta = b;
    return SPALL_OK;
}

/* matrix_crack: fiber_plane: per half-bond its twin's slot in the same row
 * (rows keep their order) and the stretch-broken flag (pd_plane.c) */
static int plane_localize(struct model *m, const struct bond_rows *rows, struct spall_error *err)
{
    uint8_t *t = bond_rows_gather(rows, m->twin, 1), *f = bond_rows_gather(rows, m->fresh, 1);
    if (!t || !f) {
        free(t);
        free(f);
        return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory localising the twins");
    }
    free(m->twin);
    m->twin = t;
    free(m->fresh);
    m->fresh = f;
    return SPALL_OK;
}

int pd_localize(struct model *m, struct sim *sim, const size_t *keep, size_t n_keep,
                size_t n_owned, const int64_t *new_of_old, struct spall_error *err)
{
    if (!keep) /* only asked whether it can */
        return SPALL_OK;
    /* eps: each half-bond i->j gets i's copy of e^dp_ji (pd_eps.c), read
     * through the reverse slots of the whole body's rows, which
     * bond_list_localize drops */
    struct pd_lps *L = &m->lps;
    if (L->ep && !L->epr) {
        const size_t nf = m->bl->offset[m->bl->n];
        if (!(L->epr = malloc((nf ? nf : 1) * sizeof *L->epr)))
            return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory localising bonds");
        for (size_t s = 0; s < nf; s++)
            L->epr[s] = L->ep[pd_eps_rev(m, s)];
    }
    struct bond_rows rows;
    int rc = bond_list_localize(m->bl, keep, n_keep, n_owned, new_of_old, &rows, err);
    if (rc)
        return rc;
    const size_t nh = rows.n_half;
    /* per half-bond: the coefficients, or the compact families' table rows */
    /* taken in place (bond_rows_take): the window's and the rank's copies
     * never coexist (at 165 888 particles on 2 ranks about 23 MB of window kinds
     * next to 18 MB of kept ones: 117.7 MiB per rank from 136.8) */
    double *coef = m->coef ? bond_rows_take(&rows, m->coef, sizeof *coef) : NULL;
    if (coef)
        m->coef = NULL;
    uint16_t *kind = m->kind ? bond_rows_take(&rows, m->kind, sizeof *kind) : NULL;
    if (kind)
        m->kind = NULL;
    size_t *n_init = array_gather(m->n_init, sizeof *n_init, keep, n_keep);
    size_t *n_init_f = array_gather(m->n_init_f, sizeof *n_init_f, keep, n_keep);
    double *diss = array_gather(m->diss, sizeof *diss, keep, n_keep);
    /* eps from a window of the distributed set-up: its state starts here
     * (pd_eps_init), zero as a fresh run's */
    const bool eps_fresh = m->opt.eps && !L->ep;
    if (!rc && m->opt.lps)
        rc = lps_localize(&m->lps, keep, n_keep, &rows, err);
    if (!rc && eps_fresh)
        rc = pd_eps_localized(&m->lps, nh, n_keep, err);
    if (!rc && m->f_prev[0])
        rc = adr_localize(m, sim->dim, keep, n_keep, err);
    if (!rc && m->mm_g)
        rc = mixed_localize(m, keep, n_keep, err);
    if (!rc && m->twin)
        rc = plane_localize(m, &rows, err);
    bond_rows_free(&rows);
    if (rc || (m->coef && !coef) || (m->kind && !kind) || !n_init || !n_init_f || !diss) {
        free(coef);
        free(kind);
        free(n_init);
        free(n_init_f);
        free(diss);
        return rc ? rc : spall_error_set(err, SPALL_ERR_NOMEM, "out of memory localising bonds");
    }
    free(m->coef);
    m->coef = coef;
    free(m->kind);
    m->kind = kind;
    free(m->n_init);
    m->n_init = n_init;
    free(m->n_init_f);
    m->n_init_f = n_init_f;
    free(m->diss);
    m->diss = diss;
    m->n_half = nh;
    return SPALL_OK;
}

/* model_ops.migrate_arrays: the family rows with their pair coefficients,
 * the initial bond counts (damage = 1 - intact / initial) and the
 * dissipated energy travel with a particle; with LPS also its weighted
 * volume, dilatation and coefficients, and the influence of each half-bond
 * (a ghost's alpha, bcoef and theta enter its partners' forces); with eps
 * the plastic extension and reverse half's plastic extension of each
 * half-bond and the halo's theta, scale and d k theta / m; with fiber_plane each
 * half-bond's twin slot and flag; with ADR the particle's model forces of
 * the last two steps. */
int pd_migrate_arrays(struct model *m, struct par_model_arrays *a, struct spall_error *err)
{
    (void)err; /* every option that distributes can migrate */
    a->bl = m->bl;
    a->n_half = &m->n_half;
    a->n_particle = 3;
    a->particle[0] = (void **)&m->n_init;
    a->particle_size[0] = sizeof *m->n_init;
    a->particle[1] = (void **)&m->n_init_f;
    a->particle_size[1] = sizeof *m->n_init_f;
    a->particle[2] = (void **)&m->diss;
    a->particle_size[2] = sizeof *m->diss;
    /* the pair coefficient per half-bond, or in compact storage the row of
     * the (length, coefficient, type) table (pd_compact.c; the table is
     * built from the whole body at set-up, the same on every rank) */
    a->n_bond = 0;
    if (m->coef) {
        a->bond[a->n_bond] = (void **)&m->coef;
        a->bond_size[a->n_bond++] = sizeof *m->coef;
    }
    if (m->kind) {
        a->bond[a->n_bond] = (void **)&m->kind;
        a->bond_size[a->n_bond++] = sizeof *m->kind;
    }
    if (m->opt.lps) {
        struct pd_lps *L = &m->lps;
        double **pp[5] = {&L->wvol, &L->theta, &L->alpha, &L->bcoef, &L->afac};
        for (int k = 0; k < (L->afac ? 5 : 4); k++) {
            a->particle[a->n_particle] = (void **)pp[k];
            a->particle_size[a->n_particle++] = sizeof(double);
        }
        double **bb[3] = {&L->ob, &L->ep, &L->epr};
        for (int k = 0; k < (L->ep ? 3 : 1); k++) {
            if (!*bb[k]) /* ob in compact storage: m->kind travels instead */
                continue;
            a->bond[a->n_bond] = (void **)bb[k];
            a->bond_size[a->n_bond++] = sizeof(double);
        }
        if (L->hs) {
            a->particle[a->n_particle] = (void **)&L->hs;
            a->particle_size[a->n_particle++] = 3 * sizeof *L->hs;
        }
        if (L->pw) { /* position_aware: both halves' influences; (theta, P) */
            a->bond[a->n_bond] = (void **)&L->pw;
            a->bond_size[a->n_bond++] = 4 * sizeof(double);
            a->particle[a->n_particle] = (void **)&L->pp;
            a->particle_size[a->n_particle++] = 2 * sizeof *L->pp;
        }
    }
    if (m->mm_g) { /* laminae, mixed mode */
        a->particle[a->n_particle] = (void **)&m->mm_g;
        a->particle_size[a->n_particle++] = sizeof *m->mm_g;
        a->particle[a->n_particle] = (void **)&m->mm_beta;
        a->particle_size[a->n_particle++] = sizeof *m->mm_beta;
    }
    if (m->twin) { /* matrix_crack: fiber_plane: twin slot and flag per half-bond */
        a->bond[a->n_bond] = (void **)&m->twin;
        a->bond_size[a->n_bond++] = 1;
        a->bond[a->n_bond] = (void **)&m->fresh;
        a->bond_size[a->n_bond++] = 1;
    }
    /* quasi_static adr: this and the previous step's model force, per axis */
    for (int d = 0; d < 3 && m->f_prev[d]; d++) {
        a->particle[a->n_particle] = (void **)&m->f_prev[d];
        a->particle_size[a->n_particle++] = 2 * sizeof(double);
    }
    return SPALL_OK;
}
