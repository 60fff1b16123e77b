/**
 * @file distinct.c
 * @brief distinct.h: open addressing over 2^17 slots (at most half full
 *        for 2^16 keys), a slot holding the table row + 1.
 */
#include "core/distinct.h"

#include "spall/error.h"

#include <stdlib.h>
#include <string.h>

#define DISTINCT_HASH_BITS 17

struct distinct16 {
    size_t key_size, max, n;
    uint32_t *slot;     /* 2^DISTINCT_HASH_BITS: row + 1, 0 = empty */
    unsigned char *tab; /* max rows of key_size bytes */
};

/* FNV-1a over the key's bytes, then a multiplicative mix into the top bits. */
static size_t slot_of(const unsigned char *b, size_t len)
{
    uint64_t h = 0xcbf29ce484222325ull;
    for (size_t i = 0; i < len; i++)
        h = (h ^ b[i]) * 0x100000001b3ull;
    return (size_t)((h * 0x9E3779B97F4A7C15ull) >> (64 - DISTINCT_HASH_BITS));
}

int distinct16_create(struct distinct16 **out, size_t key_size, size_t max_distinct,
                      struct spall_error *err)
{
    *out = NULL;
    if (key_size == 0 || key_size > DISTINCT_MAX_KEY || max_distinct > 65536u)
        return spall_error_set(err, SPALL_ERR_INTERNAL, "distinct_index16: key of %zu bytes, "
                               "%zu distinct values", key_size, max_distinct);
    struct distinct16 *d = calloc(1, sizeof *d);
    if (d) {
        d->key_size = key_size;
        d->max = max_distinct;
        d->slot = calloc((size_t)1 << DISTINCT_HASH_BITS, sizeof *d->slot);
        d->tab = malloc((max_distinct ? max_distinct : 1) * key_size);
    }
    if (!d || !d->slot || !d->tab) {
        distinct16_destroy(&d);
        return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory indexing distinct values");
    }
    *out = d;
    return SPALL_OK;
}

int32_t distinct16_add(struct distinct16 *d, const unsigned char *key)
{
    const size_t mask = ((size_t)1 << DISTINCT_HASH_BITS) - 1, ks = d->key_size;
    size_t h = slot_of(key, ks);
    while (d->slot[h] && memcmp(d->tab + (d->slot[h] - 1) * ks, key, ks) != 0)
        h = (h + 1) & mask;
    if (!d->slot[h]) {
        if (d->n == d->max)
            return -1;
        memcpy(d->tab + d->n * ks, key, ks);
        d->slot[h] = (uint32_t)++d->n;
    }
    return (int32_t)(d->slot[h] - 1);
}

void *distinct16_take_table(struct distinct16 *d, size_t *n_distinct)
{
    void *shrunk = realloc(d->tab, (d->n ? d->n : 1) * d->key_size);
    if (!shrunk)
        return NULL; /* d->tab stays with d */
    d->tab = NULL;
    *n_distinct = d->n;
    return shrunk;
}

void distinct16_destroy(struct distinct16 **pd)
{
    if (!pd || !*pd)
        return;
    free((*pd)->slot);
    free((*pd)->tab);
    free(*pd);
    *pd = NULL;
}

int distinct_index16(distinct_key_fn key, const void *ctx, size_t n, size_t key_size,
                     size_t max_distinct, uint16_t *idx, void **table, size_t *n_distinct,
                     struct spall_error *err)
{
    *table = NULL;
    *n_distinct = 0;
    struct distinct16 *d = NULL;
    int rc = distinct16_create(&d, key_size, max_distinct, err);
    if (rc)
        return rc;
    unsigned char k[DISTINCT_MAX_KEY];
    int fits = 1;
    for (size_t q = 0; q < n && fits; q++) {
        key(ctx, q, k);
        int32_t row = distinct16_add(d, k);
        fits = row >= 0;
        idx[q] = (uint16_t)(fits ? row : 0);
    }
    /* too many distinct keys (or the shrinking realloc failed): the caller
     * keeps its arrays */
    if (fits)
        *table = distinct16_take_table(d, n_distinct);
    distinct16_destroy(&d);
    return SPALL_OK;
}
