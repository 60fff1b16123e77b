/**
 * @file pen_fit.c
 * @brief Fitting the analytical models' coefficients ([Meng2021] sec. 4.2.2.2)
 *        with GSL's nonlinear least squares (gsl_multifit_nlinear, trust
 *        region with Levenberg-Marquardt steps, finite-difference Jacobian).
 *
 * Approach (a): one trajectory P(t) of a known d, v0; residual
 * P_model(t_i) - P_i [m].  Approach (b): many (d, v0, P_max) points;
 * residual (P_model,max + nose d/2 - P_max,i) / d_i, the normalised depth the
 * thesis plots (Fig. 4.5), so small and large spheres weigh alike.
 * The unknowns are the logarithms of the coefficients: they stay positive
 * and coefficients of very different size (C_d ~ 1, R ~ 1e7 Pa) are scaled
 * alike.  Standard errors come from the covariance s^2 (J^T J)^-1 in the log
 * variables (s^2 = chi^2 / (n - p)), mapped back by the delta method; the
 * 95 % intervals exp(theta +- t_0.975 sigma) use Student's t.
 */
#include "spall/penetration.h"

#include "spall/error.h"

#include <gsl/gsl_blas.h>
#include <gsl/gsl_cdf.h>
#include <gsl/gsl_errno.h>
#include <gsl/gsl_matrix.h>
#include <gsl/gsl_multifit_nlinear.h>
#include <gsl/gsl_vector.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

/* Coefficients of each model, in the order of struct pen_fit_result. */
static int coef_ptrs(struct pen_params *p, double **c, const char **names)
{
    switch (p->model) {
    case PEN_PONCELET:
        c[0] = &p->cd, names[0] = "C_d";
        c[1] = &p->R, names[1] = "R";
        return 2;
    case PEN_LIU:
        c[0] = &p->cd, names[0] = "C_d";
        c[1] = &p->cv, names[1] = "C_v";
        c[2] = &p->sigma0, names[2] = "sigma0";
        return 3;
    case PEN_MCG:
        c[0] = &p->eta, names[0] = "eta";
        c[1] = &p->R, names[1] = "R";
        return 2;
    }
    return 0;
}

struct fit_ctx {
    const struct pen_fit_input *in;
    struct pen_params work;
    double *P;                /* (a) model depths */
    struct spall_error *err;  /* first model failure */
    int failed;
};

static void set_coefs(struct fit_ctx *c, const gsl_vector *x)
{
    double *ptr[PEN_FIT_MAX_COEF];
    const char *names[PEN_FIT_MAX_COEF];
    const int nc = coef_ptrs(&c->work, ptr, names);
    for (int k = 0; k < nc; k++)
        *ptr[k] = exp(gsl_vector_get(x, (size_t)k));
}

static int fit_residual(const gsl_vector *x, void *data, gsl_vector *f)
{
    struct fit_ctx *c = data;
    const struct pen_fit_input *in = c->in;
    set_coefs(c, x);
    struct pen_result res;
    struct spall_error e = {0};
    if (in->kind == PEN_FIT_TRAJECTORY) {
        if (pen_solve(&c->work, in->v0, in->n, in->t, c->P, NULL, 0, &res, &e))
            goto fail;
        for (size_t i = 0; i < in->n; i++)
            gsl_vector_set(f, i, c->P[i] - in->P[i]);
    } else {
        for (size_t i = 0; i < in->n; i++) {
            c->work.d = in->d[i];
            if (pen_solve(&c->work, in->v0s[i], 0, NULL, NULL, NULL, 0, &res, &e))
                goto fail;
            const double pm = res.p_max + (in->nose ? 0.5 * in->d[i] : 0.0);
            gsl_vector_set(f, i, (pm - in->pmax[i]) / in->d[i]);
        }
    }
    return GSL_SUCCESS;
fail:
    if (!c->failed && c->err) {
        c->failed = 1;
        *c->err = e;
    }
    return GSL_EBADFUNC;
}

static int check_input(const struct pen_fit_input *in, int nc, struct spall_error *err)
{
    if (in->n < (size_t)nc + 1)
        return spall_error_set(err, SPALL_ERR_INPUT,
                               "%zu data rows for %d coefficients of %s; expected at least %d",
                               in->n, nc, pen_model_name(in->base.model), nc + 1);
    for (size_t i = 0; i < in->n; i++) {
        if (in->kind == PEN_FIT_TRAJECTORY) {
            if (!isfinite(in->t[i]) || in->t[i] < 0.0 || !isfinite(in->P[i]))
                return spall_error_set(err, SPALL_ERR_INPUT,
                                       "trajectory row %zu: t = %g, P = %g; expected t >= 0", i + 1,
                                       in->t[i], in->P[i]);
        } else if (!(in->d[i] > 0.0) || !(in->v0s[i] > 0.0) || !(in->pmax[i] > 0.0) ||
                   !isfinite(in->d[i] + in->v0s[i] + in->pmax[i])) {
            return spall_error_set(err, SPALL_ERR_INPUT,
                                   "point %zu: d = %g, v0 = %g, P_max = %g; expected all > 0",
                                   i + 1, in->d[i], in->v0s[i], in->pmax[i]);
        }
    }
    if (in->kind == PEN_FIT_TRAJECTORY && !(in->v0 > 0.0 && isfinite(in->v0)))
        return spall_error_set(err, SPALL_ERR_INPUT, "v0 must be > 0 for a trajectory fit");
    return SPALL_OK;
}

