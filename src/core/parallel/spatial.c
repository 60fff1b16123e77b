/**
 * @file spatial.c
 * @brief Spatial ghosts in the step (spatial.h): the rebuild test, the
 *        re-layout of the local arrays around a new ghost set, and the
 *        halo lists that refresh it.
 */
#include "core/parallel/spatial.h"

#include "core/bond_list.h"
#include "core/model.h"
#include "core/parallel/bhalo.h"
#include "core/parallel/comm.h"
#include "core/parallel/decomp.h"
#include "core/parallel/decomp_internal.h"
#include "core/parallel/sghost.h"
#include "core/particles.h"
#include "core/sim.h"
#include "core/step_passes.h"
#include "spall/error.h"

#include <limits.h>
#include <stdlib.h>
#include <string.h>

#ifdef SPALL_HAVE_MPI
#include <mpi.h>
#endif

void par_spatial_free(struct par_decomp *d)
{
    par_sghost_destroy(&d->sg);
}

long par_spatial_rebuilds(const struct sim *s)
{
    return s->par ? s->par->sg_rebuilds : 0;
}

#ifdef SPALL_HAVE_MPI

/* The model's declaration and every per-particle array a ghost carries. */
static int ghost_arrays(struct sim *s, struct par_spatial_model *sm, struct par_slots *sl,
                        size_t *rec, struct spall_error *err)
{
    memset(sm, 0, sizeof *sm);
    int rc = s->ops->spatial_ghosts(s->model, sm);
    if (rc)
        return spall_error_set(err, SPALL_ERR_INTERNAL,
                               "spatial ghosts: model '%s' gave no range", s->ops->name);
    int bad = par_particle_slots(s, sl);
    for (int k = 0; k < sm->n_particle && !bad; k++)
        bad = par_slot_add(sl, sm->particle[k], sm->particle_size[k]);
    if (bad)
        return spall_error_set(err, SPALL_ERR_INTERNAL, "spatial ghosts: too many arrays");
    *rec = 0;
    for (size_t k = 0; k < sl->n; k++)
        *rec += sl->esize[k];
    return SPALL_OK;
}

/* The halo lists of par_halo_x (positions and velocities, counts in
 * doubles) from the ghost build's lists. */
static int halo_from_lists(struct par_decomp *d, const struct par_sghost_lists *L, size_t n_owned,
                           int dim)
{
    const int size = par_size(), w = 2 * dim;
    size_t *si = malloc((L->n_send ? L->n_send : 1) * sizeof *si);
    size_t *ri = malloc((L->n_recv ? L->n_recv : 1) * sizeof *ri);
    double *sb = malloc((L->n_send ? L->n_send : 1) * (size_t)w * sizeof *sb);
    double *rb = malloc((L->n_recv ? L->n_recv : 1) * (size_t)w * sizeof *rb);
    if (!si || !ri || !sb || !rb) {
        free(si);
        free(ri);
        free(sb);
        free(rb);
        return -1;
    }
    for (size_t k = 0; k < L->n_send; k++)
        si[k] = L->send_idx[k];
    for (size_t k = 0; k < L->n_recv; k++)
        ri[k] = n_owned + L->recv_idx[k];
    for (int r = 0; r < size; r++) {
        d->send_counts[r] = L->scount[r] * w;
        d->send_displs[r] = L->sdispl[r] * w;
        d->recv_counts[r] = L->rcount[r] * w;
        d->recv_displs[r] = L->rdispl[r] * w;
    }
    free(d->send_idx);
    free(d->recv_idx);
    free(d->sbuf);
    free(d->rbuf);
    d->send_idx = si;
    d->recv_idx = ri;
    d->sbuf = sb;
    d->rbuf = rb;
    d->n_send = L->n_send;
    d->n_recv = L->n_recv;
    return 0;
}

/* The sends that hold the model's fixed partners (par_spatial_model.bonds)
 * as ghosts: owned particle i goes to the owner of each partner j held
 * here as a ghost (symmetric bonds: i is a partner of j there).  The
 * owners of the current ghosts come from the halo's receive lists (of the
 * partition, a migration or the last ghost build: counts in 2 dim doubles
 * per particle). */
