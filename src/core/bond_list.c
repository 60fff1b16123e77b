/**
 * @file bond_list.c
 * @brief Fixed bond lists in CSR form (see bond_list.h).
 *
 * Bonds come from the cell-list search on the reference positions x0, so
 * rows are sorted ascending by partner; that order is what lets the reverse
 * index use a binary search and keeps the list identical for any thread
 * count.  Every per-bond decision here (rest length, shell, pre-crack cut)
 * is evaluated from the lower index towards the higher one, or with a
 * formula symmetric bit for bit, so both halves of a bond always agree.
 */
#include "core/bond_list.h"

#include "core/distinct.h"

#include "core/geometry.h"
#include "core/neighbor.h"
#include "core/particles.h"
#include "spall/error.h"

#include <math.h>
#include <stdbool.h>
#include <stdlib.h>
#include <string.h>

/** Reference length of i-j; (x_j - x_i)^2 == (x_i - x_j)^2 exactly, so
 *  both halves get the same value. */
static inline double ref_length(const struct particles *p, size_t i, size_t j)
{
    double r2 = 0.0;
    for (int d = 0; d < p->dim; d++) {
        double dx = p->x0[d][j] - p->x0[d][i];
        r2 += dx * dx;
    }
    return sqrt(r2);
}

/** Allocate a list of @p n particles and @p m half-bonds; offset is zeroed. */
static int bond_list_alloc(struct bond_list **out, size_t n, size_t m, bool with_partner,
                           bool with_rest, bool with_type, struct spall_error *err)
{
    struct bond_list *bl = calloc(1, sizeof *bl);
    if (!bl)
        return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory for a bond list");
    bl->n = n;
    size_t mm = m ? m : 1;
    bl->rest = with_rest ? malloc(mm * sizeof *bl->rest) : NULL;
    bl->state = calloc(mm, sizeof *bl->state);
    bl->type = with_type ? calloc(mm, sizeof *bl->type) : NULL;
    if (with_partner) {
        bl->offset = calloc(n + 1, sizeof *bl->offset);
        bl->partner = malloc(mm * sizeof *bl->partner);
    }
    if ((with_rest && !bl->rest) || !bl->state || (with_type && !bl->type) ||
        (with_partner && (!bl->offset || !bl->partner))) {
        bond_list_destroy(&bl);
        return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory for %zu half-bonds", m);
    }
    *out = bl;
    return SPALL_OK;
}

static int search_reference(struct neighbor_list **nl, const struct particles *p, double radius,
                            struct spall_error *err)
{
    if (p->n > (size_t)INT32_MAX)
        return spall_error_set(err, SPALL_ERR_INPUT,
                               "bond list: %zu particles exceed the int32 index range", p->n);
    int rc = neighbor_list_build(nl, p->dim, p->n, p->x0, radius, err);
    if (rc)
        spall_error_prefix(err, "building bonds: ");
    return rc;
}

/** Rest lengths of a built list (partners and offsets set) as doubles. */
static int rest_fill(struct bond_list *bl, const struct particles *p, struct spall_error *err)
{
    const size_t n = bl->n, m = bl->offset[n];
    if (!bl->rest && !(bl->rest = malloc((m ? m : 1) * sizeof *bl->rest)))
        return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory for %zu half-bonds", m);
#pragma omp parallel for schedule(static)
    for (size_t i = 0; i < n; i++)
        for (size_t k = bl->offset[i]; k < bl->offset[i + 1]; k++)
            bl->rest[k] = ref_length(p, i, (size_t)bl->partner[k]);
    return SPALL_OK;
}

/** Rest lengths of a built list (partners and offsets set, rest and
 *  rest_idx NULL) as a 16-bit index into their distinct values, computed
 *  row by row without the 8-byte array: the index and table that
 *  bond_list_compact_rest would make of the doubles (serial, in slot order,
 *  so the table's order is that of bond_list_compact_rest on any thread
 *  count).  More distinct lengths than an index holds: the doubles. */
