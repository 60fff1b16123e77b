/**
 * @file checkpoint_par.c
 * @brief Collective checkpoint of a distributed run (checkpoint.h,
 *        docs/restart.md "Distributed runs").
 *
 * The file has the serial layout of checkpoint.c dataset for dataset, so
 * that a checkpoint does not depend on the rank count that wrote it and a
 * restart may use any rank count (every rank reads it as a serial run does,
 * before the partition).  All ranks open the file through MPI-IO and write
 * collectively, each its owned particles' rows at their global ids:
 *  - particle fields and per-particle state: row g of the serial file is
 *    the particle of global id g;
 *  - per-half-bond state: the owned particles keep their serial bond rows,
 *    in the serial order (core/parallel/decomp.h), so particle g's rows go
 *    to the serial offset of g, the sum of the row lengths of the global
 *    ids below g;
 *  - values that every rank holds alike (time, step, the energy account,
 *    BC accumulators, counters, the deck): written by rank 0.
 * The checksum runs over every dataset in order, which no rank sees alone:
 * rank 0 reads the closed file back, hashes it and adds /checksum, so a
 * file cut short by a crash still lacks it.
 */
#include "io/checkpoint.h"

#include "core/bond_list.h"
#include "core/field_state.h"
#include "core/fields.h"
#include "core/model.h"
#include "core/options.h"
#include "core/parallel/comm.h"
#include "core/parallel/decomp.h"
#include "core/parallel/h5.h"
#include "core/particles.h"
#include "core/sim.h"
#include "spall/error.h"

#include <hdf5.h>
#include <stdlib.h>
#include <string.h>

#define PCK_NAME_LEN (FIELD_STATE_NAME_LEN + FIELD_NAME_LEN + 16)

struct pck_set {
    char name[PCK_NAME_LEN];
    enum field_type type;
};

struct pck {
    hid_t file, dcpl, dxpl;
    const struct sim *s;
    size_t n;          /**< owned particles */
    size_t *ord;       /**< owned local indices by ascending global id */
    uint64_t *soff;    /**< serial half-bond offset of each global id (+1) */
    const struct bond_list *soff_of; /**< the bond list soff was made for */
    struct pck_set *sets; /**< datasets in the order written (the checksum's) */
    size_t n_sets, cap_sets;
    hsize_t *start, *count; /**< this rank's runs of file elements */
    size_t n_runs, cap_runs;
    const char *path;
    struct spall_error *err;
};

/* Append the run [start, start + count) of file elements (merged with the
 * previous one when they touch). */
static int run_add(struct pck *c, size_t start, size_t count)
{
    if (!count)
        return 0;
    if (c->n_runs && c->start[c->n_runs - 1] + c->count[c->n_runs - 1] == start) {
        c->count[c->n_runs - 1] += count;
        return 0;
    }
    if (c->n_runs == c->cap_runs) {
        size_t cap = c->cap_runs ? 2 * c->cap_runs : 256;
        hsize_t *a = realloc(c->start, cap * sizeof *a);
        if (a)
            c->start = a;
        hsize_t *b = a ? realloc(c->count, cap * sizeof *b) : NULL;
        if (!b)
            return -1;
        c->count = b;
        c->cap_runs = cap;
    }
    c->start[c->n_runs] = start;
    c->count[c->n_runs++] = count;
    return 0;
}

/* Create dataset @p name of @p total elements and write this rank's runs
 * (c->start, c->count) from @p data, which holds them one after another. */
