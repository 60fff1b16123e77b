/**
 * @file impact_spall.c
 * @brief Validation case "impact-spall": seed 000 sec. 4.2 flyer-plate spall.
 *        Target 5.2 x 0.68 cm hit by a flyer 5.2 x 0.20 cm or 2.6 x 0.20 cm
 *        at 260 m/s; E = 163.24 GPa, sigma_TS = 478.25 MPa, rho = 8900 kg/m^3,
 *        every boundary free.  Deck: examples/impact_spall.
 *
 * Choices (docs/validation.md):
 *  - failure strain: the seed lists both sigma_TS = 478.25 MPa and
 *    eps_max = 0.10, which disagree (sigma_TS / E = 0.0029).  The impact
 *    stress rho c v / 2 ~ 5 GPa is a strain of ~0.03: with eps_max = 0.10
 *    nothing could spall, so we use the seed's own rule, Eq. 26,
 *    eps_max = sigma_TS / E = 0.00293.
 *  - flyer-target contact: flyer and target are one triangular lattice
 *    (r0 = 0.2 mm, nu = 1/3) and the bonds across the interface are cut by a
 *    pre-crack; cut bonds keep the model's post-fracture repulsion, which is
 *    the contact (it pushes back with the intact stiffness, never pulls).
 *    The flyer sits one row above the target, so the contact is active from
 *    t = 0 and no gap closes numerically.
 * Measured after 8 us (two wave transits of the target): the target's
 * particles damaged during the run (fracture density > 0, away from the
 * impact face) -> the crack row y_c (the most damaged row), spalled-layer
 * thickness y_c + row/2 (the crack runs between rows), the share of damage
 * within +-2 rows of y_c (parallel to the far face) and the crack's x-extent.
 */
#include "validation/impact_cases.h"
#include "validation/lattice_cases.h"
#include "validation/validation.h"

#include "core/fields.h"
#include "core/particles.h"
#include "core/sim.h"
#include "spall/error.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define SPALL_R0 0.2e-3
#define SPALL_H_TARGET 0.0068
#define SPALL_H_FLYER 0.0020
#define SPALL_GAP                                                                                 \
    "gap: with eps_max = sigma_TS/E = 0.0029 the 2D lattice breaks almost everywhere (lattice "    \
    "ringing behind the ~0.03-strain shock and the edge releases exceed 0.0029 in tension); with " \
    "the seed's eps_max = 0.10 nothing breaks; see docs/validation.md"

int impact_spall_deck(char *buf, size_t len, double flyer_width, double r0, double end_time)
{
    double row = 0.5 * sqrt(3.0) * r0;
    int kt = (int)floor(SPALL_H_TARGET / row + 1e-9);     /* target rows 0..kt-1 */
    int kf = (int)floor(SPALL_H_FLYER / row + 1e-9);      /* flyer rows */
    double y_if = (kt - 0.5) * row;                       /* interface, between rows */
    double y_top = (kt + kf - 0.5) * row;
    double x0 = 0.5 * (0.052 - flyer_width), x1 = x0 + flyer_width;
    int n = snprintf(buf, len,
                     "title: flyer-plate spall (seed 000 sec. 4.2)\n"
                     "model: {type: lattice, law: linear}\n"
                     "materials:\n"
                     "  metal: {density: 8900, youngs_modulus: 163.24e9,\n"
                     "          poisson_ratio: 0.3333333333333333, tensile_strength: 478.25e6}\n"
                     "lattice: {type: triangular, spacing: %.17g}\n"
                     "geometry:\n"
                     "  target: {box: {min: [-1.0e-5, -1.0e-5], max: [0.05201, %.17g]}}\n"
                     "  flyer: {box: {min: [%.17g, %.17g], max: [%.17g, %.17g]}}\n"
                     "body: {geometry: {union: [target, flyer]}, material: metal}\n"
                     "groups: {flyer: flyer}\n"
                     "precracks:\n"
                     "  - {from: [-0.001, %.17g], to: [0.053, %.17g]}\n"
                     "initial_velocity: [{group: flyer, value: [0, -260.0]}]\n"
                     "run: {end_time: %.17g}\n",
                     r0, y_if, x0 - 1e-5, y_if, x1 + 1e-5, y_top, y_if, y_if, end_time);
    return n > 0 && (size_t)n < len ? SPALL_OK : SPALL_ERR_INTERNAL;
}

