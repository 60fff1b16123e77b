/**
 * @file macro_cases.c
 * @brief Validation cases of the macro-particle model: Table 1, the rod of
 *        [Saitoh] section 2.6 (elastic, large strain, plastic) and the
 *        Langevin thermostat.
 */
#include "validation/macro_cases.h"
#include "validation/lattice_cases.h"
#include "validation/validation.h"

#include "core/particles.h"
#include "core/sim.h"
#include "models/macroparticle/macro_calib.h"
#include "spall/error.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const char *const SRC_T1 = "[Saitoh] Table 1 (E from Eq. 15)";
static const char *const SRC_26 = "[Saitoh] section 2.6 (rod of 14 mm, Al, p = 4, q = 9)";

/* ---- Table 1 -------------------------------------------------------------------- */

int macro_case_calibration(struct vreport *r, struct spall_error *err)
{
    static const double pq[5][2] = {{3, 9}, {4, 8}, {4, 9}, {4, 10}, {5, 9}};
    static const double paper[5][2] = {{51.6, 76.2}, {61.1, 90.4}, {68.8, 101.6},
                                       {76.4, 112.9}, {95.5, 117.2}};
    const double rho[2] = {2700.0, 8960.0}, mu[2] = {26.98, 63.55}, e0[2] = {3.36, 3.52};
    const char *name[2] = {"Al", "Cu"};
    int rc;
    for (int k = 0; k < 5; k++)
        for (int a = 0; a < 2; a++) {
            double E = macro_eq15_modulus(rho[a], mu[a] * MACRO_AMU, e0[a] * MACRO_EV, pq[k][0],
                                          pq[k][1]) / 1e9;
            char q[96];
            snprintf(q, sizeof q, "Table 1 %s p=%g q=%g: E (Eq. 15, e0 = %.2f eV)", name[a],
                     pq[k][0], pq[k][1], e0[a]);
            if ((rc = vreport_check(r, q, "GPa", paper[k][a], E, 0.005, true, SRC_T1,
                                    "Table 1 prints 3-4 digits and the e0 behind it is known to "
                                    "2 decimals (0.3 %): 0.5 %", err)))
                return rc;
            if (k == 4) {
                double e1 = macro_eq15_modulus(rho[a], mu[a] * MACRO_AMU, MACRO_EV, 5, 9) / 1e9;
                char note[320];
                snprintf(note, sizeof note, "the paper's p=5, q=9 row follows Eq. 15 for neither "
                         "metal: it would need e0 = %.3f eV for %s, while rows 1-4 fit %.2f eV; "
                         "we report what the formula gives", paper[k][a] / e1, name[a], e0[a]);
                vreport_mark_gap(r, note);
            }
        }
    return SPALL_OK;
}

/* ---- rod, elastic ------------------------------------------------------------------ */

static int rod_elastic_one(struct vreport *r, int n_phi, double n_h, enum macro_calibration cal,
                           double *E, double *nu, size_t *np, struct spall_error *err)
{
    /* n_phi = 32 (105 k particles): 6 wave transits instead of 12 halve its
     * cost; measured at n_phi = 8 and 16 the shorter loading changes E by
     * +0.1 % (58.66 vs 58.60, 64.19 vs 64.13 GPa, lattice) */
    const double transits = n_phi >= 32 ? 6.0 : 12.0;
    struct macro_rod rod;
    memset(&rod, 0, sizeof rod);
    rod.n_phi = n_phi;
    rod.n_h = n_h;
    rod.sign = 1;
    rod.eps_end = 2e-3;
    rod.transits = transits;
    rod.calibration = cal;
    int rc = macro_rod_run(r, &rod, err);
    if (rc) {
        macro_rod_free(&rod);
        return rc;
    }
    *E = macro_fit_slope(rod.strain, rod.stress, rod.n, 0.5e-3, 2.1e-3);
    *nu = -macro_fit_slope(rod.strain, rod.lateral, rod.n, 0.5e-3, 2.1e-3);
    *np = rod.particles;
    vreport_info(r, "rod %-7s n_phi = %2d, n_h/n_phi = %-6g (%g transits): %6zu particles, r0 = "
                 "%.4g mm, E = %.4g GPa = %.4f E_[100] of the lattice (%.4g GPa), %.4f Eq. 15 "
                 "(%.4g); nu = %.4f", cal == MACRO_CAL_LATTICE ? "lattice" : "eq15", n_phi,
                 n_h / n_phi, transits,
                 rod.particles, rod.r0 * 1e3, *E / 1e9, *E / rod.E_fcc100, rod.E_fcc100 / 1e9,
                 *E / rod.E_eq15, rod.E_eq15 / 1e9, *nu);
    macro_rod_free(&rod);
    return SPALL_OK;
}

