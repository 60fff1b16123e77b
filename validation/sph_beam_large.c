/**
 * @file sph_beam_large.c
 * @brief SPH validation cases "sph-beam-large" ([Meng2021] sec. 3.4.1, the
 *        cantilever under 17.5 kN) and "sph-leapfrog" (quick: the time
 *        integration keeps an undamped elastic plate's energy).
 *
 * sph-beam-large: F = 17.5 kN ramped over 1.5 ms, h = 1.4 dx, AV (0.5, 0.8),
 *   AS zeta = 0.9, XSPH 0.5; the thesis' nonlinear reference deflection is
 *   81.1 mm with a Wendland error of 4.89 %, and kernel types 2 and 3 crack
 *   non-physically.  All six kernels in the updated form (deflection and
 *   the largest stretch of an initially adjacent pair, > 1.5 = a crack),
 *   and the total-Lagrangian form (Wendland, no AS / XSPH), which has no
 *   tensile instability by construction.  The updated form with both
 *   clamps: the thesis' fixed-particle clamp (3 columns) and the mirrored
 *   clamp (model.clamp, sph_clamp.c); info rows with the kernel-averaged
 *   artificial stress (sph_as_smooth.c), six kernels, both clamps; the
 *   averaged AS with the edge clamp (one fixed column: the thesis' "left
 *   edge fixed" read literally), six kernels, the Wendland checked: the
 *   deeper clamps tear the tension-side corner pair apart (the tensile
 *   instability of the pair across the clamp plane, docs/notes/validation-log.md).
 * sph-leapfrog: plain-SPH cubic-spline plate (6 rows, no artificial
 *   viscosity / stress / XSPH), cantilever mode, 0.1 s: the leapfrog must
 *   keep kinetic + internal energy to 1e-3 of the input; the
 *   predictor-corrector's drift on the same run is printed.
 */
#include "validation/lattice_cases.h"
#include "validation/sph_beam.h"
#include "validation/sph_cases.h"
#include "validation/validation.h"

#include "core/particles.h"
#include "core/sim.h"
#include "models/sph/sph_kernels.h"
#include "spall/error.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#define CRACK_STRETCH 1.5

/* Comma list of the kernel types flagged in @p c[0..5]. */
static void type_list(const int *c, char *list, size_t n)
{
    list[0] = 0;
    for (int k = 0; k < 6; k++)
        if (c[k])
            snprintf(list + strlen(list), n - strlen(list), "%s%d", list[0] ? ", " : "", k + 1);
    if (!list[0])
        snprintf(list, n, "none");
}

/* The Wendland check against 81.1 mm (tolerance = the thesis' Wendland
 * error), a failure marked as a gap naming the measured cause. */
static int wendland_check(struct vreport *r, const char *q, const struct sph_beam_result *res,
                          const char *gap_unstable, struct spall_error *err)
{
    const double ref = 81.1e-3, tol = 0.0489;
    char what[160], note[256];
    snprintf(what, sizeof what, "%s: mean tip deflection 1.5-3 ms", q);
    snprintf(note, sizeof note,
             "tolerance = the thesis' Wendland error; max pair stretch %.3f (crack > %.1f)",
             res->stretch, CRACK_STRETCH);
    int rc = vreport_check(r, what, "m", ref, isfinite(res->mean) ? res->mean : NAN, tol, true,
                           "[Meng2021] sec. 3.4.1 (nonlinear deflection 81.1 mm, Wendland 4.89 %)",
                           note, err);
    if (rc || r->checks[r->n - 1].pass)
        return rc;
    char gap[400];
    if (!isfinite(res->mean) || res->final > 0.2)
        snprintf(gap, sizeof gap, "GAP: %s; see docs/notes/validation-log.md", gap_unstable);
    else
        snprintf(gap, sizeof gap, "GAP: measured %.2f mm (%+.1f %%); see "
                                  "docs/notes/validation-log.md",
                 res->mean * 1e3, (res->mean - ref) / ref * 100.0);
    vreport_mark_gap(r, gap);
    return SPALL_OK;
}