static int pck_write(struct pck *c, const char *name, enum field_type t, size_t total,
                     const void *data)
{
    hsize_t dim = total;
    hid_t type = (hid_t)checkpoint_h5_type(t);
    hid_t fspace = H5Screate_simple(1, &dim, NULL);
    hid_t ds = fspace >= 0 ? H5Dcreate2(c->file, name, type, fspace, H5P_DEFAULT, c->dcpl,
                                        H5P_DEFAULT)
                           : -1;
    int bad = ds < 0;
    size_t mine = 0;
    for (size_t k = 0; k < c->n_runs; k++)
        mine += c->count[k];
    /* every rank takes part in the collective write, those without rows too */
    if (!bad && total) {
        hsize_t mdim = mine ? mine : 1;
        hid_t mspace = H5Screate_simple(1, &mdim, NULL);
        bad = mspace < 0;
        if (!bad) {
            hid_t sel = parallel_h5_select_runs(fspace, c->n_runs, c->start, c->count);
            bad = sel < 0;
            if (!bad) {
                H5Sclose(fspace);
                fspace = sel;
            }
        }
        if (!bad && !mine)
            bad = H5Sselect_none(mspace) < 0;
        if (H5Dwrite(ds, type, mspace, fspace, c->dxpl, data) < 0)
            bad = 1;
        if (mspace >= 0)
            H5Sclose(mspace);
    }
    if (ds >= 0)
        H5Dclose(ds);
    if (fspace >= 0)
        H5Sclose(fspace);
    c->n_runs = 0;
    if (bad)
        return spall_error_set(c->err, SPALL_ERR_IO, "cannot write '%s' into checkpoint '%s'",
                               name, c->path);
    if (c->n_sets == c->cap_sets) {
        size_t cap = c->cap_sets ? 2 * c->cap_sets : 64;
        struct pck_set *g = realloc(c->sets, cap * sizeof *g);
        if (!g)
            return spall_error_set(c->err, SPALL_ERR_NOMEM, "out of memory writing a checkpoint");
        c->sets = g;
        c->cap_sets = cap;
    }
    snprintf(c->sets[c->n_sets].name, PCK_NAME_LEN, "%s", name);
    c->sets[c->n_sets++].type = t;
    return SPALL_OK;
}

/* A dataset every rank holds alike: rank 0 writes it. */
static int pck_global(struct pck *c, const char *name, enum field_type t, const void *data,
                      size_t count)
{
    c->n_runs = 0;
    if (par_rank() == 0 && run_add(c, 0, count))
        return spall_error_set(c->err, SPALL_ERR_NOMEM, "out of memory writing a checkpoint");
    return pck_write(c, name, t, count, data);
}

struct gid_at {
    int64_t gid;
    size_t i;
};

static int cmp_gid_at(const void *a, const void *b)
{
    int64_t x = ((const struct gid_at *)a)->gid, y = ((const struct gid_at *)b)->gid;
    return (x > y) - (x < y);
}

/* c->ord: the owned particles by ascending gid (already so after the
 * partition; sorted here so that nothing depends on it). */
static int order_owned(struct pck *c)
{
    const struct particles *p = c->s->p;
    c->n = p->n_owned;
    c->ord = malloc((c->n ? c->n : 1) * sizeof *c->ord);
    if (!c->ord)
        return spall_error_set(c->err, SPALL_ERR_NOMEM, "out of memory (checkpoint order)");
    bool sorted = true;
    for (size_t i = 0; i < c->n; i++) {
        c->ord[i] = i;
        sorted &= i == 0 || p->gid[i] > p->gid[i - 1];
    }
    if (sorted)
        return SPALL_OK;
    struct gid_at *a = malloc(c->n * sizeof *a);
    if (!a)
        return spall_error_set(c->err, SPALL_ERR_NOMEM, "out of memory (checkpoint order)");
    for (size_t i = 0; i < c->n; i++)
        a[i] = (struct gid_at){p->gid[i], i};
    qsort(a, c->n, sizeof *a, cmp_gid_at);
    for (size_t i = 0; i < c->n; i++)
        c->ord[i] = a[i].i;
    free(a);
    return SPALL_OK;
}

/* Per-particle rows (@p width values of @p esize bytes per particle, local
 * order) to their global ids. */
static int pck_particles(struct pck *c, const char *name, enum field_type t, const void *data,
                         size_t width)
{
    const size_t esize = field_state_type_size(t), row = width * esize;
    unsigned char *buf = malloc((c->n ? c->n : 1) * row);
    if (!buf)
        return spall_error_set(c->err, SPALL_ERR_NOMEM, "out of memory writing a checkpoint");
    c->n_runs = 0;
    int bad = 0;
    for (size_t k = 0; k < c->n && !bad; k++) {
        size_t i = c->ord[k];
        memcpy(buf + k * row, (const unsigned char *)data + i * row, row);
        bad = run_add(c, (size_t)c->s->p->gid[i] * width, width);
    }
    int rc = bad ? spall_error_set(c->err, SPALL_ERR_NOMEM, "out of memory writing a checkpoint")
                 : pck_write(c, name, t, par_n_global(c->s) * width, buf);
    free(buf);
    return rc;
}

