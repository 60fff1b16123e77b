/**
 * @file decomp.c
 * @brief Zoltan partition, owned + ghost localisation and the halo exchange
 *        (decomp.h).  The ordered reductions are in reduce.c.
 */
#include "core/parallel/decomp.h"
#include "core/parallel/decomp_internal.h"
#include "core/parallel/bhalo.h"
#include "core/parallel/spatial.h"

#include "core/bond_list.h"
#include "core/contact_particles.h"
#include "core/fields.h"
#include "core/model.h"
#include "core/parallel/comm.h"
#include "core/particles.h"
#include "core/sim.h"
#include "spall/error.h"

#include <omp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#ifdef SPALL_HAVE_MPI
#include <mpi.h>
#include <zoltan.h>
#endif

void par_decomp_destroy(struct par_decomp **dp)
{
    if (!dp || !*dp)
        return;
    struct par_decomp *d = *dp;
    free(d->send_counts);
    free(d->send_displs);
    free(d->recv_counts);
    free(d->recv_displs);
    free(d->send_idx);
    free(d->recv_idx);
    free(d->sbuf);
    free(d->rbuf);
    free(d->req);
    if (d->group_key)
        for (size_t g = 0; g < d->n_groups; g++)
            free(d->group_key[g]);
    free(d->group_key);
    free(d->group_n);
    free(d->probe_owner);
    free(d->probe_local);
    par_balance_free(d);
    par_bhalo_free(d);
    par_spatial_free(d);
    free(d);
    *dp = NULL;
}

size_t par_n_global(const struct sim *s)
{
    return s->par ? s->par->n_global : s->p->n_owned;
}

size_t par_interactions_global(const struct sim *s, size_t local)
{
    return s->par ? s->par->interactions : local;
}

size_t sim_group_count(const struct sim *s, int g)
{
    return s->par ? s->par->group_n[g] : s->groups[g].n;
}

int64_t par_group_key(const struct sim *s, int g, size_t q)
{
    return s->par->group_key[g][q];
}

double par_particle_work(const struct bond_list *bl, size_t i, int intact_only)
{
    double w = 1.0;
    if (!bl)
        return w;
    if (!intact_only)
        return w + (double)(bl->offset[i + 1] - bl->offset[i]);
    for (size_t q = bl->offset[i]; q < bl->offset[i + 1]; q++)
        w += !(bl->state[q] & BOND_BROKEN);
    return w;
}

int par_check_supported(const struct sim *s, struct spall_error *err)
{
    const int n = par_size();
    if (!s->ops->localize)
        return spall_error_set(err, SPALL_ERR_INPUT,
                               "distributed runs (%d MPI ranks): model '%s' is not distributed "
                               "yet; run it on one rank (without mpirun), see docs/parallel.md",
                               n, s->ops->name);
    /* the model names what of its configuration it cannot distribute */
    return s->ops->localize(s->model, (struct sim *)s, NULL, 0, 0, NULL, err);
}

#ifdef SPALL_HAVE_MPI

/* ---- Zoltan query functions over the rows [lo, hi) of par_zobjs */

static int zq_num_obj(void *data, int *ierr)
{
    const struct par_zobjs *z = data;
    *ierr = ZOLTAN_OK;
    return (int)(z->hi - z->lo);
}

static void zq_obj_list(void *data, int ng, int nl, ZOLTAN_ID_PTR gids, ZOLTAN_ID_PTR lids,
                        int wdim, float *w, int *ierr)
{
    (void)ng;
    (void)nl;
    const struct par_zobjs *z = data;
    for (size_t k = 0; k < z->hi - z->lo; k++) {
        size_t i = z->lo + k;
        gids[k] = (ZOLTAN_ID_TYPE)(z->gid ? (size_t)z->gid[i] : i);
        lids[k] = (ZOLTAN_ID_TYPE)k;
        if (wdim > 0)
            w[k] = (float)par_particle_work(z->bl, i, z->intact_only);
    }
    *ierr = ZOLTAN_OK;
}

static int zq_num_geom(void *data, int *ierr)
{
    const struct par_zobjs *z = data;
    *ierr = ZOLTAN_OK;
    return z->dim;
}