int pen_fit(const struct pen_fit_input *in, struct pen_fit_result *out, double *residuals,
            struct spall_error *err)
{
    memset(out, 0, sizeof *out);
    struct fit_ctx ctx;
    memset(&ctx, 0, sizeof ctx);
    ctx.in = in;
    ctx.work = in->base;
    ctx.err = err;
    if (in->kind == PEN_FIT_POINTS)
        ctx.work.d = in->d && in->n ? in->d[0] : 0.0;
    double *ptr[PEN_FIT_MAX_COEF];
    const int nc = coef_ptrs(&ctx.work, ptr, out->names);
    int rc;
    if (nc == 0)
        return spall_error_set(err, SPALL_ERR_INPUT, "unknown penetration model");
    if ((rc = check_input(in, nc, err)))
        return rc;
    for (int k = 0; k < nc; k++)
        if (!(*ptr[k] > 0.0) || !isfinite(*ptr[k]))
            return spall_error_set(err, SPALL_ERR_INPUT,
                                   "initial %s = %g; expected a finite number > 0", out->names[k],
                                   *ptr[k]);
    if ((rc = pen_params_check(&ctx.work, err)))
        return rc;
    const size_t n = in->n, p = (size_t)nc;
    if (in->kind == PEN_FIT_TRAJECTORY) {
        ctx.P = malloc(n * sizeof *ctx.P);
        if (!ctx.P)
            return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory (%zu rows)", n);
    }
    gsl_error_handler_t *old = gsl_set_error_handler_off();
    gsl_multifit_nlinear_parameters fp = gsl_multifit_nlinear_default_parameters();
    fp.trs = gsl_multifit_nlinear_trs_lm;
    fp.scale = gsl_multifit_nlinear_scale_more;
    fp.fdtype = GSL_MULTIFIT_NLINEAR_CTRDIFF;
    gsl_multifit_nlinear_workspace *w =
        gsl_multifit_nlinear_alloc(gsl_multifit_nlinear_trust, &fp, n, p);
    gsl_vector *x = gsl_vector_alloc(p);
    gsl_matrix *cov = gsl_matrix_alloc(p, p);
    if (!w || !x || !cov) {
        rc = spall_error_set(err, SPALL_ERR_NOMEM, "out of memory (GSL fit workspace)");
        goto done;
    }
    for (int k = 0; k < nc; k++)
        gsl_vector_set(x, (size_t)k, log(*ptr[k]));
    gsl_multifit_nlinear_fdf fdf;
    memset(&fdf, 0, sizeof fdf);
    fdf.f = fit_residual;
    fdf.df = NULL; /* central finite differences */
    fdf.n = n;
    fdf.p = p;
    fdf.params = &ctx;
    int g = gsl_multifit_nlinear_init(x, &fdf, w);
    int info = 0;
    if (!g)
        g = gsl_multifit_nlinear_driver(500, 1e-12, 1e-12, 0.0, NULL, NULL, &info, w);
    if (ctx.failed) {
        rc = err ? err->code : SPALL_ERR_INTERNAL;
        spall_error_prefix(err, "fit of %s: ", pen_model_name(in->base.model));
        goto done;
    }
    if (g && g != GSL_EMAXITER && g != GSL_ENOPROG) {
        rc = spall_error_set(err, SPALL_ERR_INTERNAL, "fit of %s failed: %s",
                             pen_model_name(in->base.model), gsl_strerror(g));
        goto done;
    }
    out->converged = g == GSL_SUCCESS;
    out->iterations = (int)gsl_multifit_nlinear_niter(w);
    const gsl_vector *xs = gsl_multifit_nlinear_position(w);
    const gsl_vector *fs = gsl_multifit_nlinear_residual(w);
    double chisq = 0.0;
    gsl_blas_ddot(fs, fs, &chisq);
    out->chisq = chisq;
    out->dof = (int)(n - p);
    out->rms = sqrt(chisq / (double)n);
    out->max_abs = 0.0;
    for (size_t i = 0; i < n; i++) {
        const double r = gsl_vector_get(fs, i);
        if (fabs(r) > out->max_abs)
            out->max_abs = fabs(r);
        if (residuals)
            residuals[i] = r;
    }
    gsl_multifit_nlinear_covar(gsl_multifit_nlinear_jac(w), 0.0, cov);
    const double s2 = out->dof > 0 ? chisq / out->dof : 0.0;
    const double tq = out->dof > 0 ? gsl_cdf_tdist_Pinv(0.975, (double)out->dof) : NAN;
    out->n_coef = nc;
    set_coefs(&ctx, xs);
    out->fitted = ctx.work;
    if (in->kind == PEN_FIT_POINTS)
        out->fitted.d = in->base.d;
    for (int k = 0; k < nc; k++) {
        const double th = gsl_vector_get(xs, (size_t)k);
        const double sig = sqrt(fabs(gsl_matrix_get(cov, (size_t)k, (size_t)k)) * s2);
        out->value[k] = exp(th);
        out->std_err[k] = out->value[k] * sig;
        out->ci_lo[k] = exp(th - tq * sig);
        out->ci_hi[k] = exp(th + tq * sig);
    }
    for (int k = 0; k < nc; k++)
        for (int l = 0; l < nc; l++) {
            const double ckk = gsl_matrix_get(cov, (size_t)k, (size_t)k);
            const double cll = gsl_matrix_get(cov, (size_t)l, (size_t)l);
            const double den = sqrt(fabs(ckk * cll));
            out->corr[k][l] = den > 0.0 ? gsl_matrix_get(cov, (size_t)k, (size_t)l) / den : 0.0;
        }
    rc = SPALL_OK;
done:
    if (w)
        gsl_multifit_nlinear_free(w);
    gsl_vector_free(x);
    gsl_matrix_free(cov);
    gsl_set_error_handler(old);
    free(ctx.P);
    return rc;
}
