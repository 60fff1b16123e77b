/**
 * @file migrate_local.c
 * @brief After the migrants have arrived: the rank's new local arrays
 *        (owned in ascending gid, then ghosts in ascending gid), bond rows
 *        re-resolved to local indices, groups, ghosts fetched from their
 *        owners, the halo lists and the probes (migrate.h).
 */
#include "core/parallel/migrate_internal.h"
#include "core/parallel/bhalo.h"

#include "core/bond_list.h"
#include "core/parallel/comm.h"
#include "core/particles.h"
#include "core/sim.h"
#include "spall/error.h"

#include <limits.h>
#include <stdlib.h>
#include <string.h>

#ifdef SPALL_HAVE_MPI
#include <mpi.h>

/* The new local arrays: owned [0, n_own) in ascending gid, then the ghosts
 * in ascending gid; bond rows re-resolved to local indices; groups, probes
 * and the halo lists rebuilt. */

static void *alloc_n(size_t n, size_t e)
{
    return malloc((n ? n : 1) * e);
}

static int64_t new_local(const struct mig *M, int64_t g)
{
    int64_t j = mig_find_gid(M->own_gid, M->n_own, g);
    if (j >= 0)
        return j;
    j = mig_find_gid(M->gh_gid, M->n_gh, g);
    return j >= 0 ? (int64_t)M->n_own + j : -1;
}

static int rebuild_bonds(struct mig *M, struct spall_error *err)
{
    const struct layout *L = &M->L;
    struct bond_list *bl = L->ma.bl;
    const size_t n_new = M->n_own + M->n_gh;
    size_t nh = 0;
    size_t *off = alloc_n(n_new + 1, sizeof *off);
    if (!off)
        return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory migrating bonds");
    off[0] = 0;
    for (size_t j = 0; j < n_new; j++) {
        size_t c = 0;
        if (j < M->n_own)
            mig_row_of(M, j, &c);
        nh += c;
        off[j + 1] = nh;
    }
    int32_t *partner = alloc_n(nh, sizeof *partner);
    /* the list's own layout kept: rest lengths as doubles or as compact
     * indices (bond_list_compact_rest), types only where it has them */
    double *rest = bl->rest ? alloc_n(nh, sizeof *rest) : NULL;
    uint16_t *ridx = bl->rest_idx ? alloc_n(nh, sizeof *ridx) : NULL;
    uint8_t *state = alloc_n(nh, sizeof *state);
    uint8_t *type = bl->type ? alloc_n(nh, sizeof *type) : NULL;
    void *mb[PAR_MIGRATE_MAX_ARRAYS] = {NULL};
    int bad = !partner || (bl->rest && !rest) || (bl->rest_idx && !ridx) || !state ||
              (bl->type && !type);
    for (int k = 0; k < L->ma.n_bond; k++)
        bad |= !(mb[k] = alloc_n(nh, L->ma.bond_size[k]));
    for (size_t j = 0; j < M->n_own && !bad; j++) {
        size_t c;
        const char *row = mig_row_of(M, j, &c);
        for (size_t q = 0; q < c; q++) {
            size_t h = off[j] + q;
            int64_t loc = new_local(M, mig_partner_gid(M, j, row, q));
            bad |= loc < 0;
            partner[h] = (int32_t)loc;
            if (!row) {
                size_t o = bl->offset[M->own[j].old] + q;
                if (rest)
                    rest[h] = bl->rest[o];
                if (ridx)
                    ridx[h] = bl->rest_idx[o];
                state[h] = bl->state[o];
                if (type)
                    type[h] = bl->type[o];
                for (int k = 0; k < L->ma.n_bond; k++) {
                    size_t e = L->ma.bond_size[k];
                    memcpy((char *)mb[k] + h * e, (const char *)*L->ma.bond[k] + o * e, e);
                }
            } else {
                const char *b = row + q * L->half + sizeof(int64_t);
                if (rest)
                    memcpy(&rest[h], b, sizeof(double));
                if (ridx)
                    memcpy(&ridx[h], b, sizeof(uint16_t));
                b += sizeof(double);
                state[h] = (uint8_t)*b++;
                if (type)
                    type[h] = (uint8_t)*b;
                b++;
                for (int k = 0; k < L->ma.n_bond; k++) {
                    size_t e = L->ma.bond_size[k];
                    memcpy((char *)mb[k] + h * e, b, e);
                    b += e;
                }
            }
        }
    }
    if (bad) {
        free(off);
        free(partner);
        free(rest);
        free(ridx);
        free(state);
        free(type);
        for (int k = 0; k < L->ma.n_bond; k++)
            free(mb[k]);
        return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory migrating bonds");
    }
    bond_list_replace(bl, n_new, off, partner, rest, ridx, state, type);
    for (int k = 0; k < L->ma.n_bond; k++) {
        free(*L->ma.bond[k]);
        *L->ma.bond[k] = mb[k];
    }
    *L->ma.n_half = nh;
    return SPALL_OK;
}

