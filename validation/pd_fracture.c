/**
 * @file pd_fracture.c
 * @brief Dynamic-fracture validation of the PMB model (issue 4 items 5d, 5e):
 *        "pd-branching" (Ha & Bobaru 2010 soda-lime glass plate) and
 *        "pd-kalthoff" (Kalthoff-Winkler edge-notched plate).  Full
 *        `spall validate` only (tens of seconds each).
 *
 * pd-branching: 100 x 40 mm plate, 50 mm pre-crack from the left edge on
 * the mid-line, step traction 12 MPa on the top and bottom edges, E = 72 GPa,
 * rho = 2440 kg/m^3, G0 = 3.8 J/m^2, plane stress (nu = 1/3), delta =
 * 3.015 dx with dx = 1/3 mm (delta = 1.005 mm), 46 us.  The traction acts as a
 * body force on the 3 edge rows (a layer ~ delta thick, as PD codes apply
 * tractions): on one row the edge tears off at once (9000 bonds in the
 * first steps).  Crack = particles
 * with damage >= 0.35.  Checks: branching (>= 2 separate damaged bands on a
 * vertical line right of the pre-crack tip) and the maximum crack-tip speed
 * (tip = damaged particle farthest from the pre-crack tip, speed over 2 us
 * windows) below the Rayleigh speed c_R = c_s (0.862 + 1.14 nu)/(1 + nu).
 *
 * pd-kalthoff: 200 x 100 mm maraging-steel plate (E = 190 GPa, rho = 8000,
 * G0 = 2.2e4 J/m^2, Silling 2003 data), two 50 mm notches (pre-cracks) at
 * y = +-25.5 mm, the left edge between them driven at 32 m/s, dx = 1 mm,
 * delta = 3.015 mm, 90 us.  Crack angle = angle to the x axis of the line
 * from the upper notch tip to the farthest damaged particle of that crack.
 */
#include "validation/lattice_cases.h"
#include "validation/pd_cases.h"
#include "validation/validation.h"

#include "core/fields.h"
#include "core/mathconst.h"
#include "core/particles.h"
#include "core/sim.h"
#include "core/parallel/comm.h"
#include "core/model.h"
#include "spall/error.h"
#include "validation/vpar.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

/* the registered damage field (the same values as the output) of the whole
 * run, by global id (vpar.h: the serial order on any rank count) */
static int damage_field(struct sim *s, double **out, struct spall_error *err)
{
    const size_t n = s->p->n_owned;
    double *d = malloc((n ? n : 1) * sizeof *d);
    const struct field_desc *f = field_registry_find(s->fields, "damage");
    int rc = !d ? spall_error_set(err, SPALL_ERR_NOMEM, "out of memory for damage")
             : !f ? spall_error_set(err, SPALL_ERR_INTERNAL, "the model has no damage field")
                  : SPALL_OK;
    if (!rc)
        field_gather_f64(f, n, d);
    if (s->par)
        rc = par_agree(rc, err);
    free(*out);
    *out = rc ? NULL : vpar_whole(s, d, err);
    free(d);
    return rc ? rc : (*out ? SPALL_OK : err->code);
}

/* Distribute @p s (mpirun) and gather its reference positions by global id. */
static int whole_x0(struct vreport *r, struct sim *s, double *x0[2], struct spall_error *err)
{
    int rc = vpar_distribute(r, s, err);
    for (int d = 0; d < 2 && !rc; d++)
        if (!(x0[d] = vpar_whole(s, s->p->x0[d], err)))
            rc = err->code;
    return rc;
}

