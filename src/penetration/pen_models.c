/**
 * @file pen_models.c
 * @brief Force laws, closed forms and GSL ODE integration of the analytical
 *        penetration models ([Meng2021] sec. 4.2; see include/spall/penetration.h).
 *
 * Closed forms.  Poncelet and Liu have a force quadratic in V,
 * F = a V^2 + b V + c (Liu: the strain-rate term with edot = V/d adds
 * A sigma0 / (d edot0)^2 to a).  With s = sqrt(4ac - b^2) > 0,
 *     I(v) = int dv / F = (2/s) atan((2 a v + b) / s),
 *     J(v) = int v dv / F = ln(F(v)) / (2a) - b I(v) / (2a),
 * so T_f = M (I(v0) - I(0)), V(t) from I(V) = I(v0) - t / M, and
 * P(t) = M (J(v0) - J(V(t))).  For b = 0 these are the thesis' Eq. 4.2,
 * 4.3 and 4.6, which pen_poncelet evaluates literally.
 * Otherwise (MCG; Liu with b^2 >= 4ac) the ODE -M dV/dt = F(V), dP/dt = V
 * is integrated with gsl_odeiv2 (rk8pd) up to T_f, which comes from the
 * quadrature T_f = M int_0^v0 dv / F(v) (gsl_integration_qag), F >= F(0) > 0.
 */
#include "core/mathconst.h"
#include "spall/penetration.h"

#include "spall/error.h"

#include <gsl/gsl_errno.h>
#include <gsl/gsl_integration.h>
#include <gsl/gsl_odeiv2.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>


const char *pen_model_name(enum pen_model m)
{
    switch (m) {
    case PEN_PONCELET: return "poncelet";
    case PEN_LIU: return "liu";
    case PEN_MCG: return "mcg";
    }
    return "unknown";
}

int pen_model_from_name(const char *name, enum pen_model *m, struct spall_error *err)
{
    if (!name)
        return spall_error_set(err, SPALL_ERR_INPUT, "no penetration model given");
    if (strcmp(name, "poncelet") == 0)
        *m = PEN_PONCELET;
    else if (strcmp(name, "liu") == 0)
        *m = PEN_LIU;
    else if (strcmp(name, "mcg") == 0 || strcmp(name, "modified-cg") == 0)
        *m = PEN_MCG;
    else
        return spall_error_set(err, SPALL_ERR_INPUT,
                               "unknown penetration model '%s'; expected poncelet, liu or mcg",
                               name);
    return SPALL_OK;
}

static int need_pos(double v, const char *what, struct spall_error *err)
{
    if (!isfinite(v) || v <= 0.0)
        return spall_error_set(err, SPALL_ERR_INPUT, "%s must be a finite number > 0, got %g",
                               what, v);
    return SPALL_OK;
}

static int need_nonneg(double v, const char *what, struct spall_error *err)
{
    if (!isfinite(v) || v < 0.0)
        return spall_error_set(err, SPALL_ERR_INPUT, "%s must be a finite number >= 0, got %g",
                               what, v);
    return SPALL_OK;
}

int pen_params_check(const struct pen_params *p, struct spall_error *err)
{
    int rc;
    if ((rc = need_pos(p->d, "diameter d", err)) || (rc = need_pos(p->rho_p, "rho_p", err)) ||
        (rc = need_pos(p->rho_t, "rho_t", err)))
        return rc;
    switch (p->model) {
    case PEN_PONCELET:
        if ((rc = need_pos(p->cd, "C_d", err)) || (rc = need_pos(p->R, "R", err)))
            return rc;
        break;
    case PEN_LIU:
        /* sigma0 > 0 keeps F(0) > 0: the motion stops in finite time */
        if ((rc = need_nonneg(p->cd, "C_d", err)) || (rc = need_nonneg(p->cv, "C_v", err)) ||
            (rc = need_pos(p->sigma0, "sigma0", err)) || (rc = need_pos(p->edot0, "edot0", err)))
            return rc;
        break;
    case PEN_MCG:
        if ((rc = need_pos(p->eta, "eta", err)) || (rc = need_pos(p->R, "R", err)))
            return rc;
        break;
    default:
        return spall_error_set(err, SPALL_ERR_INPUT, "unknown penetration model %d",
                               (int)p->model);
    }
    return SPALL_OK;
}

double pen_mass(const struct pen_params *p)
{
    return p->rho_p * SPALL_PI * p->d * p->d * p->d / 6.0;
}

double pen_cd_clift_gauvin(double re)
{
    /* [Meng2021] Eq. 4.11 (Clift & Gauvin); "4.25e^4" in the thesis is 4.25e4 */
    return 24.0 / re * (1.0 + 0.15 * pow(re, 0.687)) + 0.42 / (1.0 + 4.25e4 * pow(re, -1.16));
}

