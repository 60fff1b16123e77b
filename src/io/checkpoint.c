/**
 * @file checkpoint.c
 * @brief Checkpoint writer and reader (see checkpoint.h, docs/restart.md).
 *
 * Layout of a checkpoint file (every dataset one-dimensional, native type):
 *   /magic          "spall-checkpoint" (bytes)
 *   /version        format version (int64)
 *   /model          model name (bytes)
 *   /deck           the deck fingerprint (bytes, checkpoint_deck_fingerprint)
 *   /particles/<f>  each FIELD_RESTART field, n x ncomp, in global-id order
 *   /state/<slot>   each slot of the restart state registry
 *   /run/...        history and frame counters, the XDMF grid entries
 *   /checksum       FNV-1a (64 bit) of the bytes of every dataset above, in
 *                   the order written; written last, so a file cut short
 *                   lacks it
 */
#include "io/checkpoint.h"

#include "core/field_state.h"
#include "core/fields.h"
#include "core/model.h"
#include "core/options.h"
#include "core/particles.h"
#include "core/sim.h"
#include "spall/error.h"

#include <hdf5.h>
#include <stdlib.h>
#include <string.h>

#define CKPT_MAGIC CHECKPOINT_MAGIC

int64_t checkpoint_fapl(void)
{
    /* the default driver: serial writes, and every restart's read (a
     * distributed run reads the whole file on each rank before it
     * partitions; its collective writes open files in checkpoint_par.c) */
    return H5Pcreate(H5P_FILE_ACCESS);
}

int64_t checkpoint_h5_type(enum field_type t)
{
    switch (t) {
    case FIELD_F64:
        return H5T_NATIVE_DOUBLE;
    case FIELD_I32:
        return H5T_NATIVE_INT32;
    case FIELD_I64:
        return H5T_NATIVE_INT64;
    case FIELD_U8:
        return H5T_NATIVE_UINT8;
    }
    return H5T_NATIVE_UINT8;
}

void checkpoint_hash(uint64_t *h, const void *data, size_t bytes)
{
    const unsigned char *c = data;
    for (size_t k = 0; k < bytes; k++) {
        *h ^= c[k];
        *h *= 0x100000001b3ULL;
    }
}

struct ck {
    hid_t file;
    hid_t dcpl; /**< write: no modification times, so equal states give equal bytes */
    uint64_t sum;
    const char *path;
    struct spall_error *err;
};

static int ck_write(struct ck *c, const char *name, enum field_type t, const void *data,
                    size_t count)
{
    hsize_t dim = count;
    hid_t space = H5Screate_simple(1, &dim, NULL);
    hid_t ds = space >= 0 ? H5Dcreate2(c->file, name, checkpoint_h5_type(t), space, H5P_DEFAULT, c->dcpl,
                                       H5P_DEFAULT)
                          : -1;
    int bad = ds < 0 || (count && H5Dwrite(ds, checkpoint_h5_type(t), H5S_ALL, H5S_ALL, H5P_DEFAULT, data) < 0);
    if (ds >= 0)
        H5Dclose(ds);
    if (space >= 0)
        H5Sclose(space);
    if (bad)
        return spall_error_set(c->err, SPALL_ERR_IO, "cannot write '%s' into checkpoint '%s'", name,
                               c->path);
    checkpoint_hash(&c->sum, data, count * field_state_type_size(t));
    return SPALL_OK;
}

static int ck_bad(struct ck *c, const char *fmt, const char *a)
{
    char msg[256];
    snprintf(msg, sizeof msg, fmt, a);
    return spall_error_set(c->err, SPALL_ERR_INPUT, "checkpoint '%s': %s", c->path, msg);
}

/** Length of dataset @p name (elements); -1 if absent or unreadable. */
static long long ck_len(struct ck *c, const char *name)
{
    if (H5Lexists(c->file, name, H5P_DEFAULT) <= 0)
        return -1;
    hid_t ds = H5Dopen2(c->file, name, H5P_DEFAULT);
    if (ds < 0)
        return -1;
    hid_t sp = H5Dget_space(ds);
    hsize_t dim = 0;
    long long n = sp >= 0 && H5Sget_simple_extent_ndims(sp) == 1 &&
                          H5Sget_simple_extent_dims(sp, &dim, NULL) == 1
                      ? (long long)dim
                      : -1;
    if (sp >= 0)
        H5Sclose(sp);
    H5Dclose(ds);
    return n;
}