struct keyed {
    int64_t key;
    size_t j;
};

static int cmp_keyed(const void *a, const void *b)
{
    const struct keyed *x = a, *y = b;
    return (x->key > y->key) - (x->key < y->key);
}

/* Group members in their serial order (the keys), local indices renewed. */
static int rebuild_groups(struct mig *M, struct spall_error *err)
{
    const struct layout *L = &M->L;
    struct keyed *kv = alloc_n(M->n_own, sizeof *kv);
    if (!kv)
        return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory migrating groups");
    for (size_t g = 0; g < L->n_groups; g++) {
        size_t m = 0;
        for (size_t j = 0; j < M->n_own; j++) {
            int64_t key;
            if (M->own[j].rec)
                memcpy(&key, M->own[j].rec + L->rec + g * sizeof(int64_t), sizeof key);
            else
                key = M->gkey[g * M->n_own_old + M->own[j].old];
            if (key >= 0)
                kv[m++] = (struct keyed){key, j};
        }
        qsort(kv, m, sizeof *kv, cmp_keyed);
        struct group *gr = &M->s->groups[g];
        size_t *idx = alloc_n(m, sizeof *idx);
        int64_t *keys = alloc_n(m, sizeof *keys);
        if (!idx || !keys) {
            free(idx);
            free(keys);
            free(kv);
            return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory migrating groups");
        }
        for (size_t q = 0; q < m; q++) {
            idx[q] = kv[q].j;
            keys[q] = kv[q].key;
        }
        free(gr->idx);
        gr->idx = idx;
        gr->n = m;
        free(M->d->group_key[g]);
        M->d->group_key[g] = keys;
    }
    free(kv);
    return SPALL_OK;
}

/* Every per-particle array renewed; owned part filled, ghosts left for
 * fetch_ghosts. */
static int rebuild_particles(struct mig *M, struct spall_error *err)
{
    const struct layout *L = &M->L;
    const size_t n_new = M->n_own + M->n_gh;
    void *na[PAR_MAX_SLOTS] = {NULL};
    int bad = 0;
    for (size_t k = 0; k < L->sl.n; k++)
        bad |= !(na[k] = calloc(n_new ? n_new : 1, L->sl.esize[k]));
    if (bad) {
        for (size_t k = 0; k < L->sl.n; k++)
            free(na[k]);
        return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory migrating particles");
    }
    size_t off = 0;
    for (size_t k = 0; k < L->sl.n; k++) {
        const size_t e = L->sl.esize[k];
        const char *old = *L->sl.ptr[k];
        for (size_t j = 0; j < M->n_own; j++) {
            const struct src *o = &M->own[j];
            memcpy((char *)na[k] + j * e, o->rec ? o->rec + off : old + o->old * e, e);
        }
        off += e;
    }
    for (size_t k = 0; k < L->sl.n; k++) {
        free(*L->sl.ptr[k]);
        *L->sl.ptr[k] = na[k];
    }
    struct particles *p = M->s->p;
    p->n = n_new;
    p->n_owned = M->n_own;
    p->cap = n_new;
    return SPALL_OK;
}