static int run_spall(struct vreport *r, double flyer_width, const char *label,
                     struct spall_error *err)
{
    char deck[2048];
    double r0 = SPALL_R0;
    double row = 0.5 * sqrt(3.0) * r0;
    if (impact_spall_deck(deck, sizeof deck, flyer_width, r0, 8.0e-6))
        return spall_error_set(err, SPALL_ERR_INTERNAL, "impact-spall: deck buffer too small");
    struct sim *s = NULL;
    double *fd = NULL;
    int *hist = NULL;
    int rc = vlat_build("impact-spall", deck, &s, err);
    if (rc)
        return rc;
    while (!sim_done(s))
        if ((rc = sim_step(s, err)))
            goto done;
    const struct field_desc *f = field_registry_find(s->fields, "fracture_density");
    if (!f) {
        rc = spall_error_set(err, SPALL_ERR_INTERNAL, "impact-spall: no fracture_density field");
        goto done;
    }
    const struct particles *p = s->p;
    fd = malloc(p->n * sizeof *fd);
    int kt = (int)floor(SPALL_H_TARGET / row + 1e-9);
    hist = calloc((size_t)kt + 1, sizeof *hist);
    if (!fd || !hist) {
        rc = spall_error_set(err, SPALL_ERR_NOMEM, "impact-spall: out of memory");
        goto done;
    }
    field_gather_f64(f, p->n, fd);
    /* damage of the target away from the impact face (whose bonds were cut) */
    size_t total = 0;
    for (size_t i = 0; i < p->n; i++) {
        int k = (int)lround(p->x0[1][i] / row);
        if (k >= 0 && k < kt - 3 && fd[i] > 0.0) {
            hist[k]++;
            total++;
        }
    }
    int kc = 0;
    for (int k = 1; k < kt - 3; k++)
        if (hist[k] > hist[kc])
            kc = k;
    size_t near = 0;
    double xmin = INFINITY, xmax = -INFINITY;
    for (size_t i = 0; i < p->n; i++) {
        int k = (int)lround(p->x0[1][i] / row);
        if (k >= 0 && k < kt - 3 && fd[i] > 0.0 && abs(k - kc) <= 2) {
            near++;
            if (p->x0[0][i] < xmin)
                xmin = p->x0[0][i];
            if (p->x0[0][i] > xmax)
                xmax = p->x0[0][i];
        }
    }
    /* the damaged rows kc and kc+1 share the broken bonds: the crack runs
     * between them, so the spalled layer is as thick as the rows below it */
    int kc2 = hist[kc + 1] >= hist[kc > 0 ? kc - 1 : 0] ? kc + 1 : kc;
    double thick = 0.5 * (kc + kc2) * row + 0.5 * row;
    double share = total ? (double)near / (double)total : 0.0;
    double length = near ? xmax - xmin : 0.0;
    char q[96];
    snprintf(q, sizeof q, "%s: spalled layer thickness", label);
    if ((rc = vreport_check(r, q, "m", SPALL_H_FLYER, thick, r0, false,
                            "seed 000 sec. 4.2: the spalled layer is as thick as the flyer",
                            "one lattice spacing (the brief's tolerance); the crack sits where "
                            "the release waves from the flyer's back and the target's far face "
                            "meet",
                            err)))
        goto done;
    if (fabs(thick - SPALL_H_FLYER) > r0)
        vreport_mark_gap(r, SPALL_GAP);
    snprintf(q, sizeof q, "%s: crack parallel to the far face", label);
    if ((rc = vreport_check_true(r, q, total > 0 && share >= 0.8,
                                 "seed 000 sec. 4.2, Fig. 17",
                                 ">= 80 % of the target's damage (away from the impact face) "
                                 "within +-2 rows of one row",
                                 err)))
        goto done;
    if (!(total > 0 && share >= 0.8))
        vreport_mark_gap(r, SPALL_GAP);
    if (flyer_width < 0.05) {
        snprintf(q, sizeof q, "%s: crack shorter than the flyer width", label);
        if ((rc = vreport_check_true(r, q, total > 0 && length < flyer_width,
                                     "seed 000 sec. 4.2 (vs MD of Krivtsov)",
                                     "qualitative: the edge release waves of the short flyer "
                                     "shorten the tensile zone",
                                     err)))
            goto done;
        if (!(total > 0 && length < flyer_width))
            vreport_mark_gap(r, SPALL_GAP);
    }
    vreport_info(r, "%s flyer %.1f cm: %zu particles, dt = %.3g s; damaged target particles %zu, "
                    "%.0f %% within +-2 rows of row %d (y = %.3f mm), spalled layer %.3f mm, "
                    "crack x-extent %.2f cm",
                 label, flyer_width * 100, p->n, s->dt, total, 100 * share, kc, kc * row * 1e3,
                 thick * 1e3, length * 100);
done:
    free(fd);
    free(hist);
    sim_destroy(&s);
    return rc;
}

int impact_case_spall(struct vreport *r, struct spall_error *err)
{
    int rc = run_spall(r, 0.052, "long flyer", err);
    if (!rc)
        rc = run_spall(r, 0.026, "short flyer", err);
    return rc;
}
