/**
 * @file impact_punch.c
 * @brief Validation case "impact-punch": [Wang2010] sec. 3.2.3, 3D punch-shear
 *        of a vinyl ester plate 10.16 x 10.16 x 1.0 cm clamped top and bottom
 *        outside a central opening of radius 3.81 cm; plunger + 5.95 kg at
 *        3.55 m/s.  Experiment: peak 10 000 N at 2.1 mm (paper's HLPM:
 *        12 800 N at 1.6 mm).  Deck: examples/impact_punch.
 *
 * Choices (docs/notes/validation-log.md): FCC lattice with central springs (the
 * natural 3D lattice; nu = 1/4 is its Cauchy value), r0 = 2.5 mm (about six
 * particle layers through the thickness, ~10 000 particles, a minute per
 * run); sigma_TS = 43.5 MPa as in impact-vinylester; flat-ended plunger of
 * radius 6.35 mm with a 1 mm edge rounding; clamps = fixed top and bottom
 * layers outside the opening.  Run twice: the seed's no-slip contact and
 * penalty contact with Coulomb friction mu = 0.3; and once without bond
 * breaking to 0.6 ms, to separate the plate's stiffness from its damage.
 */
#include "validation/impact_cases.h"
#include "validation/lattice_cases.h"
#include "validation/validation.h"

#include "core/particles.h"
#include "core/rigid.h"
#include "core/sim.h"
#include "spall/error.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define PUNCH_SMOOTH 50e-6

int impact_punch_deck(char *buf, size_t len, double r0, const char *contact, double end_time)
{
    /* FCC sites at multiples of a/2 = r0/sqrt2 from the origin; the plate
     * spans z in [0, kz a/2] with kz the last layer inside 1.0 cm */
    double half = r0 / sqrt(2.0);
    int kz = (int)floor(0.010 / half + 1e-9);
    double top = kz * half;
    int n = snprintf(
        buf, len,
        "title: vinyl ester punch-shear ([Wang2010] sec. 3.2.3)\n"
        "model: {type: lattice, law: linear}\n"
        "materials:\n"
        "  ve: {density: 1050, youngs_modulus: 2.56e9, poisson_ratio: 0.25,\n"
        "       tensile_strength: 43.5e6}\n"
        "lattice: {type: fcc, spacing: %.17g}\n"
        "geometry:\n"
        "  plate: {box: {min: [-0.0508, -0.0508, -1.0e-6], max: [0.0508, 0.0508, %.17g]}}\n"
        "  opening: {cylinder: {base: [0, 0, -1], top: [0, 0, 1], radius: 0.0381}}\n"
        "body: {geometry: plate, material: ve}\n"
        "groups:\n"
        "  clamp_bottom: {difference: [{box: {min: [-1, -1, -1], max: [1, 1, %.17g]}}, opening]}\n"
        "  clamp_top: {difference: [{box: {min: [-1, -1, %.17g], max: [1, 1, 1]}}, opening]}\n"
        "boundary_conditions:\n"
        "  - {group: clamp_bottom, type: fixed}\n"
        "  - {group: clamp_top, type: fixed}\n"
        "gravity: [0, 0, -9.80]\n"
        "impactors:\n"
        "  - {name: plunger, shape: cylinder, position: [0, 0, %.17g], radius: 0.00635,\n"
        "     edge_radius: 0.001, length: 0.05, axis: [0, 0, -1], mass: 5.95,\n"
        "     velocity: [0, 0, -3.55], contact: %s}\n"
        "run: {end_time: %.17g}\n",
        r0, top + 0.25 * half, 0.5 * half, top - 0.5 * half, top + 1e-6, contact, end_time);
    return n > 0 && (size_t)n < len ? SPALL_OK : SPALL_ERR_INTERNAL;
}

/* @p elastic: bonds never break (failure strain 10) and the run stops at
 * 0.6 ms: the plate's elastic stiffness, to tell stiffness from damage */
