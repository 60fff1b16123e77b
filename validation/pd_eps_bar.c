/**
 * @file pd_eps_bar.c
 * @brief Validation case "pd-eps-bar" (issue 26 items 2 and 4): a 2D
 *        plane-stress bar of the elastic-plastic state-based model
 *        (formulation eps, src/models/peridynamics/pd_eps.c) pulled past
 *        yield and pushed back through reverse yield, against the
 *        elastic-perfectly plastic bar.
 *
 * Set-up: steel-like E = 200 GPa, nu = 0.3, rho = 7850 kg/m^3, sigma_Y =
 * 200 MPa (eps_Y = 1e-3); bar 0.1 x 0.02 m, triangular lattice dx = 1 mm
 * (isotropic family), delta = 3.015 dx, with the LPS surface correction
 * (model.surface_correction, pd_lps_surface.c; without it the section's
 * unloading slope came out 7.8 % and its plateau 7.1 % high).  Both ends (3 columns each) are
 * driven in x only, with a velocity history of linear ramps EB_RAMP = 4
 * wave transits long and a constant speed until 16 transits: the bar is
 * stretched by 3 eps_Y, then brought back to its original length.  The
 * drive first had ramps of 2 transits (hold to 8): the velocity reversal
 * then left inertial stresses in the gauge, the unloading slopes came out
 * +2.06 % (centre) and +2.57 % (section) and fell with a slower drive to
 * +0.78 / +0.22 % (ramps 4 transits) and +0.13 / -0.05 % (8 transits;
 * 2026-12-07): the gap was the drive, not the discrete moduli (the
 * triangular family is isotropic: pd-lps-patch's plane stress rows are
 * exact).  Those two slopes of the old drive are kept as rows (known gaps,
 * that cause).  Measured: the nominal stress F / A
 * (F the right grip's reaction, A = the particles of one cross-section times
 * V_i / dx) against the gauge strain between two centreline particles at
 * L/4 and 3L/4.  References (uniaxial stress, 2D J2 = von Mises in uniaxial
 * plane stress): the plateau sigma_Y, the elastic slope E on loading and on
 * unloading, the reverse yield -sigma_Y, and the strain left when the stress
 * passes zero, eps_peak - sigma_peak / E (eps_peak, sigma_peak measured).
 */
#include "validation/lattice_cases.h"
#include "validation/pd_cases.h"
#include "validation/validation.h"

#include "core/fields.h"
#include "core/particles.h"
#include "core/sim.h"
#include "spall/error.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#define EB_E 200.0e9
#define EB_NU 0.3
#define EB_RHO 7850.0
#define EB_SY 200.0e6
#define EB_L 0.1
/* ramp length in wave transits (the hold to 4 ramps): the checked drive
 * and the old one kept as rows (file comment) */
#define EB_RAMP 4.0
#define EB_RAMP_OLD 2.0

struct eb_sample {
    double t, eps, sig; /**< time, gauge strain, F / A at the grip */
    /* every EB_EVERY steps, else NAN: */
    double sig_c;       /**< sigma_xx of the centre particle */
    double seq_c;       /**< its signed 2D equivalent stress sign(sxx - syy) sqrt((sxx - syy)^2
                             + 4 sxy^2), which the 2D J2 criterion holds to +-sigma_Y */
    double sig_s;       /**< mean sigma_xx over the middle cross-section (surface included) */
};

#define EB_EVERY 4

/* What the cycle shows: slopes, extremes, the peak and the strain at zero stress. */
struct eb_result {
    double E_load, E_unl, sig_max, sig_min, eps_peak, sig_peak, eps0;
};

