/**
 * @file macro_slip.h
 * @brief Slip detection on the FCC macro-particle lattice: the centro-symmetry
 *        parameter, the slip vector and the normal of the plane a particle
 *        slipped on, and a count of those normals by crystal plane family.
 *
 * Why: [Saitoh] section 3.2 reports that a compressed rod collapses by slip
 * on FCC (111) planes; these fields say where and on which planes particles
 * slipped (docs/validation.md, macro-rod-large).
 *
 * Definitions (per particle i; X reference positions, x current):
 *  - centro-symmetry (Kelchner, Plimpton & Hamilton 1998): the 12 nearest
 *    current neighbours r_k, the sums |r_a + r_b|^2 of all 66 pairs, the 6
 *    smallest added; divided by r0^2.  0 in a perfect crystal, 1 in an HCP
 *    (stacking-fault) environment (the three smallest sums of a partner
 *    above and one below the fault are r0^2/3 each), >= 1 per missing
 *    partner at a free surface (with fewer than 12 partners each unpaired
 *    one adds r0^2).
 *  - slip vector (Zimmerman, Kelchner, Klein, Hamilton & Foiles 2001):
 *    s_i = -(1/n_s) sum over reference nearest neighbours j with
 *    |(x_j - x_i) - (X_j - X_i)| > thr of that relative displacement.
 *  - slip normal: the unit mean of the reference bonds X_j - X_i of those
 *    same slipped neighbours.  Next to one slipped {111} plane the slipped
 *    partners are the 3 nearest sites of the adjacent (111) layer, whose
 *    mean bond is along the plane normal; zero when partners slipped on
 *    both sides (the particle is then left unclassified).
 */
#ifndef SPALL_MACRO_SLIP_H
#define SPALL_MACRO_SLIP_H

#include <stddef.h>

struct neighbor_list;
struct spall_error;

/** Counts of slipped particles by the family of their slip normal. */
struct macro_slip_stats {
    size_t n;            /**< particles examined */
    size_t n_slipped;    /**< particles with at least one slipped partner */
    size_t n_111[4];     /**< normal within `tol_deg` of (111) (11-1) (1-11) (-111) */
    size_t n_100;        /**< ... of a {100} normal */
    size_t n_110;        /**< ... of a {110} normal */
    size_t n_other;      /**< a normal, none of the above */
    size_t n_unclear;    /**< slipped partners on both sides (mean bond ~ 0) */
    double csp_mean;     /**< mean centro-symmetry of the particles with 12 reference partners */
    size_t n_fault;      /**< of those, centro-symmetry in [0.5, 2): HCP-like (stacking fault) */
};

/** Centro-symmetry / r0^2 of particles [0, n) from the current list @p cur
 *  (partners at any distance; the 12 nearest are used). */
void macro_centro_symmetry(size_t n, double *const x[3], const struct neighbor_list *cur,
                           double r0, double *csp);

/** Slip vector (out 3 per particle, may be NULL), slip normal (3 per
 *  particle, may be NULL) and the number of slipped partners (may be NULL)
 *  from the reference nearest-neighbour list @p ref (built on x0). */
void macro_slip_vectors(size_t n, double *const x[3], double *const x0[3],
                        const struct neighbor_list *ref, double thr, double *slip,
                        double *normal, int *n_slipped);

/** Build both lists for particles [0, n) (reference: x0 within 1.1 r0;
 *  current: x within 1.5 r0), classify every slipped particle's normal
 *  within tol_deg of the {111}, {100}, {110} families.  thr: slip threshold
 *  [m] (0.25 r0 is a good default: a partial Burgers vector is r0/sqrt3). */
int macro_slip_analyse(size_t n, double *const x[3], double *const x0[3], double r0, double thr,
                       double tol_deg, struct macro_slip_stats *out, struct spall_error *err);

#endif