static int rest_fill_compact(struct bond_list *bl, const struct particles *p,
                             struct spall_error *err)
{
    const size_t n = bl->n, m = bl->offset[n];
    struct distinct16 *d = NULL;
    int rc = distinct16_create(&d, sizeof(double), 65536u, err);
    if (rc)
        return rc;
    uint16_t *idx = malloc((m ? m : 1) * sizeof *idx);
    if (!idx) {
        distinct16_destroy(&d);
        return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory for %zu half-bonds", m);
    }
    bool fits = true;
    for (size_t i = 0; i < n && fits; i++)
        for (size_t k = bl->offset[i]; k < bl->offset[i + 1] && fits; k++) {
            const double r = ref_length(p, i, (size_t)bl->partner[k]);
            unsigned char key[sizeof r];
            memcpy(key, &r, sizeof r);
            const int32_t row = distinct16_add(d, key);
            fits = row >= 0;
            idx[k] = (uint16_t)(fits ? row : 0);
        }
    double *tab = fits ? distinct16_take_table(d, &bl->n_rest) : NULL;
    distinct16_destroy(&d);
    if (tab) {
        bl->rest_idx = idx;
        bl->rest_tab = tab;
        return SPALL_OK;
    }
    free(idx);
    bl->n_rest = 0;
    return rest_fill(bl, p, err);
}

/* bond_list_build(_compact): the neighbour list already is the CSR we
 * need, so the list takes its arrays. */
static int build_radius(struct bond_list **out, const struct particles *p, double radius,
                        bool compact, struct spall_error *err)
{
    *out = NULL;
    struct neighbor_list *nl = NULL;
    int rc = search_reference(&nl, p, radius, err);
    if (rc)
        return rc;
    struct bond_list *bl = NULL;
    /* compact: no types either, the caller (pd_compact_build) keys them */
    rc = bond_list_alloc(&bl, p->n, nl->offset[p->n], false, !compact, !compact, err);
    if (rc) {
        neighbor_list_destroy(&nl);
        return rc;
    }
    bl->offset = nl->offset;
    bl->partner = nl->idx;
    nl->offset = NULL;
    nl->idx = NULL;
    neighbor_list_destroy(&nl);
    if ((rc = compact ? rest_fill_compact(bl, p, err) : rest_fill(bl, p, err))) {
        bond_list_destroy(&bl);
        return rc;
    }
    *out = bl;
    return SPALL_OK;
}

int bond_list_build(struct bond_list **out, const struct particles *p, double radius,
                    struct spall_error *err)
{
    return build_radius(out, p, radius, false, err);
}

int bond_list_build_compact(struct bond_list **out, const struct particles *p, double radius,
                            struct spall_error *err)
{
    return build_radius(out, p, radius, true, err);
}

void bond_list_drop_rest(struct bond_list *bl)
{
    free(bl->rest);
    free(bl->rest_idx);
    free(bl->rest_tab);
    bl->rest = NULL;
    bl->rest_idx = NULL;
    bl->rest_tab = NULL;
    bl->n_rest = 0;
}

int bond_list_expand_rest(struct bond_list *bl, struct spall_error *err)
{
    if (!bl || !bl->rest_idx)
        return SPALL_OK;
    const size_t m = bl->offset[bl->n];
    double *rest = malloc((m ? m : 1) * sizeof *rest);
    if (!rest)
        return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory for %zu rest lengths", m);
    for (size_t k = 0; k < m; k++)
        rest[k] = bl->rest_tab[bl->rest_idx[k]];
    free(bl->rest_idx);
    free(bl->rest_tab);
    bl->rest_idx = NULL;
    bl->rest_tab = NULL;
    bl->n_rest = 0;
    bl->rest = rest;
    return SPALL_OK;
}

