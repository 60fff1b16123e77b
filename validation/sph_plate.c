/**
 * @file sph_plate.c
 * @brief Oscillating-plate runs (Gray, Monaghan & Swift 2001): L = 0.2 m,
 *        H = 0.02 m, E = 2 MPa, nu = 0.3975, rho = 1000, plane strain,
 *        started in the first bending mode with tip speed 0.1 m/s; the
 *        period from the zero crossings of the tip displacement.
 *        Clamped (L/4 of clamp particles behind x = 0: fixed or mirrored)
 *        or free-free (the bending check without any clamp).
 *        The case checks the total-Lagrangian plate with a fixed clamp (its
 *        period converges with dx) and keeps the updated CSPM form with the
 *        mirrored clamp as a second row (a known gap: pairing at the clamp
 *        corner from 16 rows on).
 */
#include "validation/sph_plate.h"

#include "validation/lattice_cases.h"
#include "validation/sph_cases.h"
#include "validation/validation.h"

#include "core/particles.h"
#include "core/sim.h"
#include "models/sph/sph_kernels.h"
#include "spall/error.h"

#include <math.h>
#include <stdio.h>

#define PLATE_L 0.2
#define PLATE_H 0.02
#define KL_CANT 1.875104068711961
#define KL_FREE 4.730040744862704

double sph_plate_theory_period(enum sph_plate_clamp clamp)
{
    const double E = 2.0e6, nu = 0.3975, rho = 1000.0;
    const double k = (clamp == SPH_PLATE_FREE ? KL_FREE : KL_CANT) / PLATE_L;
    /* plane strain: D = E H^3 / (12 (1 - nu^2)) per unit width, m = rho H */
    double w = sqrt(E * PLATE_H * PLATE_H * k * k * k * k / (12.0 * rho * (1.0 - nu * nu)));
    return 2.0 * SPALL_PI / w;
}

/* First-mode shape at x (0 <= x <= L). */
static double mode_shape(enum sph_plate_clamp clamp, double x)
{
    const double L = PLATE_L;
    if (clamp == SPH_PLATE_FREE) {
        const double kL = KL_FREE, k = kL / L;
        const double sg = (cosh(kL) - cos(kL)) / (sinh(kL) - sin(kL));
        return cosh(k * x) + cos(k * x) - sg * (sinh(k * x) + sin(k * x));
    }
    const double kL = KL_CANT, k = kL / L;
    const double Q = (cos(kL) + cosh(kL)) / (sin(kL) + sinh(kL));
    if (x <= 0.0)
        return 0.0;
    return (cos(k * x) - cosh(k * x)) - Q * (sin(k * x) - sinh(k * x));
}

