/**
 * @file pen_cavity.c
 * @brief Temporary-cavity diameters from particle positions ([Meng2021] sec.
 *        4.4.2.2, Fig. 4.17-4.19): D1 (empty cavity) and D2 (cavity
 *        including failed particles, which carry no stress) in a slab at a
 *        given depth around the shot line.  Model-independent: it reads
 *        positions, particle spacings and a failed flag, so the SPH runs of
 *        issue 7 (item 3, 4d) can call it on every frame.
 */
#include "core/mathconst.h"
#include "spall/penetration.h"

#include "spall/error.h"

#include <math.h>
#include <stdlib.h>


static int cmp_double(const void *a, const void *b)
{
    const double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}

static double median_diameter(double *r, int k)
{
    qsort(r, (size_t)k, sizeof *r, cmp_double);
    const double m = k % 2 ? r[k / 2] : 0.5 * (r[k / 2 - 1] + r[k / 2]);
    return 2.0 * m;
}

int pen_cavity_diameters(size_t n, const double *x, const double *y, const double *z,
                         const double *dx, const unsigned char *failed,
                         const struct pen_cavity_opts *o, double *d1, double *d2,
                         struct spall_error *err)
{
    const int ns = o->sectors ? o->sectors : 16;
    if (ns < 4 || ns > 4096)
        return spall_error_set(err, SPALL_ERR_INPUT, "cavity: %d sectors; expected 4..4096", ns);
    if (!(o->slab > 0.0) || !isfinite(o->depth) || !isfinite(o->surface))
        return spall_error_set(err, SPALL_ERR_INPUT,
                               "cavity: slab thickness must be > 0 and depth finite");
    double *r_all = malloc(2 * (size_t)ns * sizeof *r_all);
    if (!r_all)
        return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory (cavity sectors)");
    double *r_int = r_all + ns;
    for (int s = 0; s < ns; s++)
        r_all[s] = r_int[s] = INFINITY;
    const double zc = o->surface - o->depth;
    size_t in_slab = 0;
    for (size_t i = 0; i < n; i++) {
        if (fabs(z[i] - zc) > 0.5 * o->slab)
            continue;
        in_slab++;
        const double ax = x[i] - o->axis_x, ay = y[i] - o->axis_y;
        double r = sqrt(ax * ax + ay * ay) - (dx ? 0.5 * dx[i] : 0.0);
        if (r < 0.0)
            r = 0.0;
        int s = (int)floor((atan2(ay, ax) + SPALL_PI) / (2.0 * SPALL_PI) * ns);
        s = s < 0 ? 0 : s >= ns ? ns - 1 : s;
        if (r < r_all[s])
            r_all[s] = r;
        if ((!failed || !failed[i]) && r < r_int[s])
            r_int[s] = r;
    }
    if (in_slab == 0) {
        *d1 = *d2 = 0.0;
    } else {
        *d1 = median_diameter(r_all, ns);
        *d2 = median_diameter(r_int, ns);
    }
    free(r_all);
    return SPALL_OK;
}