int sph_case_beam_large(struct vreport *r, struct spall_error *err)
{
    const double ref = 81.1e-3;
    const char *thesis = "cspm: true, viscosity: [0.5, 0.8], artificial_stress: 0.9, xsph: 0.5";
    int rc;
    /* 1. the thesis' settings (pointwise AS 0.9), both clamp forms; the
     *    fixed-particle clamp is the thesis' set-up */
    for (int c = 0; c < 2; c++) {
        const enum sph_beam_clamp cl = c ? SPH_BEAM_MIRROR : SPH_BEAM_FIXED;
        int cracked[6] = {0};
        for (int k = 0; k < 6; k++) {
            const char *kern = SPH_BEAM_KERNELS[k];
            char q[128];
            snprintf(q, sizeof q, "17.5 kN type %d %s, %s clamp", k + 1, kern,
                     c ? "mirrored" : "fixed");
            struct sph_beam_result res;
            if ((rc = sph_beam_run_or_note(r, q, kern, 17500.0, 1.4, thesis, cl, &res, err)))
                return rc;
            cracked[k] = !isfinite(res.mean) || !(res.stretch < CRACK_STRETCH);
            if (k == 3 &&
                (rc = wendland_check(r, q, &res,
                                     "the updated form blows up at ~1 ms (tip ~90 mm, every "
                                     "kernel, either clamp): the pointwise AS 0.9 drives particle "
                                     "noise from t = 0; averaged AS: torn at the clamp; no AS: "
                                     "tensile pairing, crack at x = 16 mm; TLSPH runs",
                                     err)))
                return rc;
        }
        char list[64];
        type_list(cracked, list, sizeof list);
        vreport_info(r, "updated SPH at 17.5 kN, %s clamp: kernel types that crack (pair "
                     "stretch > %.1f or unstable): %s (thesis, fixed clamp: 2 and 3)",
                     c ? "mirrored" : "fixed", CRACK_STRETCH, list);
    }
    /* 2. the kernel-averaged artificial stress (sph_as_smooth.c), six
     *    kernels, both clamps: which run to 3 ms, which tear (info) */
    for (int c = 0; c < 2; c++) {
        const enum sph_beam_clamp cl = c ? SPH_BEAM_MIRROR : SPH_BEAM_FIXED;
        int torn[6] = {0};
        for (int k = 0; k < 6; k++) {
            const char *kern = SPH_BEAM_KERNELS[k];
            char q[128], extra[256];
            snprintf(q, sizeof q, "17.5 kN type %d %s, averaged AS, %s clamp", k + 1, kern,
                     c ? "mirrored" : "fixed");
            snprintf(extra, sizeof extra, "%s, artificial_stress_smoothing: true", thesis);
            struct sph_beam_result res;
            if ((rc = sph_beam_run_or_note(r, q, kern, 17500.0, 1.4, extra, cl, &res, err)))
                return rc;
            torn[k] = !isfinite(res.mean) || res.final > 0.2;
            vreport_info(r, "%s: %s, mean %.2f mm (%+.1f %% vs 81.1), pair stretch %.3g", q,
                         !isfinite(res.mean) ? "unstable" : torn[k] ? "torn" : "runs",
                         res.mean * 1e3, (res.mean - ref) / ref * 100.0, res.stretch);
        }
        char list[64];
        type_list(torn, list, sizeof list);
        vreport_info(r, "averaged AS at 17.5 kN, %s clamp: kernel types torn off: %s",
                     c ? "mirrored" : "fixed", list);
    }
    /* 3. the averaged AS with the edge clamp (one fixed column): the
     *    corner pair across the clamp plane does not run away (measured:
     *    corner gap <= 1.16 dx), the Wendland checked against the thesis */
    {
        int torn[6] = {0};
        for (int k = 0; k < 6; k++) {
            const char *kern = SPH_BEAM_KERNELS[k];
            char q[128], extra[256];
            snprintf(q, sizeof q, "17.5 kN type %d %s, averaged AS, edge clamp", k + 1, kern);
            snprintf(extra, sizeof extra, "%s, artificial_stress_smoothing: true", thesis);
            struct sph_beam_result res;
            if ((rc = sph_beam_run_or_note(r, q, kern, 17500.0, 1.4, extra, SPH_BEAM_EDGE, &res,
                                           err)))
                return rc;
            torn[k] = !isfinite(res.mean) || res.final > 0.2;
            if (k == 3 && (rc = wendland_check(r, q, &res,
                                               "torn at the clamp (see "
                                               "docs/notes/validation-log.md)", err)))
                return rc;
        }
        char list[64];
        type_list(torn, list, sizeof list);
        vreport_info(r, "averaged AS at 17.5 kN, edge clamp: kernel types torn off: %s", list);
    }
    /* 4. total-Lagrangian SPH (fixed clamp; sph_clamp.c is updated-form only) */
    struct sph_beam_result res;
    if ((rc = sph_beam_run_or_note(r, "17.5 kN TLSPH wendland", "wendland", 17500.0, 1.4,
                                   "type: tlsph, viscosity: [0.5, 0.8], hourglass: 1.0",
                                   SPH_BEAM_FIXED, &res, err)) ||
        (rc = wendland_check(r, "17.5 kN TLSPH wendland", &res, "TLSPH went unstable", err)))
        return rc;
    int tl_cracked = !isfinite(res.mean) || !(res.stretch < CRACK_STRETCH);
    return vreport_check_true(r, "TLSPH at 17.5 kN: no crack (pair stretch < 1.5)", !tl_cracked,
                              "[Meng2021] conclusions: TLSPH is the remedy for the tensile "
                              "instability",
                              "the total-Lagrangian kernel never changes neighbours", err);
}