int pd_case_branching(struct vreport *r, struct spall_error *err)
{
    const double dx = 1.0e-3 / 3.0, E = 72e9, rho = 2440.0, nu = 1.0 / 3.0;
    char deck[2048];
    /* sites at multiples of dx from (0, 0); the crack runs at y = 20 mm + dx/2 */
    const double yc = 60.5 * dx;
    snprintf(deck, sizeof deck,
             "model: {type: peridynamics}\n"
             "materials:\n  glass: {density: %g, youngs_modulus: %g, fracture_energy: 3.8}\n"
             "lattice: {type: square, spacing: %.17g, thickness: 1.0e-3}\n"
             "geometry:\n  plate: {box: {min: [-1e-5, -1e-5], max: [%.17g, %.17g]}}\n"
             "body: {geometry: plate, material: glass}\n"
             "precracks:\n  - {from: [-0.001, %.17g], to: [0.05, %.17g]}\n"
             "groups:\n  top: {box: {min: [-1, %.17g], max: [1, 1]}}\n"
             "  bottom: {box: {min: [-1, -1], max: [1, %.17g]}}\n"
             "boundary_conditions:\n"
             "  - {group: top, type: traction, components: [y], value: 12.0e6, area: 1.0e-4}\n"
             "  - {group: bottom, type: traction, components: [y], value: -12.0e6, area: 1.0e-4}\n"
             "run: {end_time: 46.0e-6}\n",
             rho, E, dx, 300 * dx + 1e-5, 120 * dx + 1e-5, yc, yc, 117.5 * dx, 2.5 * dx);
    struct sim *s = NULL;
    int rc = vlat_build("pd_branching", deck, &s, err);
    if (rc)
        return rc;
    const size_t n = s->p->n;
    double *x0[2] = {NULL, NULL};
    rc = whole_x0(r, s, x0, err);
    double *phi = NULL, v_max = 0.0, d_prev = 0.0, t_prev = 0.0, t_init = NAN;
    const double tip_x = 0.05, tip_y = yc, window = 2e-6;
    while (!sim_done(s) && !rc) {
        if ((rc = sim_step(s, err)))
            break;
        if (s->t - t_prev < window && !sim_done(s))
            continue;
        if ((rc = damage_field(s, &phi, err)))
            break;
        double dmax = 0.0;
        for (size_t i = 0; i < n; i++)
            if (phi[i] >= 0.35 && x0[0][i] > tip_x)
                dmax = fmax(dmax, hypot(x0[0][i] - tip_x, x0[1][i] - tip_y));
        if (dmax > 1e-3 && isnan(t_init))
            t_init = s->t;
        if (d_prev > 1e-3)
            v_max = fmax(v_max, (dmax - d_prev) / (s->t - t_prev));
        d_prev = dmax;
        t_prev = s->t;
    }
    int bands_max = 0;
    double x_bands = 0.0;
    if (!rc && (rc = damage_field(s, &phi, err)) == 0) {
        /* count separate damaged bands on vertical lines x = 55..99 mm */
        for (int col = 165; col < 298; col++) {
            int bands = 0, in = 0;
            unsigned char dmg_row[121] = {0};
            for (size_t i = 0; i < n; i++)
                if (fabs(x0[0][i] - col * dx) < 0.1 * dx && phi[i] >= 0.35) {
                    long row = lround(x0[1][i] / dx);
                    if (row >= 0 && row <= 120)
                        dmg_row[row] = 1;
                }
            /* rows 10..110: away from the loaded 3-row edge layers */
            for (int row = 10; row <= 110; row++) {
                if (dmg_row[row] && !in)
                    bands++;
                in = dmg_row[row];
            }
            if (bands > bands_max) {
                bands_max = bands;
                x_bands = col * dx;
            }
        }
    }
    const double cs = sqrt(E / (2.0 * (1.0 + nu)) / rho);
    const double cr = cs * (0.862 + 1.14 * nu) / (1.0 + nu);
    if (!rc)
        rc = vreport_check_true(r, "glass plate: crack branches (>= 2 damaged bands)",
                                bands_max >= 2, "Ha & Bobaru 2010, Int. J. Fract. 162: branching",
                                "qualitative: the experiment and PD results branch", err);
    if (!rc)
        rc = vreport_check_true(r, "glass plate: max crack-tip speed < Rayleigh speed",
                                v_max > 0.0 && v_max < cr,
                                "c_R of E = 72 GPa, nu = 1/3, rho = 2440 (plane stress)",
                                "Ha & Bobaru 2010 report ~1600-2000 m/s, well below c_R", err);
    if (!rc)
        vreport_info(r, "pd-branching: %zu particles, %ld steps; crack starts at %.3g us; max "
                     "tip speed %.0f m/s (2 us windows) = %.2f c_R (c_R = %.0f m/s); up to %d "
                     "damaged bands, at x = %.1f mm",
                     n, s->step, t_init * 1e6, v_max, v_max / cr, cr, bands_max,
                     x_bands * 1e3);
    free(phi);
    free(x0[0]);
    free(x0[1]);
    sim_destroy(&s);
    return rc;
}

int pd_case_kalthoff(struct vreport *r, struct spall_error *err)
{
    char deck[2048];
    snprintf(deck, sizeof deck,
             "model: {type: peridynamics}\n"
             "materials:\n  steel: {density: 8000, youngs_modulus: 190.0e9, fracture_energy: "
             "2.2e4}\n"
             "lattice: {type: square, spacing: 1.0e-3, thickness: 1.0e-3}\n"
             PD_KALTHOFF_PLATE_YAML);
    struct sim *s = NULL;
    int rc = vlat_build("pd_kalthoff", deck, &s, err);
    if (rc)
        return rc;
    const size_t n = s->p->n;
    double *x0[2] = {NULL, NULL};
    rc = whole_x0(r, s, x0, err);
    while (!rc && !sim_done(s))
        rc = sim_step(s, err);
    double *phi = NULL, ang = NAN, far = 0.0;
    size_t nd = 0;
    if (!rc && (rc = damage_field(s, &phi, err)) == 0) {
        const double tx = 0.0505, ty = 0.0255;
        for (size_t i = 0; i < n; i++) {
            double dxx = x0[0][i] - tx, dyy = x0[1][i] - ty;
            if (phi[i] < 0.35 || dyy < 2e-3 || dxx < -5e-3)
                continue;
            nd++;
            double d = hypot(dxx, dyy);
            if (d > far) {
                far = d;
                ang = atan2(dyy, dxx) * 180.0 / SPALL_PI;
            }
        }
    }
    if (!rc)
        rc = vreport_check(r, "Kalthoff-Winkler crack angle to the notch", "deg", 68.5, ang, 3.5,
                           false, "Kalthoff & Winkler 1988 (~70 deg); PD results 65-72 deg "
                           "(Silling 2003)",
                           "65-72 deg window of issue 4 (centre 68.5 +- 3.5)", err);
    if (!rc)
        vreport_info(r, "pd-kalthoff: %zu particles, %ld steps; %zu damaged particles above "
                     "the upper notch tip, farthest %.1f mm away at %.1f deg",
                     n, s->step, nd, far * 1e3, ang);
    free(phi);
    free(x0[0]);
    free(x0[1]);
    sim_destroy(&s);
    return rc;
}