static int eb_run(double ramp, struct eb_sample **out, size_t *nout, double *area, size_t *np,
                  struct spall_error *err)
{
    const double c = sqrt(EB_E / EB_RHO), transit = EB_L / c;
    const double tr = ramp * transit, t1 = 4.0 * tr, t2 = 2.0 * t1;
    /* each end moves v (t1 - tr) by t1: total strain 2 v (t1 - tr) / L = 3 eps_Y */
    const double v = 3.0 * (EB_SY / EB_E) * EB_L / (2.0 * (t1 - tr));
    char deck[2048];
    snprintf(deck, sizeof deck,
             "model: {type: peridynamics, formulation: eps, surface_correction: true}\n"
             "materials:\n  steel: {density: %g, youngs_modulus: %g, poisson_ratio: %g, "
             "yield_stress: %g}\n"
             "lattice: {type: triangular, spacing: 1.0e-3, thickness: 1.0e-3}\n"
             "geometry:\n  bar: {box: {min: [0, 0], max: [%g, 0.0201]}}\n"
             "body: {geometry: bar, material: steel}\n"
             "groups:\n  left: {box: {min: [-1, -1], max: [0.0026, 1]}}\n"
             "  right: {box: {min: [%g, -1], max: [1, 1]}}\n"
             "boundary_conditions:\n"
             "  - {group: left, type: velocity, components: [x], value: %.10g,\n"
             "     function: {type: table, points: [[0, 0], [%.10g, 1], [%.10g, 1], [%.10g, -1],"
             " [%.10g, -1], [%.10g, 0]]}}\n"
             "  - {group: right, type: velocity, components: [x], value: %.10g,\n"
             "     function: {type: table, points: [[0, 0], [%.10g, 1], [%.10g, 1], [%.10g, -1],"
             " [%.10g, -1], [%.10g, 0]]}}\n"
             "probes:\n  - {name: q, position: [%g, 0.01]}\n  - {name: h, position: [%g, 0.01]}\n"
             "  - {name: c, position: [%g, 0.01]}\n"
             "run: {end_time: 1.0}\n",
             EB_RHO, EB_E, EB_NU, EB_SY, EB_L + 1e-4, EB_L - 0.0025, -v, tr, t1 - tr, t1 + tr,
             t2 - tr, t2, v, tr, t1 - tr, t1 + tr, t2 - tr, t2, 0.25 * EB_L, 0.75 * EB_L, 0.5 * EB_L);
    struct sim *s = NULL;
    int rc = vlat_build("pd_eps_bar", deck, &s, err), gr = -1;
    if (rc)
        return rc;
    const struct field_desc *fs = field_registry_find(s->fields, "stress");
    if (!fs)
        rc = spall_error_set(err, SPALL_ERR_INTERNAL, "pd-eps-bar: no stress field");
    if (rc || (rc = vlat_group(s, "right", &gr, err))) {
        sim_destroy(&s);
        return rc;
    }
    const size_t ic = s->probes[2].particle;
    struct particles *p = s->p;
    const size_t iq = s->probes[0].particle, ih = s->probes[1].particle;
    const double gauge = p->x0[0][ih] - p->x0[0][iq];
    /* one particle per row in a window dx wide (rows are offset by dx/2; the
     * window is half open and shifted so that one of two boundary sites counts) */
    size_t ncut = 0, *cut = malloc(p->n * sizeof *cut);
    double vol = 0.0;
    if (!cut) {
        sim_destroy(&s);
        return spall_error_set(err, SPALL_ERR_NOMEM, "pd-eps-bar: out of memory");
    }
    for (size_t i = 0; i < p->n; i++) {
        const double dxc = p->x0[0][i] - 0.5 * EB_L - 1e-9;
        if (dxc >= -0.5e-3 && dxc < 0.5e-3) {
            cut[ncut++] = i;
            vol = p->volume[i];
        }
    }
    *area = (double)ncut * vol / 1.0e-3;
    *np = p->n;
    size_t cap = 4096, n = 0;
    struct eb_sample *smp = malloc(cap * sizeof *smp);
    double *sg = malloc(3 * p->n * sizeof *sg);
    if (!smp || !sg) {
        free(cut);
        free(smp);
        free(sg);
        sim_destroy(&s);
        return spall_error_set(err, SPALL_ERR_NOMEM, "pd-eps-bar: out of memory");
    }
    while (s->t < t2 && !rc) {
        if ((rc = sim_step(s, err)))
            break;
        double f[3];
        sim_group_reaction(s, gr, f);
        if (n == cap) {
            struct eb_sample *q = realloc(smp, 2 * cap * sizeof *smp);
            if (!q) {
                rc = spall_error_set(err, SPALL_ERR_NOMEM, "pd-eps-bar: out of memory");
                break;
            }
            smp = q;
            cap *= 2;
        }
        smp[n].t = s->t;
        smp[n].eps = ((p->x[0][ih] - p->x0[0][ih]) - (p->x[0][iq] - p->x0[0][iq])) / gauge;
        smp[n].sig = f[0] / *area;
        smp[n].sig_c = smp[n].seq_c = smp[n].sig_s = NAN;
        if (n % EB_EVERY == 0) {
            field_gather_f64(fs, p->n, sg);
            const double *cs = &sg[3 * ic];
            smp[n].sig_c = cs[0];
            smp[n].seq_c = copysign(sqrt((cs[0] - cs[1]) * (cs[0] - cs[1]) + 4.0 * cs[2] * cs[2]),
                                    cs[0] - cs[1]);
            double m = 0.0;
            for (size_t k = 0; k < ncut; k++)
                m += sg[3 * cut[k]];
            smp[n].sig_s = m / (double)ncut;
        }
        n++;
    }
    free(sg);
    free(cut);
    sim_destroy(&s);
    if (rc) {
        free(smp);
        return rc;
    }
    *out = smp;
    *nout = n;
    return SPALL_OK;
}

