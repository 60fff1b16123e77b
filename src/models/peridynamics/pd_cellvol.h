/**
 * @file pd_cellvol.h
 * @brief Partial volumes of the cell rule (`model.partial_volume_rule: cell`,
 *        pd_cellvol.c): the fraction of a neighbour's lattice cell inside the
 *        horizon sphere.  Internal to src/models/peridynamics.
 */
#ifndef SPALL_PD_CELLVOL_H
#define SPALL_PD_CELLVOL_H

#include <stddef.h>

#include "core/lattice_gen.h"

struct spall_error;
struct cv_entry;

/** The lattice's cell and the distinct cut offsets met so far (set-up only). */
struct pd_cellvol {
    enum lattice_kind kind;
    int dim;
    double m;          /**< delta / dx */
    double angle;      /**< 2D lattice rotation [rad] */
    double reach;      /**< circumradius of the cell / dx */
    int nc;            /**< nearest-neighbour vectors bounding the cell */
    double nv[12][3];  /**< those unit vectors, in the integration frame */
    double frame[3][3]; /**< rows: the integration frame in the lattice frame */
    double vcell;      /**< the cell's volume / dx^d, as integrated */
    struct cv_entry *tab;
    size_t n, cap;
};

/** Circumradius of the lattice's cell in units of the spacing (0: no cell
 *  rule for that lattice): the family then reaches delta + reach dx. */
double pd_cellvol_reach(enum lattice_kind kind);
/** Set up the cell of @p kind (triangular and square in 2D, sc and fcc in
 *  3D; others refused), for the horizon @p delta_dx = delta / dx. */
int pd_cellvol_init(struct pd_cellvol *c, enum lattice_kind kind, int dim, double delta_dx,
                    double angle, struct spall_error *err);
void pd_cellvol_free(struct pd_cellvol *c);
/** Volume of the cell centred at the origin inside the ball |o + s| <= r
 *  (o, r in units of dx, lattice frame; r = INFINITY: the whole cell), as a
 *  fraction of the cell (of dx^d before the cell's volume is known). */
double pd_cellvol_cut(const struct pd_cellvol *c, const double *o, double r);
/** beta of the bond with reference offset @p e [m] on a lattice of spacing
 *  @p dx: 1 inside, 0 outside, the cut fraction in between. */
int pd_cellvol_beta(struct pd_cellvol *c, const double *e, double dx, double *beta,
                    struct spall_error *err);

#endif
