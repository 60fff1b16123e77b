/**
 * @file macro_half.h
 * @brief Private interface between the two files of the once-per-pair loop:
 *        macro_half.c (the pair table, pass 1, the drivers) and
 *        macro_half_rows.c (pass 2, the rows' sums, and its slot layout by
 *        groups of four rows).
 */
#ifndef SPALL_MACRO_HALF_H
#define SPALL_MACRO_HALF_H

#include "models/macroparticle/macro_internal.h"

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

struct neighbor_list;


/** Everything one force call shares between the rows. */
struct half_ctx {
    struct model *m;
    const struct macro_pair *w;
    const struct neighbor_list *nl;
    double *const *x, *const *v, *const *f;
    const int64_t *gid;
    int dim;
    size_t n;
    bool plastic;
    bool bounded; /**< 3D: every position (owned and ghost) within +-1e300 */
    bool stress;  /**< form the virial (m->sig): false when nothing reads it after
                       this step (sim.stress_skip); the groups of pass 2 then
                       leave it as it was */
    double mu, sp, g, sg, dt, rlist2;
    uint64_t seed, step;
};

/** Pass 2 of rows [i0, i1): each row's sums over all its slots in list
 *  order, then its outputs (force, energy, virial, dissipation); in 3D the
 *  rows of whole groups of four (rows 4g .. 4g + 3) at once, a row a lane,
 *  through the group layout (macro_half_groups). */
void macro_half_pass2(const struct half_ctx *h, size_t i0, size_t i1);

/** The group layout of the n owned rows of a 3D run from the list and the
 *  slot -> pair index m->pid (after each list change; m->half_pairs set):
 *  for group g its steps [goff[g], goff[g + 1]), step k holding slot k of
 *  each of its four rows, lane by lane (the partner, the pair); a row that
 *  has ended points at itself and at the zero pair, index half_pairs, whose
 *  c and phi stay +0.  Returns false when out of memory (macro_half_free
 *  frees the arrays). */
bool macro_half_groups(struct model *m, size_t n);

/** Whether the three coordinates of particles [i0, i1) lie within +-1e300
 *  (no NaN): pass 2 then need not mask the pair vectors of pairs that add
 *  nothing. */
bool macro_half_bounded(double *const *x, size_t i0, size_t i1);


#endif
