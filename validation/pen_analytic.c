/**
 * @file pen_analytic.c
 * @brief Validation cases "pen-check-value" and "pen-ode" ([Meng2021] sec. 4.2).
 *
 * Check value (digest of [Meng2021] chapter 4): silica d = 7.38 um into 10 wt%
 * gelatin at 1290 m/s, C_d = 0.375, R = 21 MPa -> P_max = 65.8 um (Eq. 4.6),
 * 69.5 um with the nose d/2 (Eq. 4.7).  Densities: the thesis' Tab. 4.4
 * (silica 1850 kg/m^3) and Tab. 4.3 (10 wt% gelatin 1030 kg/m^3); with
 * these Eq. 4.6 gives 65.78 um, the digest's value to 0.03 %.
 *
 * ODE: P(t) integrated with gsl_odeiv2 (rk8pd) must match the closed form
 * (Eq. 4.2 for Poncelet; the quadratic-force closed form for Liu) to 1e-6 of
 * P_max at every one of 401 times in [0, T_f]; for the Modified-CG model,
 * which has no closed form, the ODE's P(T_f) must match an independent
 * quadrature P_max = M int_0^v0 v dv / F(v) (gsl_integration_qag).
 */
#include "validation/pen_cases.h"
#include "validation/validation.h"

#include "spall/error.h"
#include "spall/penetration.h"

#include <gsl/gsl_errno.h>
#include <gsl/gsl_integration.h>
#include <math.h>
#include <stdio.h>

#define CV_SRC "digest of [Meng2021] ch. 4 (check value); Eq. 4.6/4.7, rho from Tab. 4.3/4.4"

static struct pen_params gelatin_silica(void)
{
    struct pen_params p = {0};
    p.model = PEN_PONCELET;
    p.d = 7.38e-6;
    p.rho_p = 1850.0; /* Tab. 4.4 silica */
    p.rho_t = 1030.0; /* Tab. 4.3 10 wt% gelatin */
    p.cd = 0.375;
    p.R = 21.0e6;
    return p;
}

int pen_case_check_value(struct vreport *r, struct spall_error *err)
{
    const struct pen_params p = gelatin_silica();
    const double v0 = 1290.0;
    struct pen_result res;
    double tf_arr[1], P_end[1];
    int rc = pen_poncelet(&p, v0, 0, NULL, NULL, NULL, &res, err);
    if (rc)
        return rc;
    tf_arr[0] = res.t_f;
    if ((rc = pen_poncelet(&p, v0, 1, tf_arr, P_end, NULL, &res, err)))
        return rc;
    if ((rc = vreport_check(r, "P_max, Poncelet Eq. 4.6", "um", 65.8, res.p_max * 1e6, 1e-3, true,
                            CV_SRC,
                            "0.1 % (issue 7): the digest quotes 3 significant digits, so the "
                            "reference itself is rounded by up to 0.08 %",
                            err)) ||
        (rc = vreport_check(r, "P_max + d/2, Eq. 4.7 (nose)", "um", 69.5,
                            (res.p_max + 0.5 * p.d) * 1e6, 1e-3, true, CV_SRC,
                            "0.1 % (issue 7); reference rounded to 3 digits", err)) ||
        (rc = vreport_check(r, "P(T_f) of Eq. 4.2 / P_max of Eq. 4.6", "1", 1.0,
                            P_end[0] / res.p_max, 1e-12, true, "identity of Eq. 4.2 and 4.6",
                            "1e-12: the two closed forms are the same function; the gap is "
                            "rounding of ln cos",
                            err)))
        return rc;
    vreport_info(r, "rho_p = 1850, rho_t = 1030 kg/m^3: M = %.5g kg, T_f = %.5g ns (Eq. 4.3), "
                 "P_max = %.5g um, with nose %.5g um, P_max/d = %.5g",
                 pen_mass(&p), res.t_f * 1e9, res.p_max * 1e6, (res.p_max + 0.5 * p.d) * 1e6,
                 res.p_max / p.d);
    return SPALL_OK;
}

/* max_i |P_ode(t_i) - P_cf(t_i)| / P_max over n times in [0, T_f] */
static int ode_vs_closed(const struct pen_params *p, double v0, double *rel, double *tf_rel,
                         struct spall_error *err)
{
    enum { N = 401 };
    double t[N], Pc[N], Po[N];
    struct pen_result rc_, ro;
    int rc = pen_solve(p, v0, 0, NULL, NULL, NULL, 0, &rc_, err);
    if (rc)
        return rc;
    if (!rc_.closed_form)
        return spall_error_set(err, SPALL_ERR_INTERNAL, "pen-ode: no closed form for %s",
                               pen_model_name(p->model));
    for (int i = 0; i < N; i++)
        t[i] = rc_.t_f * i / (N - 1);
    if ((rc = pen_solve(p, v0, N, t, Pc, NULL, 0, &rc_, err)) ||
        (rc = pen_solve(p, v0, N, t, Po, NULL, 1, &ro, err)))
        return rc;
    double m = 0.0;
    for (int i = 0; i < N; i++)
        m = fmax(m, fabs(Po[i] - Pc[i]));
    *rel = m / rc_.p_max;
    *tf_rel = fabs(ro.t_f - rc_.t_f) / rc_.t_f;
    return SPALL_OK;
}