static void zq_geom_multi(void *data, int ng, int nl, int n, ZOLTAN_ID_PTR gids,
                          ZOLTAN_ID_PTR lids, int ndim, double *geom, int *ierr)
{
    (void)ng;
    (void)nl;
    (void)gids;
    const struct par_zobjs *z = data;
    for (int k = 0; k < n; k++)
        for (int c = 0; c < ndim; c++)
            geom[(size_t)k * (size_t)ndim + (size_t)c] = z->pos[c][z->lo + lids[k]];
    *ierr = ZOLTAN_OK;
}

struct Zoltan_Struct *par_zoltan_rcb(int reuse)
{
    struct Zoltan_Struct *zz = Zoltan_Create(MPI_COMM_WORLD);
    if (!zz)
        return NULL;
    Zoltan_Set_Param(zz, "DEBUG_LEVEL", "0");
    Zoltan_Set_Param(zz, "LB_METHOD", "RCB");
    Zoltan_Set_Param(zz, "NUM_GID_ENTRIES", "1");
    Zoltan_Set_Param(zz, "NUM_LID_ENTRIES", "1");
    Zoltan_Set_Param(zz, "OBJ_WEIGHT_DIM", "1");
    Zoltan_Set_Param(zz, "RETURN_LISTS", "EXPORT");
    Zoltan_Set_Param(zz, "RCB_OUTPUT_LEVEL", "0");
    Zoltan_Set_Param(zz, "KEEP_CUTS", reuse ? "1" : "0");
    if (reuse) { /* start each repartition from the previous cuts */
        Zoltan_Set_Param(zz, "LB_APPROACH", "REPARTITION");
        Zoltan_Set_Param(zz, "RCB_REUSE", "1");
    }
    return zz;
}

void par_zoltan_queries(struct Zoltan_Struct *zz, struct par_zobjs *z)
{
    Zoltan_Set_Num_Obj_Fn(zz, zq_num_obj, z);
    Zoltan_Set_Obj_List_Fn(zz, zq_obj_list, z);
    Zoltan_Set_Num_Geom_Fn(zz, zq_num_geom, z);
    Zoltan_Set_Geom_Multi_Fn(zz, zq_geom_multi, z);
}

