/**
 * @file migrate.c
 * @brief Migration of owned particles with all their state, then the
 *        ghosts and the halo rebuilt (migrate.h).
 */
#include "core/parallel/migrate.h"
#include "core/parallel/decomp.h"
#include "core/parallel/decomp_internal.h"

#include "core/bond_list.h"
#include "core/model.h"
#include "core/parallel/comm.h"
#include "core/particles.h"
#include "core/sim.h"
#include "spall/error.h"

#include <limits.h>
#include <stdlib.h>
#include <string.h>

#ifdef SPALL_HAVE_MPI
#include <mpi.h>
#include <zoltan.h>

/* The layout of one particle's record: the arrays of the engine, the
 * registry and the model (migrate.h), then (migrants only) the group keys
 * and the bond row. */
struct layout {
    struct par_slots sl;     /**< per-particle arrays */
    size_t rec;              /**< bytes of the per-particle arrays */
    struct par_model_arrays ma;
    size_t half;             /**< bytes of one half-bond: partner gid, rest, state, type, model */
    size_t n_groups;
};

static int make_layout(struct sim *s, struct layout *L, struct spall_error *err)
{
    memset(L, 0, sizeof *L);
    if (!s->ops->migrate_arrays)
        return spall_error_set(err, SPALL_ERR_INPUT,
                               "distributed runs: model '%s' cannot migrate particles; leave "
                               "parallel.rebalance_every at 0",
                               s->ops->name);
    int rc = s->ops->migrate_arrays(s->model, &L->ma);
    if (rc)
        return rc;
    if (!L->ma.bl || !L->ma.n_half)
        return spall_error_set(err, SPALL_ERR_INTERNAL, "migration: model '%s' lent no bond list",
                               s->ops->name);
    int bad = par_particle_slots(s, &L->sl);
    for (int k = 0; k < L->ma.n_particle && !bad; k++)
        bad = par_slot_add(&L->sl, L->ma.particle[k], L->ma.particle_size[k]);
    if (bad)
        return spall_error_set(err, SPALL_ERR_INTERNAL, "migration: too many per-particle arrays");
    for (size_t k = 0; k < L->sl.n; k++)
        L->rec += L->sl.esize[k];
    L->half = sizeof(int64_t) + sizeof(double) + 2 * sizeof(uint8_t);
    for (int k = 0; k < L->ma.n_bond; k++)
        L->half += L->ma.bond_size[k];
    L->n_groups = s->n_groups;
    return SPALL_OK;
}

static void pack_rec(const struct layout *L, size_t i, char *buf)
{
    for (size_t k = 0; k < L->sl.n; k++) {
        size_t e = L->sl.esize[k];
        memcpy(buf, (const char *)*L->sl.ptr[k] + i * e, e);
        buf += e;
    }
}

static void unpack_rec(const struct layout *L, size_t i, const char *buf)
{
    for (size_t k = 0; k < L->sl.n; k++) {
        size_t e = L->sl.esize[k];
        memcpy((char *)*L->sl.ptr[k] + i * e, buf, e);
        buf += e;
    }
}

static int cmp_i64(const void *a, const void *b)
{
    int64_t x = *(const int64_t *)a, y = *(const int64_t *)b;
    return (x > y) - (x < y);
}

/* index of @p g in the sorted @p a[0, n), or -1 */
static int64_t find_gid(const int64_t *a, size_t n, int64_t g)
{
    size_t lo = 0, hi = n;
    while (lo < hi) {
        size_t mid = lo + (hi - lo) / 2;
        if (a[mid] < g)
            lo = mid + 1;
        else
            hi = mid;
    }
    return lo < n && a[lo] == g ? (int64_t)lo : -1;
}

/* a new owned particle: from the old local index, or from a received record */
struct src {
    int64_t gid;
    size_t old;        /**< old local index (stayed) */
    const char *rec;   /**< received record (moved in), NULL when stayed */
};

static int cmp_src(const void *a, const void *b)
{
    const struct src *x = a, *y = b;
    return (x->gid > y->gid) - (x->gid < y->gid);
}

