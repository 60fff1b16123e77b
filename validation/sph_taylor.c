/**
 * @file sph_taylor.c
 * @brief SPH validation case "sph-taylor-3d": the 4340 steel Taylor bar of
 *        [Meng2021] sec. 3.4.3 (Table 3.6): L0 = 37.97 mm, D0 = 7.595 mm,
 *        181 m/s onto a rigid frictionless wall, Johnson-Cook yield with
 *        plastic-work heating; final length against 34.5 mm (LS-DYNA, the
 *        issue's 2 % target), with the thesis SPH (34.3 mm) and MSPH
 *        (34.7 mm) values and the mushroom radius reported; the full case
 *        also runs the bar with a power-law yield of the same constants
 *        against a converged FE run of that material (length and the
 *        radius 0.5 mm above the face, validation/fe/taylor_4340).
 *
 * The rod is a simple-cubic lattice with dx = D0 / n (n particles across)
 * and exactly 5 n particles along (L0 / D0 = 5.0); a convergence series
 * n = 8, 12, 16 is run in the full suite (the printed dx = 3.88 mm of the
 * thesis cannot resolve the rod).  Melting temperature: 1793 K (4340 steel,
 * Johnson & Cook 1985) instead of the printed 1293 K.  Linear EOS with
 * K = 169.1 GPa (pressures stay below 2 GPa at 181 m/s).
 * The bar is a quarter model (x, y >= 0, mirror planes x = 0 and y = 0,
 * sph_symmetry.c): same result as the full bar to round-off, 1/4 the cost.
 * Final length = the bar's axial extent at 90 us: it rebounds from the
 * wall at ~19 m/s after ~35 us, so the position of its top alone (used
 * before) overstated the length by up to 3.5 %.
 */
#include "validation/lattice_cases.h"
#include "validation/sph_cases.h"
#include "validation/validation.h"
#include "validation/vpar.h"

#include "core/particles.h"
#include "core/profile.h"
#include "core/sim.h"
#include "core/model.h"
#include "spall/error.h"

#include <math.h>
#include <omp.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Finite-element reference of the bar with the power-law yield of the
 * same constants, isothermal and rate-independent (validation/fe/
 * taylor_4340/README.md: CalculiX C3D20R axisymmetric wedge, NR = 2, 3,
 * 4): final length at rest and the outer radius 0.5 mm above the face. */
#define T3D_FE_L 34.09e-3
#define T3D_FE_R05 4.94e-3

/** Run the bar with @p n particles across (a quarter with mirror planes
 *  x = 0 and y = 0 when @p quarter); final length, face radius and the
 *  outer radius 0.5 mm above the face [m] (@p r05 may be NULL).
 *  @p power_law: the yield sigma_y = a + b eps_p^n of the same constants
 *  without rate and temperature terms (the FE reference's material)
 *  instead of Johnson-Cook. */
int sph_taylor3d_run(struct vreport *r, int n, bool quarter, bool power_law, double *len,
                     double *rad, double *r05, size_t *np, double *secs, struct spall_error *err)
{
    const double D0 = 7.595e-3, dx = D0 / n, L0 = 5.0 * D0;
    char deck[3072], geom[512];
    if (quarter)
        snprintf(geom, sizeof geom,
                 "{intersection: [{cylinder: {base: [0, 0, 0], top: [0, 0, %.17g], radius: "
                 "%.17g}}, {box: {min: [0, 0, -1], max: [1, 1, 1]}}]}",
                 L0, 0.5 * D0);
    else
        snprintf(geom, sizeof geom,
                 "{cylinder: {base: [0, 0, 0], top: [0, 0, %.17g], radius: %.17g}}", L0,
                 0.5 * D0);
    snprintf(deck, sizeof deck,
             "model: {type: sph, kernel: wendland, h_factor: 1.5, viscosity: [1.5, 1.5],\n"
             "        xsph: 0.1, wall: {point: [0, 0, 0], normal: [0, 0, 1]}, symmetry: %s}\n"
             "materials:\n"
             "  steel4340: {density: 7830, bulk_modulus: 169.1e9, shear_modulus: 89.2e9,\n"
             "              yield: %s, yield_a: 792.0e6, yield_b: 510.0e6,\n"
             "              yield_n: 0.26%s}\n"
             "lattice: {type: sc, spacing: %.17g, origin: [%.17g, %.17g, %.17g]}\n"
             "body: {geometry: %s, material: steel4340}\n"
             "initial_velocity: [{group: all, value: [0, 0, -181.0]}]\n"
             "run: {end_time: 9.0e-5, dt_factor: 0.3}\n",
             quarter ? "xy" : "none", power_law ? "power" : "johnson_cook",
             power_law ? ""
                       : ", jc_c: 0.014, jc_m: 1.03, melt_temperature: 1793,\n"
                         "              room_temperature: 293, reference_strain_rate: 1.0,\n"
                         "              specific_heat: 477, taylor_quinney: 0.9",
             dx, 0.5 * dx, 0.5 * dx, 0.5 * dx, geom);
    struct sim *s = NULL;
    int rc = vlat_build("sph_taylor3d", deck, &s, err);
    if (!rc && (rc = vpar_distribute(r, s, err))) /* mpirun: the bar's shape by global id below */
        sim_destroy(&s);
    if (rc)
        return rc;
    double t0 = omp_get_wtime();
    while (!sim_done(s))
        if ((rc = sim_step(s, err)))
            break;
    *secs = omp_get_wtime() - t0;
    /* the whole bar by global id on every rank (one rank: copies of its
     * arrays), so that every measure below is the serial one */
    const struct particles *p = s->p;
    const size_t nw = vpar_n(s);
    double *w[4] = {NULL, NULL, NULL, NULL};
    const double *src[4] = {p->x[0], p->x[1], p->x[2], p->x0[2]};
    for (int k = 0; k < 4 && !rc; k++)
        if (!(w[k] = vpar_whole(s, src[k], err)))
            rc = err->code ? err->code : SPALL_ERR_NOMEM;
    /* length = extent along the axis: the bar rebounds from the wall
     * (~20 m/s) and flies off, so its top alone keeps rising */
    double zmax = -INFINITY, zmin = INFINITY, rmax = 0.0;
    for (size_t i = 0; i < nw && !rc; i++) {
        zmax = fmax(zmax, w[2][i]);
        zmin = fmin(zmin, w[2][i]);
    }
    for (size_t i = 0; i < nw && !rc; i++)
        if (w[3][i] < 1.5 * dx) /* the impact face's particles */
            rmax = fmax(rmax, hypot(w[0][i], w[1][i]));
    *len = zmax - zmin + dx;
    *rad = rmax + 0.5 * dx;
    /* the mushroom 0.5 mm above the impact face (its surface dx/2 below
     * the lowest centre), where the FE radius converges (core/profile.h),
     * on the whole bar's positions */
    if (!rc && r05) {
        struct particles whole;
        memset(&whole, 0, sizeof whole);
        whole.dim = 3;
        whole.n = whole.n_owned = nw;
        for (int d = 0; d < 3; d++)
            whole.x[d] = w[d];
        rc = profile_radius(&whole, zmin - 0.5 * dx + 0.5e-3, dx, 0.5 * dx, r05, err);
    }
    *np = nw;
    for (int k = 0; k < 4; k++)
        free(w[k]);
    sim_destroy(&s);
    return rc;
}