/* owner[i] for every particle of the whole body (same on all ranks). */
static int partition(const struct sim *s, const struct bond_list *bl, int *owner,
                     struct spall_error *err)
{
    const size_t n = s->p->n_owned;
    const int size = par_size(), rank = par_rank();
    if (n > (size_t)0xFFFFFFFFu)
        return spall_error_set(err, SPALL_ERR_INPUT,
                               "distributed runs: %zu particles exceed Zoltan's 32-bit ids", n);
    /* this rank's slice of the whole body, at the reference positions,
     * weighted by 1 + half-bonds (the force loop visits every half-bond) */
    struct par_zobjs z = {n * (size_t)rank / (size_t)size, n * (size_t)(rank + 1) / (size_t)size,
                          NULL, s->p->x0, s->p->dim, bl, 0};
    float ver = 0.0f;
    struct Zoltan_Struct *zz = NULL;
    int rc = par_fault("partition", err);
    if (!rc && Zoltan_Initialize(0, NULL, &ver) != ZOLTAN_OK)
        rc = spall_error_set(err, SPALL_ERR_INTERNAL, "Zoltan_Initialize failed");
    /* Zoltan_Create duplicates the communicator (collective), and so is
     * the partition */
    if (!(rc = par_agree(rc, err)) && !(zz = par_zoltan_rcb(0)))
        rc = spall_error_set(err, SPALL_ERR_INTERNAL, "Zoltan_Create failed");
    if ((rc = par_agree(rc, err))) {
        Zoltan_Destroy(&zz);
        return rc;
    }
    par_zoltan_queries(zz, &z);
    int changes, ngid, nlid, nimp, nexp;
    ZOLTAN_ID_PTR imp_g = NULL, imp_l = NULL, exp_g = NULL, exp_l = NULL;
    int *imp_p = NULL, *imp_parts = NULL, *exp_p = NULL, *exp_parts = NULL;
    int zrc = Zoltan_LB_Partition(zz, &changes, &ngid, &nlid, &nimp, &imp_g, &imp_l, &imp_p,
                                  &imp_parts, &nexp, &exp_g, &exp_l, &exp_p, &exp_parts);
    int *mine = malloc((z.hi - z.lo + 1) * sizeof *mine);
    int *counts = malloc((size_t)size * sizeof *counts), *displs = malloc((size_t)size * sizeof *displs);
    if (zrc != ZOLTAN_OK)
        rc = spall_error_set(err, SPALL_ERR_INTERNAL, "Zoltan RCB partition failed (%d)", zrc);
    else if (!mine || !counts || !displs)
        rc = spall_error_set(err, SPALL_ERR_NOMEM, "out of memory partitioning");
    if (!(rc = par_agree(rc, err))) {
        for (size_t k = 0; k < z.hi - z.lo; k++)
            mine[k] = rank;
        for (int k = 0; k < nexp; k++)
            mine[exp_l[k]] = exp_parts[k];
        for (int r = 0; r < size; r++) {
            size_t lo = n * (size_t)r / (size_t)size, hi = n * (size_t)(r + 1) / (size_t)size;
            counts[r] = (int)(hi - lo);
            displs[r] = (int)lo;
        }
        MPI_Allgatherv(mine, counts[rank], MPI_INT, owner, counts, displs, MPI_INT,
                       MPI_COMM_WORLD);
    }
    Zoltan_LB_Free_Part(&imp_g, &imp_l, &imp_p, &imp_parts);
    Zoltan_LB_Free_Part(&exp_g, &exp_l, &exp_p, &exp_parts);
    Zoltan_Destroy(&zz);
    free(mine);
    free(counts);
    free(displs);
    return rc;
}

/* Replace *ptr (elements of @p esize bytes, old indexing) by the kept ones. */
static int compact(void **ptr, size_t esize, const size_t *keep, size_t n_keep)
{
    if (!*ptr)
        return 0;
    char *dst = malloc((n_keep ? n_keep : 1) * esize);
    if (!dst)
        return -1;
    const char *src = *ptr;
    for (size_t k = 0; k < n_keep; k++)
        memcpy(dst + k * esize, src + keep[k] * esize, esize);
    free(*ptr);
    *ptr = dst;
    return 0;
}

int par_slot_add(struct par_slots *sl, void **ptr, size_t esize)
{
    if (!*ptr)
        return 0;
    for (size_t k = 0; k < sl->n; k++)
        if (sl->ptr[k] == ptr || *sl->ptr[k] == *ptr)
            return 0; /* the same array, reached twice */
    if (sl->n == PAR_MAX_SLOTS)
        return -1;
    sl->ptr[sl->n] = ptr;
    sl->esize[sl->n++] = esize;
    return 0;
}

static size_t type_size(enum field_type t)
{
    switch (t) {
    case FIELD_F64: return sizeof(double);
    case FIELD_I32: return sizeof(int32_t);
    case FIELD_I64: return sizeof(int64_t);
    case FIELD_U8:
    default: return 1;
    }
}

int par_particle_slots(struct sim *s, struct par_slots *sl)
{
    struct particles *p = s->p;
    int bad = 0;
    sl->n = 0;
    for (int d = 0; d < p->dim; d++) {
        bad |= par_slot_add(sl, (void **)&p->x[d], sizeof(double));
        bad |= par_slot_add(sl, (void **)&p->x0[d], sizeof(double));
        bad |= par_slot_add(sl, (void **)&p->v[d], sizeof(double));
        bad |= par_slot_add(sl, (void **)&p->f[d], sizeof(double));
        bad |= par_slot_add(sl, (void **)&s->v_half[d], sizeof(double));
    }
    bad |= par_slot_add(sl, (void **)&p->mass, sizeof(double));
    bad |= par_slot_add(sl, (void **)&p->volume, sizeof(double));
    bad |= par_slot_add(sl, (void **)&p->gid, sizeof(int64_t));
    bad |= par_slot_add(sl, (void **)&p->material, sizeof(int32_t));
    bad |= par_slot_add(sl, (void **)&p->body, sizeof(int32_t));
    bad |= par_slot_add(sl, (void **)&s->no_drift_velocity, sizeof(uint8_t));
    for (int d = 0; d < p->dim && s->pcontact; d++) /* contact's build positions */
        bad |= par_slot_add(sl, particle_contact_built_at(s->pcontact, d), sizeof(double));
    const struct field_registry *reg = s->fields;
    for (size_t k = 0; k < reg->n && !bad; k++) {
        const struct field_desc *f = &reg->fields[k];
        if (f->compute)
            continue;
        for (int c = 0; c < f->ncomp && f->comp[c]; c++)
            bad |= par_slot_add(sl, f->comp[c], type_size(f->type));
    }
    return bad ? -1 : 0;
}