/* Ask the owners for the ghosts' records; the requests are the new halo
 * lists (each owner sends, to each rank, what that rank asked for, in
 * ascending gid). */
static int fetch_ghosts(struct mig *M, struct spall_error *err)
{
    const int size = M->size;
    const struct layout *L = &M->L;
    struct par_decomp *d = M->d;
    int *qc = calloc((size_t)size, sizeof *qc), *qd = calloc((size_t)size, sizeof *qd);
    int *ac = calloc((size_t)size, sizeof *ac), *ad = calloc((size_t)size, sizeof *ad);
    int64_t *qg = alloc_n(M->n_gh, sizeof *qg);
    size_t *qslot = alloc_n(M->n_gh, sizeof *qslot);
    int rc = SPALL_OK;
    if (!qc || !qd || !ac || !ad || !qg || !qslot)
        rc = spall_error_set(err, SPALL_ERR_NOMEM, "out of memory fetching ghosts");
    int64_t *ag = NULL;
    char *sb = NULL, *rb = NULL;
    size_t na = 0;
    if (!rc) {
        for (size_t q = 0; q < M->n_gh; q++)
            qc[M->gh_owner[q]]++;
        int acc = 0;
        for (int r = 0; r < size; r++) {
            qd[r] = acc;
            acc += qc[r];
        }
        int *fill = calloc((size_t)size, sizeof *fill);
        if (!fill)
            rc = spall_error_set(err, SPALL_ERR_NOMEM, "out of memory fetching ghosts");
        for (size_t q = 0; q < M->n_gh && fill; q++) { /* owner-major, ascending gid */
            int r = M->gh_owner[q];
            size_t at = (size_t)(qd[r] + fill[r]++);
            qg[at] = M->gh_gid[q];
            qslot[at] = M->n_own + q;
        }
        free(fill);
    }
    if ((rc = par_agree(rc, err)))
        goto out;
    MPI_Alltoall(qc, 1, MPI_INT, ac, 1, MPI_INT, MPI_COMM_WORLD);
    for (int r = 0; r < size; r++) {
        ad[r] = (int)na;
        na += (size_t)ac[r];
    }
    ag = alloc_n(na, sizeof *ag);
    sb = alloc_n(na, L->rec);
    rb = alloc_n(M->n_gh, L->rec);
    if (!ag || !sb || !rb || na * L->rec > (size_t)INT_MAX || M->n_gh * L->rec > (size_t)INT_MAX)
        rc = spall_error_set(err, SPALL_ERR_NOMEM, "out of memory fetching ghosts");
    if ((rc = par_agree(rc, err)))
        goto out;
    MPI_Alltoallv(qg, qc, qd, MPI_INT64_T, ag, ac, ad, MPI_INT64_T, MPI_COMM_WORLD);
    size_t *send_idx = alloc_n(na, sizeof *send_idx);
    size_t *recv_idx = alloc_n(M->n_gh, sizeof *recv_idx);
    if (!send_idx || !recv_idx)
        rc = spall_error_set(err, SPALL_ERR_NOMEM, "out of memory fetching ghosts");
    for (size_t k = 0; k < na && !rc; k++) {
        int64_t j = mig_find_gid(M->own_gid, M->n_own, ag[k]);
        if (j < 0) {
            rc = spall_error_set(err, SPALL_ERR_INTERNAL,
                                 "migration: asked for particle %lld, not owned here",
                                 (long long)ag[k]);
            break;
        }
        send_idx[k] = (size_t)j;
        mig_pack_rec(L, (size_t)j, sb + k * L->rec);
    }
    if ((rc = par_agree(rc, err))) {
        free(send_idx);
        free(recv_idx);
        goto out;
    }
    for (int r = 0; r < size; r++) { /* in bytes for the records */
        ac[r] *= (int)L->rec;
        ad[r] *= (int)L->rec;
        qc[r] *= (int)L->rec;
        qd[r] *= (int)L->rec;
    }
    MPI_Alltoallv(sb, ac, ad, MPI_BYTE, rb, qc, qd, MPI_BYTE, MPI_COMM_WORLD);
    for (size_t k = 0; k < M->n_gh; k++) {
        mig_unpack_rec(L, qslot[k], rb + k * L->rec);
        recv_idx[k] = qslot[k];
    }
    /* the halo: counts in doubles (positions and velocities) */
    const int w = 2 * M->s->dim;
    for (int r = 0; r < size; r++) {
        d->send_counts[r] = ac[r] / (int)L->rec * w;
        d->send_displs[r] = ad[r] / (int)L->rec * w;
        d->recv_counts[r] = qc[r] / (int)L->rec * w;
        d->recv_displs[r] = qd[r] / (int)L->rec * w;
    }
    free(d->send_idx);
    free(d->recv_idx);
    d->send_idx = send_idx;
    d->recv_idx = recv_idx;
    d->n_send = na;
    d->n_recv = M->n_gh;
    double *s2 = alloc_n(na * (size_t)w, sizeof *s2), *r2 = alloc_n(M->n_gh * (size_t)w, sizeof *r2);
    if (!s2 || !r2) {
        free(s2);
        free(r2);
        rc = spall_error_set(err, SPALL_ERR_NOMEM, "out of memory fetching ghosts");
    } else {
        free(d->sbuf);
        free(d->rbuf);
        d->sbuf = s2;
        d->rbuf = r2;
    }
    d->n_owned = M->n_own;
    d->n_ghost = M->n_gh;
out:
    free(qc);
    free(qd);
    free(ac);
    free(ad);
    free(qg);
    free(qslot);
    free(ag);
    free(sb);
    free(rb);
    return par_agree(rc, err);
}

