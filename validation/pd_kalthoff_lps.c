/**
 * @file pd_kalthoff_lps.c
 * @brief Validation case "pd-kalthoff-lps" (issue 26 item 4): the
 *        Kalthoff-Winkler plate of pd-kalthoff (validation/pd_fracture.c)
 *        with the linear peridynamic solid instead of pair forces.
 *
 * Same plate, notches, drive and crack-angle measure as pd-kalthoff (200 x
 * 100 mm maraging steel, E = 190 GPa, rho = 8000 kg/m^3, G0 = 2.2e4 J/m^2,
 * dx = 1 mm, delta = 3.015 dx, the left edge between the notches at 32 m/s,
 * 90 us); here formulation lps with nu = 0.3 (plane strain: the thick plate
 * of the experiment), influence_correction cubic (isotropic response on the
 * square lattice), critical stretch from G0 by the LPS relation (pd_calib.c).
 * Besides the chord angle of pd-kalthoff (notch tip to the farthest damaged
 * particle) it reports the direction of the crack beyond 10 mm from the
 * tip (principal axis of those damaged particles): the LPS crack leaves the
 * notch lower than PMB's and then turns (the gap note).
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

int pd_case_kalthoff_lps(struct vreport *r, struct spall_error *err)
{
    const char *deck =
        "model: {type: peridynamics, formulation: lps, plane: plane_strain,\n"
        "        influence_correction: cubic}\n"
        "materials:\n  steel: {density: 8000, youngs_modulus: 190.0e9, poisson_ratio: 0.3,\n"
        "         fracture_energy: 2.2e4}\n"
        "lattice: {type: square, spacing: 1.0e-3, thickness: 1.0e-3}\n"
        "geometry:\n  plate: {box: {min: [-1e-5, -0.05001], max: [0.20001, 0.05001]}}\n"
        "body: {geometry: plate, material: steel}\n"
        "precracks:\n  - {from: [-0.001, 0.0255], to: [0.0505, 0.0255]}\n"
        "  - {from: [-0.001, -0.0255], to: [0.0505, -0.0255]}\n"
        "groups:\n  impact: {box: {min: [-1, -0.025], max: [0.0025, 0.025]}}\n"
        "boundary_conditions:\n"
        "  - {group: impact, type: velocity, components: [x], value: 32.0}\n"
        "run: {end_time: 90.0e-6}\n";
    struct sim *s = NULL;
    int rc = vlat_build("pd_kalthoff_lps", deck, &s, err);
    if (rc)
        return rc;
    while (!sim_done(s) && !rc)
        rc = sim_step(s, err);
    struct particles *p = s->p;
    const struct field_desc *f = field_registry_find(s->fields, "damage");
    double *phi = malloc((p->n ? p->n : 1) * sizeof *phi), ang = NAN, far = 0.0;
    size_t nd = 0, nf = 0;
    double mx = 0.0, my = 0.0, cxx = 0.0, cyy = 0.0, cxy = 0.0; /* beyond 10 mm */
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
            nd++;
            double d = hypot(dxx, dyy);
            if (d > 10e-3) {
                nf++;
                mx += dxx;
                my += dyy;
                cxx += dxx * dxx;
                cyy += dyy * dyy;
                cxy += dxx * dyy;
            }
            if (d > far) {
                far = d;
                ang = atan2(dyy, dxx) * 180.0 / SPALL_PI;
            }
        }
    }
    double run = NAN; /* principal axis of the damaged particles beyond 10 mm */
    if (nf > 2) {
        mx /= (double)nf;
        my /= (double)nf;
        const double sxx = cxx / (double)nf - mx * mx, syy = cyy / (double)nf - my * my,
                     sxy = cxy / (double)nf - mx * my;
        run = 0.5 * atan2(2.0 * sxy, sxx - syy) * 180.0 / SPALL_PI;
        if (run < 0.0)
            run += 180.0;
    }
    if (!rc)
        rc = vreport_check(r, "Kalthoff-Winkler crack angle to the notch (LPS)", "deg", 68.5,
                           ang, 3.5, false, "Kalthoff & Winkler 1988 (~70 deg); PD results "
                           "65-72 deg (Silling 2003)",
                           "65-72 deg window of issue 26 item 4 (centre 68.5 +- 3.5)", err);
    if (!rc && !r->checks[r->n - 1].pass)
        vreport_mark_gap(r, "measured 2026-12-07: 63.0 deg, the crack 27.5 mm long at 90 us "
                         "(pair forces: 68.8 deg). Cause: the crack leaves the notch low "
                         "(mean 44 deg 5-10 mm from the tip, PMB 55) and turns (beyond 10 mm "
                         "it runs at 74.1 deg), so the chord is low; not nu or the LPS s0 "
                         "(plane stress nu = 1/3, where moduli and s0 equal PMB's: 63.0; "
                         "plane stress nu = 0.3: 64.9; s0 = PMB's: 61.1), nor the surface "
                         "correction (63.0), break order next_step (61.1), influence inverse "
                         "(59.4), no cubic correction (59.4). It grows with the family: "
                         "horizon 4.015 dx 66.8, partial volumes off (full weight to delta + "
                         "dx/2) 66.8: a resolution effect of delta = 3 dx at the notch tip, "
                         "not a defect; dx = 0.5 mm not run (8x cost)");
    if (!rc)
        vreport_info(r, "pd-kalthoff-lps: %zu particles, %ld steps; %zu damaged particles "
                     "above the upper notch tip, farthest %.1f mm away at %.1f deg; the "
                     "%zu beyond 10 mm run at %.1f deg",
                     p->n, s->step, nd, far * 1e3, ang, nf, run);
    free(phi);
    sim_destroy(&s);
    return rc;
}