struct mig {
    struct sim *s;
    struct par_decomp *d;
    struct layout L;
    int size, rank;
    size_t n_old, n_own_old;
    /* the exchange of migrants (bytes) */
    int *scnt, *sdsp, *rcnt, *rdsp;
    char *sbuf, *rbuf;
    /* the new owned set */
    struct src *own;
    int64_t *own_gid;
    size_t n_own;
    /* the new ghosts (ascending gid) and their owners */
    int64_t *gh_gid;
    int *gh_owner;
    size_t n_gh;
    /* group keys of the old owned particles, n_groups x n_own_old (-1: not a member) */
    int64_t *gkey;
};

static void mig_free(struct mig *M)
{
    free(M->scnt);
    free(M->sdsp);
    free(M->rcnt);
    free(M->rdsp);
    free(M->sbuf);
    free(M->rbuf);
    free(M->own);
    free(M->own_gid);
    free(M->gh_gid);
    free(M->gh_owner);
    free(M->gkey);
}

static size_t row_len(const struct bond_list *bl, size_t i)
{
    return bl->offset[i + 1] - bl->offset[i];
}

static size_t migrant_bytes(const struct mig *M, size_t i)
{
    return M->L.rec + M->L.n_groups * sizeof(int64_t) + sizeof(int64_t) +
           row_len(M->L.ma.bl, i) * M->L.half;
}

static char *pack_migrant(const struct mig *M, size_t i, char *b)
{
    const struct layout *L = &M->L;
    const struct bond_list *bl = L->ma.bl;
    pack_rec(L, i, b);
    b += L->rec;
    for (size_t g = 0; g < L->n_groups; g++) {
        memcpy(b, &M->gkey[g * M->n_own_old + i], sizeof(int64_t));
        b += sizeof(int64_t);
    }
    int64_t cnt = (int64_t)row_len(bl, i);
    memcpy(b, &cnt, sizeof cnt);
    b += sizeof cnt;
    for (size_t q = bl->offset[i]; q < bl->offset[i + 1]; q++) {
        int64_t pg = M->s->p->gid[bl->partner[q]];
        memcpy(b, &pg, sizeof pg);
        b += sizeof pg;
        memcpy(b, &bl->rest[q], sizeof(double));
        b += sizeof(double);
        *b++ = (char)bl->state[q];
        *b++ = (char)(bl->type ? bl->type[q] : 0);
        for (int k = 0; k < L->ma.n_bond; k++) {
            size_t e = L->ma.bond_size[k];
            memcpy(b, (const char *)*L->ma.bond[k] + q * e, e);
            b += e;
        }
    }
    return b;
}

/* The bytes of the migrants, rank-major, in ascending gid. */
static int exchange_migrants(struct mig *M, const int *dest, unsigned long long *moved,
                             struct spall_error *err)
{
    const int size = M->size;
    M->scnt = calloc((size_t)size, sizeof(int));
    M->sdsp = calloc((size_t)size, sizeof(int));
    M->rcnt = calloc((size_t)size, sizeof(int));
    M->rdsp = calloc((size_t)size, sizeof(int));
    if (!M->scnt || !M->sdsp || !M->rcnt || !M->rdsp)
        return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory migrating particles");
    size_t bytes[2] = {0, 0};
    unsigned long long out = 0;
    size_t *per = calloc((size_t)size, sizeof *per);
    if (!per)
        return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory migrating particles");
    for (size_t i = 0; i < M->n_own_old; i++)
        if (dest[i] != M->rank) {
            per[dest[i]] += migrant_bytes(M, i);
            out++;
        }
    for (int r = 0; r < size; r++) {
        if (per[r] > (size_t)INT_MAX - bytes[0]) {
            free(per);
            return spall_error_set(err, SPALL_ERR_INTERNAL,
                                   "migration: more than 2 GB to send at once");
        }
        M->sdsp[r] = (int)bytes[0];
        M->scnt[r] = (int)per[r];
        bytes[0] += per[r];
    }
    free(per);
    M->sbuf = malloc(bytes[0] ? bytes[0] : 1);
    if (!M->sbuf)
        return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory migrating particles");
    for (int r = 0; r < size; r++) {
        char *b = M->sbuf + M->sdsp[r];
        for (size_t i = 0; i < M->n_own_old; i++)
            if (dest[i] == r && r != M->rank)
                b = pack_migrant(M, i, b);
    }
    MPI_Alltoall(M->scnt, 1, MPI_INT, M->rcnt, 1, MPI_INT, MPI_COMM_WORLD);
    for (int r = 0; r < size; r++) {
        M->rdsp[r] = (int)bytes[1];
        bytes[1] += (size_t)M->rcnt[r];
    }
    M->rbuf = malloc(bytes[1] ? bytes[1] : 1);
    if (!M->rbuf || bytes[1] > (size_t)INT_MAX)
        return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory migrating particles");
    MPI_Alltoallv(M->sbuf, M->scnt, M->sdsp, MPI_BYTE, M->rbuf, M->rcnt, M->rdsp, MPI_BYTE,
                  MPI_COMM_WORLD);
    *moved = out;
    return SPALL_OK;
}