/** Shell of a pair at distance r: the first s with r_lo[s] <= r < r_hi[s], or -1. */
static inline int shell_of(double r, int n_shells, const double *r_lo, const double *r_hi)
{
    for (int s = 0; s < n_shells; s++)
        if (r >= r_lo[s] && r < r_hi[s])
            return s;
    return -1;
}

static int build_shells(struct bond_list **out, const struct particles *p, int n_shells,
                        const double *r_lo, const double *r_hi, bool compact,
                        struct spall_error *err)
{
    *out = NULL;
    if (n_shells < 1 || n_shells > 256)
        return spall_error_set(err, SPALL_ERR_INPUT, "bond shells: need 1..256 shells (got %d)",
                               n_shells);
    double r_max = 0.0;
    for (int s = 0; s < n_shells; s++) {
        if (!(r_lo[s] >= 0.0) || !(r_hi[s] > r_lo[s]) || !isfinite(r_hi[s]))
            return spall_error_set(err, SPALL_ERR_INPUT,
                                   "bond shell %d: need 0 <= r_lo < r_hi (got [%g, %g))", s,
                                   r_lo[s], r_hi[s]);
        r_max = fmax(r_max, r_hi[s]);
    }
    /* Search slightly wider so a pair whose rounded distance is just below
     * r_hi is never lost to rounding of the squared comparison. */
    struct neighbor_list *nl = NULL;
    int rc = search_reference(&nl, p, r_max * (1.0 + 1e-12), err);
    if (rc)
        return rc;
    size_t n = p->n;
    size_t *cnt = calloc(n + 1, sizeof *cnt);
    if (!cnt) {
        neighbor_list_destroy(&nl);
        return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory for bond shells");
    }
    /* Pass 1: count bonds kept per row; pass 2: fill (same order, sorted). */
#pragma omp parallel for schedule(static)
    for (size_t i = 0; i < n; i++) {
        size_t m = 0;
        for (size_t k = nl->offset[i]; k < nl->offset[i + 1]; k++)
            m += p->body[i] == p->body[nl->idx[k]] &&
                 shell_of(ref_length(p, i, (size_t)nl->idx[k]), n_shells, r_lo, r_hi) >= 0;
        cnt[i + 1] = m;
    }
    for (size_t i = 0; i < n; i++)
        cnt[i + 1] += cnt[i];
    struct bond_list *bl = NULL;
    rc = bond_list_alloc(&bl, n, cnt[n], true, !compact, true, err);
    if (rc) {
        free(cnt);
        neighbor_list_destroy(&nl);
        return rc;
    }
    memcpy(bl->offset, cnt, (n + 1) * sizeof *cnt);
    free(cnt);
#pragma omp parallel for schedule(static)
    for (size_t i = 0; i < n; i++) {
        size_t w = bl->offset[i];
        for (size_t k = nl->offset[i]; k < nl->offset[i + 1]; k++) {
            double r = ref_length(p, i, (size_t)nl->idx[k]);
            int s = shell_of(r, n_shells, r_lo, r_hi);
            if (s < 0 || p->body[i] != p->body[nl->idx[k]]) /* bonds never cross bodies */
                continue;
            bl->partner[w] = nl->idx[k];
            if (!compact)
                bl->rest[w] = r;
            bl->type[w] = (uint8_t)s;
            w++;
        }
    }
    neighbor_list_destroy(&nl);
    if (compact && (rc = rest_fill_compact(bl, p, err))) {
        bond_list_destroy(&bl);
        return rc;
    }
    *out = bl;
    return SPALL_OK;
}

int bond_list_build_shells(struct bond_list **out, const struct particles *p, int n_shells,
                           const double *r_lo, const double *r_hi, struct spall_error *err)
{
    return build_shells(out, p, n_shells, r_lo, r_hi, false, err);
}

int bond_list_build_shells_compact(struct bond_list **out, const struct particles *p,
                                   int n_shells, const double *r_lo, const double *r_hi,
                                   struct spall_error *err)
{
    return build_shells(out, p, n_shells, r_lo, r_hi, true, err);
}

