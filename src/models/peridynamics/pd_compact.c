/**
 * @file pd_compact.c
 * @brief Compact families of the bond-based kernel: each half-bond keeps
 *        its partner, its state and a 16-bit row of a table of the distinct
 *        (reference length, coefficient, bond type) triples, instead of an
 *        8-byte length, an 8-byte coefficient and a type byte.  On a
 *        regular lattice of one material a family has a few distinct
 *        lengths, and every particle's rows repeat them: at delta = 3.015 dx
 *        in 3D the family storage falls from 22 to 7 bytes per half-bond.
 *        The table holds the very doubles the arrays held, so every result
 *        stays bit for bit the same.  Formulations with more per-bond data
 *        (lps, eps) and orthotropic laminae (their calibration rebuilds the
 *        coefficients of a built model; the mixed-mode and fiber-plane rules)
 *        keep the arrays, as does a problem with more than 65 535 distinct
 *        triples (e.g. a surface-corrected irregular body).
 */
#include "models/peridynamics/pd_internal.h"

#include "core/bond_list.h"
#include "core/sim.h"
#include "spall/error.h"

#include <stdlib.h>
#include <string.h>

#define PD_KIND_MAX 65535u

struct kind_key {
    uint64_t rest, coef; /* bit patterns */
    uint8_t type;
};

static uint64_t key_hash(const struct kind_key *k)
{
    uint64_t h = k->rest * 0x9E3779B97F4A7C15ull;
    h ^= (k->coef + 0x632BE59BD9B4E019ull) * 0xC2B2AE3D27D4EB4Full;
    h ^= (uint64_t)k->type * 0x165667B19E3779F9ull;
    return h ^ (h >> 29);
}

bool pd_compact_eligible(const struct model *m)
{
    return !m->opt.full_bonds && !m->opt.lps && !m->opt.eps && !m->ortho && !m->mixed &&
           !m->fresh && !m->twin && m->coef && m->bl->rest && m->bl->type;
}

int pd_compact(struct model *m, struct spall_error *err)
{
    struct bond_list *bl = m->bl;
    const size_t nh = bl->offset[bl->n];
    if (!pd_compact_eligible(m) || nh == 0)
        return SPALL_OK;
    /* open addressing, twice the largest table, slots hold kind + 1 */
    const size_t cap = 2u * 65536u;
    uint32_t *slot = calloc(cap, sizeof *slot);
    struct kind_key *keys = malloc(PD_KIND_MAX * sizeof *keys);
    uint16_t *kind = malloc(nh * sizeof *kind);
    if (!slot || !keys || !kind) {
        free(slot);
        free(keys);
        free(kind);
        return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory for peridynamic bonds");
    }
    size_t nk = 0;
    bool fits = true;
    for (size_t s = 0; s < nh && fits; s++) {
        struct kind_key k = {0, 0, bl->type[s]};
        memcpy(&k.rest, &bl->rest[s], sizeof k.rest);
        memcpy(&k.coef, &m->coef[s], sizeof k.coef);
        size_t h = (size_t)(key_hash(&k) & (cap - 1));
        while (slot[h]) {
            const struct kind_key *q = &keys[slot[h] - 1];
            if (q->rest == k.rest && q->coef == k.coef && q->type == k.type)
                break;
            h = (h + 1) & (cap - 1);
        }
        if (!slot[h]) {
            if (nk == PD_KIND_MAX) {
                fits = false; /* keep the arrays */
                break;
            }
            keys[nk] = k;
            slot[h] = (uint32_t)++nk;
        }
        kind[s] = (uint16_t)(slot[h] - 1);
    }
    free(slot);
    double *k_rest = fits ? malloc(nk * sizeof *k_rest) : NULL;
    double *k_coef = fits ? malloc(nk * sizeof *k_coef) : NULL;
    uint8_t *k_type = fits ? malloc(nk * sizeof *k_type) : NULL;
    if (!fits || !k_rest || !k_coef || !k_type) {
        free(keys);
        free(kind);
        free(k_rest);
        free(k_coef);
        free(k_type);
        return fits ? spall_error_set(err, SPALL_ERR_NOMEM, "out of memory for peridynamic bonds")
                    : SPALL_OK;
    }
    for (size_t q = 0; q < nk; q++) {
        memcpy(&k_rest[q], &keys[q].rest, sizeof k_rest[q]);
        memcpy(&k_coef[q], &keys[q].coef, sizeof k_coef[q]);
        k_type[q] = keys[q].type;
    }
    free(keys);
    free(bl->rest);
    free(bl->type);
    free(m->coef);
    bl->rest = NULL;
    bl->type = NULL;
    m->coef = NULL;
    m->kind = kind;
    m->k_rest = k_rest;
    m->k_coef = k_coef;
    m->k_type = k_type;
    m->n_kind = nk;
    return SPALL_OK;
}

size_t pd_model_bytes(const struct model *m, size_t n)
{
    const struct bond_list *bl = m->bl;
    const size_t nh = bl ? bl->offset[bl->n] : 0;
    size_t b = bl ? bond_list_bytes(bl) : 0;
    b += (m->coef ? nh * sizeof(double) : 0) + (m->kind ? nh * sizeof(uint16_t) : 0);
    b += m->n_kind * (2 * sizeof(double) + sizeof(uint8_t));
    b += n * (2 * sizeof(size_t) + sizeof(double)); /* n_init, n_init_f, diss */
    for (int d = 0; d < 3; d++)
        b += m->f_prev[d] ? 2 * n * sizeof(double) : 0;
    return b;
}