/* Every per-particle array of the engine and the registry, compacted once. */
static int compact_particles(struct sim *s, const size_t *keep, size_t n_keep, size_t n_owned,
                             struct spall_error *err)
{
    struct particles *p = s->p;
    struct par_slots sl;
    if (par_particle_slots(s, &sl))
        return spall_error_set(err, SPALL_ERR_INTERNAL, "distributed runs: too many fields");
    for (size_t k = 0; k < sl.n; k++)
        if (compact(sl.ptr[k], sl.esize[k], keep, n_keep))
            return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory localising particles");
    p->n = n_keep;
    p->n_owned = n_owned;
    p->cap = n_keep;
    return SPALL_OK;
}

/* Groups keep their owned members (local indices) with their serial
 * positions as order keys; probes remember their owner. */
static int localize_sets(struct sim *s, struct par_decomp *d, const int *owner,
                         const int64_t *new_of_old, struct spall_error *err)
{
    const int rank = par_rank();
    d->n_groups = s->n_groups;
    d->group_n = calloc(s->n_groups + 1, sizeof *d->group_n);
    d->group_key = calloc(s->n_groups + 1, sizeof *d->group_key);
    d->probe_owner = calloc(s->n_probes + 1, sizeof *d->probe_owner);
    d->probe_local = calloc(s->n_probes + 1, sizeof *d->probe_local);
    if (!d->group_n || !d->group_key || !d->probe_owner || !d->probe_local)
        return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory localising groups");
    for (size_t g = 0; g < s->n_groups; g++) {
        struct group *gr = &s->groups[g];
        d->group_n[g] = gr->n;
        d->group_key[g] = malloc((gr->n ? gr->n : 1) * sizeof *d->group_key[g]);
        if (!d->group_key[g])
            return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory localising groups");
        size_t m = 0;
        for (size_t q = 0; q < gr->n; q++) {
            size_t i = gr->idx[q];
            if (owner[i] != rank)
                continue;
            gr->idx[m] = (size_t)new_of_old[i];
            d->group_key[g][m++] = (int64_t)q;
        }
        gr->n = m;
    }
    for (size_t k = 0; k < s->n_probes; k++) {
        size_t i = s->probes[k].particle;
        d->probe_owner[k] = owner[i];
        d->probe_local[k] = owner[i] == rank ? (size_t)new_of_old[i] : 0;
        s->probes[k].particle = d->probe_local[k];
    }
    return SPALL_OK;
}

/* Halo lists (@p dim: doubles per particle): my owned particles that rank r
 * holds as ghosts (ascending gid), and my ghosts by owner (ascending gid: the
 * order of `keep`).  Bonds are symmetric, so both sides derive the same lists
 * without talking. */