static int run_punch(struct vreport *r, const char *contact, const char *label, int elastic,
                     double *peak_out, double *defl_out, struct spall_error *err)
{
    char deck[3072];
    if (impact_punch_deck(deck, sizeof deck, 2.5e-3, contact, elastic ? 0.6e-3 : 1.5e-3))
        return spall_error_set(err, SPALL_ERR_INTERNAL, "impact-punch: deck buffer too small");
    if (elastic) {
        static const char from[] = "tensile_strength: 43.5e6", to[] = "failure_strain: 10.00000";
        _Static_assert(sizeof from == sizeof to, "same length: the deck stays in place");
        char *at = strstr(deck, from);
        if (!at)
            return spall_error_set(err, SPALL_ERR_INTERNAL, "impact-punch: no strength in deck");
        memcpy(at, to, sizeof to - 1); /* same length: the deck stays in place */
    }
    struct sim *s = NULL;
    int rc = vlat_build("impact-punch", deck, &s, err);
    if (rc)
        return rc;
    const struct impactor *pl = &s->rigid->im[0];
    size_t cap = (size_t)s->n_steps + 2, n = 0;
    double *f = malloc(cap * sizeof *f), *u = malloc(cap * sizeof *u);
    if (!f || !u) {
        rc = spall_error_set(err, SPALL_ERR_NOMEM, "impact-punch: out of memory");
        goto done;
    }
    long first_break = -1; /* step of the first broken bond (sampled every 10 steps) */
    while (!sim_done(s) && n < cap) {
        if ((rc = sim_step(s, err)))
            goto done;
        f[n] = pl->f_noslip[2] + pl->f_pen[2];
        u[n] = -(pl->x[2] - pl->x0[2]);
        if (first_break < 0 && s->step % 10 == 0 && vlat_history(s, "bonds_broken") > 0)
            first_break = (long)n;
        n++;
    }
    long w = (long)ceil(0.5 * PUNCH_SMOOTH / s->dt);
    double best = -1.0, d_peak = 0.0, acc = 0.0, f_break = 0.0, d_10k = NAN;
    long lo = 0, hi = -1;
    for (long k = 0; k < (long)n; k++) {
        while (hi < k + w && hi + 1 < (long)n)
            acc += f[++hi];
        while (lo < k - w)
            acc -= f[lo++];
        double mean = acc / (double)(hi - lo + 1);
        if (mean > best) {
            best = mean;
            d_peak = u[k];
        }
        if (k == first_break)
            f_break = mean;
        if (isnan(d_10k) && mean >= 1.0e4)
            d_10k = u[k];
    }
    *peak_out = best;
    *defl_out = d_peak;
    vreport_info(r, "%s: %zu particles, dt = %.3g s, %ld steps: smoothed peak load %.0f N at "
                    "plunger displacement %.3f mm; bonds broken %g; absorbed %.3g J; first bond "
                    "broken at %.0f N, %.3f mm; load 10 kN first reached at %.3f mm",
                 label, s->p->n, s->dt, s->step, best, d_peak * 1e3,
                 vlat_history(s, "bonds_broken"), rigid_absorbed(pl), f_break,
                 first_break >= 0 ? u[first_break] * 1e3 : NAN, d_10k * 1e3);
done:
    free(f);
    free(u);
    sim_destroy(&s);
    return rc;
}

int impact_case_punch(struct vreport *r, struct spall_error *err)
{
    double F = 0, d = 0, Ff = 0, df = 0;
    int rc = run_punch(r, "no_slip", "no-slip", 0, &F, &d, err);
    if (!rc)
        rc = run_punch(r, "penalty, friction: 0.3", "penalty mu = 0.3", 0, &Ff, &df, err);
    double Fe = 0, de = 0;
    if (!rc)
        rc = run_punch(r, "no_slip", "elastic (no breaking, to 0.6 ms)", 1, &Fe, &de, err);
    if (rc)
        return rc;
    const char *src = "[Wang2010] sec. 3.2.3 (experiment; paper's HLPM 12 800 N at 1.6 mm)";
    if ((rc = vreport_check(r, "peak load (no-slip)", "N", 10000.0, F, 0.10, true, src,
                            "10 %: as the indentation cases", err)))
        return rc;
    if (fabs(F - 1e4) > 1e3)
        vreport_mark_gap(r, "not stiffness: the unbroken plate reaches 10 kN at 1.76 mm; bending "
                            "cracks on the tension face from 4.8 kN (0.92 mm) soften it and the "
                            "peak comes late; see docs/notes/validation-log.md");
    if ((rc = vreport_check(r, "deflection at peak load (no-slip)", "m", 2.1e-3, d, 0.10, true,
                            src, "10 %", err)))
        return rc;
    if (fabs(d - 2.1e-3) > 0.21e-3)
        vreport_mark_gap(r, "as above");
    vreport_info(r, "friction contact (penalty, mu = 0.3) vs no-slip: peak %.0f N vs %.0f N, "
                    "deflection at peak %.3f mm vs %.3f mm",
                 Ff, F, df * 1e3, d * 1e3);
    return SPALL_OK;
}
