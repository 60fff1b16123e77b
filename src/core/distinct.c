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
#define DISTINCT_MAX_KEY 64

/* FNV-1a over the key's bytes, then a multiplicative mix into the top bits. */
static size_t slot_of(const unsigned char *b, size_t len)
{
    uint64_t h = 0xcbf29ce484222325ull;
    for (size_t i = 0; i < len; i++)
        h = (h ^ b[i]) * 0x100000001b3ull;
    return (size_t)((h * 0x9E3779B97F4A7C15ull) >> (64 - DISTINCT_HASH_BITS));
}

int distinct_index16(distinct_key_fn key, const void *ctx, size_t n, size_t key_size,
                     size_t max_distinct, uint16_t *idx, void **table, size_t *n_distinct,
                     struct spall_error *err)
{
    *table = NULL;
    *n_distinct = 0;
    if (key_size == 0 || key_size > DISTINCT_MAX_KEY || max_distinct > 65536u)
        return spall_error_set(err, SPALL_ERR_INTERNAL, "distinct_index16: key of %zu bytes, "
                               "%zu distinct values", key_size, max_distinct);
    const size_t nslot = (size_t)1 << DISTINCT_HASH_BITS;
    uint32_t *slot = calloc(nslot, sizeof *slot);
    unsigned char *tab = malloc((max_distinct ? max_distinct : 1) * key_size);
    if (!slot || !tab) {
        free(slot);
        free(tab);
        return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory indexing distinct values");
    }
    unsigned char k[DISTINCT_MAX_KEY];
    size_t nt = 0;
    int fits = 1;
    for (size_t q = 0; q < n && fits; q++) {
        key(ctx, q, k);
        size_t h = slot_of(k, key_size);
        while (slot[h] && memcmp(tab + (slot[h] - 1) * key_size, k, key_size) != 0)
            h = (h + 1) & (nslot - 1);
        if (!slot[h]) {
            if (nt == max_distinct) {
                fits = 0;
                break;
            }
            memcpy(tab + nt * key_size, k, key_size);
            slot[h] = (uint32_t)++nt;
        }
        idx[q] = (uint16_t)(slot[h] - 1);
    }
    free(slot);
    void *shrunk = fits ? realloc(tab, (nt ? nt : 1) * key_size) : NULL;
    if (!shrunk) { /* too many distinct keys (or realloc failed: keep the arrays) */
        free(tab);
        return SPALL_OK;
    }
    *table = shrunk;
    *n_distinct = nt;
    return SPALL_OK;
}