static int build_halo(struct par_decomp *d, const struct bond_list *bl, const int *owner,
                      const size_t *keep, size_t n_owned, size_t n_keep, int dim,
                      struct spall_error *err)
{
    const int size = par_size(), rank = par_rank();
    d->send_counts = calloc((size_t)size, sizeof(int));
    d->send_displs = calloc((size_t)size, sizeof(int));
    d->recv_counts = calloc((size_t)size, sizeof(int));
    d->recv_displs = calloc((size_t)size, sizeof(int));
    unsigned char *seen = calloc((size_t)size, 1);
    if (!d->send_counts || !d->send_displs || !d->recv_counts || !d->recv_displs || !seen) {
        free(seen);
        return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory building the halo");
    }
    /* count, then fill (rank-major, ascending gid within a rank) */
    size_t total = 0;
    for (int pass = 0; pass < 2; pass++) {
        size_t *pos = NULL;
        if (pass == 1) {
            d->send_idx = malloc((total ? total : 1) * sizeof *d->send_idx);
            pos = calloc((size_t)size, sizeof *pos);
            if (!d->send_idx || !pos) {
                free(pos);
                free(seen);
                return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory building the halo");
            }
            size_t acc = 0;
            for (int r = 0; r < size; r++) {
                pos[r] = acc;
                acc += (size_t)d->send_counts[r];
            }
        }
        for (size_t k = 0; k < n_owned; k++) {
            size_t i = keep[k];
            memset(seen, 0, (size_t)size);
            /* no bond list: spatial ghosts only (spatial.c sets the lists) */
            for (size_t s = bl ? bl->offset[i] : 0; bl && s < bl->offset[i + 1]; s++) {
                int r = owner[bl->partner[s]];
                if (r == rank || seen[r])
                    continue;
                seen[r] = 1;
                if (pass == 0) {
                    d->send_counts[r]++;
                    total++;
                } else {
                    d->send_idx[pos[r]++] = k;
                }
            }
        }
        free(pos);
    }
    free(seen);
    for (size_t k = n_owned; k < n_keep; k++)
        d->recv_counts[owner[keep[k]]]++;
    /* ghosts are sorted by gid, not by owner: receive in owner-major order
     * through recv_idx; here, with ascending gid within each owner */
    int acc_s = 0, acc_r = 0;
    for (int r = 0; r < size; r++) {
        d->send_displs[r] = acc_s;
        d->recv_displs[r] = acc_r;
        acc_s += d->send_counts[r];
        acc_r += d->recv_counts[r];
    }
    d->n_send = (size_t)acc_s;
    d->n_recv = (size_t)acc_r;
    d->recv_idx = malloc((d->n_recv ? d->n_recv : 1) * sizeof *d->recv_idx);
    int *fill = calloc((size_t)size, sizeof *fill);
    d->sbuf = malloc((d->n_send ? d->n_send : 1) * (size_t)dim * sizeof *d->sbuf);
    d->rbuf = malloc((d->n_recv ? d->n_recv : 1) * (size_t)dim * sizeof *d->rbuf);
    if (!d->recv_idx || !fill || !d->sbuf || !d->rbuf) {
        free(fill);
        return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory building the halo");
    }
    for (size_t k = n_owned; k < n_keep; k++) {
        int r = owner[keep[k]];
        d->recv_idx[(size_t)(d->recv_displs[r] + fill[r]++)] = k;
    }
    free(fill);
    d->req = malloc(2 * (size_t)size * sizeof(MPI_Request));
    if (!d->req)
        return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory building the halo");
    for (int r = 0; r < size; r++) { /* in doubles, for the exchange */
        d->send_counts[r] *= dim;
        d->send_displs[r] *= dim;
        d->recv_counts[r] *= dim;
        d->recv_displs[r] *= dim;
    }
    return SPALL_OK;
}

