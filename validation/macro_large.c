/**
 * @file macro_large.c
 * @brief Large-strain rod cases of seed 001 section 2.6: tension against
 *        compression, the compressive collapse, and tension with pair
 *        plasticity (monotonic and loading-unloading-reloading).
 */
#include "validation/macro_cases.h"
#include "validation/validation.h"

#include "spall/error.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const char *const SRC_26 = "seed 001 section 2.6 (rod of 14 mm, Al, p = 4, q = 9)";

/** Stress interpolated at |strain| = e on the loading part (first crossing). */
static double stress_at(const struct macro_rod *rod, double e)
{
    for (size_t k = 1; k < rod->n; k++) {
        double a = fabs(rod->strain[k - 1]), b = fabs(rod->strain[k]);
        if (a <= e && b >= e && b > a) {
            double t = (e - a) / (b - a);
            return fabs(rod->stress[k - 1] + t * (rod->stress[k] - rod->stress[k - 1]));
        }
    }
    return NAN;
}

static void print_curve(struct vreport *r, const char *label, const struct macro_rod *rod)
{
    char line[1024];
    size_t w = (size_t)snprintf(line, sizeof line, "%s (strain %%: stress MPa):", label);
    size_t step = rod->n / 14 + 1;
    for (size_t k = 0; k < rod->n && w < sizeof line; k += step)
        w += (size_t)snprintf(line + w, sizeof line - w, " %.2f:%.0f", 100.0 * rod->strain[k],
                              rod->stress[k] / 1e6);
    vreport_info(r, "%s", line);
}

