/**
 * @file share.h
 * @brief A small table whose rows are each known to one rank, handed to
 *        every rank inside the time step (issue 22: the mirrored clamp of
 *        SPH, whose clamp particles take the values of their mirror
 *        images, which any rank may own).
 *
 * The bits of each row are copied, never combined, so what a rank computes
 * from the table is what one rank computes from its own arrays.  The cost
 * is the whole table to every rank (an all-gather): meant for tables of a
 * few thousand rows at most, such as a clamp band; gather.h reads whole
 * runs for measurements.
 */
#ifndef SPALL_CORE_PARALLEL_SHARE_H
#define SPALL_CORE_PARALLEL_SHARE_H

#include <stddef.h>

struct spall_error;

/** Row k of a table of @p n rows of @p w doubles (the same n and w on every
 *  rank) into all[k * w ..) on every rank.  This rank knows the @p n_mine
 *  rows rows[q] (values vals[q * w ..)); every row must be known by at
 *  most one rank (a row nobody knows is left as it was in @p all; a row two
 *  ranks know is refused on every rank alike, SPALL_ERR_INTERNAL).
 *  Collective when distributed, errors agreed (out of memory); without MPI
 *  or on one rank a copy. */
int par_share_rows(size_t n, int w, const size_t *rows, size_t n_mine, const double *vals,
                   double *all, struct spall_error *err);

#endif