struct quad_ctx {
    const struct pen_params *p;
    double m;
};

static double quad_vdv(double v, void *par)
{
    const struct quad_ctx *c = par;
    return c->m * v / pen_force(c->p, v);
}

int pen_case_ode(struct vreport *r, struct spall_error *err)
{
    int rc;
    double rel = 0, tf_rel = 0;
    const char *note = "1e-6 (issue 7); rk8pd at error 1e-14 + 1e-12 |y| per step reaches ~1e-15 here";
    /* Poncelet: the check-value case and a steel sphere in SEBS (thesis a-fit) */
    struct pen_params p = gelatin_silica();
    if ((rc = ode_vs_closed(&p, 1290.0, &rel, &tf_rel, err)) ||
        (rc = vreport_check(r, "Poncelet gelatin 1290 m/s: max |P_ode - P_Eq4.2| / P_max", "1",
                            0.0, rel, 1e-6, false, "Eq. 4.2 (closed form)", note, err)) ||
        (rc = vreport_check(r, "Poncelet gelatin: T_f quadrature vs Eq. 4.3 (relative)", "1", 0.0,
                            tf_rel, 1e-6, false, "Eq. 4.3", note, err)))
        return rc;
    struct pen_params s = {0};
    s.model = PEN_PONCELET;
    s.d = 13e-6;
    s.rho_p = 7800.0;
    s.rho_t = 875.0;
    s.cd = 0.8708;
    s.R = 36.3e6;
    if ((rc = ode_vs_closed(&s, 630.0, &rel, &tf_rel, err)) ||
        (rc = vreport_check(r, "Poncelet SEBS 13 um 630 m/s: max |P_ode - P_Eq4.2| / P_max", "1",
                            0.0, rel, 1e-6, false, "Eq. 4.2; coefficients of the thesis' fit (a)",
                            note, err)))
        return rc;
    /* Liu with all three terms of weight: C_v V ~ sigma0 at a few hundred m/s */
    struct pen_params l = s;
    l.model = PEN_LIU;
    l.d = 16e-6;
    l.cd = 0.4;
    l.cv = 2.0e4;
    l.sigma0 = 20.0e6;
    l.edot0 = 1.0e7;
    if ((rc = ode_vs_closed(&l, 440.0, &rel, &tf_rel, err)) ||
        (rc = vreport_check(r, "Liu SEBS 16 um 440 m/s: max |P_ode - P_closed| / P_max", "1", 0.0,
                            rel, 1e-6, false, "closed form of Eq. 4.8 (quadratic force)", note,
                            err)) ||
        (rc = vreport_check(r, "Liu: T_f quadrature vs closed form (relative)", "1", 0.0, tf_rel,
                            1e-6, false, "closed form of Eq. 4.8", note, err)))
        return rc;
    /* MCG: ODE end point against an independent quadrature of M v / F(v) */
    struct pen_params g = s;
    g.model = PEN_MCG;
    g.eta = 4.5e-2;
    g.R = 25.0e6;
    const double cases[][2] = {{20e-6, 215.0}, {13e-6, 630.0}, {12e-6, 735.0}};
    double worst = 0.0;
    for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
        g.d = cases[k][0];
        struct pen_result res;
        if ((rc = pen_solve(&g, cases[k][1], 0, NULL, NULL, NULL, 0, &res, err)))
            return rc;
        struct quad_ctx qc = {&g, pen_mass(&g)};
        gsl_function fn = {quad_vdv, &qc};
        gsl_integration_workspace *ws = gsl_integration_workspace_alloc(200);
        if (!ws)
            return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory");
        double q = 0.0, qe = 0.0;
        gsl_error_handler_t *old = gsl_set_error_handler_off();
        gsl_integration_qag(&fn, 0.0, cases[k][1], 0.0, 1e-12, 200, GSL_INTEG_GAUSS61, ws, &q,
                            &qe);
        gsl_set_error_handler(old);
        gsl_integration_workspace_free(ws);
        worst = fmax(worst, fabs(res.p_max - q) / q);
        vreport_info(r, "MCG d = %g um, v0 = %g m/s: P_max ODE %.10g um, quadrature %.10g um",
                     g.d * 1e6, cases[k][1], res.p_max * 1e6, q * 1e6);
    }
    return vreport_check(r, "MCG SEBS (3 cases): max |P_ode(T_f) - quadrature| / P_max", "1", 0.0,
                         worst, 1e-6, false,
                         "P_max = M int_0^v0 v dv / F(v) (Eq. 4.10, dP = -M v dv / F)", note,
                         err);
}
