/**
 * @file sph_plate_probe.c
 * @brief Diagnostic runs of the sph-plate geometry (docs/validation.md,
 *        sph-plate) that the validation case does not make: the period at
 *        any tip speed, and the static tip deflection under a uniform load
 *        with mass damping, both printing every 1/60 of the run the
 *        smallest neighbour distance (pairing) and the velocity noise near
 *        the clamp (x < 15 mm) and in the bulk.  Not part of the build;
 *        scripts/sph_plate_probe.sh compiles it against build/libspall.a.
 *
 * usage: sph_plate_probe ROWS fixed|mirror|free "MODEL KEYS" period|static
 *                        [TIP_SPEED | GRAVITY] [END_TIME] [DAMPING]
 */
#include "validation/lattice_cases.h"

#include "core/particles.h"
#include "core/sim.h"
#include "spall/error.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define PL 0.2
#define PH 0.02
#define T_THIN 0.25403243479234483 /* thin-plate cantilever period (sph_plate.c) */

/* First cantilever mode (free-free: the free-free mode). */
static double mode(int free_free, double x)
{
    const double kL = free_free ? 4.730040744862704 : 1.875104068711961, k = kL / PL;
    if (free_free) {
        const double sg = (cosh(kL) - cos(kL)) / (sinh(kL) - sin(kL));
        return cosh(k * x) + cos(k * x) - sg * (sinh(k * x) + sin(k * x));
    }
    const double Q = (cos(kL) + cosh(kL)) / (sin(kL) + sinh(kL));
    return x <= 0.0 ? 0.0 : (cos(k * x) - cosh(k * x)) - Q * (sin(k * x) - sinh(k * x));
}

/* Smallest distance / dx of initially adjacent pairs and largest velocity
 * deviation from the mean of the lattice neighbours, near the clamp and in
 * the bulk; brute force (diagnostic only). */
static void diagnose(const struct sim *s, double dx, size_t tip)
{
    const struct particles *p = s->p;
    double dmin[2] = {9, 9}, noise[2] = {0, 0}, xn = 0, yn = 0, xp = 0, yp = 0;
    for (size_t i = 0; i < p->n; i++) {
        if (p->x0[0][i] < 0.0)
            continue;
        const int z = p->x0[0][i] < 0.015 ? 0 : 1;
        double vs[2] = {0, 0};
        int nn = 0;
        for (size_t j = 0; j < p->n; j++) {
            double X = p->x0[0][j] - p->x0[0][i], Y = p->x0[1][j] - p->x0[1][i];
            if (j == i || X * X + Y * Y > 1.01 * dx * dx)
                continue;
            double r = hypot(p->x[0][j] - p->x[0][i], p->x[1][j] - p->x[1][i]) / dx;
            if (r < fmin(dmin[0], dmin[1])) {
                xp = p->x0[0][i];
                yp = p->x0[1][i];
            }
            dmin[z] = fmin(dmin[z], r);
            vs[0] += p->v[0][j];
            vs[1] += p->v[1][j];
            nn++;
        }
        double d = hypot(p->v[0][i] - vs[0] / nn, p->v[1][i] - vs[1] / nn);
        if (z == 0 && d > noise[0]) {
            xn = p->x0[0][i];
            yn = p->x0[1][i];
        }
        noise[z] = fmax(noise[z], d);
    }
    printf("t %.4f tip %+.4e mm  pair min clamp %.3f bulk %.3f (at %.3f %.3f mm)  "
           "v noise clamp %.2e bulk %.2e (at %.3f %.3f mm)\n",
           s->t, (p->x[1][tip] - p->x0[1][tip]) * 1e3, dmin[0], dmin[1], xp * 1e3, yp * 1e3,
           noise[0], noise[1], xn * 1e3, yn * 1e3);
}

