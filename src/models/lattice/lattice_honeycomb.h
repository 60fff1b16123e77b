/**
 * @file lattice_honeycomb.h
 * @brief Triple honeycomb lattice (alpha-beta-gamma model, [Wang2010] Fig. 3d;
 *        Ostoja-Starzewski, Appl. Mech. Rev. 55 (2002) 35): the sites of the
 *        triangular lattice, central springs only, but the nearest-neighbour
 *        bonds split into three honeycomb families of stiffness alpha, beta,
 *        gamma by the pair of sublattices they join.
 *
 * Effective 2D moduli per unit thickness (derivation in lattice_honeycomb.c):
 *   kappa t = (alpha + beta + gamma) / (2 sqrt3),
 *   mu t    = 3 sqrt3 / (4 (1/alpha + 1/beta + 1/gamma)),
 * so mu / kappa = (harmonic mean) / (2 arithmetic mean) is in (0, 1/2] and the
 * plane-stress nu = (kappa - mu) / (kappa + mu) is in [1/3, 1).  Not part of
 * the public interface.
 */
#ifndef SPALL_LATTICE_HONEYCOMB_H
#define SPALL_LATTICE_HONEYCOMB_H

#include <stdbool.h>

struct bond_list;
struct lattice_spec;
struct model;
struct particles;
struct sim;
struct spall_error;

/** Family stiffnesses [N/m] for plane-stress E [Pa], nu, thickness t [m]:
 *  k[0] = alpha (the softer family), k[1] = k[2] = beta = gamma.  Refuses
 *  nu outside [1/3, 1) with SPALL_ERR_PHYSICS and the reason (nu within
 *  LATTICE_NU_TOL below 1/3 is taken as 1/3: all three equal). */
int lattice_honeycomb_constants(double E, double nu, double t, double k[3],
                                struct spall_error *err);

/** 2D bulk and shear moduli times thickness [N/m] of families @p k. */
void lattice_honeycomb_moduli(const double k[3], double *kappa_t, double *mu_t);

/** Set the type of every first-shell half-bond to its family 3 - a - b
 *  (a, b the sublattices of its ends, lattice_sublattice on x0). */
void lattice_honeycomb_retype(struct bond_list *bl, const struct particles *p,
                              const struct lattice_spec *spec);

/** Patch test helper: with the particles at an affine state, shift
 *  sublattices 1 and 2 rigidly (sublattice 0 fixed) so that the summed force
 *  on each sublattice's @p inner particles vanishes (Cauchy-Born with
 *  internal relaxation; two Newton steps with a finite-difference Jacobian,
 *  the forces being linear in the shifts at small strain). */
int lattice_honeycomb_relax(struct model *m, struct sim *s, const bool *inner, double h,
                            struct spall_error *err);

#endif