void bond_list_destroy(struct bond_list **pbl)
{
    if (!pbl || !*pbl)
        return;
    bond_list_replace(*pbl, 0, NULL, NULL, NULL, NULL, NULL, NULL); /* frees the arrays */
    free((*pbl)->rest_tab);
    free(*pbl);
    *pbl = NULL;
}

size_t bond_list_slot(const struct bond_list *bl, size_t j, int32_t who)
{
    size_t a = bl->offset[j], b = bl->offset[j + 1];
    while (a < b) {
        size_t mid = a + (b - a) / 2;
        if (bl->partner[mid] < who)
            a = mid + 1;
        else
            b = mid;
    }
    return (a < bl->offset[j + 1] && bl->partner[a] == who) ? a : SIZE_MAX;
}

int bond_list_build_reverse(struct bond_list *bl, struct spall_error *err)
{
    size_t n = bl->n, m = bl->offset[n];
    size_t *rev = malloc((m ? m : 1) * sizeof *rev);
    if (!rev)
        return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory for %zu reverse slots", m);
    int missing = 0;
#pragma omp parallel for schedule(static) reduction(| : missing)
    for (size_t i = 0; i < n; i++) {
        for (size_t k = bl->offset[i]; k < bl->offset[i + 1]; k++) {
            rev[k] = bond_list_slot(bl, (size_t)bl->partner[k], (int32_t)i);
            missing |= rev[k] == SIZE_MAX;
        }
    }
    if (missing) {
        free(rev);
        return spall_error_set(err, SPALL_ERR_INTERNAL,
                               "bond list is not symmetric: a bond has no reverse half");
    }
    free(bl->reverse);
    bl->reverse = rev;
    return SPALL_OK;
}

size_t bond_list_apply_precrack(struct bond_list *bl, const struct particles *p,
                                const struct precrack *c)
{
    if (!bl || !p || !c)
        return 0;
    size_t n = bl->n, cut = 0;
    int dim = p->dim;
    /* Gather: each row marks only its own slots, evaluating the pair from the
     * lower index to the higher so both halves take the same decision. */
#pragma omp parallel for schedule(dynamic, 1024) reduction(+ : cut)
    for (size_t i = 0; i < n; i++) {
        for (size_t k = bl->offset[i]; k < bl->offset[i + 1]; k++) {
            size_t j = (size_t)bl->partner[k];
            size_t a = i < j ? i : j, b = i < j ? j : i;
            double xa[3] = {0, 0, 0}, xb[3] = {0, 0, 0};
            for (int d = 0; d < dim; d++) {
                xa[d] = p->x0[d][a];
                xb[d] = p->x0[d][b];
            }
            if (precrack_cuts(c, xa, xb)) {
                bl->state[k] |= (uint8_t)(BOND_BROKEN | BOND_PRECUT);
                cut += j > i;
            }
        }
    }
    return cut;
}

size_t bond_list_count(const struct bond_list *bl)
{
    return bl ? bl->offset[bl->n] / 2 : 0;
}

size_t bond_list_count_broken(const struct bond_list *bl)
{
    if (!bl)
        return 0;
    /* Both halves of a bond are broken together (identical decisions from
     * both ends), so half the broken slots is the number of bonds. */
    size_t m = bl->offset[bl->n], broken = 0;
    const uint8_t *st = bl->state;
#pragma omp parallel for schedule(static) reduction(+ : broken)
    for (size_t k = 0; k < m; k++)
        broken += (st[k] & BOND_BROKEN) != 0;
    return broken / 2;
}