/* Energy drift / input of the plain cubic plate, 6 rows, 0.1 s. */
static int plate_drift(const char *tint, double *drift, struct spall_error *err)
{
    const double L = 0.2, H = 0.02, dx = H / 6;
    char deck[2048];
    snprintf(deck, sizeof deck,
             "model: {type: sph, kernel: cubic_spline, h_factor: 1.5, plane: strain,\n"
             "        viscosity: [0, 0], time_integration: %s}\n"
             "materials: {rubber: {density: 1000, youngs_modulus: 2.0e6, poisson_ratio: 0.3975}}\n"
             "lattice: {type: square, spacing: %.17g, origin: [%.17g, %.17g], thickness: 1.0}\n"
             "body: {geometry: {box: {min: [%.17g, %.17g], max: [%.17g, %.17g]}}, "
             "material: rubber}\n"
             "groups: {clamp: {box: {min: [-1, -1], max: [0, 1]}}}\n"
             "boundary_conditions: [{group: clamp, type: fixed}]\n"
             "run: {end_time: 0.1}\n",
             tint, dx, 0.5 * dx, 0.5 * dx, -0.25 * L, -0.5 * H, L, 0.5 * H);
    struct sim *s = NULL;
    int rc = vlat_build("sph_leapfrog", deck, &s, err);
    if (rc)
        return rc;
    /* the predictor-corrector run is meant to grow: its growth up to the
     * cut-off below is the measurement, so sim_step's blow-up stop is off */
    s->energy_blowup = INFINITY;
    struct particles *p = s->p;
    for (size_t i = 0; i < p->n; i++) /* a smooth bending start, tip 0.1 m/s */
        p->v[1][i] = p->x0[0][i] > 0.0 ? 0.1 * pow(p->x0[0][i] / L, 2.0) : 0.0;
    if (!(rc = sim_initial_forces(s, err))) {
        double e0 = s->energy.initial_total, worst = 0.0;
        while (!sim_done(s) && !rc) {
            if ((rc = sim_step(s, err)))
                break;
            sim_update_energy(s);
            worst = fmax(worst, fabs(s->energy.balance) / e0);
            if (!(worst < 1e3))
                break; /* blown up: enough said */
        }
        *drift = worst;
    }
    if (rc == SPALL_ERR_UNSTABLE) {
        *drift = INFINITY;
        err->code = 0;
        err->msg[0] = 0;
        rc = SPALL_OK;
    }
    sim_destroy(&s);
    return rc;
}

int sph_case_leapfrog(struct vreport *r, struct spall_error *err)
{
    double lf = NAN, pc = NAN;
    int rc = plate_drift("leapfrog", &lf, err);
    if (!rc)
        rc = plate_drift("predictor_corrector", &pc, err);
    if (rc)
        return rc;
    vreport_info(r, "same run with the predictor-corrector (Eqs. 3.35-3.37): max |energy "
                 "balance| / input = %.3g",
                 pc);
    return vreport_check(r, "leapfrog, undamped plain-SPH plate: max |energy balance| / input",
                         "1", 0.0, lf, 1e-3, false,
                         "exact: no dissipation (no AV, AS or XSPH); elastic energy conserved",
                         "1e-3: second-order time error at dt_factor 0.3 over 0.1 s (~2500 "
                         "steps); the predictor-corrector grows without bound here",
                         err);
}