int sph_plate_run(int rows, const char *model, enum sph_plate_clamp clamp, bool half_only,
                  struct sph_plate_result *out, struct spall_error *err)
{
    const double L = PLATE_L, H = PLATE_H, dx = H / rows;
    const double T0 = sph_plate_theory_period(clamp);
    char deck[4096], cl[512] = "";
    if (clamp == SPH_PLATE_MIRROR)
        snprintf(cl, sizeof cl, ",\n        clamp: {group: clamp, point: [0, 0], normal: [1, 0]}");
    if (clamp == SPH_PLATE_FREE)
        snprintf(deck, sizeof deck,
                 "model: {plane: strain, %s}\n"
                 "materials: {rubber: {density: 1000, youngs_modulus: 2.0e6, "
                 "poisson_ratio: 0.3975}}\n"
                 "lattice: {type: square, spacing: %.17g, origin: [%.17g, %.17g], "
                 "thickness: 1.0}\n"
                 "body: {geometry: {box: {min: [0, %.17g], max: [%.17g, %.17g]}}, "
                 "material: rubber}\n"
                 "run: {end_time: %.17g}\n",
                 model, dx, 0.5 * dx, 0.5 * dx, -0.5 * H, L, 0.5 * H, 1.6 * T0);
    else
        snprintf(deck, sizeof deck,
                 "model: {plane: strain, %s%s}\n"
                 "materials: {rubber: {density: 1000, youngs_modulus: 2.0e6, "
                 "poisson_ratio: 0.3975}}\n"
                 "lattice: {type: square, spacing: %.17g, origin: [%.17g, %.17g], "
                 "thickness: 1.0}\n"
                 "body: {geometry: {box: {min: [%.17g, %.17g], max: [%.17g, %.17g]}}, "
                 "material: rubber}\n"
                 "groups: {clamp: {box: {min: [-1, -1], max: [0, 1]}}}\n"
                 "boundary_conditions: [{group: clamp, type: fixed}]\n"
                 "run: {end_time: %.17g}\n",
                 model, cl, dx, 0.5 * dx, 0.5 * dx, -0.25 * L, -0.5 * H, L, 0.5 * H, 1.6 * T0);
    struct sim *s = NULL;
    int rc = vlat_build("sph_plate", deck, &s, err);
    if (rc)
        return rc;
    struct particles *p = s->p;
    const double V = 0.1; /* tip speed [m/s]: amplitude V/omega = 4 mm = 2 % of L */
    const double fL = mode_shape(clamp, L);
    size_t tip = 0;
    for (size_t i = 0; i < p->n; i++) {
        p->v[1][i] = V * mode_shape(clamp, p->x0[0][i]) / fL;
        if (p->x0[0][i] > p->x0[0][tip] ||
            (p->x0[0][i] == p->x0[0][tip] && fabs(p->x0[1][i]) < fabs(p->x0[1][tip])))
            tip = i;
    }
    if ((rc = sim_initial_forces(s, err))) {
        sim_destroy(&s);
        return rc;
    }
    out->energy0 = s->energy.kinetic;
    /* zero crossings of the tip displacement: down-crossing ~T/2, up ~T */
    double prev = 0.0, t_prev = 0.0, t_down = NAN, t_up = NAN;
    while (!sim_done(s) && !isfinite(t_up) && !(half_only && isfinite(t_down))) {
        if ((rc = sim_step(s, err)))
            break;
        double u = p->x[1][tip] - p->x0[1][tip];
        if (s->step > 5) {
            if (prev > 0.0 && u <= 0.0 && !isfinite(t_down))
                t_down = t_prev + (s->t - t_prev) * prev / (prev - u);
            else if (prev < 0.0 && u >= 0.0 && isfinite(t_down))
                t_up = t_prev + (s->t - t_prev) * (-prev) / (u - prev);
        }
        prev = u;
        t_prev = s->t;
    }
    sim_update_energy(s);
    out->period = t_up;
    out->half = 2.0 * t_down;
    out->np = p->n;
    out->steps = s->step;
    out->balance = s->energy.balance;
    sim_destroy(&s);
    return rc;
}

/* The case's forms, both cubic spline h = 1.5 dx (Gray et al.), weak AV,
 * leapfrog (sph_leapfrog.c).
 * Total-Lagrangian (sph_tlsph.c) with the clamp as plain fixed particles:
 * the reference kernel never changes neighbours, so no pairing instability
 * can start at the clamp corners, and its period converges with dx
 * (docs/notes/validation-log.md, sph-plate: +19.6 / +8.1 / +3.9 / +2.9 / +2.3 % at
 * 6 / 10 / 16 / 20 / 24 rows; insensitive to the hourglass coefficient,
 * the AV, the amplitude and the time integrator).  CSPM is built into its
 * corrected reference gradient. */
static const char *const PLATE_TLSPH = "type: tlsph, kernel: cubic_spline, h_factor: 1.5, "
                                       "hourglass: 0.1, viscosity: [0.1, 0.1], "
                                       "time_integration: leapfrog";
/* Updated form (the thesis' method): CSPM, mirrored clamp (sph_clamp.c).
 * At 16 rows particles pair on the compressed side of the clamp corner
 * (measured: the cubic spline at h = 1.5 dx has its nearest neighbours at
 * the kernel's inflection point q = 2/3), so it is run at 10 rows. */