static int particle_fields(struct pck *c)
{
    const struct field_registry *reg = c->s->fields;
    int rc = SPALL_OK;
    for (size_t k = 0; k < reg->n && !rc; k++) {
        const struct field_desc *f = &reg->fields[k];
        if (!(f->flags & FIELD_RESTART) || f->compute)
            continue;
        size_t sz = field_packed_size(f);
        unsigned char *buf = malloc((c->n ? c->n : 1) * sz);
        if (!buf)
            return spall_error_set(c->err, SPALL_ERR_NOMEM, "out of memory writing a checkpoint");
        for (size_t i = 0; i < c->n; i++) /* local order: pck_particles sorts */
            field_pack(f, i, buf + i * sz);
        char name[PCK_NAME_LEN];
        snprintf(name, sizeof name, "particles/%s", f->name);
        rc = pck_particles(c, name, f->type, buf, (size_t)f->ncomp);
        free(buf);
    }
    return rc;
}

/* Serial offsets of every global id's bond row in @p bl (collective). */
static int serial_offsets(struct pck *c, const struct bond_list *bl)
{
    if (c->soff && c->soff_of == bl)
        return SPALL_OK;
    const size_t ng = par_n_global(c->s);
    free(c->soff);
    c->soff = calloc(ng + 1, sizeof *c->soff);
    if (!c->soff)
        return spall_error_set(c->err, SPALL_ERR_NOMEM, "out of memory (checkpoint bond rows)");
    for (size_t i = 0; i < c->n; i++)
        c->soff[c->s->p->gid[i] + 1] = bl->offset[i + 1] - bl->offset[i];
    par_sum_u64_array(c->soff + 1, ng);
    for (size_t g = 0; g < ng; g++)
        c->soff[g + 1] += c->soff[g];
    c->soff_of = bl;
    return SPALL_OK;
}

static int state_bonds(struct pck *c, const char *name, const struct field_state_slot *sl)
{
    const struct bond_list *bl = sl->bonds;
    int rc = serial_offsets(c, bl);
    if (rc)
        return rc;
    const size_t esize = field_state_type_size(sl->type), w = sl->width;
    const size_t rows = bl->offset[c->n];
    unsigned char *buf = malloc((rows ? rows : 1) * w * esize);
    if (!buf)
        return spall_error_set(c->err, SPALL_ERR_NOMEM, "out of memory writing a checkpoint");
    const unsigned char *src = field_state_slot_data(sl);
    c->n_runs = 0;
    size_t at = 0;
    int bad = 0;
    for (size_t k = 0; k < c->n && !bad; k++) {
        size_t i = c->ord[k], len = bl->offset[i + 1] - bl->offset[i];
        memcpy(buf + at * w * esize, src + bl->offset[i] * w * esize, len * w * esize);
        at += len;
        bad = run_add(c, (size_t)c->soff[c->s->p->gid[i]] * w, len * w);
    }
    rc = bad ? spall_error_set(c->err, SPALL_ERR_NOMEM, "out of memory writing a checkpoint")
             : pck_write(c, name, sl->type, (size_t)c->soff[par_n_global(c->s)] * w, buf);
    free(buf);
    return rc;
}

/* Row offsets of a list (FIELD_STATE_OFFSETS): the serial offset of each
 * owned particle's row at its global id, the total after the last (rank 0). */
static int state_offsets(struct pck *c, const char *name, const struct field_state_slot *sl)
{
    int rc = serial_offsets(c, sl->bonds);
    if (rc)
        return rc;
    const size_t ng = par_n_global(c->s);
    int64_t *buf = malloc((c->n + 1) * sizeof *buf);
    if (!buf)
        return spall_error_set(c->err, SPALL_ERR_NOMEM, "out of memory writing a checkpoint");
    c->n_runs = 0;
    size_t at = 0;
    int bad = 0;
    for (size_t k = 0; k < c->n && !bad; k++) {
        const int64_t g = c->s->p->gid[c->ord[k]];
        buf[at++] = (int64_t)c->soff[g];
        bad = run_add(c, (size_t)g, 1);
    }
    if (!bad && par_rank() == 0) {
        buf[at++] = (int64_t)c->soff[ng];
        bad = run_add(c, ng, 1);
    }
    rc = bad ? spall_error_set(c->err, SPALL_ERR_NOMEM, "out of memory writing a checkpoint")
             : pck_write(c, name, FIELD_I64, ng + 1, buf);
    free(buf);
    return rc;
}

