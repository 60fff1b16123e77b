/**
 * @file impact_indent.c
 * @brief Validation cases "impact-nylon" and "impact-vinylester": [Wang2010]
 *        sec. 3.2 drop-weight indentation of a simply supported beam by a
 *        rigid round-nose tup coupled to the lattice (no-slip push-out,
 *        M a = R_F - M g).  Decks: examples/impact_nylon, impact_vinylester.
 *
 * Set-up (choices where the seed is silent; see docs/notes/validation-log.md):
 *  - beam 12.7 cm long, 1.27 cm deep, 0.993 cm wide (the seed's "12.7 x 12.7
 *    x 0.993 cm" read with a 1.27 cm height: a 12.7 cm deep block cannot
 *    deflect 3 mm with 1.2 J), 2D plane-stress triangular lattice in the
 *    length-depth plane, thickness 0.993 cm, two-layer axial interaction;
 *  - r0 = 1.0475 mm: 14 rows of (sqrt 3 / 2) r0 make the 12.7 mm depth
 *    exactly (each row carries a strip of that height);
 *  - rigid roller supports (radius 5 mm, at rest, frictionless penalty
 *    contact: horizontal movement allowed), span 11.0 cm (8.5 mm from each
 *    end: "both ends simply supported");
 *  - hemispherical tup of radius 6.35 mm (1/2 in) and the drop weight as one
 *    free rigid body, touching the beam at t = 0 with the measured speed,
 *    gravity 9.80 m/s^2.
 * Measured: load = resistant force on the tup, smoothed by a 50 us moving
 * average (the push-out force comes in spikes of a few steps; the
 * experiment's load cell is filtered too); time of its peak; tup
 * displacement at that time; absorbed energy (initial KE - KE + gravity
 * work) at the end of the run (3 ms, the load is back to zero by then).
 */
#include "validation/impact_cases.h"
#include "validation/lattice_cases.h"
#include "validation/validation.h"
#include "validation/vpar.h"

#include "core/particles.h"
#include "core/rigid.h"
#include "core/sim.h"
#include "spall/error.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define INDENT_R0 1.0475e-3
#define INDENT_SPAN 0.110
#define INDENT_SMOOTH 50e-6

struct indent_material {
    const char *name;
    const char *law;   /* deck model.law */
    const char *extra; /* extra material keys of that law ("" for none) */
    const char *tag;   /* prefix of the check names ("" for the seed's brittle law) */
    double rho, E, sigma, v0;
    double t_ref, d_ref, e_ref;       /* experiment */
    double t_hlpm, d_hlpm, e_hlpm;    /* the paper's HLPM */
    /* note of the deflection check when an input was calibrated on it (NULL: none) */
    const char *d_calibrated;
};

int impact_indent_deck(char *buf, size_t len, double rho, double E, double sigma, double v0,
                       double r0, double end_time)
{
    return impact_indent_deck_law(buf, len, "linear", "", rho, E, sigma, v0, r0, end_time);
}

int impact_indent_deck_law(char *buf, size_t len, const char *law, const char *extra, double rho,
                           double E, double sigma, double v0, double r0, double end_time)
{
    /* rows 0..13 at (sqrt 3/2) r0: top row y_top */
    double row = 0.5 * sqrt(3.0) * r0;
    int kmax = (int)floor(0.0127 / row - 1e-9);
    double y_top = kmax * row;
    double xl = 0.5 * (0.127 - INDENT_SPAN), xr = xl + INDENT_SPAN;
    int n = snprintf(buf, len,
                     "title: drop-weight indentation ([Wang2010] sec. 3.2)\n"
                     "model: {type: lattice, law: %s, layers: 2}\n"
                     "materials:\n"
                     "  beam: {density: %.17g, youngs_modulus: %.17g,\n"
                     "         poisson_ratio: 0.3333333333333333, tensile_strength: %.17g%s}\n"
                     "lattice: {type: triangular, spacing: %.17g, thickness: 0.00993}\n"
                     "body: {geometry: {box: {min: [0, 0], max: [0.127, %.17g]}}, material: beam}\n"
                     "gravity: [0, -9.80]\n"
                     "impactors:\n"
                     "  - {name: tup, shape: round_nose, position: [0.0635, %.17g],\n"
                     "     radius: 0.00635, length: 0.05, axis: [0, -1], mass: %.17g,\n"
                     "     velocity: [0, %.17g], contact: no_slip}\n"
                     "  - {name: left_roller, shape: sphere, position: [%.17g, -0.005001],\n"
                     "     radius: 0.005, motion: prescribed, contact: penalty}\n"
                     "  - {name: right_roller, shape: sphere, position: [%.17g, -0.005001],\n"
                     "     radius: 0.005, motion: prescribed, contact: penalty}\n"
                     "run: {end_time: %.17g}\n",
                     law, rho, E, sigma, extra, r0, y_top + 0.25 * row, y_top + 1e-6, 3.318, -v0, xl, xr,
                     end_time);
    return n > 0 && (size_t)n < len ? SPALL_OK : SPALL_ERR_INTERNAL;
}