/* The new owned set, ascending gid: the particles that stayed and those
 * that arrived. */
static int new_owned(struct mig *M, const int *dest, struct spall_error *err)
{
    const struct layout *L = &M->L;
    size_t stay = 0, in = 0, total_bytes = 0;
    for (size_t i = 0; i < M->n_own_old; i++)
        stay += dest[i] == M->rank;
    for (int r = 0; r < M->size; r++)
        total_bytes += (size_t)M->rcnt[r];
    /* count the arrivals by walking the records */
    for (const char *b = M->rbuf; b < M->rbuf + total_bytes; in++) {
        int64_t cnt;
        memcpy(&cnt, b + L->rec + L->n_groups * sizeof(int64_t), sizeof cnt);
        b += L->rec + L->n_groups * sizeof(int64_t) + sizeof cnt + (size_t)cnt * L->half;
    }
    M->n_own = stay + in;
    M->own = malloc((M->n_own ? M->n_own : 1) * sizeof *M->own);
    M->own_gid = malloc((M->n_own ? M->n_own : 1) * sizeof *M->own_gid);
    if (!M->own || !M->own_gid)
        return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory migrating particles");
    size_t k = 0;
    for (size_t i = 0; i < M->n_own_old; i++)
        if (dest[i] == M->rank)
            M->own[k++] = (struct src){M->s->p->gid[i], i, NULL};
    /* the gid sits in the record at the offset of p->gid among the slots */
    size_t goff = 0;
    for (size_t q = 0; q < L->sl.n && *L->sl.ptr[q] != (void *)M->s->p->gid; q++)
        goff += L->sl.esize[q];
    for (const char *b = M->rbuf; b < M->rbuf + total_bytes;) {
        int64_t cnt, g;
        memcpy(&g, b + goff, sizeof g);
        memcpy(&cnt, b + L->rec + L->n_groups * sizeof(int64_t), sizeof cnt);
        M->own[k++] = (struct src){g, 0, b};
        b += L->rec + L->n_groups * sizeof(int64_t) + sizeof cnt + (size_t)cnt * L->half;
    }
    qsort(M->own, M->n_own, sizeof *M->own, cmp_src);
    for (size_t j = 0; j < M->n_own; j++)
        M->own_gid[j] = M->own[j].gid;
    return SPALL_OK;
}

/* partner gid of half-bond q of new owned particle j (row from either source) */
static const char *row_of(const struct mig *M, size_t j, size_t *cnt)
{
    const struct layout *L = &M->L;
    const struct src *o = &M->own[j];
    if (!o->rec) {
        *cnt = row_len(L->ma.bl, o->old);
        return NULL;
    }
    int64_t c;
    const char *b = o->rec + L->rec + L->n_groups * sizeof(int64_t);
    memcpy(&c, b, sizeof c);
    *cnt = (size_t)c;
    return b + sizeof c;
}

static int64_t partner_gid(const struct mig *M, size_t j, const char *row, size_t q)
{
    if (!row)
        return M->s->p->gid[M->L.ma.bl->partner[M->L.ma.bl->offset[M->own[j].old] + q]];
    int64_t g;
    memcpy(&g, row + q * M->L.half, sizeof g);
    return g;
}

/* The ghosts: partners of the new owned particles held elsewhere, and
 * their owners from a Zoltan distributed directory of the new ownership. */
