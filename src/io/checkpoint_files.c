#define _POSIX_C_SOURCE 200809L
/**
 * @file checkpoint_files.c
 * @brief Checkpoint files on disk: the deck keys (`output.checkpoint`), the
 *        deck fingerprint, naming, atomic writes, keep-N and finding the
 *        newest checkpoint of a run directory.
 */
#include "io/checkpoint.h"

#include "core/options.h"
#include "core/parallel/comm.h"
#include "core/sim.h"
#include "spall/error.h"

#include <dirent.h>
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

int checkpoint_parse_options(const struct deck_node *output, struct checkpoint_options *o,
                             struct spall_error *err)
{
    static const char *const keys[] = {"every_time", "every_steps", "every_minutes", "keep", NULL};
    memset(o, 0, sizeof *o);
    o->keep = 2;
    const struct deck_node *c = output ? deck_get(output, "checkpoint") : NULL;
    if (!c)
        return SPALL_OK;
    int rc;
    if ((rc = deck_expect_map(c, "the checkpoint mapping (every_time, every_steps, "
                                 "every_minutes, keep)",
                              err)) ||
        (rc = deck_double_pos(c, "every_time", false, &o->every_time, err)) ||
        (rc = deck_long(c, "every_steps", false, 1, 2000000000L, &o->every_steps, err)) ||
        (rc = deck_double_pos(c, "every_minutes", false, &o->every_minutes, err)) ||
        (rc = deck_long(c, "keep", false, 1, 1000, &o->keep, err)) ||
        (rc = deck_check_unused(c, "output.checkpoint", keys, err)))
        return rc;
    int given = (o->every_time > 0) + (o->every_steps > 0) + (o->every_minutes > 0);
    if (given != 1)
        return deck_error(err, c, "checkpoint needs exactly one of every_time (s), every_steps "
                                  "or every_minutes");
    o->on = true;
    return SPALL_OK;
}

/* ---- fingerprint --------------------------------------------------------- */

/* Keys a restart may change: they decide when to stop and what to write,
 * not the state the run evolves. */
static bool safe_key(const char *path)
{
    static const char *const safe[] = {"run.end_time", "run.steps", "run.threads",
                                       "output.field_interval", "output.field_every",
                                       "output.history_every", "title", "description", NULL};
    for (size_t k = 0; safe[k]; k++)
        if (strcmp(path, safe[k]) == 0)
            return true;
    return strncmp(path, "output.checkpoint", 17) == 0 &&
           (path[17] == '\0' || path[17] == '.');
}

struct text {
    char *s;
    size_t len, cap;
    bool bad;
};

static void text_add(struct text *t, const char *a, size_t la)
{
    if (t->bad)
        return;
    if (t->len + la + 1 > t->cap) {
        size_t cap = 2 * (t->len + la + 1) + 256;
        char *g = realloc(t->s, cap);
        if (!g) {
            t->bad = true;
            return;
        }
        t->s = g;
        t->cap = cap;
    }
    memcpy(t->s + t->len, a, la);
    t->len += la;
    t->s[t->len] = '\0';
}

static void flatten(const struct deck_node *n, char *path, size_t plen, struct text *t)
{
    size_t at = strlen(path);
    if (safe_key(path))
        return;
    if (n->kind == DECK_SCALAR) {
        text_add(t, path, at);
        text_add(t, "=", 1);
        text_add(t, n->scalar, strlen(n->scalar));
        text_add(t, "\n", 1);
        return;
    }
    for (size_t k = 0; k < n->n; k++) {
        if (n->kind == DECK_MAPPING)
            snprintf(path + at, plen - at, "%s%s", at ? "." : "", n->keys[k]);
        else
            snprintf(path + at, plen - at, "[%zu]", k);
        flatten(n->items[k], path, plen, t);
        path[at] = '\0';
    }
    if (n->n == 0) { /* an empty mapping or list is still a value */
        text_add(t, path, at);
        text_add(t, n->kind == DECK_MAPPING ? "={}\n" : "=[]\n", 4);
    }
}

char *checkpoint_deck_fingerprint(const struct deck_node *root)
{
    struct text t = {0};
    text_add(&t, "", 0);
    char path[1024] = "";
    if (root)
        flatten(root, path, sizeof path, &t);
    if (t.bad) {
        free(t.s);
        return NULL;
    }
    return t.s;
}

/* ---- files ---------------------------------------------------------------- */

#define CKPT_PREFIX "checkpoint_"
#define CKPT_SUFFIX ".h5"

/* Step of a complete checkpoint's name, -1 for other names. */
static long name_step(const char *name)
{
    size_t lp = strlen(CKPT_PREFIX), ls = strlen(CKPT_SUFFIX), l = strlen(name);
    if (l <= lp + ls || strncmp(name, CKPT_PREFIX, lp) != 0 || strcmp(name + l - ls, CKPT_SUFFIX))
        return -1;
    long v = 0;
    for (size_t k = lp; k < l - ls; k++) {
        if (name[k] < '0' || name[k] > '9' || v > 100000000000000L)
            return -1;
        v = 10 * v + (name[k] - '0');
    }
    return v;
}