/** Read exactly @p count values of dataset @p name into @p data. */
static int ck_read(struct ck *c, const char *name, enum field_type t, void *data, size_t count)
{
    long long n = ck_len(c, name);
    if (n < 0)
        return ck_bad(c, "'%s' is missing (truncated, or not a spall checkpoint)", name);
    if ((size_t)n != count) {
        char what[160];
        snprintf(what, sizeof what, "'%s' holds %lld values, this run needs %zu", name, n, count);
        return ck_bad(c, "%s", what);
    }
    hid_t ds = H5Dopen2(c->file, name, H5P_DEFAULT);
    int bad = ds < 0 || (count && H5Dread(ds, checkpoint_h5_type(t), H5S_ALL, H5S_ALL, H5P_DEFAULT, data) < 0);
    if (ds >= 0)
        H5Dclose(ds);
    if (bad)
        return ck_bad(c, "'%s' cannot be read (corrupt file)", name);
    checkpoint_hash(&c->sum, data, count * field_state_type_size(t));
    return SPALL_OK;
}

/** Read a byte string dataset into a malloc'd, terminated buffer. */
static int ck_read_text(struct ck *c, const char *name, char **out, size_t *len)
{
    *out = NULL;
    long long n = ck_len(c, name);
    if (n < 0)
        return ck_bad(c, "'%s' is missing (not a spall checkpoint, or truncated)", name);
    char *b = malloc((size_t)n + 1);
    if (!b)
        return spall_error_set(c->err, SPALL_ERR_NOMEM, "out of memory reading a checkpoint");
    int rc = ck_read(c, name, FIELD_U8, b, (size_t)n);
    if (rc) {
        free(b);
        return rc;
    }
    b[n] = '\0';
    *out = b;
    if (len)
        *len = (size_t)n;
    return SPALL_OK;
}

/* Owned particles in global-id order: the file does not depend on how a
 * run (or, later, its ranks) ordered them in memory. */
static int gid_order(const struct particles *p, size_t **out, struct spall_error *err)
{
    size_t n = p->n_owned;
    size_t *o = malloc((n ? n : 1) * sizeof *o);
    if (!o)
        return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory (checkpoint order)");
    /* gids are 0..n-1 in a serial run: the order is their inverse */
    for (size_t i = 0; i < n; i++)
        if (p->gid[i] < 0 || (size_t)p->gid[i] >= n) {
            free(o);
            return spall_error_set(err, SPALL_ERR_INTERNAL,
                                   "particle %zu has global id %lld outside [0, %zu)", i,
                                   (long long)p->gid[i], n);
        }
    for (size_t i = 0; i < n; i++)
        o[p->gid[i]] = i;
    *out = o;
    return SPALL_OK;
}

static int particles_io(struct ck *c, const struct sim *s, bool write)
{
    size_t n = s->p->n_owned, *ord = NULL;
    int rc = gid_order(s->p, &ord, c->err);
    const struct field_registry *reg = s->fields;
    for (size_t k = 0; k < reg->n && !rc; k++) {
        const struct field_desc *f = &reg->fields[k];
        if (!(f->flags & FIELD_RESTART) || f->compute)
            continue;
        size_t sz = field_packed_size(f);
        unsigned char *buf = malloc((n ? n : 1) * sz);
        if (!buf) {
            rc = spall_error_set(c->err, SPALL_ERR_NOMEM, "out of memory writing a checkpoint");
            break;
        }
        char name[FIELD_NAME_LEN + 16];
        snprintf(name, sizeof name, "particles/%s", f->name);
        size_t count = n * (size_t)f->ncomp;
        if (write) {
            for (size_t g = 0; g < n; g++)
                field_pack(f, ord[g], buf + g * sz);
            rc = ck_write(c, name, f->type, buf, count);
        } else if (!(rc = ck_read(c, name, f->type, buf, count))) {
            for (size_t g = 0; g < n; g++)
                field_unpack(f, ord[g], buf + g * sz);
        }
        free(buf);
    }
    free(ord);
    return rc;
}