static int forced_sends(struct par_decomp *d, const struct sim *s, const struct bond_list *bl,
                        struct spall_error *err)
{
    const struct particles *p = s->p;
    const size_t no = p->n_owned, n = p->n, ng = n - no;
    const int size = par_size(), w = 2 * p->dim;
    int *own = malloc((ng ? ng : 1) * sizeof *own);
    size_t cnt = 0;
    for (size_t i = 0; i < no && i < bl->n; i++)
        cnt += bl->offset[i + 1] - bl->offset[i];
    size_t *idx = malloc((cnt ? cnt : 1) * sizeof *idx);
    int *rk = malloc((cnt ? cnt : 1) * sizeof *rk);
    int rc = own && idx && rk ? SPALL_OK
                              : spall_error_set(err, SPALL_ERR_NOMEM,
                                                "out of memory (spatial ghosts: partners)");
    for (size_t q = 0; q < ng && !rc; q++)
        own[q] = -1;
    for (int r = 0; r < size && !rc; r++)
        for (int k = d->recv_displs[r] / w; k < (d->recv_displs[r] + d->recv_counts[r]) / w; k++)
            if (d->recv_idx[k] >= no && d->recv_idx[k] < n)
                own[d->recv_idx[k] - no] = r;
    size_t nf = 0;
    for (size_t i = 0; i < no && i < bl->n && !rc; i++)
        for (size_t k = bl->offset[i]; k < bl->offset[i + 1]; k++) {
            const size_t j = (size_t)bl->partner[k];
            if (j < no)
                continue;
            if (j >= n || own[j - no] < 0) {
                rc = spall_error_set(err, SPALL_ERR_INTERNAL,
                                     "spatial ghosts: particle %lld's partner %zu is no ghost "
                                     "of this rank",
                                     (long long)p->gid[i], j);
                break;
            }
            idx[nf] = i;
            rk[nf++] = own[j - no];
        }
    if (!rc)
        rc = par_sghost_set_forced(d->sg, nf, idx, rk, err);
    free(own);
    free(idx);
    free(rk);
    return rc;
}

/* Byte counts per rank of @p cnt particles of @p rec bytes; -1 past INT_MAX. */
static int byte_counts(const int *cnt, size_t rec, int size, int *bc, int *bd)
{
    size_t at = 0;
    for (int r = 0; r < size; r++) {
        size_t b = (size_t)cnt[r] * rec;
        if (b > (size_t)INT_MAX || at > (size_t)INT_MAX)
            return -1;
        bc[r] = (int)b;
        bd[r] = (int)at;
        at += b;
    }
    return at > (size_t)INT_MAX ? -1 : 0;
}

/* Re-lay out the local arrays around the ghost set of @p sg's last build:
 * owned [0, n_owned) unchanged, then the ghosts in ascending gid with
 * their owners' records (the arrays of @p sl, @p rec bytes per particle);
 * the halo lists follow. */
