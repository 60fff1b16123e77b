/**
 * @file pen_thesis.c
 * @brief Validation cases "pen-thesis-refs" and "pen-gelatin-time": the
 *        thesis' experiments (data/penetration) against the analytical
 *        models with the thesis' coefficients ([Meng2021] sec. 4.2, 4.4, 4.5).
 *
 * pen-thesis-refs:
 *  - the recorded reference tables (gelatin_poncelet_reference.csv,
 *    sebs_mcg_reference.csv, written by scripts/pen_references.sh) are what
 *    the SPH cases of issue 7 item 4 will be checked against; they must equal
 *    the library's current predictions (1e-9), so they cannot drift;
 *  - every SEBS case stays in the Modified-CG model's range, Re < 1e5
 *    (sec. 4.2.2.1);
 *  - Poncelet (C_d = 0.375, R = 21 MPa) with the nose (Eq. 4.7) against the
 *    measured ~67 um at 1290 m/s (sec. 4.4.2.1, Fig. 4.1);
 *  - Poncelet (C_d = 0.8, R = 33.7 MPa) and Modified-CG (eta = 4.5e-2,
 *    R = 25 MPa), both fitted by the thesis to the same P_max points
 *    (approach b, Fig. 4.5), agree on the SEBS cases.
 * pen-gelatin-time: Poncelet's T_f against "maximum depth reached 200-250 ns
 *    after impact" (Fig. 4.8) -- a known gap, explained in the check.
 */
#include "validation/pen_cases.h"
#include "validation/validation.h"

#include "spall/error.h"
#include "spall/penetration.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#ifndef SPALL_SOURCE_DIR
#define SPALL_SOURCE_DIR "."
#endif

static int read_data(const char *name, struct pen_csv *c, struct spall_error *err)
{
    const char *root = getenv("SPALL_SOURCE_DIR");
    char path[1024];
    snprintf(path, sizeof path, "%s/data/penetration/%s", root && *root ? root : SPALL_SOURCE_DIR,
             name);
    return pen_csv_read(path, c, err);
}

static int need_cols(const struct pen_csv *c, const char *file, const char *const *names,
                     int *idx, int n, struct spall_error *err)
{
    for (int k = 0; k < n; k++)
        if ((idx[k] = pen_csv_column(c, names[k])) < 0)
            return spall_error_set(err, SPALL_ERR_INPUT, "%s has no column '%s'", file, names[k]);
    return SPALL_OK;
}

static double cell(const struct pen_csv *c, size_t row, int col)
{
    return c->data[row * c->n_cols + (size_t)col];
}

static struct pen_params gelatin_poncelet(void)
{
    struct pen_params p = {0};
    p.model = PEN_PONCELET;
    p.rho_p = 1850.0, p.rho_t = 1030.0, p.cd = 0.375, p.R = 21.0e6, p.d = 7.38e-6;
    return p;
}

static struct pen_params sebs(enum pen_model m)
{
    struct pen_params p = {0};
    p.model = m;
    p.rho_p = 7800.0, p.rho_t = 875.0;
    if (m == PEN_MCG)
        p.eta = 4.5e-2, p.R = 25.0e6; /* fit (b), sec. 4.2.2.2 */
    else
        p.cd = 0.8, p.R = 33.7e6;     /* Poncelet fit (b) */
    return p;
}

/* Largest relative difference between a reference table and the library;
 * also the largest Re (MCG) and, for the gelatin table, nothing else. */