int main(int argc, char **argv)
{
    if (argc < 5) {
        fprintf(stderr, "usage: %s ROWS fixed|mirror|free MODEL period|static [V|g] [END] "
                        "[DAMPING]\n", argv[0]);
        return 2;
    }
    const int rows = atoi(argv[1]), ff = !strcmp(argv[2], "free");
    const int mirror = !strcmp(argv[2], "mirror"), stat = !strcmp(argv[4], "static");
    const double par = argc > 5 ? atof(argv[5]) : 0.1, tend = argc > 6 ? atof(argv[6]) : 0.3;
    const double dx = PH / rows;
    char deck[4096], cl[128] = "", load[128] = "", grp[256] = "";
    if (mirror)
        snprintf(cl, sizeof cl, ", clamp: {group: clamp, point: [0, 0], normal: [1, 0]}");
    if (stat)
        snprintf(load, sizeof load, "gravity: [0, %.17g]\ndamping: %g\n", -par,
                 argc > 7 ? atof(argv[7]) : 40.0);
    if (!ff)
        snprintf(grp, sizeof grp, "groups: {clamp: {box: {min: [-1, -1], max: [0, 1]}}}\n"
                                  "boundary_conditions: [{group: clamp, type: fixed}]\n");
    snprintf(deck, sizeof deck,
             "model: {type: sph, plane: strain, %s%s}\n"
             "materials: {rubber: {density: 1000, youngs_modulus: 2.0e6, poisson_ratio: 0.3975}}\n"
             "lattice: {type: square, spacing: %.17g, origin: [%.17g, %.17g], thickness: 1.0}\n"
             "body: {geometry: {box: {min: [%.17g, %.17g], max: [%.17g, %.17g]}}, "
             "material: rubber}\n%s%srun: {end_time: %.17g}\n",
             argv[3], cl, dx, 0.5 * dx, 0.5 * dx, ff ? 0.0 : -0.25 * PL, -0.5 * PH, PL, 0.5 * PH,
             grp, load, tend);
    struct sim *s = NULL;
    struct spall_error err = {0};
    if (vlat_build("sph_plate_probe", deck, &s, &err)) {
        fprintf(stderr, "%s\n", err.msg);
        return 1;
    }
    struct particles *p = s->p;
    size_t tip = 0;
    for (size_t i = 0; i < p->n; i++) {
        if (!stat)
            p->v[1][i] = par * mode(ff, p->x0[0][i]) / mode(ff, PL);
        if (p->x0[0][i] > p->x0[0][tip] ||
            (p->x0[0][i] == p->x0[0][tip] && fabs(p->x0[1][i]) < fabs(p->x0[1][tip])))
            tip = i;
    }
    int rc = sim_initial_forces(s, &err);
    double next = 0.0, prev = 0.0, tprev = 0.0, tdown = NAN, tup = NAN;
    const bool diag = !getenv("NODIAG");
    while (!rc && !sim_done(s) && !isfinite(tup)) {
        if ((rc = sim_step(s, &err)))
            break;
        double u = p->x[1][tip] - p->x0[1][tip];
        if (!stat && s->step > 5) {
            if (prev > 0.0 && u <= 0.0 && !isfinite(tdown))
                tdown = tprev + (s->t - tprev) * prev / (prev - u);
            else if (prev < 0.0 && u >= 0.0 && isfinite(tdown))
                tup = tprev + (s->t - tprev) * (-prev) / (u - prev);
        }
        prev = u;
        tprev = s->t;
        if (diag && s->t >= next) {
            next += tend / 60.0;
            diagnose(s, dx, tip);
        }
    }
    if (rc)
        fprintf(stderr, "%s\n", err.msg);
    else if (!stat)
        printf("PERIOD rows %d T %.5f s (%+.2f %% vs the cantilever's thin-plate %.5f s) "
               "2 x down-crossing %.5f s\n",
               rows, tup, (tup / T_THIN - 1.0) * 100.0, T_THIN, 2.0 * tdown);
    else
        printf("STATIC rows %d tip %.5e m at t = %.3f s\n", rows, p->x[1][tip] - p->x0[1][tip],
               s->t);
    sim_destroy(&s);
    return rc ? 1 : 0;
}