size_t bond_list_bytes(const struct bond_list *bl)
{
    if (!bl)
        return 0;
    size_t m = bl->offset[bl->n];
    size_t per = sizeof *bl->partner + sizeof *bl->state + (bl->type ? sizeof *bl->type : 0) +
                 (bl->rest_idx ? sizeof *bl->rest_idx : bl->rest ? sizeof *bl->rest : 0);
    return sizeof *bl + (bl->n + 1) * sizeof *bl->offset + m * per +
           bl->n_rest * sizeof *bl->rest_tab + (bl->reverse ? m * sizeof *bl->reverse : 0);
}

static void rest_key(const void *ctx, size_t k, unsigned char *out)
{
    memcpy(out, &((const double *)ctx)[k], sizeof(double));
}

int bond_list_compact_rest(struct bond_list *bl, struct spall_error *err)
{
    if (!bl || !bl->rest)
        return SPALL_OK;
    const size_t m = bl->offset[bl->n];
    uint16_t *idx = malloc((m ? m : 1) * sizeof *idx);
    if (!idx)
        return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory compacting rest lengths");
    void *tab = NULL;
    size_t nt = 0;
    int rc = distinct_index16(rest_key, bl->rest, m, sizeof(double), 65536u, idx, &tab, &nt, err);
    if (rc || !tab) { /* more distinct values than an index holds: keep the doubles */
        free(idx);
        return rc;
    }
    free(bl->rest);
    bl->rest = NULL;
    bl->rest_idx = idx;
    bl->rest_tab = tab;
    bl->n_rest = nt;
    return SPALL_OK;
}

void *array_gather(const void *a, size_t size, const size_t *idx, size_t n)
{
    unsigned char *out = malloc((n ? n : 1) * size);
    if (!out)
        return NULL;
    const unsigned char *in = a;
    for (size_t k = 0; k < n; k++)
        memcpy(out + k * size, in + idx[k] * size, size);
    return out;
}

void bond_list_replace(struct bond_list *bl, size_t n, size_t *offset, int32_t *partner,
                       double *rest, uint16_t *rest_idx, uint8_t *state, uint8_t *type)
{
    free(bl->offset);
    free(bl->partner);
    free(bl->rest);
    free(bl->rest_idx);
    free(bl->state);
    free(bl->type);
    free(bl->reverse);
    bl->n = n;
    bl->offset = offset;
    bl->partner = partner;
    bl->rest = rest;
    bl->rest_idx = rest_idx;
    bl->state = state;
    bl->type = type;
    bl->reverse = NULL;
    bl->gen++;
}

/* Whether the owned rows keep their old order (keep ascending), which
 * lets every kept row move down in place: its new start is at most its
 * old one.  Both set-ups (decomp.c, setup_dist.c) keep their owned
 * particles in index order; anything else takes a copy. */
static bool rows_ascending(const size_t *keep, size_t n_owned)
{
    for (size_t k = 1; k < n_owned; k++)
        if (keep[k] <= keep[k - 1])
            return false;
    return true;
}

/* Row k of the new list, k < n_owned, is row keep[k] of the old one: copy
 * the rows one after another (the elements of @p size bytes of the old
 * slots old_offset[keep[k]] ..) to @p out, which may be @p a itself when
 * the rows are ascending (each row moves down or stays: memmove). */
static void rows_copy(unsigned char *out, const unsigned char *a, size_t size,
                      const struct bond_rows *r)
{
    size_t w = 0;
    for (size_t k = 0; k < r->n_owned; k++) {
        const size_t i = r->keep[k], len = r->old_offset[i + 1] - r->old_offset[i];
        if (len)
            memmove(out + w * size, a + r->old_offset[i] * size, len * size);
        w += len;
    }
}

void *bond_rows_gather(const struct bond_rows *r, const void *a, size_t size)
{
    unsigned char *out = malloc((r->n_half ? r->n_half : 1) * size);
    if (out)
        rows_copy(out, a, size, r);
    return out;
}