static const char *const PLATE_UPDATED = "type: sph, kernel: cubic_spline, h_factor: 1.5, "
                                         "cspm: true, viscosity: [0.1, 0.1], "
                                         "time_integration: leapfrog";

static int plate_check(struct vreport *r, const char *what, int rows, const char *model,
                       enum sph_plate_clamp clamp, double T_ref, struct sph_plate_result *res,
                       struct spall_error *err)
{
    int rc = sph_plate_run(rows, model, clamp, false, res, err);
    if (rc)
        return rc;
    char q[128];
    snprintf(q, sizeof q, "%s, %d rows: period of the first mode", what, rows);
    vreport_info(r, "%s: %d rows (%zu particles), T = %.5f s (%+.2f %%), 2 x first "
                 "down-crossing %.5f s, energy balance %.3g J of %.3g J",
                 what, rows, res->np, res->period, (res->period / T_ref - 1.0) * 100.0, res->half,
                 res->balance, res->energy0);
    return vreport_check(r, q, "s", T_ref, res->period, 0.03, true,
                         "thin-plate theory, plane strain: omega^2 = E H^2 k^4/(12 rho (1-nu^2)), "
                         "kL = 1.8751 (Gray, Monaghan & Swift 2001)",
                         "3 %: the issue's tolerance; shear and rotary inertia (Timoshenko, "
                         "T = 0.2564 s) make the thick plate 0.94 % slower than thin-plate "
                         "theory",
                         err);
}

int sph_case_plate(struct vreport *r, struct spall_error *err)
{
    const double T_ref = sph_plate_theory_period(SPH_PLATE_FIXED);
    /* TLSPH: two resolutions for the convergence (error ~ (dx/H)^2) */
    const int coarse = r->quick ? 6 : 16, fine = r->quick ? 10 : 24;
    struct sph_plate_result rc1, res;
    int rc = sph_plate_run(coarse, PLATE_TLSPH, SPH_PLATE_FIXED, false, &rc1, err);
    if (!rc)
        rc = plate_check(r, "TLSPH, fixed clamp", fine, PLATE_TLSPH, SPH_PLATE_FIXED, T_ref,
                         &res, err);
    if (rc)
        return rc;
    {
        const double e1 = rc1.period / T_ref - 1.0, e2 = res.period / T_ref - 1.0;
        const double a = (double)coarse * coarse, b = (double)fine * fine;
        vreport_info(r, "TLSPH: %d rows T = %.5f s (%+.2f %%); Richardson (dx^2) limit of %d "
                     "and %d rows: %+.2f %% (Timoshenko +0.94 %%)",
                     coarse, rc1.period, e1 * 100.0, coarse, fine,
                     (e2 * b - e1 * a) / (b - a) * 100.0);
    }
    if (!r->checks[r->n - 1].pass)
        vreport_mark_gap(r, "GAP: TLSPH converges as (dx/H)^2 towards Timoshenko (+0.94 %) "
                            "but this resolution is too coarse; see docs/notes/validation-log.md");
    /* the thesis-style updated form, kept as a row */
    const int rows_up = r->quick ? 6 : 10;
    if ((rc = plate_check(r, "updated SPH (CSPM), mirrored clamp", rows_up, PLATE_UPDATED,
                          SPH_PLATE_MIRROR, T_ref, &res, err)))
        return rc;
    if (!r->checks[r->n - 1].pass)
        vreport_mark_gap(r, "GAP (updated form): +17 / +7 % at 6 / 10 rows, but +15 / +28 % at "
                            "16 / 20 rows: particles pair on the compressed side of the clamp "
                            "corner (cubic spline h = 1.5 dx: nearest neighbours at W'' = 0, "
                            "q = 2/3); the TLSPH row is the founded one; "
                            "docs/notes/validation-log.md");
    return rc;
}