/* Coefficients of F = a V^2 + b V + c for the quadratic models. */
static void pen_quadratic(const struct pen_params *p, double *a, double *b, double *c)
{
    const double area = 0.25 * SPALL_PI * p->d * p->d;
    if (p->model == PEN_PONCELET) {
        *a = p->rho_t * SPALL_PI * p->d * p->d * p->cd / 8.0; /* Eq. 4.4 */
        *b = 0.0;
        *c = p->R * area;                                     /* Eq. 4.5 */
    } else {                                                  /* Liu, Eq. 4.9, edot = V/d */
        const double k = 1.0 / (p->d * p->edot0);
        *a = 0.5 * p->cd * p->rho_t * area + area * p->sigma0 * k * k;
        *b = p->cv * area;
        *c = area * p->sigma0;
    }
}

double pen_force(const struct pen_params *p, double v)
{
    if (v < 0.0)
        v = 0.0;
    if (p->model == PEN_MCG) {
        const double area = 0.25 * SPALL_PI * p->d * p->d;
        double drag = 0.0;
        if (v > 0.0) {
            const double re = p->rho_t * v * p->d / p->eta;
            drag = 0.5 * pen_cd_clift_gauvin(re) * p->rho_t * area * v * v;
        }
        return drag + area * p->R; /* Eq. 4.10 */
    }
    double a, b, c;
    pen_quadratic(p, &a, &b, &c);
    return (a * v + b) * v + c;
}

static int check_times(size_t n, const double *t, struct spall_error *err)
{
    for (size_t i = 0; i < n; i++)
        if (!isfinite(t[i]) || t[i] < 0.0)
            return spall_error_set(err, SPALL_ERR_INPUT, "time %zu is %g; expected >= 0", i, t[i]);
    return SPALL_OK;
}

int pen_poncelet(const struct pen_params *p, double v0, size_t n, const double *t, double *P,
                 double *V, struct pen_result *res, struct spall_error *err)
{
    int rc;
    if (p->model != PEN_PONCELET)
        return spall_error_set(err, SPALL_ERR_INTERNAL, "pen_poncelet called for model %s",
                               pen_model_name(p->model));
    if ((rc = pen_params_check(p, err)) || (rc = need_pos(v0, "v0", err)) ||
        (rc = check_times(n, t, err)))
        return rc;
    const double M = pen_mass(p);
    const double B = p->rho_t * SPALL_PI * p->d * p->d * p->cd / 8.0; /* Eq. 4.4 */
    const double C = p->R * SPALL_PI * p->d * p->d / 4.0;             /* Eq. 4.5 */
    const double w = sqrt(B * C) / M;
    const double t_f = atan(v0 * sqrt(B / C)) / w;                  /* Eq. 4.3 */
    const double lc0 = log(cos(w * t_f));
    for (size_t i = 0; i < n; i++) {
        const double tt = t[i] < t_f ? t[i] : t_f;
        const double th = w * (t_f - tt);
        if (P)
            P[i] = M / B * (log(cos(th)) - lc0);                    /* Eq. 4.2, Inc = ln cos */
        if (V)
            V[i] = sqrt(C / B) * tan(th);
    }
    res->t_f = t_f;
    /* Eq. 4.6 */
    res->p_max = 2.0 * p->rho_p * p->d / (3.0 * p->rho_t * p->cd) *
                 log1p(p->rho_t * p->cd * v0 * v0 / (2.0 * p->R));
    res->re_max = 0.0;
    res->closed_form = 1;
    return SPALL_OK;
}

/* Liu closed form (header comment); returns 0 if 4ac - b^2 <= 0. */
static int pen_liu_closed(const struct pen_params *p, double v0, size_t n, const double *t,
                          double *P, double *V, struct pen_result *res)
{
    double a, b, c;
    pen_quadratic(p, &a, &b, &c);
    const double disc = 4.0 * a * c - b * b;
    if (!(disc > 0.0) || !(a > 0.0))
        return 0;
    const double M = pen_mass(p), s = sqrt(disc);
    const double phi0 = atan((2.0 * a * v0 + b) / s), phif = atan(b / s);
    const double t_f = 2.0 * M / s * (phi0 - phif);
    const double f0 = (a * v0 + b) * v0 + c;
    for (size_t i = 0; i < n; i++) {
        const double tt = t[i] < t_f ? t[i] : t_f;
        const double phi = phi0 - s * tt / (2.0 * M);
        double v = (s * tan(phi) - b) / (2.0 * a);
        if (v < 0.0)
            v = 0.0;
        const double fv = (a * v + b) * v + c;
        /* M (J(v0) - J(v)), J = ln F / 2a - b I / 2a, I = 2 phi / s */
        if (P)
            P[i] = M / (2.0 * a) * (log(f0 / fv) - b * 2.0 / s * (phi0 - phi));
        if (V)
            V[i] = v;
    }
    res->t_f = t_f;
    res->p_max = M / (2.0 * a) * (log(f0 / c) - b * 2.0 / s * (phi0 - phif));
    res->re_max = 0.0;
    res->closed_form = 1;
    return 1;
}

struct ode_ctx {
    const struct pen_params *p;
    double inv_m;
};