static int run_indent(struct vreport *r, const struct indent_material *m, struct spall_error *err)
{
    char deck[3072];
    const double end_time = 3.0e-3;
    if (impact_indent_deck_law(deck, sizeof deck, m->law, m->extra, m->rho, m->E, m->sigma, m->v0,
                               INDENT_R0, end_time))
        return spall_error_set(err, SPALL_ERR_INTERNAL, "impact: deck buffer too small");
    struct sim *s = NULL;
    int rc = vlat_build(m->name, deck, &s, err);
    if (rc)
        return rc;
    const size_t n_particles = s->p->n;
    if ((rc = vpar_distribute(r, s, err))) { /* mpirun: every rank moves the tup alike */
        sim_destroy(&s);
        return rc;
    }
    const struct impactor *tup = &s->rigid->im[0];
    size_t cap = (size_t)s->n_steps + 2, n = 0;
    double *t = malloc(cap * sizeof *t), *f = malloc(cap * sizeof *f), *u = malloc(cap * sizeof *u);
    if (!t || !f || !u) {
        rc = spall_error_set(err, SPALL_ERR_NOMEM, "impact: out of memory");
        goto done;
    }
    while (!sim_done(s) && n < cap) {
        if ((rc = sim_step(s, err)))
            goto done;
        t[n] = s->t;
        f[n] = tup->f_noslip[1] + tup->f_pen[1];
        u[n] = -(tup->x[1] - tup->x0[1]);
        n++;
    }
    /* moving average of the load over INDENT_SMOOTH (centred) */
    long w = (long)ceil(0.5 * INDENT_SMOOTH / s->dt);
    double best = -1.0, t_peak = 0.0, d_peak = 0.0, acc = 0.0;
    long lo = 0, hi = -1;
    for (long k = 0; k < (long)n; k++) {
        while (hi < k + w && hi + 1 < (long)n)
            acc += f[++hi];
        while (lo < k - w)
            acc -= f[lo++];
        double mean = acc / (double)(hi - lo + 1);
        if (mean > best) {
            best = mean;
            t_peak = t[k];
            d_peak = u[k];
        }
    }
    sim_update_energy(s);
    double absorbed = rigid_absorbed(tup);
    /* the load cell's energy, int F d(delta) (trapezoid over the raw load):
     * by the tup's work-energy theorem it equals the KE lost + gravity work */
    double w_fd = 0.0;
    for (size_t k = 1; k < n; k++)
        w_fd += 0.5 * (f[k] + f[k - 1]) * (u[k] - u[k - 1]);
    double broken = vlat_history(s, "bonds_broken");
    char src[160], q[160];
    const int soft = m->tag[0] != '\0';
    snprintf(src, sizeof src, "[Wang2010] sec. 3.2 (experiment; paper's HLPM %.2f ms)",
             m->t_hlpm * 1e3);
    snprintf(q, sizeof q, "%stime of peak load", m->tag);
    if ((rc = vreport_check(r, q, "s", m->t_ref, t_peak, 0.10, true, src,
                            "10 %: the seed's HLPM matched the experiment to 2-3 %; support span "
                            "and tup radius are our choices",
                            err)))
        goto done;
    if (fabs(t_peak - m->t_ref) > 0.10 * m->t_ref)
        vreport_mark_gap(r, "see docs/notes/validation-log.md: the peak comes with the first "
                            "bending "
                            "crack, whose deflection is set by eps_max and the chosen span");
    snprintf(src, sizeof src, "[Wang2010] sec. 3.2 (experiment; paper's HLPM %.2f mm)",
             m->d_hlpm * 1e3);
    snprintf(q, sizeof q, "%sdeflection at peak load", m->tag);
    if ((rc = vreport_check(r, q, "m", m->d_ref, d_peak, 0.10, true, src,
                            m->d_calibrated ? m->d_calibrated : "10 %: as above", err)))
        goto done;
    if (fabs(d_peak - m->d_ref) > 0.10 * m->d_ref)
        vreport_mark_gap(r, "see docs/notes/validation-log.md: beam theory puts the first bending "
                            "crack "
                            "at eps_max S^2 / (6 h); the elastic-brittle lattice follows it");
    snprintf(src, sizeof src, "[Wang2010] sec. 3.2 (experiment; paper's HLPM %.2f J)", m->e_hlpm);
    snprintf(q, sizeof q, "%sabsorbed energy", m->tag);
    if ((rc = vreport_check(r, q, "J", m->e_ref, absorbed, 0.10, true, src,
                            "10 %: as above", err)))
        goto done;
    if (fabs(absorbed - m->e_ref) > 0.10 * m->e_ref && soft)
        vreport_mark_gap(r, "cohesive softening with G_f = 3 kJ/m^2 still lets the beam snap "
                            "through the depth and lose contact; see docs/notes/validation-log.md "
                            "for the "
                            "G_f scan (energy vs peak time trade-off)");
    else if (fabs(absorbed - m->e_ref) > 0.10 * m->e_ref)
        vreport_mark_gap(r, "an elastic-brittle beam absorbs about its strain energy at "
                            "fracture, 1/2 k delta^2; the experiment's extra energy (local "
                            "crushing under the tup, plasticity, friction) is not in the model");
    vreport_info(r, "%s: absorbed energy as the load cell sees it, int F d(delta) = %.4g J "
                    "(tup KE lost + gravity work: %.4g J)",
                 m->name, w_fd, absorbed);
    vreport_info(r, "%s: %zu particles, dt = %.3g s, %ld steps; smoothed peak load %.1f N at "
                    "%.4g ms, deflection %.4g mm; absorbed %.4g J; bonds broken %g; energy "
                    "balance %.3g J",
                 m->name, n_particles, s->dt, s->step, best, t_peak * 1e3, d_peak * 1e3, absorbed,
                 broken, s->energy.balance);
done:
    free(t);
    free(f);
    free(u);
    sim_destroy(&s);
    return rc;
}

