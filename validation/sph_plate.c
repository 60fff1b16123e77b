/**
 * @file sph_plate.c
 * @brief Oscillating-plate runs (Gray, Monaghan & Swift 2001): L = 0.2 m,
 *        H = 0.02 m, E = 2 MPa, nu = 0.3975, rho = 1000, plane strain,
 *        started in the first bending mode with tip speed 0.1 m/s; the
 *        period from the zero crossings of the tip displacement.
 *        Clamped (L/4 of clamp particles behind x = 0: fixed or mirrored)
 *        or free-free (the bending check without any clamp).
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
    return 2.0 * SPH_PI / w;
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
                 "model: {type: sph, plane: strain, %s}\n"
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
                 "model: {type: sph, plane: strain, %s%s}\n"
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

/* The case's model settings: cubic spline h = 1.5 dx (Gray et al.), CSPM,
 * weak AV against spurious particle modes, leapfrog (sph_leapfrog.c). */
static const char *const PLATE_MODEL = "kernel: cubic_spline, h_factor: 1.5, cspm: true, "
                                       "viscosity: [0.1, 0.1], time_integration: leapfrog";

int sph_case_plate(struct vreport *r, struct spall_error *err)
{
    const double T_ref = sph_plate_theory_period(SPH_PLATE_MIRROR);
    const int rows = r->quick ? 6 : 10;
    struct sph_plate_result res;
    int rc = sph_plate_run(rows, PLATE_MODEL, SPH_PLATE_MIRROR, false, &res, err);
    if (rc)
        return rc;
    vreport_info(r, "plate: %d rows (%zu particles), mirrored clamp, T = %.5f s, omega = %.4f "
                 "rad/s (thin-plate theory %.4f; Timoshenko plane strain 24.50 rad/s, T = "
                 "0.2564 s)",
                 rows, res.np, res.period, 2.0 * SPH_PI / res.period, 2.0 * SPH_PI / T_ref);
    vreport_info(r, "plate: 2 x first down-crossing = %.5f s", res.half);
    rc = vreport_check(r, "oscillating plate: period of the first mode", "s", T_ref, res.period,
                       0.03, true,
                       "thin-plate theory, plane strain: omega^2 = E H^2 k^4/(12 rho (1-nu^2)), "
                       "kL = 1.8751 (Gray, Monaghan & Swift 2001)",
                       "3 %: the issue's tolerance; shear and rotary inertia (Timoshenko) "
                       "make the thick plate 0.94 % slower than thin-plate theory",
                       err);
    if (!rc && !r->checks[r->n - 1].pass)
        vreport_mark_gap(r, "GAP: with the mirrored clamp the plate matches the free-free "
                            "plate (+16 % / +6 % vs Timoshenko at 6 / 10 rows: SPH bending "
                            "error ~ (h/H)^2), but at 16 rows a distortion growing at the "
                            "clamp (tensile instability at its corners suspected) makes it "
                            "slower again (+15 %); see docs/validation.md");
    return rc;
}