static int state_io(struct ck *c, const struct field_state *fs, bool write)
{
    int rc = SPALL_OK;
    for (size_t k = 0; k < fs->n && !rc; k++) {
        const struct field_state_slot *sl = &fs->slots[k];
        char name[FIELD_STATE_NAME_LEN + 8];
        snprintf(name, sizeof name, "state/%s", sl->name);
        if (write) {
            size_t count = field_state_slot_rows(sl) * sl->width;
            rc = ck_write(c, name, sl->type, field_state_slot_data(sl), count);
            continue;
        }
        long long len = ck_len(c, name);
        /* A slot the run registers and the file lacks: the model's options
         * differ, or the file predates the slot.  Refused rather than
         * started from zeros or a recomputed value, which would break the
         * bitwise restart silently; the format version stays, as the
         * layout is the same (docs/restart.md, "Bad checkpoints"). */
        if (len < 0)
            return ck_bad(c, "state '%s' is missing: a checkpoint of other model options, or "
                             "of a spall that did not save it yet; continue with that spall "
                             "or rerun from the start", sl->name);
        if ((size_t)len % sl->width)
            return ck_bad(c, "state '%s' is malformed (not a whole number of rows)", sl->name);
        if ((rc = field_state_slot_resize(sl, (size_t)len / sl->width, c->err)))
            return rc;
        rc = ck_read(c, name, sl->type, field_state_slot_data(sl), (size_t)len);
    }
    return rc;
}

static int meta_io(struct ck *c, struct checkpoint_meta *m, bool write)
{
    int64_t ints[2] = {m->frames, m->history_bytes};
    double dbl[2] = {m->next_frame_t, m->next_ckpt_t};
    int rc;
    if (write) {
        if ((rc = ck_write(c, "run/counters", FIELD_I64, ints, 2)) ||
            (rc = ck_write(c, "run/next_times", FIELD_F64, dbl, 2)))
            return rc;
        return ck_write(c, "run/xdmf_grids", FIELD_U8, m->xdmf_grids ? m->xdmf_grids : "",
                        m->xdmf_len);
    }
    if ((rc = ck_read(c, "run/counters", FIELD_I64, ints, 2)) ||
        (rc = ck_read(c, "run/next_times", FIELD_F64, dbl, 2)) ||
        (rc = ck_read_text(c, "run/xdmf_grids", &m->xdmf_owned, &m->xdmf_len)))
        return rc;
    m->xdmf_grids = m->xdmf_owned;
    m->frames = ints[0];
    m->history_bytes = ints[1];
    m->next_frame_t = dbl[0];
    m->next_ckpt_t = dbl[1];
    return SPALL_OK;
}

