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
#include "core/distinct.h"
#include "core/sim.h"
#include "spall/error.h"

#include <stdlib.h>
#include <string.h>

#define PD_KIND_MAX 65535u

/* The key of half-bond k: the bit patterns of its reference length and
 * coefficient, then its type (17 bytes, compared as bytes). */
#define PD_KIND_KEY (2 * sizeof(double) + 1)

static void kind_key(const void *ctx, size_t k, unsigned char *out)
{
    const struct model *m = ctx;
    memcpy(out, &m->bl->rest[k], sizeof(double));
    memcpy(out + sizeof(double), &m->coef[k], sizeof(double));
    out[2 * sizeof(double)] = m->bl->type[k];
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
    uint16_t *kind = malloc(nh * sizeof *kind);
    if (!kind)
        return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory for peridynamic bonds");
    void *tab = NULL;
    size_t nk = 0;
    int rc = distinct_index16(kind_key, m, nh, PD_KIND_KEY, PD_KIND_MAX, kind, &tab, &nk, err);
    if (rc || !tab) { /* more distinct triples than a row index holds: keep the arrays */
        free(kind);
        return rc;
    }
    double *k_rest = malloc(nk * sizeof *k_rest);
    double *k_coef = malloc(nk * sizeof *k_coef);
    uint8_t *k_type = malloc(nk * sizeof *k_type);
    if (!k_rest || !k_coef || !k_type) {
        free(tab);
        free(kind);
        free(k_rest);
        free(k_coef);
        free(k_type);
        return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory for peridynamic bonds");
    }
    for (size_t q = 0; q < nk; q++) {
        const unsigned char *r = (const unsigned char *)tab + q * PD_KIND_KEY;
        memcpy(&k_rest[q], r, sizeof k_rest[q]);
        memcpy(&k_coef[q], r + sizeof(double), sizeof k_coef[q]);
        k_type[q] = r[2 * sizeof(double)];
    }
    free(tab);
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
