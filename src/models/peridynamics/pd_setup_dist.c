/**
 * @file pd_setup_dist.c
 * @brief Peridynamics in the distributed set-up (core/parallel/setup_dist.h):
 *        the table of compact families (pd_compact.c) made the same on
 *        every rank.
 *
 * Each rank builds its families from its own window, so its table of
 * distinct (length, coefficient, type) triples lists other rows in another
 * order than its neighbours'; a particle that migrates takes its 16-bit row
 * numbers along, so every rank must read them in one table.  The union of
 * the ranks' tables holds the very doubles each rank built, so each bond
 * keeps its values bit for bit.
 */
#include "models/peridynamics/pd_internal.h"

#include "core/bond_list.h"
#include "core/parallel/setup_dist.h"
#include "spall/error.h"

#include <stdlib.h>
#include <string.h>

/* the row key of pd_compact.c: length, coefficient, type */
#define PD_ROW_KEY (2 * sizeof(double) + 1)

int pd_setup_tables(struct model *m, struct sim *sim, struct spall_error *err)
{
    (void)sim;
    const size_t nk = m->kind ? m->n_kind : 0;
    unsigned char *tab = NULL;
    if (m->kind && !(tab = malloc((nk ? nk : 1) * PD_ROW_KEY)))
        return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory for peridynamic bonds");
    for (size_t q = 0; q < nk; q++) {
        unsigned char *r = tab + q * PD_ROW_KEY;
        memcpy(r, &m->k_rest[q], sizeof(double));
        memcpy(r + sizeof(double), &m->k_coef[q], sizeof(double));
        r[2 * sizeof(double)] = m->k_type[q];
    }
    size_t rows = nk;
    void *t = tab;
    int rc = par_setup_merge_table(&t, PD_ROW_KEY, &rows, m->kind,
                                   m->kind ? m->bl->offset[m->bl->n] : 0, err);
    tab = t;
    if (rc || !m->kind) {
        free(tab);
        return rc;
    }
    double *k_rest = malloc((rows ? rows : 1) * sizeof *k_rest);
    double *k_coef = malloc((rows ? rows : 1) * sizeof *k_coef);
    uint8_t *k_type = malloc((rows ? rows : 1) * sizeof *k_type);
    if (!k_rest || !k_coef || !k_type) {
        free(tab);
        free(k_rest);
        free(k_coef);
        free(k_type);
        return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory for peridynamic bonds");
    }
    for (size_t q = 0; q < rows; q++) {
        const unsigned char *r = tab + q * PD_ROW_KEY;
        memcpy(&k_rest[q], r, sizeof(double));
        memcpy(&k_coef[q], r + sizeof(double), sizeof(double));
        k_type[q] = r[2 * sizeof(double)];
    }
    free(tab);
    free(m->k_rest);
    free(m->k_coef);
    free(m->k_type);
    m->k_rest = k_rest;
    m->k_coef = k_coef;
    m->k_type = k_type;
    m->n_kind = rows;
    return SPALL_OK;
}