int checkpoint_write(const char *path, const struct sim *s, const struct field_state *fs,
                     const struct deck *d, const struct checkpoint_meta *meta,
                     struct spall_error *err)
{
    char *fp = checkpoint_deck_fingerprint(d->root);
    if (!fp)
        return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory (deck fingerprint)");
    H5E_auto2_t func;
    void *data;
    H5Eget_auto2(H5E_DEFAULT, &func, &data);
    H5Eset_auto2(H5E_DEFAULT, NULL, NULL);
    hid_t fapl = checkpoint_fapl();
    struct ck c = {.sum = CHECKPOINT_HASH_SEED, .path = path, .err = err, .dcpl = -1};
    c.file = H5Fcreate(path, H5F_ACC_TRUNC, H5P_DEFAULT, fapl);
    H5Pclose(fapl);
    int rc = SPALL_OK;
    if (c.file < 0) {
        rc = spall_error_set(err, SPALL_ERR_IO, "cannot create checkpoint '%s'", path);
        goto done;
    }
    c.dcpl = H5Pcreate(H5P_DATASET_CREATE);
    hid_t gcpl = H5Pcreate(H5P_GROUP_CREATE);
    int gbad = c.dcpl < 0 || gcpl < 0 || H5Pset_obj_track_times(c.dcpl, 0) < 0 ||
               H5Pset_obj_track_times(gcpl, 0) < 0;
    static const char *const groups[] = {"particles", "state", "run"};
    for (int k = 0; k < 3 && !gbad; k++) {
        hid_t g = H5Gcreate2(c.file, groups[k], H5P_DEFAULT, gcpl, H5P_DEFAULT);
        gbad = g < 0 || H5Gclose(g) < 0;
    }
    if (gcpl >= 0)
        H5Pclose(gcpl);
    if (gbad) {
        rc = spall_error_set(err, SPALL_ERR_IO, "cannot write checkpoint '%s'", path);
        goto done;
    }
    int64_t version = CHECKPOINT_FORMAT_VERSION;
    struct checkpoint_meta m = *meta;
    if ((rc = ck_write(&c, "magic", FIELD_U8, CKPT_MAGIC, strlen(CKPT_MAGIC))) ||
        (rc = ck_write(&c, "version", FIELD_I64, &version, 1)) ||
        (rc = ck_write(&c, "model", FIELD_U8, s->ops->name, strlen(s->ops->name))) ||
        (rc = ck_write(&c, "deck", FIELD_U8, fp, strlen(fp))) || (rc = particles_io(&c, s, true)) ||
        (rc = state_io(&c, fs, true)) || (rc = meta_io(&c, &m, true)))
        goto done;
    uint64_t sum = c.sum;
    rc = ck_write(&c, "checksum", FIELD_I64, &sum, 1);
done:
    if (c.dcpl >= 0)
        H5Pclose(c.dcpl);
    if (c.file >= 0 && H5Fclose(c.file) < 0 && !rc)
        rc = spall_error_set(err, SPALL_ERR_IO, "cannot close checkpoint '%s'", path);
    H5Eset_auto2(H5E_DEFAULT, func, data);
    free(fp);
    return rc;
}

/* Length of the key of the fingerprint line at @p line (before '='). */
static size_t key_len(const char *line, size_t len)
{
    const char *eq = memchr(line, '=', len);
    return eq ? (size_t)(eq - line) : len;
}

/* Does fingerprint @p text hold a line with key @p k (length @p kl)? */
static bool has_key(const char *text, const char *k, size_t kl)
{
    for (const char *l = text; *l;) {
        if (!strncmp(l, k, kl) && l[kl] == '=')
            return true;
        const char *e = strchr(l, '\n');
        if (!e)
            break;
        l = e + 1;
    }
    return false;
}

/* Value of key @p k in fingerprint @p text into @p out ("(absent)" if none). */
static void value_of(const char *text, const char *k, size_t kl, char *out, size_t len)
{
    snprintf(out, len, "%s", "(absent)");
    for (const char *l = text; *l;) {
        const char *e = strchr(l, '\n');
        size_t ll = e ? (size_t)(e - l) : strlen(l);
        if (ll > kl && !strncmp(l, k, kl) && l[kl] == '=') {
            snprintf(out, len, "%.*s", (int)(ll - kl - 1), l + kl + 1);
            return;
        }
        if (!e)
            break;
        l = e + 1;
    }
}

/* The first key whose line differs between fingerprints @p a (checkpoint)
 * and @p b (deck now), with both values: a changed value names its key; at
 * an added or removed key the lines shift, so the key one side lacks is
 * named rather than its neighbour. */
static void first_difference(const char *a, const char *b, char *key, size_t klen, char *va,
                             char *vb, size_t vlen)
{
    const char *fa = a, *fb = b;
    key[0] = '\0';
    while (*a || *b) {
        const char *ea = strchr(a, '\n'), *eb = strchr(b, '\n');
        size_t la = ea ? (size_t)(ea - a) : strlen(a), lb = eb ? (size_t)(eb - b) : strlen(b);
        if (la != lb || memcmp(a, b, la) != 0) {
            size_t ka = key_len(a, la), kb = key_len(b, lb);
            const char *k = a;
            size_t kl = ka;
            if (!*a || (*b && !(ka == kb && !memcmp(a, b, ka)) && !has_key(fa, b, kb))) {
                k = b; /* b's key is new (or a has ended) */
                kl = kb;
            }
            snprintf(key, klen, "%.*s", (int)kl, k);
            value_of(fa, k, kl, va, vlen);
            value_of(fb, k, kl, vb, vlen);
            return;
        }
        a += la + (ea ? 1 : 0);
        b += lb + (eb ? 1 : 0);
    }
}