static int find_ghosts(struct mig *M, struct spall_error *err)
{
    size_t total = 0;
    for (size_t j = 0; j < M->n_own; j++) {
        size_t c;
        row_of(M, j, &c);
        total += c;
    }
    M->gh_gid = malloc((total ? total : 1) * sizeof *M->gh_gid);
    if (!M->gh_gid)
        return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory migrating particles");
    size_t n = 0;
    for (size_t j = 0; j < M->n_own; j++) {
        size_t c;
        const char *row = row_of(M, j, &c);
        for (size_t q = 0; q < c; q++) {
            int64_t g = partner_gid(M, j, row, q);
            if (find_gid(M->own_gid, M->n_own, g) < 0)
                M->gh_gid[n++] = g;
        }
    }
    qsort(M->gh_gid, n, sizeof *M->gh_gid, cmp_i64);
    size_t u = 0;
    for (size_t k = 0; k < n; k++)
        if (u == 0 || M->gh_gid[u - 1] != M->gh_gid[k])
            M->gh_gid[u++] = M->gh_gid[k];
    M->n_gh = u;
    M->gh_owner = malloc((u ? u : 1) * sizeof *M->gh_owner);
    ZOLTAN_ID_TYPE *ids = malloc(((M->n_own > u ? M->n_own : u) + 1) * sizeof *ids);
    int rc = SPALL_OK;
    if (!M->gh_owner || !ids)
        rc = spall_error_set(err, SPALL_ERR_NOMEM, "out of memory migrating particles");
    if ((rc = par_agree(rc, err))) {
        free(ids);
        return rc;
    }
    Zoltan_DD_Directory *dd = NULL;
    int zrc = Zoltan_DD_Create(&dd, MPI_COMM_WORLD, 1, 0, 0, 0, 0);
    if (zrc == ZOLTAN_OK) {
        for (size_t j = 0; j < M->n_own; j++)
            ids[j] = (ZOLTAN_ID_TYPE)M->own_gid[j];
        zrc = Zoltan_DD_Update(dd, ids, NULL, NULL, NULL, (int)M->n_own);
    }
    if (zrc == ZOLTAN_OK) {
        for (size_t k = 0; k < u; k++)
            ids[k] = (ZOLTAN_ID_TYPE)M->gh_gid[k];
        zrc = Zoltan_DD_Find(dd, ids, NULL, NULL, NULL, (int)u, M->gh_owner);
    }
    Zoltan_DD_Destroy(&dd);
    free(ids);
    if (zrc != ZOLTAN_OK)
        rc = spall_error_set(err, SPALL_ERR_INTERNAL, "migration: Zoltan directory failed (%d)",
                             zrc);
    for (size_t k = 0; k < u && !rc; k++)
        if (M->gh_owner[k] < 0 || M->gh_owner[k] >= M->size || M->gh_owner[k] == M->rank)
            rc = spall_error_set(err, SPALL_ERR_INTERNAL,
                                 "migration: no owner found for particle %lld",
                                 (long long)M->gh_gid[k]);
    return par_agree(rc, err);
}

/* The new local arrays: owned [0, n_own) in ascending gid, then the ghosts
 * in ascending gid; bond rows re-resolved to local indices; groups, probes
 * and the halo lists rebuilt. */

static void *alloc_n(size_t n, size_t e)
{
    return malloc((n ? n : 1) * e);
}