/* The cycle read from the samples' grip F / A (which = 0), centre sigma_xx (1),
 * centre equivalent stress (2) or mean section sigma_xx (3). */
static void eb_analyse(const struct eb_sample *sm, size_t n, int which, struct eb_result *o)
{
#define SIG(k) (which == 0 ? sm[k].sig : which == 1 ? sm[k].sig_c : which == 2 ? sm[k].seq_c \
                                                                        : sm[k].sig_s)
    /* peak of the loading branch; slopes by least squares over the elastic
     * parts: loading |sigma| < sigma_Y / 2, unloading from the peak down to
     * sigma_peak - sigma_Y */
    size_t kp = 0, kl = 0; /* kl: the previous sample with a stress */
    for (size_t k = 0; k < n; k++)
        if (!isnan(SIG(k)) && sm[k].eps > sm[kp].eps)
            kp = k;
    double sig_max = -INFINITY, sig_min = INFINITY;
    for (size_t k = 0; k < n; k++) {
        sig_max = fmax(sig_max, SIG(k));
        sig_min = fmin(sig_min, SIG(k));
    }
    const double sig_peak = SIG(kp), eps_peak = sm[kp].eps;
    double sxx = 0, sxy = 0, uxx = 0, uxy = 0, eps0 = NAN;
    for (size_t k = 0; k < n; k++) {
        if (k < kp && fabs(SIG(k)) < 0.5 * EB_SY && sm[k].eps > 0) {
            sxx += sm[k].eps * sm[k].eps;
            sxy += sm[k].eps * SIG(k);
        }
        if (k > kp && SIG(k) > sig_peak - EB_SY && SIG(k) < sig_peak - 0.1 * EB_SY) {
            const double de = sm[k].eps - eps_peak, ds = SIG(k) - sig_peak;
            uxx += de * de;
            uxy += de * ds;
        }
        if (isnan(SIG(k)))
            continue;
        if (k > kp && isnan(eps0) && SIG(k) <= 0.0 && SIG(kl) > 0.0)
            eps0 = sm[kl].eps + (sm[k].eps - sm[kl].eps) * SIG(kl) / (SIG(kl) - SIG(k));
        kl = k;
    }
    o->E_load = sxx > 0 ? sxy / sxx : NAN;
    o->E_unl = uxx > 0 ? uxy / uxx : NAN;
    o->sig_max = sig_max;
    o->sig_min = sig_min;
    o->eps_peak = eps_peak;
    o->sig_peak = sig_peak;
    o->eps0 = eps0;
#undef SIG
}

