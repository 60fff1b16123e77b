/**
 * @file pd_kalthoff_lps.c
 * @brief Validation case "pd-kalthoff-lps" (issue 26 item 4): the
 *        Kalthoff-Winkler plate of pd-kalthoff (validation/pd_fracture.c)
 *        with the linear peridynamic solid instead of pair forces.
 *
 * Same plate, notches, drive and crack-angle measure as pd-kalthoff (200 x
 * 100 mm maraging steel, E = 190 GPa, rho = 8000 kg/m^3, G0 = 2.2e4 J/m^2,
 * delta = 3.015 dx, the left edge between the notches at 32 m/s, 90 us);
 * here formulation lps with nu = 0.3 (plane strain: the thick plate of the
 * experiment), influence_correction cubic (isotropic response on the square
 * lattice), critical stretch from G0 by the LPS relation (pd_calib.c).
 * The check is at dx = 0.5 mm (80 000 particles): at pd-kalthoff's dx = 1
 * mm the LPS chord is 63.0 deg, below the band, because the crack leaves
 * the notch low (mean 44 deg 5-10 mm from the tip, PMB 55) and turns; it
 * grows with the family (delta = 4.015 dx: 66.8 deg) and with refinement at
 * fixed m (0.5 mm: 68.1 deg), while the direction beyond 10 mm stays (74.1,
 * 74.6 deg), so the 1 mm value is a resolution effect of delta = 3 dx at
 * the notch tip.  Variants at 1 mm that did not move it (2026-12-07): plane
 * stress nu = 1/3 (moduli and s0 equal PMB's) 63.0, plane stress nu = 0.3
 * 64.9, s0 = PMB's 61.1, surface correction 63.0, break order next_step
 * 61.1, influence inverse 59.4, no cubic correction 59.4, partial volumes
 * off 66.8.  Both runs are reported: the chord angle of pd-kalthoff (notch
 * tip to the farthest damaged particle) and the direction of the crack
 * beyond 10 mm from the tip (principal axis of those damaged particles).
 */
#include "validation/lattice_cases.h"
#include "validation/pd_cases.h"
#include "validation/validation.h"

#include "core/fields.h"
#include "core/mathconst.h"
#include "core/particles.h"
#include "core/sim.h"
#include "spall/error.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

/* One run of the plate: lattice spacing @p dx [m] with its sites at
 * multiples of dx from (o, o), horizon delta = @p hf dx. */
struct kl_run {
    double ang;  /**< chord angle, deg */
    double far;  /**< its length, m */
    double run;  /**< principal axis beyond 10 mm, deg */
    size_t n, nd, nf;
    long steps;
    double wall; /**< wall time of the run, s */
};

static int kl_one(double dx, double o, double hf, struct kl_run *k, struct spall_error *err)
{
    char deck[2048];
    snprintf(deck, sizeof deck,
             "model: {type: peridynamics, formulation: lps, plane: plane_strain,\n"
             "        influence_correction: cubic, horizon_factor: %.17g}\n"
             "materials:\n  steel: {density: 8000, youngs_modulus: 190.0e9, poisson_ratio: 0.3,\n"
             "         fracture_energy: 2.2e4}\n"
             "lattice: {type: square, spacing: %.17g, thickness: 1.0e-3, origin: [%.17g, %.17g]}\n"
             PD_KALTHOFF_PLATE_YAML,
             hf, dx, o, o);
    const double t0 = vclock_wall();
    struct sim *s = NULL;
    int rc = vlat_build("pd_kalthoff_lps", deck, &s, err);
    if (rc)
        return rc;
    while (!sim_done(s) && !rc)
        rc = sim_step(s, err);
    struct particles *p = s->p;
    const struct field_desc *f = field_registry_find(s->fields, "damage");
    double *phi = malloc((p->n ? p->n : 1) * sizeof *phi);
    double mx = 0.0, my = 0.0, cxx = 0.0, cyy = 0.0, cxy = 0.0; /* beyond 10 mm */
    *k = (struct kl_run){.ang = NAN, .run = NAN, .n = p->n, .steps = s->step};
    if (!rc && (!f || !phi))
        rc = spall_error_set(err, SPALL_ERR_NOMEM, "pd-kalthoff-lps: no damage field");
    if (!rc) {
        field_gather_f64(f, p->n, phi);
        /* as pd-kalthoff: the farthest damaged particle above the upper notch tip */
        const double tx = 0.0505, ty = 0.0255;
        for (size_t i = 0; i < p->n; i++) {
            double dxx = p->x0[0][i] - tx, dyy = p->x0[1][i] - ty;
            if (phi[i] < 0.35 || dyy < 2e-3 || dxx < -5e-3)
                continue;
            k->nd++;
            double d = hypot(dxx, dyy);
            if (d > 10e-3) {
                k->nf++;
                mx += dxx;
                my += dyy;
                cxx += dxx * dxx;
                cyy += dyy * dyy;
                cxy += dxx * dyy;
            }
            if (d > k->far) {
                k->far = d;
                k->ang = atan2(dyy, dxx) * 180.0 / SPALL_PI;
            }
        }
    }
    if (k->nf > 2) { /* principal axis of the damaged particles beyond 10 mm */
        const double nf = (double)k->nf;
        mx /= nf;
        my /= nf;
        const double sxx = cxx / nf - mx * mx, syy = cyy / nf - my * my, sxy = cxy / nf - mx * my;
        k->run = 0.5 * atan2(2.0 * sxy, sxx - syy) * 180.0 / SPALL_PI;
        if (k->run < 0.0)
            k->run += 180.0;
    }
    free(phi);
    sim_destroy(&s);
    k->wall = vclock_wall() - t0;
    return rc;
}

int pd_case_kalthoff_lps(struct vreport *r, struct spall_error *err)
{
    /* the check at dx = 0.5 mm, sites at (k + 1/2) dx so that the notch
     * faces (y = +-25.5 mm) and tips (x = 50.5 mm) fall between rows and
     * columns as at dx = 1 mm (sites at k dx); the 1 mm run for comparison */
    struct kl_run f, c;
    int rc = kl_one(0.5e-3, 0.25e-3, 3.015, &f, err);
    if (!rc)
        rc = kl_one(1.0e-3, 0.0, 3.015, &c, err);
    if (!rc)
        rc = vreport_check(r, "Kalthoff-Winkler crack angle to the notch (LPS, dx = 0.5 mm)",
                           "deg", 68.5, f.ang, 3.5, false,
                           "Kalthoff & Winkler 1988 (~70 deg); PD results 65-72 deg "
                           "(Silling 2003)",
                           "65-72 deg window of issue 26 item 4 (centre 68.5 +- 3.5); at dx = 1 "
                           "mm (delta = 3.015 dx as here) the chord is 63.0 deg (info line): the "
                           "crack leaves the notch low and turns, a resolution effect of the "
                           "notch tip (delta = 4.015 dx at 1 mm: 66.8 deg; dx = 0.5 mm: 68.1 "
                           "deg, 2026-12-07)",
                           err);
    for (int k = 0; k < 2 && !rc; k++) {
        const struct kl_run *q = k ? &c : &f;
        vreport_info(r, "pd-kalthoff-lps dx = %.1f mm: %zu particles, %ld steps, %.1f s wall; "
                     "%zu damaged particles above the upper notch tip, farthest %.1f mm away at "
                     "%.1f deg; the %zu beyond 10 mm run at %.1f deg",
                     k ? 1.0 : 0.5, q->n, q->steps, q->wall, q->nd, q->far * 1e3, q->ang, q->nf,
                     q->run);
    }
    return rc;
}