/** E and nu over n_phi at n_h/n_phi = 1; returns the count run. */
static int convergence(struct vreport *r, enum macro_calibration cal, const int *nphi, int nn,
                       double *E, double *nu, struct spall_error *err)
{
    for (int k = 0; k < nn; k++) {
        size_t np;
        int rc = rod_elastic_one(r, nphi[k], nphi[k], cal, &E[k], &nu[k], &np, err);
        if (rc)
            return rc;
    }
    return SPALL_OK;
}

static bool monotone(const double *E, int nn, double target)
{
    bool mono = true;
    for (int k = 1; k < nn; k++)
        mono = mono && E[k] > E[k - 1] && fabs(target - E[k]) < fabs(target - E[k - 1]);
    return mono;
}

int macro_case_rod_elastic(struct vreport *r, struct spall_error *err)
{
    /* seed's calibration to n_phi = 16; the lattice calibration to 32 (E/E_[100]
     * is the same for both: every force scales with D, and the loading is
     * set in wave transits) */
    const int nphi[5] = {2, 4, 8, 16, 32};
    const int n_eq = r->quick ? 3 : 4, n_lat = r->quick ? 3 : 5;
    double E[5] = {0}, nu[5] = {0}, El[5] = {0}, nul[5] = {0};
    int rc;
    struct macro_calib c;
    memset(&c, 0, sizeof c);
    c.rho = 2700.0;
    c.atom_mass = 26.98 * MACRO_AMU;
    c.e0 = 3.39 * MACRO_EV;
    c.p = 4;
    c.q = 9;
    c.r0 = 1e-3;
    if ((rc = macro_calibrate(&c, err)))
        return rc;
    const double Eeq = c.E, Efcc = c.E_fcc100;
    vreport_info(r, "convergence with n_phi at n_h/n_phi = 1 (E: least-squares slope of the "
                 "nominal stress over 0.05-0.2 %% strain); seed calibration (eq15, D = "
                 "P_atom/6): lattice E_[100] = %.4g GPa = %.4f x Eq. 15 (%.4g GPa):", Efcc / 1e9,
                 Efcc / Eeq, Eeq / 1e9);
    if ((rc = convergence(r, MACRO_CAL_EQ15, nphi, n_eq, E, nu, err)))
        return rc;
    vreport_info(r, "lattice calibration (D scaled by %.4f so that the lattice E_[100] = Eq. "
                 "15):", Eeq / Efcc);
    if ((rc = convergence(r, MACRO_CAL_LATTICE, nphi, n_lat, El, nul, err)))
        return rc;
    if ((rc = vreport_check_true(r, "rod E converges monotonically with n_phi (eq15)",
                                 monotone(E, n_eq, Efcc), SRC_26,
                                 "surface particles miss bonds: the modulus rises towards the "
                                 "bulk value as the surface fraction falls", err)) ||
        (rc = vreport_check_true(r, "rod E converges monotonically with n_phi (lattice)",
                                 monotone(El, n_lat, Eeq), SRC_26,
                                 "as above, towards the calibrated E", err)))
        return rc;
    char q[112];
    const int f = n_eq - 1, fl = n_lat - 1;
    if (!r->quick) {
        /* the check on the seed's own calibration: a known gap */
        snprintf(q, sizeof q, "eq15 finest rod (n_phi = %d): E vs the calibrated Eq. 15",
                 nphi[f]);
        if ((rc = vreport_check(r, q, "GPa", Eeq / 1e9, E[f] / 1e9, 0.05, true, SRC_26,
                                "the issue's 5 %", err)))
            return rc;
        {
            char note[360];
            snprintf(note, sizeof note, "Eq. 15 (phi''/2r0) is a chain estimate: the FCC "
                     "crystal of the seed's pairs has E_[100] = (2 sqrt2/3) phi''/r0 = %.4g GPa "
                     "= %.3f x Eq. 15 and the rod converges to that; calibration: lattice "
                     "closes this (checks below)", Efcc / 1e9, Efcc / Eeq);
            vreport_mark_gap(r, note);
        }
        snprintf(q, sizeof q, "eq15 finest rod (n_phi = %d): E vs its lattice E_[100]", nphi[f]);
        if ((rc = vreport_check(r, q, "GPa", Efcc / 1e9, E[f] / 1e9, 0.05, true,
                                "Cauchy-Born of the Mie pair on FCC, C11 = 2 C12 = 2 C44",
                                "the issue's 5 %", err)))
            return rc;
        if (!r->checks[r->n - 1].pass)
            vreport_mark_gap(r, "surface particles miss bonds; at n_phi = 16 they still "
                             "soften the rod; n_phi = 32 reaches 5 % (lattice calibration "
                             "below, same ratio E / E_[100])");
        snprintf(q, sizeof q, "lattice finest rod (n_phi = %d): E vs the calibrated Eq. 15",
                 nphi[fl]);
        if ((rc = vreport_check(r, q, "GPa", Eeq / 1e9, El[fl] / 1e9, 0.05, true, SRC_26,
                                "the issue's 5 %: 'the finest model is within 5 % of the "
                                "calibrated value'", err)))
            return rc;
    }
    for (int k = r->quick ? n_eq - 1 : 0; k < n_eq; k++) {
        /* the source's band, 0.30-0.33 ([Saitoh] sec. 3.1, Fig. 5), centre 0.315 +- 0.015 */
        snprintf(q, sizeof q, "rod n_phi = %d: Poisson's ratio (0.30-0.33)", nphi[k]);
        if ((rc = vreport_check(r, q, "1", 0.315, nu[k], 0.015, false,
                                "[Saitoh] sec. 3.1, Fig. 5: nu of the sec. 2.6 rod 0.30-0.33 "
                                "(printed '3.0 to 3.3')",
                                "the source's band 0.30-0.33; not a fitted input", err)))
            return rc;
        if (!r->checks[r->n - 1].pass) {
            char note[320];
            snprintf(note, sizeof note,
                     "nu = %.4f, above the band; the bulk [100] nu of this FCC pair lattice is 1/3 "
                     "by construction (C11 = 2 C12: nu = C12 / (C11 + C12)), 0.0033 above the "
                     "band; coarse rods lie above 1/3 (surface particles miss bonds) and approach "
                     "it with n_phi",
                     nu[k]);
            vreport_mark_gap(r, note);
        }
    }
    if (r->quick)
        return SPALL_OK;
    /* aspect ratio sweeps, lattice calibration: n_phi = 4 (1/4..8; 1/8 leaves
     * only the two driven layers), n_phi = 8 (1/8..8), n_phi = 16 (1/8 and
     * 4: the paper's 51 413-particle model) */
    static const double ra[7] = {0.125, 0.25, 0.5, 1, 2, 4, 8};
    static const struct { int nphi, k0, k1; } sweep[3] = {{4, 1, 6}, {8, 0, 6}, {16, 0, 0}};
    for (int g = 0; g < 3; g++) {
        vreport_info(r, "aspect ratio sweep at n_phi = %d (lattice calibration):", sweep[g].nphi);
        double emin = INFINITY, emax = 0.0;
        for (int k = sweep[g].k0; k <= sweep[g].k1; k++) {
            double e1, n1;
            size_t p1;
            if ((rc = rod_elastic_one(r, sweep[g].nphi, sweep[g].nphi * ra[k], MACRO_CAL_LATTICE,
                                      &e1, &n1, &p1, err)))
                return rc;
            emin = fmin(emin, e1);
            emax = fmax(emax, e1);
        }
        if (g == 2) {
            double e1, n1;
            size_t p1;
            if ((rc = rod_elastic_one(r, 16, 64, MACRO_CAL_LATTICE, &e1, &n1, &p1, err)))
                return rc;
            snprintf(q, sizeof q, "n_phi = 16, n_h/n_phi = 4 (%zu particles): E vs Eq. 15", p1);
            if ((rc = vreport_check(r, q, "GPa", Eeq / 1e9, e1 / 1e9, 0.05, true, SRC_26,
                                    "the issue's 5 %, on the paper's model", err)))
                return rc;
            if (!r->checks[r->n - 1].pass)
                vreport_mark_gap(r, "n_phi = 16 is still surface-softened (see the "
                                 "convergence); n_phi = 32 reaches the 5 %");
        } else {
            vreport_info(r, "n_phi = %d: E over the aspect ratios %.4g-%.4g GPa", sweep[g].nphi,
                         emin / 1e9, emax / 1e9);
        }
    }
    return SPALL_OK;
}
