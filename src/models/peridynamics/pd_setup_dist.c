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

int pd_setup_tables(struct model *m, struct sim *sim, struct spall_error *err)
{
    (void)sim;
    const size_t nk = m->kind ? m->n_kind : 0;
    unsigned char *tab = NULL;
    if (m->kind && !(tab = malloc((nk ? nk : 1) * PD_KIND_KEY)))
        return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory for peridynamic bonds");
    for (size_t q = 0; q < nk; q++) {
        unsigned char *r = tab + q * PD_KIND_KEY;
        memcpy(r, &m->k_rest[q], sizeof(double));
        memcpy(r + sizeof(double), &m->k_coef[q], sizeof(double));
        r[2 * sizeof(double)] = m->k_type[q];
    }
    size_t rows = nk;
    void *t = tab;
    int rc = par_setup_merge_table(&t, PD_KIND_KEY, &rows, m->kind,
                                   m->kind ? m->bl->offset[m->bl->n] : 0, err);
    tab = t;
    if (rc || !m->kind) {
        free(tab);
        return rc;
    }
    /* the merged table replaces this rank's own kinds (pd_compact.c) */
    free(m->k_rest);
    free(m->k_coef);
    free(m->k_type);
    m->k_rest = m->k_coef = NULL;
    m->k_type = NULL;
    return pd_kinds_from_table(m, tab, rows, err);
}
