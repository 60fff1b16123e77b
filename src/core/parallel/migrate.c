/**
 * @file migrate.c
 * @brief Migration of owned particles with all their state, then the
 *        ghosts and the halo rebuilt (migrate.h).
 */
#include "core/parallel/migrate.h"
#include "core/parallel/decomp.h"
#include "core/parallel/decomp_internal.h"
#include "core/parallel/migrate_internal.h"

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

static int make_layout(struct sim *s, struct layout *L, struct spall_error *err)
{
    memset(L, 0, sizeof *L);
    if (!s->ops->migrate_arrays)
        return spall_error_set(err, SPALL_ERR_INPUT,
                               "distributed runs: model '%s' cannot migrate particles; leave "
                               "parallel.rebalance_every at 0",
                               s->ops->name);
    int rc = s->ops->migrate_arrays(s->model, &L->ma, err);
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

void mig_pack_rec(const struct layout *L, size_t i, char *buf)
{
    for (size_t k = 0; k < L->sl.n; k++) {
        size_t e = L->sl.esize[k];
        memcpy(buf, (const char *)*L->sl.ptr[k] + i * e, e);
        buf += e;
    }
}

void mig_unpack_rec(const struct layout *L, size_t i, const char *buf)
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
int64_t mig_find_gid(const int64_t *a, size_t n, int64_t g)
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

static int cmp_src(const void *a, const void *b)
{
    const struct src *x = a, *y = b;
    return (x->gid > y->gid) - (x->gid < y->gid);
}

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
    mig_pack_rec(L, i, b);
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
        /* the rest length as stored: a double, or the 16-bit index into the
         * compact table (bond_list_compact_rest; built from the whole body
         * at set-up, the same on every rank) in the slot's first bytes */
        memset(b, 0, sizeof(double));
        if (bl->rest)
            memcpy(b, &bl->rest[q], sizeof(double));
        else if (bl->rest_idx)
            memcpy(b, &bl->rest_idx[q], sizeof(uint16_t));
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
const char *mig_row_of(const struct mig *M, size_t j, size_t *cnt)
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

int64_t mig_partner_gid(const struct mig *M, size_t j, const char *row, size_t q)
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
        mig_row_of(M, j, &c);
        total += c;
    }
    M->gh_gid = malloc((total ? total : 1) * sizeof *M->gh_gid);
    if (!M->gh_gid)
        return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory migrating particles");
    size_t n = 0;
    for (size_t j = 0; j < M->n_own; j++) {
        size_t c;
        const char *row = mig_row_of(M, j, &c);
        for (size_t q = 0; q < c; q++) {
            int64_t g = mig_partner_gid(M, j, row, q);
            if (mig_find_gid(M->own_gid, M->n_own, g) < 0)
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
        rc = mig_rebuild_local(&M, err);
    if (!rc && s->ops->migrated) /* the model's caches of the lent arrays */
        rc = par_agree(s->ops->migrated(s->model, s, err), err);
    mig_free(&M);
    *moved = (unsigned long long)par_sum_u64((uint64_t)out);
    if (!rc)
        s->par->migrated += *moved;
    s->par->layouts++; /* (even after a failure: the local arrays may have changed) */
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