static int exchange_records(struct sim *s, struct par_sghost *sg, const struct par_slots *sl,
                            size_t rec, struct spall_error *err)
{
    struct par_decomp *d = s->par;
    struct particles *p = s->p;
    const int dim = p->dim, size = par_size();
    const size_t no = p->n_owned;
    struct par_sghost_lists L;
    par_sghost_lists(sg, &L);
    const size_t ng = par_sghost_count(sg), nn = no + ng;
    int *bc = malloc(4 * (size_t)size * sizeof *bc);
    char *sbuf = malloc((L.n_send ? L.n_send : 1) * rec);
    char *rbuf = malloc((L.n_recv ? L.n_recv : 1) * rec);
    int rc = !bc || !sbuf || !rbuf ? SPALL_ERR_NOMEM : SPALL_OK;
    if (!rc && (byte_counts(L.scount, rec, size, bc, bc + size) ||
                byte_counts(L.rcount, rec, size, bc + 2 * size, bc + 3 * size)))
        rc = SPALL_ERR_NOMEM;
    if (!rc) {
        char *b = sbuf;
        for (size_t k = 0; k < L.n_send; k++)
            for (size_t q = 0; q < sl->n; q++) {
                size_t e = sl->esize[q];
                memcpy(b, (const char *)*sl->ptr[q] + L.send_idx[k] * e, e);
                b += e;
            }
    }
    /* the new arrays: the owned rows stay where they are */
    for (size_t q = 0; q < sl->n && !rc; q++) {
        void *a = realloc(*sl->ptr[q], (nn ? nn : 1) * sl->esize[q]);
        if (a)
            *sl->ptr[q] = a;
        else
            rc = SPALL_ERR_NOMEM;
    }
    if (!rc && halo_from_lists(d, &L, no, dim))
        rc = SPALL_ERR_NOMEM;
    if (rc)
        spall_error_set(err, rc, "out of memory (spatial ghosts: %zu ghosts)", ng);
    if ((rc = par_agree(rc, err))) {
        free(bc);
        free(sbuf);
        free(rbuf);
        return rc;
    }
    MPI_Alltoallv(sbuf, bc, bc + size, MPI_BYTE, rbuf, bc + 2 * size, bc + 3 * size, MPI_BYTE,
                  MPI_COMM_WORLD);
    const char *b = rbuf;
    for (size_t k = 0; k < L.n_recv; k++) {
        const size_t i = no + L.recv_idx[k];
        for (size_t q = 0; q < sl->n; q++) {
            size_t e = sl->esize[q];
            memcpy((char *)*sl->ptr[q] + i * e, b, e);
            b += e;
        }
    }
    free(bc);
    free(sbuf);
    free(rbuf);
    p->n = nn;
    p->cap = nn;
    d->n_ghost = ng;
    return SPALL_OK;
}

/* Rebuild the ghosts around the owned build positions (moved: the owned
 * particles' current positions become the build positions first), re-lay
 * out the local arrays and let the model rebuild its list. */
static int relayout(struct sim *s, bool moved, struct spall_error *err)
{
    struct par_decomp *d = s->par;
    struct particles *p = s->p;
    const int dim = p->dim;
    const size_t no = p->n_owned;
    struct par_spatial_model sm;
    struct par_slots sl;
    size_t rec = 0;
    int rc = ghost_arrays(s, &sm, &sl, &rec, err);
    /* the model's range of the list it builds now: it may have grown since
     * the last build (SPH with a variable h, whose radius follows h_max) */
    if (!rc && !d->sg)
        rc = par_sghost_create(&d->sg, dim, sm.range, sm.skin, err);
    else if (!rc)
        rc = par_sghost_set_range(d->sg, sm.range, sm.skin, err);
    if ((rc = par_agree(rc, err)))
        return rc;
    par_sghost_set_mirror(d->sg, sm.mirror_planes);
    d->sg_bonds = sm.bonds != NULL;
    if (sm.bonds && (rc = par_agree(forced_sends(d, s, sm.bonds, err), err)))
        return rc;
    if (moved)
        for (int c = 0; c < dim; c++)
            memcpy(sm.xb[c], p->x[c], no * sizeof(double));
    const double *xb[3] = {NULL, NULL, NULL};
    for (int c = 0; c < dim; c++)
        xb[c] = sm.xb[c];
    if ((rc = par_sghost_build(d->sg, no, xb, p->gid, err)))
        return rc;
    if ((rc = exchange_records(s, d->sg, &sl, rec, err)))
        return rc;
    if (moved)
        d->sg_rebuilds++;
    return par_agree(s->ops->spatial_rebuilt(s->model, s, moved, err), err);
}

/* Regathering with the current ghosts kept: every owned particle goes
 * again to each rank it is a ghost of now (the halo's send lists, counts
 * in 2 dim doubles per particle). */
static int keep_sends(struct par_sghost *g, const struct par_decomp *d, int dim,
                      struct spall_error *err)
{
    const int size = par_size(), w = 2 * dim;
    size_t *idx = malloc((d->n_send ? d->n_send : 1) * sizeof *idx);
    int *rk = malloc((d->n_send ? d->n_send : 1) * sizeof *rk);
    int rc = idx && rk ? SPALL_OK
                       : spall_error_set(err, SPALL_ERR_NOMEM,
                                         "out of memory (spatial ghosts: %zu kept)", d->n_send);
    size_t nf = 0;
    for (int r = 0; r < size && !rc; r++)
        for (int k = d->send_displs[r] / w; k < (d->send_displs[r] + d->send_counts[r]) / w;
             k++) {
            idx[nf] = d->send_idx[k];
            rk[nf++] = r;
        }
    if (!rc)
        rc = par_sghost_set_forced(g, nf, idx, rk, err);
    free(idx);
    free(rk);
    return rc;
}

