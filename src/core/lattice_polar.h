/**
 * @file lattice_polar.h
 * @brief Body-fitted fills: concentric rings (2D) and spherical shells (3D)
 *        around the lattice origin, for round bodies (projectiles) whose
 *        surface must not be a staircase.  Sites of one layer own equal
 *        parts of the layer, so the site volume depends on the layer
 *        (lattice_polar_site_volume); only models that take each particle's
 *        own volume can use them (model_ops.particle_volumes).
 */
#ifndef SPALL_LATTICE_POLAR_H
#define SPALL_LATTICE_POLAR_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "core/lattice_gen.h"

struct geom;
struct particles;
struct spall_error;

/** True for LATTICE_RINGS and LATTICE_SHELLS. */
bool lattice_kind_is_polar(enum lattice_kind kind);

/** Append the sites of the rings / shells centred at spec->origin that lie
 *  inside @p region, whose finite bounding box is @p lo .. @p hi, up to
 *  @p limit particles in the run (lattice_fill checks the spec and the
 *  region, then calls this for the polar kinds). */
int lattice_polar_fill(struct particles *p, const struct lattice_spec *spec,
                       const struct geom *region, const double lo[3], const double hi[3],
                       double limit, int32_t material, size_t *n_added, struct spall_error *err);

/** Volume owned by the site at @p pos [m^3]: its layer's area (rings, times
 *  @p thickness) or volume (shells) over the layer's site count. */
double lattice_polar_site_volume(const struct lattice_spec *spec, const double pos[3],
                                 double thickness);

#endif