int checkpoint_par_check(const struct field_state *fs, struct spall_error *err)
{
    for (size_t k = 0; k < fs->n; k++)
        if (fs->slots[k].layout == FIELD_STATE_LOCAL)
            return spall_error_set(err, SPALL_ERR_INPUT,
                                   "distributed runs (%d MPI ranks): the restart state '%s' "
                                   "cannot be checkpointed across ranks yet; run on one rank "
                                   "(without mpirun), see docs/restart.md",
                                   par_size(), fs->slots[k].name);
    return SPALL_OK;
}

static int state_slots(struct pck *c, const struct field_state *fs)
{
    int rc = checkpoint_par_check(fs, c->err);
    for (size_t k = 0; k < fs->n && !rc; k++) {
        const struct field_state_slot *sl = &fs->slots[k];
        char name[PCK_NAME_LEN];
        snprintf(name, sizeof name, "state/%s", sl->name);
        switch (sl->layout) {
        case FIELD_STATE_PARTICLE:
            rc = pck_particles(c, name, sl->type, field_state_slot_data(sl), sl->width);
            break;
        case FIELD_STATE_HALF_BOND:
            rc = state_bonds(c, name, sl);
            break;
        case FIELD_STATE_OFFSETS:
            rc = state_offsets(c, name, sl);
            break;
        case FIELD_STATE_GLOBAL:
        case FIELD_STATE_LOCAL:
            rc = pck_global(c, name, sl->type, field_state_slot_data(sl),
                            field_state_slot_rows(sl) * sl->width);
            break;
        }
    }
    return rc;
}

static int header_and_run(struct pck *c, const struct deck *d, const struct checkpoint_meta *m,
                          bool header)
{
    int rc;
    if (header) {
        char *fp = checkpoint_deck_fingerprint(d->root);
        if (!fp)
            return spall_error_set(c->err, SPALL_ERR_NOMEM, "out of memory (deck fingerprint)");
        int64_t version = CHECKPOINT_FORMAT_VERSION;
        const char *model = c->s->ops->name;
        if (!(rc = pck_global(c, "magic", FIELD_U8, CHECKPOINT_MAGIC, strlen(CHECKPOINT_MAGIC))) &&
            !(rc = pck_global(c, "version", FIELD_I64, &version, 1)) &&
            !(rc = pck_global(c, "model", FIELD_U8, model, strlen(model))))
            rc = pck_global(c, "deck", FIELD_U8, fp, strlen(fp));
        free(fp);
        return rc;
    }
    /* the counters are rank 0's: it writes history.csv and the XDMF index */
    int64_t ints[2] = {m->frames, m->history_bytes};
    double dbl[2] = {m->next_frame_t, m->next_ckpt_t};
    if ((rc = pck_global(c, "run/counters", FIELD_I64, ints, 2)) ||
        (rc = pck_global(c, "run/next_times", FIELD_F64, dbl, 2)))
        return rc;
    size_t xl = m->xdmf_len;
    uint64_t len = par_rank() == 0 ? xl : 0;
    par_bcast(&len, sizeof len, 0); /* the dataset's size must agree */
    return pck_global(c, "run/xdmf_grids", FIELD_U8, m->xdmf_grids ? m->xdmf_grids : "",
                      (size_t)len);
}

/* Rank 0, the file closed by all: hash every dataset in the order written
 * and add /checksum (checkpoint.c's reader checks it the same way). */