int sph_case_taylor3d(struct vreport *r, struct spall_error *err)
{
    static const int series[3] = {8, 12, 16};
    const int first = 0, last = r->quick ? 0 : 2;
    double len[3] = {NAN, NAN, NAN}, rad[3] = {NAN, NAN, NAN}, r05[3] = {NAN, NAN, NAN};
    for (int k = first; k <= last; k++) {
        size_t np = 0;
        double secs = 0.0;
        int rc = sph_taylor3d_run(r, series[k], true, false, &len[k], &rad[k], &r05[k], &np, &secs,
                                  err);
        if (rc)
            return rc;
        vreport_info(r, "Taylor bar, %d across (%zu particles, dx = %.4g mm): final length "
                     "%.3f mm, mushroom radius %.3f mm, outer radius 0.5 mm above the face "
                     "%.3f mm (%.0f s)",
                     series[k], np, 7.595 / series[k], len[k] * 1e3, rad[k] * 1e3, r05[k] * 1e3,
                     secs);
    }
    const double L = len[last], R = rad[last];
    int rc = vreport_check(r, "final length (finest dx)", "m", 34.5e-3, L, 0.02, true,
                           "LS-DYNA 34.5 mm ([Meng2021] Table 3.6); thesis SPH 34.3, MSPH 34.7",
                           "2 %: the issue's target", err);
    if (rc)
        return rc;
    if (!r->checks[r->n - 1].pass)
        vreport_mark_gap(r, "GAP: see docs/notes/validation-log.md (frictionless penalty wall, "
                            "linear EOS)");
    if (last > first &&
        (rc = vreport_check(r, "final length change, two finest dx", "1", 0.0,
                            fabs(len[last] - len[last - 1]) / len[last], 0.005, false,
                            "convergence in dx", "0.5 %: a quarter of the 2 % target", err)))
        return rc;
    vreport_info(r, "mushroom radius %.3f mm (R0 = 3.80 mm; no tabulated reference radius: the "
                 "thesis, MSPH and LS-DYNA radii are only plotted, Fig. 3.16)",
                 R * 1e3);
    if (last == first)
        return SPALL_OK;
    /* The radius's reference: the same bar with the power-law yield of the
     * same constants (no rate, no heating) against a converged FE run of
     * that material; the 2 % for both measures */
    double pl = 0.0, pr = 0.0, p05 = 0.0, secs = 0.0;
    size_t np = 0;
    if ((rc = sph_taylor3d_run(r, series[last], true, true, &pl, &pr, &p05, &np, &secs, err)))
        return rc;
    vreport_info(r, "power-law yield (a + b eps_p^n, no rate or heating), %d across: final length "
                 "%.3f mm, face radius %.3f mm, outer radius 0.5 mm above the face %.3f mm "
                 "(%.0f s); FE reference (CalculiX, validation/fe/taylor_4340) %.2f / %.2f mm",
                 series[last], pl * 1e3, pr * 1e3, p05 * 1e3, secs, T3D_FE_L * 1e3,
                 T3D_FE_R05 * 1e3);
    static const char *src = "CalculiX C3D20R axisymmetric wedge, power-law yield, converged "
                             "(validation/fe/taylor_4340)";
    if ((rc = vreport_check(r, "final length, power-law bar, against FE", "m", T3D_FE_L, pl, 0.02,
                            true, src, "2 %: the issue's target", err)) ||
        (rc = vreport_check(r, "outer radius 0.5 mm above the face, power-law bar, against FE",
                            "m", T3D_FE_R05, p05, 0.02, true, src, "2 %: as the length", err)))
        return rc;
    return SPALL_OK;
}