int impact_case_nylon(struct vreport *r, struct spall_error *err)
{
    const struct indent_material m = {"impact-nylon", "linear", "", "", 1140.0, 3.0e9, 60.0e6,
                                      1.87, 1.70e-3, 3.03e-3, 1.2, 1.66e-3, 3.0e-3, 1.2, NULL};
    int rc = run_indent(r, &m, err);
    if (rc)
        return rc;
    /* variant: cohesive softening law (lattice_softening.h), onset at
     * sigma_TS / E as above, fracture energy G_f = K_IC^2 / E with K_IC ~
     * 3 MPa m^0.5 for dry nylon-6,6 (a handbook-range value, our choice, not
     * fitted to this test; docs/notes/validation-log.md) */
    const struct indent_material ms = {"impact-nylon (softening)", "softening",
                                       ", fracture_energy: 3.0e3", "softening G_f 3 kJ/m^2: ",
                                       1140.0, 3.0e9, 60.0e6, 1.87, 1.70e-3, 3.03e-3, 1.2,
                                       1.66e-3, 3.0e-3, 1.2, NULL};
    return run_indent(r, &ms, err);
}

int impact_case_vinylester(struct vreport *r, struct spall_error *err)
{
    /* sigma_TS: the seed gives 25.6-51.2 MPa.  The midpoint 38.4 MPa put the
     * first crack at 2.05 mm / 1.08 ms (-21 %, -22 %), 49 MPa at 3.24 mm /
     * 1.73 ms; we keep 43.5 MPa, chosen inside the range (by interpolating
     * those two runs) so that the first crack falls near the measured
     * deflection: the deflection check is therefore a calibration, the time
     * of the peak and the absorbed energy stay independent checks. */
    const struct indent_material m = {
        "impact-vinylester", "linear", "", "", 1050.0, 2.56e9, 43.5e6, 1.91,
        1.38e-3, 2.60e-3, 0.7, 1.42e-3, 2.66e-3, 0.76,
        "10 %; a calibrated input: sigma_TS = 43.5 MPa was chosen inside the seed's 25.6-51.2 "
        "MPa so that the first crack lands at the measured deflection (38.4 MPa: -21 %), so "
        "this check is a calibration; peak time and absorbed energy stay independent"};
    return run_indent(r, &m, err);
}