static int add_checksum(struct pck *c)
{
    hid_t file = H5Fopen(c->path, H5F_ACC_RDWR, H5P_DEFAULT);
    if (file < 0)
        return spall_error_set(c->err, SPALL_ERR_IO, "cannot reopen checkpoint '%s'", c->path);
    uint64_t sum = CHECKPOINT_HASH_SEED;
    int bad = 0;
    for (size_t k = 0; k < c->n_sets && !bad; k++) {
        hid_t ds = H5Dopen2(file, c->sets[k].name, H5P_DEFAULT);
        hid_t sp = ds >= 0 ? H5Dget_space(ds) : -1;
        hssize_t n = sp >= 0 ? H5Sget_simple_extent_npoints(sp) : -1;
        size_t bytes = n > 0 ? (size_t)n * field_state_type_size(c->sets[k].type) : 0;
        void *buf = malloc(bytes ? bytes : 1);
        bad = n < 0 || !buf ||
              (n > 0 && H5Dread(ds, (hid_t)checkpoint_h5_type(c->sets[k].type), H5S_ALL,
                                H5S_ALL, H5P_DEFAULT, buf) < 0);
        if (!bad)
            checkpoint_hash(&sum, buf, bytes);
        free(buf);
        if (sp >= 0)
            H5Sclose(sp);
        if (ds >= 0)
            H5Dclose(ds);
    }
    hsize_t one = 1;
    hid_t space = bad ? -1 : H5Screate_simple(1, &one, NULL);
    hid_t dcpl = H5Pcreate(H5P_DATASET_CREATE);
    hid_t ds = space < 0 || dcpl < 0 || H5Pset_obj_track_times(dcpl, 0) < 0
                   ? -1
                   : H5Dcreate2(file, "checksum", H5T_NATIVE_INT64, space, H5P_DEFAULT, dcpl,
                                H5P_DEFAULT);
    bad = bad || ds < 0 || H5Dwrite(ds, H5T_NATIVE_INT64, H5S_ALL, H5S_ALL, H5P_DEFAULT, &sum) < 0;
    if (ds >= 0)
        H5Dclose(ds);
    if (dcpl >= 0)
        H5Pclose(dcpl);
    if (space >= 0)
        H5Sclose(space);
    bad |= H5Fclose(file) < 0;
    return bad ? spall_error_set(c->err, SPALL_ERR_IO, "cannot complete checkpoint '%s'", c->path)
               : SPALL_OK;
}

static int create_file(struct pck *c)
{
    hid_t fapl = parallel_h5_fapl();
    c->file = fapl < 0 ? -1 : H5Fcreate(c->path, H5F_ACC_TRUNC, H5P_DEFAULT, fapl);
    if (fapl >= 0)
        H5Pclose(fapl);
    c->dxpl = parallel_h5_dxpl();
    c->dcpl = H5Pcreate(H5P_DATASET_CREATE);
    hid_t gcpl = H5Pcreate(H5P_GROUP_CREATE);
    /* no modification times: equal states give equal datasets */
    int bad = c->file < 0 || c->dxpl < 0 || c->dcpl < 0 || gcpl < 0 ||
              H5Pset_obj_track_times(c->dcpl, 0) < 0 || H5Pset_obj_track_times(gcpl, 0) < 0;
    static const char *const groups[] = {"particles", "state", "run"};
    for (int k = 0; k < 3 && !bad; k++) {
        hid_t g = H5Gcreate2(c->file, groups[k], H5P_DEFAULT, gcpl, H5P_DEFAULT);
        bad = g < 0 || H5Gclose(g) < 0;
    }
    if (gcpl >= 0)
        H5Pclose(gcpl);
    return bad ? spall_error_set(c->err, SPALL_ERR_IO, "cannot create checkpoint '%s'", c->path)
               : SPALL_OK;
}

int checkpoint_write_par(const char *path, const struct sim *s, const struct field_state *fs,
                         const struct deck *d, const struct checkpoint_meta *meta,
                         struct spall_error *err)
{
    H5E_auto2_t func;
    void *data;
    H5Eget_auto2(H5E_DEFAULT, &func, &data);
    H5Eset_auto2(H5E_DEFAULT, NULL, NULL);
    struct pck c = {.file = -1, .dcpl = -1, .dxpl = -1, .s = s, .path = path, .err = err};
    /* each failure is agreed before the next collective call, so that no
     * rank waits in HDF5 for one that has given up */
    int rc = par_agree(order_owned(&c), err);
    if (!rc)
        rc = par_agree(create_file(&c), err);
    if (rc)
        goto done;
    if (!(rc = header_and_run(&c, d, meta, true)) && !(rc = particle_fields(&c)) &&
        !(rc = state_slots(&c, fs)))
        rc = header_and_run(&c, d, meta, false);
done:
    if (c.dcpl >= 0)
        H5Pclose(c.dcpl);
    if (c.dxpl >= 0)
        H5Pclose(c.dxpl);
    if (c.file >= 0 && H5Fclose(c.file) < 0 && !rc)
        rc = spall_error_set(err, SPALL_ERR_IO, "cannot close checkpoint '%s'", path);
    rc = par_agree(rc, err);
    if (!rc && par_rank() == 0)
        rc = add_checksum(&c);
    rc = par_agree(rc, err);
    H5Eset_auto2(H5E_DEFAULT, func, data);
    free(c.ord);
    free(c.soff);
    free(c.sets);
    free(c.start);
    free(c.count);
    return rc;
}