static int cmp_long_desc(const void *a, const void *b)
{
    long x = *(const long *)a, y = *(const long *)b;
    return (x < y) - (x > y);
}

/* Steps of the complete checkpoints in @p dir, newest first. */
static int list_steps(const char *dir, long **out, size_t *n, struct spall_error *err)
{
    *out = NULL;
    *n = 0;
    DIR *dp = opendir(dir);
    if (!dp)
        return spall_error_set(err, SPALL_ERR_INPUT, "cannot read run directory '%s': %s", dir,
                               strerror(errno));
    size_t cap = 0;
    long *v = NULL;
    struct dirent *e;
    int rc = SPALL_OK;
    while ((e = readdir(dp))) {
        long st = name_step(e->d_name);
        if (st < 0)
            continue;
        if (*n == cap) {
            cap = cap ? 2 * cap : 16;
            long *g = realloc(v, cap * sizeof *g);
            if (!g) {
                rc = spall_error_set(err, SPALL_ERR_NOMEM, "out of memory listing '%s'", dir);
                break;
            }
            v = g;
        }
        v[(*n)++] = st;
    }
    closedir(dp);
    if (rc) {
        free(v);
        *n = 0;
        return rc;
    }
    if (*n)
        qsort(v, *n, sizeof *v, cmp_long_desc);
    *out = v;
    return SPALL_OK;
}

static void ckpt_name(char *out, size_t len, const char *dir, long step, bool tmp)
{
    snprintf(out, len, "%s/%s" CKPT_PREFIX "%010ld" CKPT_SUFFIX "%s", dir, tmp ? "." : "", step,
             tmp ? ".tmp" : "");
}

/* The written temporary @p tmp becomes @p final, then all but the newest
 * @p keep complete checkpoints of @p dir are removed. */
static int publish(const char *dir, long keep, const char *tmp, const char *final,
                   struct spall_error *err)
{
    if (rename(tmp, final) != 0) {
        int rc = spall_error_set(err, SPALL_ERR_IO, "cannot rename '%s' to '%s': %s", tmp, final,
                                 strerror(errno));
        remove(tmp);
        return rc;
    }
    /* only now, with the new one complete, drop the oldest */
    long *steps = NULL;
    size_t n = 0;
    int rc = list_steps(dir, &steps, &n, err);
    if (rc)
        return rc;
    for (size_t k = (size_t)keep; k < n; k++) {
        char old[1200];
        ckpt_name(old, sizeof old, dir, steps[k], false);
        remove(old);
    }
    free(steps);
    return SPALL_OK;
}

int checkpoint_save(const char *dir, long keep, const struct sim *s, const struct field_state *fs,
                    const struct deck *d, const struct checkpoint_meta *meta, char *written,
                    size_t len, struct spall_error *err)
{
    char tmp[1200], final[1200];
    ckpt_name(tmp, sizeof tmp, dir, s->step, true);
    ckpt_name(final, sizeof final, dir, s->step, false);
    /* distributed: one file written by all ranks (agreed result), then
     * renamed and rotated by rank 0 alone, the outcome agreed again */
    int rc = s->par ? checkpoint_write_par(tmp, s, fs, d, meta, err)
                    : checkpoint_write(tmp, s, fs, d, meta, err);
    if (par_rank() == 0) {
        if (rc)
            remove(tmp);
        else
            rc = publish(dir, keep, tmp, final, err);
    }
    if (s->par)
        rc = par_agree(rc, err);
    if (!rc && written)
        snprintf(written, len, "%s", final);
    return rc;
}

int checkpoint_locate(const char *arg, char *file, size_t file_len, char *dir, size_t dir_len,
                      struct spall_error *err)
{
    struct stat st;
    if (stat(arg, &st) != 0)
        return spall_error_set(err, SPALL_ERR_INPUT, "--restart '%s': %s", arg, strerror(errno));
    if (S_ISDIR(st.st_mode)) {
        long *steps = NULL;
        size_t n = 0;
        int rc = list_steps(arg, &steps, &n, err);
        if (rc)
            return rc;
        if (n == 0) {
            free(steps);
            return spall_error_set(err, SPALL_ERR_INPUT,
                                   "--restart '%s': the directory holds no checkpoint "
                                   "(checkpoint_*.h5; set output.checkpoint in the deck)",
                                   arg);
        }
        ckpt_name(file, file_len, arg, steps[0], false);
        free(steps);
        snprintf(dir, dir_len, "%s", arg);
        return SPALL_OK;
    }
    snprintf(file, file_len, "%s", arg);
    const char *slash = strrchr(arg, '/');
    if (slash)
        snprintf(dir, dir_len, "%.*s", (int)(slash - arg), arg);
    else
        snprintf(dir, dir_len, ".");
    if (slash == arg)
        snprintf(dir, dir_len, "/");
    return SPALL_OK;
}