static int compare_table(const char *file, struct pen_params p, double *worst, double *re_max,
                         struct vreport *r, struct spall_error *err)
{
    struct pen_csv c;
    int rc = read_data(file, &c, err);
    if (rc)
        return rc;
    static const char *const names[] = {"d", "v0", "T_f", "P_max", "P_max_nose", "P_max_over_d"};
    int col[6];
    *worst = 0.0;
    *re_max = 0.0;
    if ((rc = need_cols(&c, file, names, col, 6, err)))
        goto done;
    for (size_t i = 0; i < c.n_rows; i++) {
        struct pen_result res;
        p.d = cell(&c, i, col[0]);
        const double v0 = cell(&c, i, col[1]);
        if ((rc = pen_solve(&p, v0, 0, NULL, NULL, NULL, 0, &res, err)))
            goto done;
        const double mine[4] = {res.t_f, res.p_max, res.p_max + 0.5 * p.d, res.p_max / p.d};
        for (int k = 0; k < 4; k++)
            *worst = fmax(*worst, fabs(mine[k] / cell(&c, i, col[k + 2]) - 1.0));
        *re_max = fmax(*re_max, res.re_max);
        vreport_info(r, "%s: d = %5.2f um, v0 = %6.1f m/s: P_max = %7.3f um, P_max/d = %7.4f, "
                     "T_f = %6.1f ns",
                     pen_model_name(p.model), p.d * 1e6, v0, res.p_max * 1e6, res.p_max / p.d,
                     res.t_f * 1e9);
    }
done:
    pen_csv_free(&c);
    return rc;
}

int pen_case_thesis_refs(struct vreport *r, struct spall_error *err)
{
    double worst = 0.0, re_max = 0.0;
    const char *ref_note = "1e-9: the table is printed with 11 significant digits; any larger "
                           "gap means the models changed and the table must be regenerated";
    int rc = compare_table("gelatin_poncelet_reference.csv", gelatin_poncelet(), &worst, &re_max,
                           r, err);
    if (rc ||
        (rc = vreport_check(r, "gelatin_poncelet_reference.csv vs library (max rel. diff.)", "1",
                            0.0, worst, 1e-9, false,
                            "scripts/pen_references.sh; Poncelet C_d = 0.375, R = 21 MPa "
                            "(sec. 4.4.2, Fig. 4.14)",
                            ref_note, err)))
        return rc;
    if ((rc = compare_table("sebs_mcg_reference.csv", sebs(PEN_MCG), &worst, &re_max, r, err)) ||
        (rc = vreport_check(r, "sebs_mcg_reference.csv vs library (max rel. diff.)", "1", 0.0,
                            worst, 1e-9, false,
                            "scripts/pen_references.sh; Modified-CG eta = 4.5e-2, R = 25 MPa "
                            "(sec. 4.2.2.2, Fig. 4.28)",
                            ref_note, err)) ||
        (rc = vreport_check_true(r, "SEBS cases: Re = rho_t v0 d / eta < 1e5 (max printed below)",
                                 re_max < PEN_MCG_RE_MAX, "[Meng2021] sec. 4.2.2.1 (Eq. 4.11 range)",
                                 "the Clift-Gauvin law holds for Re < 1e5 only", err)))
        return rc;
    vreport_info(r, "largest Reynolds number of the SEBS cases: %.4g", re_max);
    /* experiment at 1290 m/s */
    struct pen_csv c;
    if ((rc = read_data("gelatin_silica_experiment.csv", &c, err)))
        return rc;
    static const char *const names[] = {"d", "v0", "P_max"};
    int col[3];
    if ((rc = need_cols(&c, "gelatin_silica_experiment.csv", names, col, 3, err))) {
        pen_csv_free(&c);
        return rc;
    }
    struct pen_params p = gelatin_poncelet();
    p.d = cell(&c, 0, col[0]);
    const double v0 = cell(&c, 0, col[1]), pexp = cell(&c, 0, col[2]);
    pen_csv_free(&c);
    struct pen_result res;
    if ((rc = pen_solve(&p, v0, 0, NULL, NULL, NULL, 0, &res, err)) ||
        (rc = vreport_check(r, "gelatin 1290 m/s: Poncelet P_max + d/2 vs experiment", "um",
                            pexp * 1e6, (res.p_max + 0.5 * p.d) * 1e6, 0.05, true,
                            "Veysset et al. via [Meng2021] sec. 4.4.2.1 ('around 67 um')",
                            "5 %: the experiment is quoted as 'around 67 um' and the thesis "
                            "calls this curve in agreement (Fig. 4.1); without the nose the "
                            "model gives 65.8 um (-1.8 %)",
                            err)))
        return rc;
    /* the one check of this regression case against an experiment */
    vreport_set_kind(r, VKIND_VALIDATION);
    /* Poncelet (b) vs MCG (b) on the SEBS cases */
    if ((rc = read_data("sebs_steel_cases.csv", &c, err)))
        return rc;
    double worst_pm = 0.0;
    static const char *const n2[] = {"d", "v0"};
    if (!(rc = need_cols(&c, "sebs_steel_cases.csv", n2, col, 2, err))) {
        for (size_t i = 0; i < c.n_rows && !rc; i++) {
            struct pen_params a = sebs(PEN_PONCELET), b = sebs(PEN_MCG);
            struct pen_result ra, rb;
            a.d = b.d = cell(&c, i, col[0]);
            const double v = cell(&c, i, col[1]);
            if (!(rc = pen_solve(&a, v, 0, NULL, NULL, NULL, 0, &ra, err)) &&
                !(rc = pen_solve(&b, v, 0, NULL, NULL, NULL, 0, &rb, err)))
                worst_pm = fmax(worst_pm, fabs(ra.p_max / rb.p_max - 1.0));
        }
    }
    pen_csv_free(&c);
    if (rc)
        return rc;
    return vreport_check(r, "SEBS: Poncelet(b) vs Modified-CG(b) P_max, max rel. diff.", "1", 0.0,
                         worst_pm, 0.15, false,
                         "[Meng2021] Fig. 4.5: both fitted to the same P_max points (approach b)",
                         "15 % (issue 7 item 4c's tolerance for SEBS): the fitted curves cross "
                         "(sec. 4.2.2.2); a larger gap would mean a wrong unit for eta or rho "
                         "in Eq. 4.10",
                         err);
}