int macro_case_rod_large(struct vreport *r, struct spall_error *err)
{
    const int nphi = r->quick ? 4 : 8;
    struct macro_rod t, c;
    memset(&t, 0, sizeof t);
    t.n_phi = nphi;
    t.n_h = nphi;
    t.sign = 1;
    t.eps_end = 0.05;
    t.transits = 40.0;
    c = t;
    c.sign = -1;
    int rc = macro_rod_run(&t, err);
    if (!rc)
        rc = macro_rod_run(&c, err);
    if (rc)
        goto done;
    print_curve(r, "tension", &t);
    print_curve(r, "compression", &c);
    /* strain up to which |sigma_c| and sigma_t agree within 5 % */
    double agree = 0.0;
    for (double e = 0.001; e <= 0.05; e += 0.0005) {
        double st = stress_at(&t, e), sc = stress_at(&c, e);
        if (!isfinite(st) || !isfinite(sc) || fabs(sc - st) > 0.05 * st)
            break;
        agree = e;
    }
    char q[96];
    snprintf(q, sizeof q, "n_phi = %d: tension/compression agree (5 %%) up to strain", nphi);
    if ((rc = vreport_check(r, q, "%", 3.0, 100.0 * agree, 1.0, false, SRC_26,
                            "the paper reads 'symmetric to about 3 %' off a plot; +-1 % strain",
                            err)))
        goto done;
    if (!r->checks[r->n - 1].pass) {
        char note[320];
        snprintf(note, sizeof note, "measured: the rod is softer in compression than in tension "
                 "(|sigma_c|/sigma_t = %.3f at 1 %%, %.3f at 3 %%): the [100] FCC lattice "
                 "softens towards its compressive instability (see the collapse check)",
                 stress_at(&c, 0.01) / stress_at(&t, 0.01),
                 stress_at(&c, 0.03) / stress_at(&t, 0.03));
        vreport_mark_gap(r, note);
    }
    /* compressive collapse: the peak of |stress| followed by a drop */
    size_t kp = 0;
    for (size_t k = 0; k < c.n; k++)
        if (-c.stress[k] > -c.stress[kp])
            kp = k;
    /* smallest compressive stress after the peak, relative to the peak */
    double drop = 1.0;
    for (size_t k = kp + 1; k < c.n; k++)
        drop = fmin(drop, -c.stress[k] / -c.stress[kp]);
    vreport_info(r, "compression: peak |stress| %.4g MPa at strain %.3f %% (lateral strain %.3f "
                 "%%), min stress after / peak = %.3f; at the end strain %.3f %%, lateral "
                 "strain %.3f %%", fabs(c.stress[kp]) / 1e6, 100.0 * fabs(c.strain[kp]),
                 100.0 * c.lateral[kp], drop, 100.0 * c.strain[c.n - 1],
                 100.0 * c.lateral[c.n - 1]);
    {
        /* slip planes: on a {111} plane the three <110> bond families lying
         * in the plane survive, the three crossing it break */
        static const int nrm[4][3] = {{1, 1, 1}, {1, 1, -1}, {1, -1, 1}, {-1, 1, 1}};
        static const int fam[6][3] = {{1, 1, 0}, {1, -1, 0}, {1, 0, 1}, {1, 0, -1}, {0, 1, 1},
                                      {0, 1, -1}};
        size_t tot = 0;
        for (int k = 0; k < 6; k++)
            tot += c.broken[k];
        char line[400];
        size_t w = (size_t)snprintf(line, sizeof line, "compression end: %zu of %zu nearest-"
                                    "neighbour pairs separated (> 1.2 r0); by family (110) "
                                    "(1-10) (101) (10-1) (011) (01-1):", tot, c.bonds0);
        for (int k = 0; k < 6 && w < sizeof line; k++)
            w += (size_t)snprintf(line + w, sizeof line - w, " %zu", c.broken[k]);
        vreport_info(r, "%s", line);
        for (int n = 0; n < 4; n++) {
            size_t in = 0, out = 0;
            for (int k = 0; k < 6; k++) {
                int dot = nrm[n][0] * fam[k][0] + nrm[n][1] * fam[k][1] + nrm[n][2] * fam[k][2];
                if (dot == 0)
                    in += c.broken[k];
                else
                    out += c.broken[k];
            }
            vreport_info(r, "  plane (%+d%+d%+d): separated bonds crossing it %zu, lying in it "
                         "%zu", nrm[n][0], nrm[n][1], nrm[n][2], out, in);
        }
    }
    snprintf(q, sizeof q, "n_phi = %d: compressive collapse strain", nphi);
    if ((rc = vreport_check(r, q, "%", 3.2, kp + 1 < c.n && drop < 0.5 ? 100.0 * fabs(c.strain[kp])
                                                                      : NAN,
                            0.5, false, SRC_26,
                            "the paper's 3.2 % read off its figure; +-0.5 % strain", err)))
        goto done;
    if (!r->checks[r->n - 1].pass)
        vreport_mark_gap(r, "measured: the peak compressive stress before the collapse (NaN: "
                         "no drop within 5 %); the collapse is a homogeneous lattice "
                         "instability (section expands, no bond separates, see the counts "
                         "above), later than the paper's (111) slip at 3.2 %");
done:
    macro_rod_free(&t);
    macro_rod_free(&c);
    return rc;
}