static int64_t new_local(const struct mig *M, int64_t g)
{
    int64_t j = find_gid(M->own_gid, M->n_own, g);
    if (j >= 0)
        return j;
    j = find_gid(M->gh_gid, M->n_gh, g);
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
            row_of(M, j, &c);
        nh += c;
        off[j + 1] = nh;
    }
    int32_t *partner = alloc_n(nh, sizeof *partner);
    double *rest = alloc_n(nh, sizeof *rest);
    uint8_t *state = alloc_n(nh, sizeof *state), *type = alloc_n(nh, sizeof *type);
    void *mb[PAR_MIGRATE_MAX_ARRAYS] = {NULL};
    int bad = !partner || !rest || !state || !type;
    for (int k = 0; k < L->ma.n_bond; k++)
        bad |= !(mb[k] = alloc_n(nh, L->ma.bond_size[k]));
    for (size_t j = 0; j < M->n_own && !bad; j++) {
        size_t c;
        const char *row = row_of(M, j, &c);
        for (size_t q = 0; q < c; q++) {
            size_t h = off[j] + q;
            int64_t loc = new_local(M, partner_gid(M, j, row, q));
            bad |= loc < 0;
            partner[h] = (int32_t)loc;
            if (!row) {
                size_t o = bl->offset[M->own[j].old] + q;
                rest[h] = bl->rest[o];
                state[h] = bl->state[o];
                type[h] = bl->type ? bl->type[o] : 0;
                for (int k = 0; k < L->ma.n_bond; k++) {
                    size_t e = L->ma.bond_size[k];
                    memcpy((char *)mb[k] + h * e, (const char *)*L->ma.bond[k] + o * e, e);
                }
            } else {
                const char *b = row + q * L->half + sizeof(int64_t);
                memcpy(&rest[h], b, sizeof(double));
                b += sizeof(double);
                state[h] = (uint8_t)*b++;
                type[h] = (uint8_t)*b++;
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
        free(state);
        free(type);
        for (int k = 0; k < L->ma.n_bond; k++)
            free(mb[k]);
        return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory migrating bonds");
    }
    free(bl->offset);
    free(bl->partner);
    free(bl->rest);
    free(bl->state);
    free(bl->type);
    free(bl->reverse);
    bl->reverse = NULL;
    bl->offset = off;
    bl->partner = partner;
    bl->rest = rest;
    bl->state = state;
    bl->type = type;
    bl->n = n_new;
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
        int64_t j = find_gid(M->own_gid, M->n_own, ag[k]);
        if (j < 0) {
            rc = spall_error_set(err, SPALL_ERR_INTERNAL,
                                 "migration: asked for particle %lld, not owned here",
                                 (long long)ag[k]);
            break;
        }
        send_idx[k] = (size_t)j;
        pack_rec(L, (size_t)j, sb + k * L->rec);
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
        unpack_rec(L, qslot[k], rb + k * L->rec);
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
        int64_t j = find_gid(M->own_gid, M->n_own, probe_gid[k]);
        int owner = j >= 0 ? M->rank : -1;
        int all;
        MPI_Allreduce(&owner, &all, 1, MPI_INT, MPI_MAX, MPI_COMM_WORLD);
        d->probe_owner[k] = all;
        d->probe_local[k] = j >= 0 ? (size_t)j : 0;
        s->probes[k].particle = d->probe_local[k];
    }
}

static int rebuild_local(struct mig *M, struct spall_error *err)
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
    if (!rc)
        rebuild_probes(M, pg);
    free(pg);
    return rc;
}

int par_migrate(struct sim *s, const int *dest, unsigned long long *moved,
                struct spall_error *err)
{
    struct mig M;
    memset(&M, 0, sizeof M);
    M.s = s;
    M.d = s->par;
    M.size = par_size();
    M.rank = par_rank();
    M.n_old = s->p->n;
    M.n_own_old = s->p->n_owned;
    *moved = 0;
    int rc = make_layout(s, &M.L, err);
    if (!rc) {
        M.gkey = malloc((M.L.n_groups * M.n_own_old + 1) * sizeof *M.gkey);
        if (!M.gkey)
            rc = spall_error_set(err, SPALL_ERR_NOMEM, "out of memory migrating particles");
        for (size_t k = 0; k < M.L.n_groups * M.n_own_old && !rc; k++)
            M.gkey[k] = -1;
        for (size_t g = 0; g < M.L.n_groups && !rc; g++)
            for (size_t q = 0; q < s->groups[g].n; q++)
                M.gkey[g * M.n_own_old + s->groups[g].idx[q]] = M.d->group_key[g][q];
    }
    if ((rc = par_agree(rc, err))) {
        mig_free(&M);
        return rc;
    }
    unsigned long long out = 0;
    rc = par_agree(exchange_migrants(&M, dest, &out, err), err);
    if (!rc)
        rc = par_agree(new_owned(&M, dest, err), err);
    if (!rc)
        rc = find_ghosts(&M, err);
    if (!rc)
        rc = rebuild_local(&M, err);
    mig_free(&M);
    *moved = (unsigned long long)par_sum_u64((uint64_t)out);
    if (!rc)
        s->par->migrated += *moved;
    return rc;
}

#else

int par_migrate(struct sim *s, const int *dest, unsigned long long *moved,
                struct spall_error *err)
{
    (void)s;
    (void)dest;
    *moved = 0;
    return spall_error_set(err, SPALL_ERR_INTERNAL, "migration in a build without MPI");
}

#endif
