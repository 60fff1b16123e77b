/**
 * @file profile.h
 * @brief Outer profile of a body of revolution about the z axis (x = y = 0):
 *        the radius at a given height of the deformed configuration, for
 *        the Taylor-bar mushroom (docs/notes/performance-log.md
 *        "Taylor bar accuracy: where the length error comes from").
 *
 * Why a height rather than the impact face: the face radius of the copper
 * bar is set by a lip where the free surface meets the wall, which the FE
 * reference does not converge (validation/fe/taylor_cu: 7.09 -> 7.19 mm
 * for NR = 2 -> 6) and which a particle method resolves even less; 0.5 mm
 * and 1 mm above the wall the FE radius is converged to 0.02-0.04 mm.
 *
 * Measure (particles [0, n_owned)): the outermost particle (largest
 * sqrt(x^2 + y^2); in 2D, an axisymmetric body in the half-plane x = r,
 * y = z, the largest |x| with y as the height) of the band z0 - w <= z < z0
 * and that of the band
 * z0 <= z < z0 + w; the straight line through the two, evaluated at z0
 * (one band empty: the other's radius); plus @p offset, the distance from
 * an outermost particle centre to the surface (dx/2 for a particle that is
 * the centre of a cubic cell of side dx, as the face radius of
 * docs/performance.md).  The interpolation removes the bias of a plain
 * band maximum, which on a surface that narrows with height returns the
 * radius at the band's bottom (up to w dr/dz too wide).
 */
#ifndef SPALL_PROFILE_H
#define SPALL_PROFILE_H

struct particles;
struct spall_error;

/** Outer radius at height @p z0 [m] over bands of half-width @p w > 0 [m]
 *  (see the file comment), plus @p offset [m], into *r.  SPALL_ERR_INPUT
 *  naming z0 and w when w is not positive or no particle lies within
 *  z0 - w <= z < z0 + w. */
int profile_radius(const struct particles *p, double z0, double w, double offset, double *r,
                   struct spall_error *err);

#endif