int macro_case_rod_plastic(struct vreport *r, struct spall_error *err)
{
    const int nphi = r->quick ? 4 : 8;
    /* pair yield stretch so that a [100] rod yields at 1 % (our calibration
     * of the paper's observation): the 45-degree bonds stretch by
     * eps (1 - nu)/2 with nu = 1/3 */
    const double ey = 0.01 * (1.0 - 1.0 / 3.0) / 2.0;
    struct macro_rod t, l;
    memset(&t, 0, sizeof t);
    t.n_phi = nphi;
    t.n_h = nphi;
    t.sign = 1;
    t.eps_end = 0.03;
    t.transits = 40.0;
    t.yield_strain = ey;
    l = t;
    /* loop: load to 2 %, unload, reload to 3 % (velocity table, times / T) */
    static const double loop[][2] = {{0, 0},    {0.05, 1},  {0.45, 1}, {0.5, -1},
                                      {0.62, -1}, {0.67, 1}, {1.0, 1}};
    l.table = loop;
    l.n_table = 7;
    l.eps_end = 0.045;
    int rc = macro_rod_run(&t, err);
    if (!rc)
        rc = macro_rod_run(&l, err);
    if (rc)
        goto done;
    print_curve(r, "plastic tension", &t);
    print_curve(r, "load-unload-reload", &l);
    double E0 = macro_fit_slope(t.strain, t.stress, t.n, 1e-3, 4e-3);
    /* yield: first strain where the secant modulus falls 5 % below E0 */
    double ey_rod = NAN;
    for (size_t k = 0; k < t.n; k++)
        if (t.strain[k] > 1e-3 && t.stress[k] / t.strain[k] < 0.95 * E0) {
            ey_rod = t.strain[k];
            break;
        }
    char q[96];
    snprintf(q, sizeof q, "n_phi = %d: yield strain in tension (5 %% secant drop)", nphi);
    if ((rc = vreport_check(r, q, "%", 1.0, 100.0 * ey_rod, 0.3, false, SRC_26,
                            "the paper's ~1 % read off its figure; the pair yield stretch is "
                            "set from it (eps_y (1 - nu)/2), so this checks the mapping; "
                            "+-0.3 % strain", err)))
        goto done;
    double s15 = stress_at(&t, 0.015), s28 = stress_at(&t, 0.028);
    snprintf(q, sizeof q, "n_phi = %d: hardening after yield (stress 2.8 %% > 1.5 %%)", nphi);
    if ((rc = vreport_check_true(r, q, s28 > s15, SRC_26, "the paper's rod hardens after "
                                 "yield; our pairs harden linearly (tangent 0.1)", err)))
        goto done;
    vreport_info(r, "plastic tension: E0 = %.4g GPa, stress at 1.5 %% = %.4g MPa, at 2.8 %% = "
                 "%.4g MPa", E0 / 1e9, s15 / 1e6, s28 / 1e6);
    /* loop: max strain before unloading, min after, slopes */
    size_t kmax = 0;
    for (size_t k = 0; k < l.n && k < (size_t)(0.5 * (double)l.n); k++)
        if (l.strain[k] > l.strain[kmax])
            kmax = k;
    size_t kmin = kmax;
    for (size_t k = kmax; k < l.n && k < (size_t)(0.72 * (double)l.n); k++)
        if (l.strain[k] < l.strain[kmin])
            kmin = k;
    double smax = l.stress[kmax];
    double Eu = (l.stress[kmax] - l.stress[kmin]) / (l.strain[kmax] - l.strain[kmin]);
    vreport_info(r, "loop: unloading from strain %.3f %% (stress %.4g MPa) to %.3f %% (stress "
                 "%.4g MPa), unloading modulus %.4g GPa", 100.0 * l.strain[kmax], smax / 1e6,
                 100.0 * l.strain[kmin], l.stress[kmin] / 1e6, Eu / 1e9);
    if ((rc = vreport_check(r, "loop: unloading modulus / initial modulus", "1", 1.0, Eu / E0,
                            0.1, true, "seed 001 Eq. 16 (shifted elastic unloading branch)",
                            "unloading follows the elastic branch; 10 % for the dynamic "
                            "overshoot at the velocity reversal", err)))
        goto done;
    double res = l.strain[kmin] - l.stress[kmin] / E0;
    if ((rc = vreport_check_true(r, "loop: permanent strain after unloading > 0.2 %",
                                 res > 0.002, "seed 001 Eq. 16 / Fig. 2",
                                 "pairs keep their plastic offset dr0", err)))
        goto done;
    /* reloading reaches the earlier maximum stress near the earlier maximum strain */
    double s_re = NAN;
    for (size_t k = kmin; k + 1 < l.n; k++)
        if (l.strain[k] <= l.strain[kmax] && l.strain[k + 1] >= l.strain[kmax]) {
            s_re = l.stress[k + 1];
            break;
        }
    if ((rc = vreport_check(r, "loop: reloading meets the earlier curve at the unloading point",
                            "MPa", smax / 1e6, s_re / 1e6, 0.05, true,
                            "seed 001 Fig. 2 (elastic reloading up to the earlier yield)",
                            "5 % for the dynamic response at the reversals", err)))
        goto done;
done:
    macro_rod_free(&t);
    macro_rod_free(&l);
    return rc;
}