void *bond_rows_take(const struct bond_rows *r, void *a, size_t size)
{
    if (!r->ascending) {
        void *kept = bond_rows_gather(r, a, size);
        if (kept)
            free(a);
        return kept;
    }
    rows_copy(a, a, size, r);
    void *shrunk = realloc(a, (r->n_half ? r->n_half : 1) * size);
    return shrunk ? shrunk : a; /* a failed shrink keeps the larger block */
}

/* bond_rows_take for the list's own arrays (NULL: nothing); *ok false once
 * out of memory (then NULL, and nothing more is done). */
static void *rows_take(void *old, size_t size, const struct bond_rows *r, int *ok)
{
    if (!old || !*ok) {
        free(old);
        return NULL;
    }
    void *kept = bond_rows_take(r, old, size);
    if (!kept) {
        *ok = 0;
        free(old);
    }
    return kept;
}

void bond_rows_free(struct bond_rows *r)
{
    free(r->old_offset);
    r->old_offset = NULL;
}

int bond_list_localize(struct bond_list *bl, const size_t *keep, size_t n_keep, size_t n_owned,
                       const int64_t *new_of_old, struct bond_rows *rows,
                       struct spall_error *err)
{
    size_t nh = 0;
    for (size_t k = 0; k < n_owned; k++)
        nh += bl->offset[keep[k] + 1] - bl->offset[keep[k]];
    size_t *offset = calloc(n_keep + 1, sizeof *offset);
    if (!offset)
        return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory localising bonds");
    *rows = (struct bond_rows){bl->offset, keep, n_owned, nh, rows_ascending(keep, n_owned)};
    bl->offset = NULL; /* the rows' old starts, for the model's arrays */
    int32_t *partner = rows->ascending ? bl->partner : malloc((nh ? nh : 1) * sizeof *partner);
    if (!partner) {
        bl->offset = rows->old_offset;
        rows->old_offset = NULL;
        free(offset);
        return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory localising bonds");
    }
    /* renumbered row by row; in place, each slot is read before a later
     * row's (or its own row's later slot's) write can reach it */
    size_t w = 0;
    for (size_t k = 0; k < n_keep; k++) {
        if (k < n_owned) {
            const size_t i = keep[k];
            for (size_t s = rows->old_offset[i]; s < rows->old_offset[i + 1]; s++, w++)
                partner[w] = (int32_t)new_of_old[bl->partner[s]];
        }
        offset[k + 1] = w;
    }
    /* The old arrays go one by one, each as its kept rows are taken (in
     * place when the rows keep their order, else copied), so that a
     * distributed set-up (each rank holds its window until here) never
     * holds the window's list and the kept one at once.  The rest lengths
     * as they are stored: doubles, the compact index (the table stays: it
     * holds every value a kept index can name) or neither (a model that
     * keeps them elsewhere); type may be NULL likewise.  Out of memory
     * leaves a list the run can only destroy. */
    if (rows->ascending) {
        int32_t *shrunk = realloc(partner, (nh ? nh : 1) * sizeof *partner);
        partner = shrunk ? shrunk : partner;
    } else {
        free(bl->partner);
    }
    bl->partner = NULL;
    free(bl->reverse);
    bl->reverse = NULL;
    int ok = 1;
    double *rest = rows_take(bl->rest, sizeof *rest, rows, &ok);
    uint16_t *ridx = rows_take(bl->rest_idx, sizeof *ridx, rows, &ok);
    uint8_t *state = rows_take(bl->state, sizeof *state, rows, &ok);
    uint8_t *type = rows_take(bl->type, sizeof *type, rows, &ok);
    bl->rest = NULL;
    bl->rest_idx = NULL;
    bl->state = NULL;
    bl->type = NULL;
    if (!ok || !state) {
        free(offset);
        free(partner);
        free(rest);
        free(ridx);
        free(state);
        free(type);
        bond_rows_free(rows);
        return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory localising bonds");
    }
    bond_list_replace(bl, n_keep, offset, partner, rest, ridx, state, type);
    return SPALL_OK;
}