static int ode_rhs(double t, const double y[], double dydt[], void *params)
{
    (void)t;
    const struct ode_ctx *c = params;
    dydt[0] = y[1];
    dydt[1] = -pen_force(c->p, y[1]) * c->inv_m;
    return GSL_SUCCESS;
}

static double quad_dt(double v, void *params)
{
    const struct ode_ctx *c = params;
    return 1.0 / (pen_force(c->p, v) * c->inv_m);
}

/* insertion sort of indices by time: the callers pass at most a few
 * thousand times, usually already sorted (O(n) then) */
static void sort_idx(size_t *idx, size_t n, const double *t)
{
    for (size_t i = 1; i < n; i++) {
        size_t k = idx[i], j = i;
        while (j > 0 && t[idx[j - 1]] > t[k]) {
            idx[j] = idx[j - 1];
            j--;
        }
        idx[j] = k;
    }
}

static int pen_ode(const struct pen_params *p, double v0, size_t n, const double *t, double *P,
                   double *V, struct pen_result *res, struct spall_error *err)
{
    struct ode_ctx ctx = {p, 1.0 / pen_mass(p)};
    /* T_f = M int_0^v0 dv / F(v): smooth, bounded integrand (F >= F(0) > 0) */
    gsl_integration_workspace *ws = gsl_integration_workspace_alloc(200);
    if (!ws)
        return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory (GSL integration workspace)");
    gsl_function fn = {quad_dt, &ctx};
    double t_f = 0.0, abserr = 0.0;
    int g = gsl_integration_qag(&fn, 0.0, v0, 0.0, 1e-13, 200, GSL_INTEG_GAUSS61, ws, &t_f,
                                &abserr);
    gsl_integration_workspace_free(ws);
    if (g && g != GSL_EROUND)
        return spall_error_set(err, SPALL_ERR_INTERNAL, "stopping time quadrature failed: %s",
                               gsl_strerror(g));
    size_t *idx = NULL;
    if (n) {
        idx = malloc(n * sizeof *idx);
        if (!idx)
            return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory (%zu times)", n);
        for (size_t i = 0; i < n; i++)
            idx[i] = i;
        sort_idx(idx, n, t);
    }
    gsl_odeiv2_system sys = {ode_rhs, NULL, 2, &ctx};
    /* rk8pd (Prince-Dormand 8(9)), first step T_f / 1e4 */
    gsl_odeiv2_driver *drv =
        gsl_odeiv2_driver_alloc_y_new(&sys, gsl_odeiv2_step_rk8pd, t_f * 1e-4, 1e-14, 1e-12);
    if (!drv) {
        free(idx);
        return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory (GSL ODE driver)");
    }
    /* error bound per component 1e-14 + 1e-12 |y|: P (~1e-5..1e-3 m) to
     * ~1e-9 relative or better; hmax keeps at least 50 steps per run */
    gsl_odeiv2_driver_set_hmax(drv, t_f / 50.0);
    double tc = 0.0, y[2] = {0.0, v0};
    int rc = SPALL_OK;
    for (size_t k = 0; k <= n; k++) {
        const double target = k < n ? (t[idx[k]] < t_f ? t[idx[k]] : t_f) : t_f;
        if (target > tc) {
            g = gsl_odeiv2_driver_apply(drv, &tc, target, y);
            if (g) {
                rc = spall_error_set(err, SPALL_ERR_INTERNAL,
                                     "ODE integration failed at t = %g s: %s", tc, gsl_strerror(g));
                break;
            }
        }
        if (k < n) {
            if (P)
                P[idx[k]] = y[0];
            if (V)
                V[idx[k]] = t[idx[k]] < t_f ? (y[1] > 0.0 ? y[1] : 0.0) : 0.0;
        }
    }
    gsl_odeiv2_driver_free(drv);
    free(idx);
    if (rc)
        return rc;
    res->t_f = t_f;
    res->p_max = y[0];
    res->closed_form = 0;
    return SPALL_OK;
}

int pen_solve(const struct pen_params *p, double v0, size_t n, const double *t, double *P,
              double *V, int force_ode, struct pen_result *res, struct spall_error *err)
{
    int rc;
    if ((rc = pen_params_check(p, err)) || (rc = need_pos(v0, "v0", err)) ||
        (rc = check_times(n, t, err)))
        return rc;
    memset(res, 0, sizeof *res);
    gsl_error_handler_t *old = gsl_set_error_handler_off();
    if (!force_ode && p->model == PEN_PONCELET)
        rc = pen_poncelet(p, v0, n, t, P, V, res, err);
    else if (!force_ode && p->model == PEN_LIU && pen_liu_closed(p, v0, n, t, P, V, res))
        rc = SPALL_OK;
    else
        rc = pen_ode(p, v0, n, t, P, V, res, err);
    gsl_set_error_handler(old);
    if (!rc && p->model == PEN_MCG)
        res->re_max = p->rho_t * v0 * p->d / p->eta;
    return rc;
}
