/**
 * @file profile.c
 * @brief Outer radius of a body of revolution at a height (profile.h).
 */
#include "core/profile.h"

#include "core/particles.h"
#include "spall/error.h"

#include <math.h>

int profile_radius(const struct particles *p, double z0, double w, double offset, double *r,
                   struct spall_error *err)
{
    if (!(w > 0.0) || !isfinite(z0))
        return spall_error_set(err, SPALL_ERR_INPUT,
                               "profile radius: height %g m, band half-width %g m; expected a "
                               "finite height and a half-width > 0",
                               z0, w);
    if (p->dim < 2)
        return spall_error_set(err, SPALL_ERR_INPUT,
                               "profile radius: %dD particles; expected 3D, or 2D axisymmetric "
                               "(x = r, y = z)",
                               p->dim);
    /* outermost particle of the band below z0 (k = 0) and above it (k = 1) */
    double rb[2] = {-1.0, -1.0}, zb[2] = {0.0, 0.0};
    /* 3D: the axis is z; 2D: an axisymmetric body in the (r, z) half-plane
     * (sph plane: axisymmetric, x = r >= 0, y = z) */
    const int ax = p->dim == 3 ? 2 : 1;
    for (size_t i = 0; i < p->n_owned; i++) {
        const double z = p->x[ax][i];
        if (!(z >= z0 - w && z < z0 + w))
            continue;
        const int k = z >= z0;
        const double ri = p->dim == 3 ? hypot(p->x[0][i], p->x[1][i]) : fabs(p->x[0][i]);
        if (ri > rb[k]) {
            rb[k] = ri;
            zb[k] = z;
        }
    }
    if (rb[0] < 0.0 && rb[1] < 0.0)
        return spall_error_set(err, SPALL_ERR_INPUT,
                               "profile radius: no particle within %g m of the height %g m "
                               "(a wider band, or a height inside the body)",
                               w, z0);
    double rr;
    if (rb[0] < 0.0)
        rr = rb[1];
    else if (rb[1] < 0.0 || !(zb[1] > zb[0]))
        rr = rb[0];
    else /* the line through (zb0, rb0) and (zb1, rb1) at z0, zb0 < z0 <= zb1 */
        rr = rb[0] + (rb[1] - rb[0]) * (z0 - zb[0]) / (zb[1] - zb[0]);
    *r = rr + offset;
    return SPALL_OK;
}