int pen_case_gelatin_time(struct vreport *r, struct spall_error *err)
{
    struct pen_params p = gelatin_poncelet();
    enum { N = 2001 };
    double t[N], P[N];
    struct pen_result res;
    int rc = pen_solve(&p, 1290.0, 0, NULL, NULL, NULL, 0, &res, err);
    if (rc)
        return rc;
    for (int i = 0; i < N; i++)
        t[i] = res.t_f * i / (N - 1);
    if ((rc = pen_solve(&p, 1290.0, N, t, P, NULL, 0, &res, err)))
        return rc;
    double t99 = res.t_f;
    for (int i = 0; i < N; i++)
        if (P[i] >= 0.99 * res.p_max) {
            t99 = t[i];
            break;
        }
    rc = vreport_check(r, "gelatin 1290 m/s: Poncelet T_f (Eq. 4.3) vs 200-250 ns", "ns", 225.0,
                       res.t_f * 1e9, 25.0, false,
                       "Veysset et al. via [Meng2021] Fig. 4.8 / sec. 4.4.2.1",
                       "the band 200-250 ns is the experiment's", err);
    if (!rc) {
        char note[320];
        snprintf(note, sizeof note,
                 "known gap: Poncelet stops at %.1f ns, %.1f ns before the band; it reaches 99 %% "
                 "of P_max at %.1f ns.  P(t) is flat near T_f, so the frame-based time of the "
                 "experiment's maximum is loose; the thesis tunes C_d to the whole P(t), not T_f",
                 res.t_f * 1e9, 200.0 - res.t_f * 1e9, t99 * 1e9);
        vreport_mark_gap(r, note);
        vreport_info(r, "T_f = %.2f ns, 99 %% of P_max at %.2f ns, P(150 ns) = %.4f P_max",
                     res.t_f * 1e9, t99 * 1e9, P[(int)((N - 1) * 150e-9 / res.t_f)] / res.p_max);
    }
    return rc;
}