int par_spatial_regather(struct sim *s, double range, const struct par_spatial_model *sm,
                         bool keep, struct spall_error *err)
{
    struct particles *p = s->p;
    struct par_slots sl;
    int rc = par_particle_slots(s, &sl) ? SPALL_ERR_INTERNAL : SPALL_OK;
    for (int k = 0; k < sm->n_particle && !rc; k++)
        rc = par_slot_add(&sl, sm->particle[k], sm->particle_size[k]) ? SPALL_ERR_INTERNAL : rc;
    if (rc)
        spall_error_set(err, rc, "spatial ghosts: too many arrays");
    size_t rec = 0;
    for (size_t k = 0; k < sl.n; k++)
        rec += sl.esize[k];
    /* a ghost set of its own (the step keeps the model's bond halo) */
    struct par_sghost *g = NULL;
    if (!rc)
        rc = par_sghost_create(&g, p->dim, range, 1e-6 * range, err);
    if (!rc && keep)
        rc = keep_sends(g, s->par, p->dim, err);
    if ((rc = par_agree(rc, err))) {
        par_sghost_destroy(&g);
        return rc;
    }
    const double *x[3] = {NULL, NULL, NULL};
    for (int c = 0; c < p->dim; c++)
        x[c] = p->x[c];
    rc = par_sghost_build(g, p->n_owned, x, p->gid, err);
    if (!rc)
        rc = exchange_records(s, g, &sl, rec, err);
    par_sghost_destroy(&g);
    par_bhalo_free(s->par); /* a per-bond halo plan is for the old ghosts */
    return rc;
}

int par_spatial_init(struct sim *s, struct spall_error *err)
{
    if (!s->ops->spatial_ghosts)
        return SPALL_OK;
    struct par_spatial_model sm;
    memset(&sm, 0, sizeof sm);
    if (s->ops->spatial_ghosts(s->model, &sm) > 0)
        return SPALL_OK; /* not in this run (every rank answers alike) */
    return relayout(s, false, err);
}

int par_ghosts_step(struct sim *s, struct spall_error *err)
{
    struct par_decomp *d = s->par;
    if (d->sg) {
        /* the serial model's test (e.g. macro_neighbors_update), over the
         * owned particles of every rank: the same steps rebuild */
        struct par_spatial_model sm;
        memset(&sm, 0, sizeof sm);
        s->ops->spatial_ghosts(s->model, &sm);
        if (sm.place) { /* prescribed particles first (SPH's mirrored clamp) */
            int rc = par_agree(sm.place(s->model, s, err), err);
            if (rc)
                return rc;
        }
        const struct particles *p = s->p;
        double d2max = par_max_double(step_max_shift2(s->dim, p->n_owned, p->x, sm.xb));
        const bool due = sm.rebuild_due ? sm.rebuild_due(s->model, s, d2max)
                                        : !(4.0 * d2max < sm.skin * sm.skin);
        if (due) {
            int rc = relayout(s, true, err);
            if (rc)
                return rc;
        }
    }
    par_halo_x(s);
    return SPALL_OK;
}

#else /* serial build: no ranks, no ghosts */

int par_spatial_init(struct sim *s, struct spall_error *err)
{
    (void)s;
    (void)err;
    return SPALL_OK;
}

int par_ghosts_step(struct sim *s, struct spall_error *err)
{
    (void)s;
    (void)err;
    return SPALL_OK;
}

int par_spatial_regather(struct sim *s, double range, const struct par_spatial_model *sm,
                         bool keep, struct spall_error *err)
{
    (void)s;
    (void)range;
    (void)sm;
    (void)keep;
    (void)err;
    return SPALL_OK;
}

#endif