void par_halo_x(struct sim *s)
{
    struct par_decomp *d = s->par;
    struct particles *p = s->p;
    const int dim = p->dim, w = 2 * dim;
    double t0 = MPI_Wtime();
    for (size_t k = 0; k < d->n_send; k++)
        for (int c = 0; c < dim; c++) {
            d->sbuf[k * (size_t)w + (size_t)c] = p->x[c][d->send_idx[k]];
            d->sbuf[k * (size_t)w + (size_t)(dim + c)] = p->v[c][d->send_idx[k]];
        }
    /* point to point with the neighbour ranks only (those sharing bonds),
     * so the cost per step does not grow with the number of ranks */
    const int size = par_size();
    MPI_Request *req = d->req;
    int nreq = 0;
    for (int r = 0; r < size; r++) {
        if (d->recv_counts[r])
            MPI_Irecv(d->rbuf + d->recv_displs[r], d->recv_counts[r], MPI_DOUBLE, r, 17,
                      MPI_COMM_WORLD, &req[nreq++]);
    }
    for (int r = 0; r < size; r++) {
        if (d->send_counts[r])
            MPI_Isend(d->sbuf + d->send_displs[r], d->send_counts[r], MPI_DOUBLE, r, 17,
                      MPI_COMM_WORLD, &req[nreq++]);
    }
    MPI_Waitall(nreq, req, MPI_STATUSES_IGNORE);
    for (size_t k = 0; k < d->n_recv; k++)
        for (int c = 0; c < dim; c++) {
            p->x[c][d->recv_idx[k]] = d->rbuf[k * (size_t)w + (size_t)c];
            p->v[c][d->recv_idx[k]] = d->rbuf[k * (size_t)w + (size_t)(dim + c)];
        }
    d->comm_seconds += MPI_Wtime() - t0;
    d->halo_calls++;
}

int par_keep_ghosts(struct sim *s, struct par_decomp *d, const struct bond_list *bl,
                    const int *owner, int64_t *new_of_old, size_t *keep, size_t n_owned,
                    size_t n, size_t *n_keep, struct spall_error *err)
{
    const int rank = par_rank();
    /* ghosts: bond partners held elsewhere, marked, then taken by gid */
    for (size_t k = 0; k < n_owned && bl; k++)
        for (size_t q = bl->offset[keep[k]]; q < bl->offset[keep[k] + 1]; q++) {
            size_t j = (size_t)bl->partner[q];
            if (owner[j] != rank)
                new_of_old[j] = -2;
        }
    size_t m = n_owned;
    for (size_t j = 0; j < n; j++)
        if (new_of_old[j] == -2) {
            new_of_old[j] = (int64_t)m;
            keep[m++] = j;
        }
    *n_keep = m;
    d->n_owned = n_owned;
    d->n_ghost = m - n_owned;
    /* per particle: position and velocity (the models' force calls may
     * read a partner's drift velocity, sim_drift_velocities) */
    return build_halo(d, bl, owner, keep, n_owned, m, 2 * s->dim, err);
}

int par_localize_kept(struct sim *s, const size_t *keep, size_t n_keep, size_t n_owned,
                      const int64_t *new_of_old, struct spall_error *err)
{
    /* the model renumbers its bond rows (which needs the old list) first */
    int rc = par_fault("localize", err);
    if (!rc)
        rc = s->ops->localize(s->model, s, keep, n_keep, n_owned, new_of_old, err);
    return rc ? rc : compact_particles(s, keep, n_keep, n_owned, err);
}

static int distribute(struct sim *s, struct par_decomp *d, struct spall_error *err)
{
    const struct bond_list *bl = s->ops->halo_bonds ? s->ops->halo_bonds(s->model)
                                 : s->ops->bonds    ? s->ops->bonds(s->model)
                                                    : NULL;
    if (!bl && !s->ops->spatial_ghosts)
        return spall_error_set(err, SPALL_ERR_INPUT,
                               "distributed runs: model '%s' has no bond list", s->ops->name);
    const size_t n = s->p->n_owned;
    const int rank = par_rank();
    d->n_global = n;
    d->interactions = s->ops->interactions ? s->ops->interactions(s->model, s) : 0;
    int *owner = malloc((n ? n : 1) * sizeof *owner);
    int64_t *new_of_old = malloc((n ? n : 1) * sizeof *new_of_old);
    size_t *keep = malloc((n ? n : 1) * sizeof *keep);
    int rc = owner && new_of_old && keep
                 ? SPALL_OK
                 : spall_error_set(err, SPALL_ERR_NOMEM, "out of memory partitioning");
    if (!rc) /* agreed inside, before Zoltan's collectives */
        rc = partition(s, bl, owner, err);
    else
        rc = par_agree(rc, err); /* the agreement partition() would have made */
    size_t n_keep = 0, n_owned = 0;
    if (!rc) {
        for (size_t i = 0; i < n; i++)
            new_of_old[i] = -1;
        for (size_t i = 0; i < n; i++)
            if (owner[i] == rank) {
                new_of_old[i] = (int64_t)n_keep;
                keep[n_keep++] = i;
            }
        n_owned = n_keep;
        rc = par_keep_ghosts(s, d, bl, owner, new_of_old, keep, n_owned, n, &n_keep, err);
    }
    if (!rc)
        rc = localize_sets(s, d, owner, new_of_old, err);
    /* the models' localisers may reduce over the ranks: agreed first */
    if (!(rc = par_agree(rc, err)))
        rc = par_localize_kept(s, keep, n_keep, n_owned, new_of_old, err);
    free(owner);
    free(new_of_old);
    free(keep);
    return rc;
}