int pd_case_eps_bar(struct vreport *r, struct spall_error *err)
{
    struct eb_sample *sm = NULL;
    size_t n = 0, np = 0;
    double area = 0.0;
    /* the old drive (file comment): its unloading slopes, kept as rows */
    int rc = eb_run(EB_RAMP_OLD, &sm, &n, &area, &np, err);
    if (rc)
        return rc;
    struct eb_result ocen, osec;
    eb_analyse(sm, n, 1, &ocen);
    eb_analyse(sm, n, 3, &osec);
    free(sm);
    sm = NULL;
    if ((rc = eb_run(EB_RAMP, &sm, &n, &area, &np, err)))
        return rc;
    struct eb_result nom, cen, ceq, sec;
    eb_analyse(sm, n, 0, &nom);
    eb_analyse(sm, n, 1, &cen);
    eb_analyse(sm, n, 2, &ceq);
    eb_analyse(sm, n, 3, &sec);
    if (r->keep_series) {
        double *x = malloc(n * sizeof *x), *y = malloc(n * sizeof *y);
        double *xc = malloc(n * sizeof *xc), *yc = malloc(n * sizeof *yc);
        size_t nc = 0;
        if (x && y && xc && yc) {
            for (size_t k = 0; k < n; k++) {
                x[k] = sm[k].eps * 1e3;
                y[k] = sm[k].sig / 1e6;
                if (!isnan(sm[k].sig_c)) {
                    xc[nc] = x[k];
                    yc[nc++] = sm[k].sig_c / 1e6;
                }
            }
            rc = vreport_series(r, "stress-strain", "gauge strain [1e-3]", "stress [MPa]",
                                "F/A", VSERIES_LINE, x, y, n, err);
            if (!rc)
                rc = vreport_series(r, "stress-strain", "gauge strain [1e-3]", "stress [MPa]",
                                    "centre sigma_xx", VSERIES_LINE, xc, yc, nc, err);
        }
        free(x);
        free(y);
        free(xc);
        free(yc);
        if (rc) {
            free(sm);
            return rc;
        }
    }
    free(sm);
    const char *src = "elastic-perfectly plastic bar (uniaxial stress), input E and sigma_Y";
    const char *note_c = "2 %: the centre particle (complete, isotropic family) under the "
                         "residual waves of the quasi-static drive";
    const char *note_y = "1 %: the return map holds the equivalent stress on the yield surface "
                         "(2D J2: sqrt((sxx - syy)^2 + 4 sxy^2) = sigma_Y)";
    const char *gap_old = "ramps of 2 wave transits: the velocity reversal leaves inertial "
                          "stress in the gauge; the same slopes with ramps of 4 transits (rows "
                          "above) +0.78 / +0.22 %, of 8 transits +0.13 / -0.05 % (centre / "
                          "section)";
    if ((rc = vreport_check(r, "centre: loading elastic slope", "Pa", EB_E, cen.E_load, 0.02,
                            true, src, note_c, err)))
        return rc;
    if ((rc = vreport_check(r, "centre: unloading elastic slope", "Pa", EB_E, cen.E_unl, 0.02,
                            true, src, note_c, err)))
        return rc;
    if ((rc = vreport_check(r, "centre: yield, largest equivalent stress", "Pa", EB_SY,
                            ceq.sig_max, 0.01, true, src, note_y, err)) ||
        (rc = vreport_check(r, "centre: reverse yield, smallest equivalent stress", "Pa",
                            -EB_SY, ceq.sig_min, 0.01, true, src, note_y, err)) ||
        (rc = vreport_check(r, "centre: strain at zero stress on unloading", "1",
                            cen.eps_peak - cen.sig_peak / EB_E, cen.eps0, 0.02 * EB_SY / EB_E,
                            false, "eps_peak - sigma_peak / E (measured peak)",
                            "2 % of eps_Y: the plastic strain the unloading leaves", err)))
        return rc;
    if ((rc = vreport_check(r, "section: unloading elastic slope (mean sigma_xx)", "Pa", EB_E,
                            sec.E_unl, 0.02, true, src, "2 %: the middle cross-section, surface "
                            "particles included", err)))
        return rc;
    if ((rc = vreport_check(r, "section: yield plateau (largest mean sigma_xx)", "Pa", EB_SY,
                            sec.sig_max, 0.02, true, src, "2 %: as the section slope", err)))
        return rc;
    /* the old drive's slopes (kept: they were the case's rows until 2026-12-07) */
    if ((rc = vreport_check(r, "ramps 2 transits: centre: unloading elastic slope", "Pa", EB_E,
                            ocen.E_unl, 0.02, true, src, note_c, err)))
        return rc;
    if (!r->checks[r->n - 1].pass)
        vreport_mark_gap(r, gap_old);
    if ((rc = vreport_check(r, "ramps 2 transits: section: unloading elastic slope", "Pa", EB_E,
                            osec.E_unl, 0.02, true, src, "2 %: the middle cross-section, surface "
                            "particles included", err)))
        return rc;
    if (!r->checks[r->n - 1].pass)
        vreport_mark_gap(r, gap_old);
    vreport_info(r, "pd-eps-bar: %zu particles, A = %.4g m^2; grip F/A (inertia included): "
                 "slopes %.4g / %.4g GPa (load / unload), max %.4g, min %.4g MPa; section mean: "
                 "slopes %.4g / %.4g GPa, max %.4g, min %.4g MPa; centre sigma_xx: slopes %.4g "
                 "/ %.4g GPa, max %.4g, min %.4g MPa, peak strain %.4g, zero stress at strain "
                 "%.4g; ramps of 2 transits: unloading slopes %.4g (centre), %.4g GPa (section), "
                 "section max %.4g MPa", np, area, nom.E_load / 1e9, nom.E_unl / 1e9,
                 nom.sig_max / 1e6, nom.sig_min / 1e6, sec.E_load / 1e9, sec.E_unl / 1e9, sec.sig_max / 1e6,
                 sec.sig_min / 1e6, cen.E_load / 1e9, cen.E_unl / 1e9, cen.sig_max / 1e6,
                 cen.sig_min / 1e6, cen.eps_peak, cen.eps0, ocen.E_unl / 1e9, osec.E_unl / 1e9,
                 osec.sig_max / 1e6);
    return SPALL_OK;
}