/* Probes follow their particle: the new owner announces itself. */
static void rebuild_probes(struct mig *M, const int64_t *probe_gid)
{
    struct sim *s = M->s;
    struct par_decomp *d = M->d;
    for (size_t k = 0; k < s->n_probes; k++) {
        int64_t j = mig_find_gid(M->own_gid, M->n_own, probe_gid[k]);
        int owner = j >= 0 ? M->rank : -1;
        int all;
        MPI_Allreduce(&owner, &all, 1, MPI_INT, MPI_MAX, MPI_COMM_WORLD);
        d->probe_owner[k] = all;
        d->probe_local[k] = j >= 0 ? (size_t)j : 0;
        s->probes[k].particle = d->probe_local[k];
    }
}

int mig_rebuild_local(struct mig *M, struct spall_error *err)
{
    struct sim *s = M->s;
    int64_t *pg = alloc_n(s->n_probes, sizeof *pg);
    int rc = pg ? SPALL_OK : spall_error_set(err, SPALL_ERR_NOMEM, "out of memory");
    if ((rc = par_agree(rc, err))) {
        free(pg);
        return rc;
    }
    for (size_t k = 0; k < s->n_probes; k++) {
        int64_t g = M->d->probe_owner[k] == M->rank ? s->p->gid[M->d->probe_local[k]] : -1;
        MPI_Allreduce(&g, &pg[k], 1, MPI_INT64_T, MPI_MAX, MPI_COMM_WORLD);
    }
    /* bonds first: their partners' ids are read through the old gid array */
    rc = rebuild_bonds(M, err);
    if (!rc)
        rc = rebuild_groups(M, err);
    if (!rc)
        rc = rebuild_particles(M, err);
    if ((rc = par_agree(rc, err))) {
        free(pg);
        return rc;
    }
    rc = fetch_ghosts(M, err);
    par_bhalo_free(M->d); /* the per-bond halo's plan is for the old rows */
    if (!rc)
        rebuild_probes(M, pg);
    free(pg);
    return rc;
}

#endif