int par_distribute(struct sim *s, struct spall_error *err)
{
    struct par_decomp *d = calloc(1, sizeof *d);
    if (!d)
        return par_agree(spall_error_set(err, SPALL_ERR_NOMEM, "out of memory"), err);
    double t0 = MPI_Wtime();
    int rc = distribute(s, d, err);
    d->setup_seconds = MPI_Wtime() - t0;
    rc = par_agree(rc, err);
    if (rc) {
        par_decomp_destroy(&d);
        return rc;
    }
    s->par = d;
    /* a model with a neighbour search: its first spatial ghosts */
    rc = par_spatial_init(s, err);
    if (rc) {
        par_decomp_destroy(&d);
        s->par = NULL;
    }
    return rc;
}

void par_describe(const struct sim *s, char *buf, size_t len)
{
    const struct par_decomp *d = s->par;
    const int size = par_size();
    uint64_t mine[3] = {d->n_owned, d->n_ghost, d->n_send}, *all = NULL;
    if (par_rank() == 0)
        all = malloc((size_t)size * 3 * sizeof *all);
    MPI_Gather(mine, 3, MPI_UINT64_T, all, 3, MPI_UINT64_T, 0, MPI_COMM_WORLD);
    if (!all)
        return;
    size_t w = 0;
#define PUT(...)                                                                                \
    do {                                                                                        \
        if (w < len)                                                                            \
            w += (size_t)snprintf(buf + w, len - w, __VA_ARGS__);                               \
    } while (0)
    PUT("mpi_ranks: %d\nranks_x_threads: %d x %d\n", size, size, omp_get_max_threads());
    PUT("decomposition: Zoltan RCB on the reference positions, weight 1 + bonds per particle; "
        "ghosts = %s (set-up %.3g s)\n",
        d->sg && d->sg_bonds ? "the particles of other ranks within range + skin (spatial "
                               "ghosts) and the model's fixed partners on other ranks"
        : d->sg              ? "the particles of other ranks within range + skin (spatial ghosts)"
                             : "bond partners on other ranks",
        d->setup_seconds);
    PUT("decomposition_per_rank: |\n");
    for (int r = 0; r < size; r++)
        PUT("  rank %d: %llu owned, %llu ghosts, %llu particles sent per halo exchange (%llu "
            "bytes)\n", r, (unsigned long long)all[3 * r], (unsigned long long)all[3 * r + 1],
            (unsigned long long)all[3 * r + 2],
            (unsigned long long)(all[3 * r + 2] * 2u * (uint64_t)s->dim * sizeof(double)));
#undef PUT
    free(all);
}

#else /* no MPI: par_distribute is never reached (par_size() == 1) */

int par_distribute(struct sim *s, struct spall_error *err)
{
    (void)s;
    return spall_error_set(err, SPALL_ERR_INTERNAL, "distributed run in a build without MPI");
}

void par_halo_x(struct sim *s)
{
    (void)s;
}

void par_describe(const struct sim *s, char *buf, size_t len)
{
    (void)s;
    if (len)
        buf[0] = '\0';
}

#endif

void par_halo_stats(const struct sim *s, long *calls, double *seconds)
{
    *calls = s->par ? s->par->halo_calls : 0;
    *seconds = s->par ? s->par->comm_seconds : 0.0;
}