static int check_identity(struct ck *c, const struct sim *s, const struct deck *d)
{
    char *magic = NULL, *model = NULL, *deck = NULL;
    int rc = SPALL_OK;
    if (ck_len(c, "magic") != (long long)strlen(CKPT_MAGIC) ||
        ck_read_text(c, "magic", &magic, NULL) || strcmp(magic, CKPT_MAGIC) != 0) {
        rc = ck_bad(c, "%s", "not a spall checkpoint");
        goto done;
    }
    int64_t version = 0;
    if ((rc = ck_read(c, "version", FIELD_I64, &version, 1)))
        goto done;
    if (version > CHECKPOINT_FORMAT_VERSION || version < 1) {
        char what[160];
        snprintf(what, sizeof what,
                 "format version %lld, this spall reads versions 1 to %d (written by a newer "
                 "spall?)",
                 (long long)version, CHECKPOINT_FORMAT_VERSION);
        rc = ck_bad(c, "%s", what);
        goto done;
    }
    if ((rc = ck_read_text(c, "model", &model, NULL)))
        goto done;
    if (strcmp(model, s->ops->name) != 0) {
        char what[200];
        snprintf(what, sizeof what, "written by a run of model '%.40s', the deck's model is '%s'",
                 model, s->ops->name);
        rc = ck_bad(c, "%s", what);
        goto done;
    }
    if ((rc = ck_read_text(c, "deck", &deck, NULL)))
        goto done;
    char *now = checkpoint_deck_fingerprint(d->root);
    if (!now) {
        rc = spall_error_set(c->err, SPALL_ERR_NOMEM, "out of memory (deck fingerprint)");
        goto done;
    }
    if (strcmp(now, deck) != 0) {
        char key[SPALL_ERROR_KEY_LEN], was[80], is[80];
        first_difference(deck, now, key, sizeof key, was, is, sizeof was);
        rc = spall_error_set_key(c->err, SPALL_ERR_INPUT, key,
                                 "checkpoint '%s': deck key '%s' differs from the checkpointed "
                                 "run ('%s', now '%s'); a restart may change only run.end_time, "
                                 "run.steps, run.threads and output intervals",
                                 c->path, key, was, is);
    }
    free(now);
done:
    free(magic);
    free(model);
    free(deck);
    return rc;
}

int checkpoint_read(const char *path, struct sim *s, const struct field_state *fs,
                    const struct deck *d, struct checkpoint_meta *meta, struct spall_error *err)
{
    memset(meta, 0, sizeof *meta);
    H5E_auto2_t func;
    void *data;
    H5Eget_auto2(H5E_DEFAULT, &func, &data);
    H5Eset_auto2(H5E_DEFAULT, NULL, NULL);
    struct ck c = {.sum = CHECKPOINT_HASH_SEED, .path = path, .err = err, .dcpl = -1};
    int rc = SPALL_OK;
    hid_t fapl = checkpoint_fapl();
    c.file = H5Fis_hdf5(path) > 0 ? H5Fopen(path, H5F_ACC_RDONLY, fapl) : -1;
    H5Pclose(fapl);
    if (c.file < 0) {
        rc = ck_bad(&c, "%s", "not a readable HDF5 file (missing, truncated or corrupt)");
        goto done;
    }
    uint64_t sum = 0;
    if ((rc = check_identity(&c, s, d)))
        goto done;
    if (ck_len(&c, "checksum") != 1) { /* written last: before the state is touched */
        rc = ck_bad(&c, "%s", "has no checksum (incomplete)");
        goto done;
    }
    if ((rc = particles_io(&c, s, false)) || (rc = state_io(&c, fs, false)) ||
        (rc = meta_io(&c, meta, false)))
        goto done;
    uint64_t want = c.sum;
    if ((rc = ck_read(&c, "checksum", FIELD_I64, &sum, 1)))
        goto done;
    if (sum != want)
        rc = ck_bad(&c, "%s", "checksum mismatch (corrupt file)");
done:
    if (c.file >= 0)
        H5Fclose(c.file);
    H5Eset_auto2(H5E_DEFAULT, func, data);
    if (rc) {
        free(meta->xdmf_owned);
        meta->xdmf_owned = NULL;
        meta->xdmf_grids = NULL;
    }
    return rc;
}
