/**
 * @file cmd_penetrate.c
 * @brief `spall penetrate`: the analytical penetration models of [Meng2021]
 *        sec. 4.2 (Poncelet, Liu, Modified Clift-Gauvin), their fits to data
 *        (approaches a and b) and velocity sweeps, writing CSV tables.
 */
#include "cli/cli.h"
#include "io/plot.h"

#include "spall/error.h"
#include "spall/penetration.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#define PEN_MAX_D 64

static void pen_usage(FILE *out)
{
    fprintf(out,
            "usage: spall penetrate poncelet|liu|mcg (--diameter M | --radius M) --v0 M_S\n"
            "                       [--rho-projectile KG_M3 | --projectile P]\n"
            "                       [--rho-target KG_M3 | --target T] [coefficients] [--ode]\n"
            "                       [--csv TRAJ.csv] [--n N]\n"
            "       spall penetrate fit --model poncelet|liu|mcg (--trajectory P.csv --diameter M --v0 M_S\n"
            "                       | --points PTS.csv [--nose]) [densities] [initial coefficients]\n"
            "                       [--csv FIT.csv (also FIT.png: data vs model)] [--curve CURVE.csv]\n"
            "       spall penetrate sweep --model poncelet|liu|mcg --v0 FROM:TO:STEP --diameter D1[,D2,...]\n"
            "                       [densities] [coefficients] --csv TABLE.csv\n"
            "\n"
            "Rigid sphere into a soft target, -M dV/dt = F(V) ([Meng2021] sec. 4.2):\n"
            "  poncelet  F = B V^2 + C, B = rho_t pi d^2 C_d / 8, C = R pi d^2 / 4 (Eq. 4.1-4.6),\n"
            "            closed form;\n"
            "  liu       F = A (C_d rho_t V^2 / 2 + C_v V + sigma0 [1 + (V / (d edot0))^2])\n"
            "            (Eq. 4.8-4.9), closed form when 4ac > b^2, else integrated;\n"
            "  mcg       F = A (C_d^CG(Re) rho_t V^2 / 2 + R), Re = rho_t V d / eta (Eq. 4.10-4.11),\n"
            "            integrated (GSL rk8pd); warns when Re > 1e5.\n"
            "Prints T_f, P_max, P_max + d/2 (nose, Eq. 4.7) and P_max/d; --csv writes t, P, V.\n"
            "\n"
            "options (SI units):\n"
            "  --diameter M, --v0 M_S   sphere diameter d, impact velocity\n"
            "  --radius M               or the radius (d = 2 r), as decks give impactors\n"
            "  --rho-projectile, --rho-target   projectile / target density\n"
            "  --projectile silica|steel  rho_p = 1850 / 7800 (thesis Tab. 4.4)\n"
            "  --target gelatin|sebs    rho_t = 1030 / 875 (10 wt%% gelatin, 40 vol%% SEBS, Tab. 4.3)\n"
            "  --Cd, --R PA             Poncelet (C_d, R), Liu (C_d), MCG (R)\n"
            "  --Cv PA_S_M, --sigma0 PA, --edot0 1_S   Liu (edot0 default 1e7 1/s)\n"
            "  --eta PA_S               MCG viscosity\n"
            "  --nose                   fit (b): measured P_max include the nose d/2 (Eq. 4.7)\n"
            "  --ode                    integrate the ODE even where a closed form exists\n"
            "  --n N                    trajectory samples in --csv (default 201)\n"
            "  --overwrite              replace existing --csv/--curve/PNG files (refused otherwise)\n"
            "fit: --trajectory CSV has columns t, P [s, m] (approach a, one curve of given d, v0);\n"
            "     --points CSV has columns d, v0, P_max [m, m/s, m] (approach b).  Coefficient\n"
            "     options give the initial guess.  Prints coefficients, standard errors, 95 %%\n"
            "     confidence intervals and residuals; --csv writes data, model and residuals;\n"
            "     --curve writes the fitted model densely (a: t, P, V; b: P_max vs v0 per d).\n"
            "sweep: --csv writes d, v0, T_f, P_max, P_max_nose, P_max_over_d (and Re for mcg).\n");
}

struct pen_opts {
    struct pen_params p;
    double v0;
    int have_d, have_v0, nose, ode, n, overwrite;
    int d_is_radius; /**< --radius given: the list holds radii, d = 2 r */
    const char *csv, *curve, *traj, *points, *model, *vrange, *dlist;
};

static int bad(const char *fmt, const char *a, const char *b)
{
    fprintf(stderr, "spall penetrate: ");
    fprintf(stderr, fmt, a, b);
    fprintf(stderr, "\n");
    return 2;
}

static int num(const char *opt, const char *s, double *out)
{
    char *end = NULL;
    *out = strtod(s, &end);
    if (end == s || *end || !isfinite(*out))
        return bad("%s needs a number, got '%s'", opt, s);
    return 0;
}

/* Old spellings, refused with the new name (issue 24: one convention for
 * every command).  The convention: a material constant is its symbol as in
 * the equations of --help and calibrate (--E, --nu, --rho, --R, --Cd, --Cv),
 * a qualifier follows with a hyphen (--rho-projectile), and a length is
 * named in words (--diameter, or --radius as the decks give impactors). */
static const char *renamed_option(const char *a)
{
    static const char *const old_new[][2] = {
        {"--d", "--diameter (or --radius, as decks give impactor radii)"},
        {"--rho-p", "--rho-projectile"},
        {"--rho-t", "--rho-target"},
        {"--cd", "--Cd"},
        {"--cv", "--Cv"},
    };
    for (size_t k = 0; k < sizeof old_new / sizeof old_new[0]; k++)
        if (strcmp(a, old_new[k][0]) == 0)
            return old_new[k][1];
    return NULL;
}

/* Parse options from argv[first..]; the model (if any) is already in o->p. */
static int parse_opts(int argc, char **argv, int first, struct pen_opts *o)
{
    for (int k = first; k < argc; k++) {
        const char *a = argv[k];
        if (strcmp(a, "--nose") == 0) {
            o->nose = 1;
            continue;
        }
        if (strcmp(a, "--ode") == 0) {
            o->ode = 1;
            continue;
        }
        if (strcmp(a, "--overwrite") == 0) {
            o->overwrite = 1;
            continue;
        }
        if (strncmp(a, "--", 2) != 0)
            return bad("unexpected argument '%s'%s; see spall penetrate --help", a, "");
        const char *renamed = renamed_option(a);
        if (renamed)
            return bad("%s was renamed %s; see spall penetrate --help", a, renamed);
        if (k + 1 >= argc)
            return bad("%s needs a value%s", a, "");
        const char *v = argv[++k];
        double x = 0.0;
        int rc = 0;
        if (strcmp(a, "--diameter") == 0 || strcmp(a, "--radius") == 0) {
            if (o->dlist)
                return bad("give one of --diameter and --radius, once%s%s", "", "");
            o->dlist = v;
            o->d_is_radius = a[2] == 'r';
            if (!strchr(v, ',')) {
                rc = num(a, v, &o->p.d), o->have_d = 1;
                if (o->d_is_radius)
                    o->p.d *= 2.0;
            }
        } else if (strcmp(a, "--v0") == 0) {
            o->vrange = v;
            if (!strchr(v, ':'))
                rc = num(a, v, &o->v0), o->have_v0 = 1;
        } else if (strcmp(a, "--rho-projectile") == 0) rc = num(a, v, &o->p.rho_p);
        else if (strcmp(a, "--rho-target") == 0) rc = num(a, v, &o->p.rho_t);
        else if (strcmp(a, "--Cd") == 0) rc = num(a, v, &o->p.cd);
        else if (strcmp(a, "--R") == 0) rc = num(a, v, &o->p.R);
        else if (strcmp(a, "--Cv") == 0) rc = num(a, v, &o->p.cv);
        else if (strcmp(a, "--sigma0") == 0) rc = num(a, v, &o->p.sigma0);
        else if (strcmp(a, "--edot0") == 0) rc = num(a, v, &o->p.edot0);
        else if (strcmp(a, "--eta") == 0) rc = num(a, v, &o->p.eta);
        else if (strcmp(a, "--csv") == 0) o->csv = v;
        else if (strcmp(a, "--curve") == 0) o->curve = v;
        else if (strcmp(a, "--trajectory") == 0) o->traj = v;
        else if (strcmp(a, "--points") == 0) o->points = v;
        else if (strcmp(a, "--model") == 0) o->model = v;
        else if (strcmp(a, "--n") == 0) {
            rc = num(a, v, &x);
            if (!rc && (x < 2 || x > 1e7 || x != floor(x)))
                return bad("--n must be an integer in [2, 1e7], got '%s'%s", v, "");
            o->n = (int)x;
        } else if (strcmp(a, "--projectile") == 0) {
            if (strcmp(v, "silica") == 0) o->p.rho_p = 1850.0;
            else if (strcmp(v, "steel") == 0) o->p.rho_p = 7800.0;
            else return bad("unknown projectile '%s'; expected silica or steel%s", v, "");
        } else if (strcmp(a, "--target") == 0) {
            if (strcmp(v, "gelatin") == 0) o->p.rho_t = 1030.0;
            else if (strcmp(v, "sebs") == 0) o->p.rho_t = 875.0;
            else return bad("unknown target '%s'; expected gelatin or sebs%s", v, "");
        } else {
            return bad("unknown option '%s'%s; see spall penetrate --help", a, "");
        }
        if (rc)
            return rc;
    }
    return 0;
}

static int fail(const struct spall_error *e)
{
    fprintf(stderr, "spall penetrate: %s\n", e->msg);
    return cli_exit_status(e->code);
}

static void warn_re(const struct pen_params *p, double v0, double re)
{
    if (p->model == PEN_MCG && re > PEN_MCG_RE_MAX)
        fprintf(stderr,
                "spall penetrate: warning: Re = %.4g > 1e5 at v0 = %g m/s, d = %g m: the "
                "Clift-Gauvin drag law (Eq. 4.11) is outside its range\n",
                re, v0, p->d);
}

static int write_open(const char *path, FILE **f)
{
    *f = fopen(path, "w");
    if (!*f) {
        fprintf(stderr, "spall penetrate: cannot write '%s'\n", path);
        return 4;
    }
    return 0;
}

static int cmd_model(struct pen_opts *o)
{
    struct spall_error e = {0};
    if (!o->have_d || !o->have_v0)
        return bad("%s needs --diameter (or --radius) and --v0 (single numbers)%s", pen_model_name(o->p.model), "");
    struct pen_result r;
    int rc = pen_solve(&o->p, o->v0, 0, NULL, NULL, NULL, o->ode, &r, &e);
    if (rc)
        return fail(&e);
    warn_re(&o->p, o->v0, r.re_max);
    const double M = pen_mass(&o->p);
    printf("model            %s (%s)\n", pen_model_name(o->p.model),
           r.closed_form ? "closed form" : "ODE integrated, GSL rk8pd");
    printf("d                %.6g m\nv0               %.6g m/s\nmass M           %.6g kg\n",
           o->p.d, o->v0, M);
    printf("T_f              %.6g s\n", r.t_f);
    printf("P_max            %.6g m   (P_max/d = %.6g)\n", r.p_max, r.p_max / o->p.d);
    printf("P_max + d/2      %.6g m   (nose, Eq. 4.7; /d = %.6g)\n", r.p_max + 0.5 * o->p.d,
           r.p_max / o->p.d + 0.5);
    if (o->p.model == PEN_MCG)
        printf("Re at v0         %.6g%s\n", r.re_max,
               r.re_max > PEN_MCG_RE_MAX ? " (above 1e5: outside the drag law's range)" : "");
    if (!o->csv)
        return 0;
    const int n = o->n ? o->n : 201;
    double *t = malloc(3 * (size_t)n * sizeof *t);
    if (!t)
        return bad("out of memory%s%s", "", "");
    double *P = t + n, *V = P + n;
    for (int i = 0; i < n; i++)
        t[i] = r.t_f * i / (n - 1);
    rc = pen_solve(&o->p, o->v0, (size_t)n, t, P, V, o->ode, &r, &e);
    FILE *f = NULL;
    if (!rc && !(rc = write_open(o->csv, &f))) {
        fprintf(f, "# spall penetrate %s: d = %.9g m, v0 = %.9g m/s\n", pen_model_name(o->p.model),
                o->p.d, o->v0);
        fprintf(f, "t,P,V\n");
        for (int i = 0; i < n; i++)
            fprintf(f, "%.10e,%.10e,%.10e\n", t[i], P[i], V[i]);
        if (fclose(f))
            rc = bad("error writing '%s'%s", o->csv, "");
    } else if (rc && rc != 4) {
        rc = fail(&e);
    }
    free(t);
    return rc;
}

static int col(const struct pen_csv *c, const char *name, const char *path, int *k)
{
    *k = pen_csv_column(c, name);
    if (*k < 0)
        return bad("%s has no column '%s'", path, name);
    return 0;
}

static int cmp_dbl(const void *a, const void *b)
{
    const double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}

/* FILE.csv -> FILE.png (or FILE.csv.png when there is no .csv suffix). */
static void png_path(const char *csv, char *out, size_t len)
{
    snprintf(out, len, "%s", csv);
    size_t n = strlen(out);
    if (n > 4 && strcmp(out + n - 4, ".csv") == 0)
        out[n - 4] = '\0';
    strncat(out, ".png", len - strlen(out) - 1);
}

/* Fitted model against the data, beside the CSV: approach (a) P(t) data
 * points and model curve; approach (b) P_max/d against v0, data and model. */
static int plot_fit(const struct pen_opts *o, const struct pen_fit_input *in, const double *a0,
                    const double *a1, const double *a2, const double *res)
{
    size_t n = in->n;
    double *buf = malloc(4 * (n ? n : 1) * sizeof *buf);
    if (!buf)
        return bad("out of memory plotting the fit%s%s", "", "");
    double *x = buf, *yd = buf + n, *ym = buf + 2 * n;
    for (size_t i = 0; i < n; i++) {
        if (o->traj) {
            x[i] = a0[i] * 1e9;            /* ns */
            yd[i] = a1[i] * 1e6;           /* um */
            ym[i] = (a1[i] + res[i]) * 1e6;
        } else {
            x[i] = a1[i];                  /* v0 [m/s] */
            yd[i] = a2[i] / a0[i];         /* P_max / d */
            ym[i] = a2[i] / a0[i] + res[i];
        }
    }
    struct plot_series ser[2] = {
        {"data", x, yd, n, PLOT_POINTS},
        {"fitted model", x, ym, n, o->traj ? PLOT_LINE : PLOT_POINTS},
    };
    char title[96];
    snprintf(title, sizeof title, "%s fit, approach %s", pen_model_name(in->base.model),
             o->traj ? "(a)" : "(b)");
    struct plot_spec spec = {title, o->traj ? "time [ns]" : "impact velocity v0 [m/s]",
                             o->traj ? "penetration depth P [um]" : "P_max / d [1]", 0, 0,
                             ser, 2, NULL, 0};
    char path[1024];
    png_path(o->csv, path, sizeof path);
    struct spall_error e = {0};
    int rc = plot_png(path, &spec, &e);
    free(buf);
    if (rc)
        return fail(&e);
    printf("wrote %s\n", path);
    return 0;
}

/* Dense curves of the fitted model, for plotting against the data:
 * (a) t, P, V over [0, T_f]; (b) per distinct diameter, P_max vs v0 over
 * (0, 1.1 max v0], with the nose if the fit used it. */
static int write_curve(const struct pen_opts *o, const struct pen_fit_input *in,
                       const struct pen_params *fitted, const double *d_sorted)
{
    struct spall_error e = {0};
    FILE *f = NULL;
    int rc = write_open(o->curve, &f);
    if (rc)
        return rc;
    enum { NC = 201 };
    fprintf(f, "# spall penetrate fit: %s with the fitted coefficients\n",
            pen_model_name(fitted->model));
    if (in->kind == PEN_FIT_TRAJECTORY) {
        double t[NC], P[NC], V[NC];
        struct pen_result r;
        if (!(rc = pen_solve(fitted, in->v0, 0, NULL, NULL, NULL, 0, &r, &e))) {
            for (int i = 0; i < NC; i++)
                t[i] = r.t_f * i / (NC - 1);
            rc = pen_solve(fitted, in->v0, NC, t, P, V, 0, &r, &e);
        }
        if (!rc) {
            fprintf(f, "t,P,V\n");
            for (int i = 0; i < NC; i++)
                fprintf(f, "%.10e,%.10e,%.10e\n", t[i], P[i], V[i]);
        }
    } else {
        double vmax = 0.0;
        for (size_t i = 0; i < in->n; i++)
            vmax = in->v0s[i] > vmax ? in->v0s[i] : vmax;
        fprintf(f, "d,v0,P_max,P_max_over_d\n");
        for (size_t k = 0; k < in->n && !rc; k++) {
            if (k > 0 && d_sorted[k] == d_sorted[k - 1])
                continue;
            struct pen_params p = *fitted;
            p.d = d_sorted[k];
            for (int i = 1; i <= NC - 1 && !rc; i++) {
                const double v = 1.1 * vmax * i / (NC - 1);
                struct pen_result r;
                if ((rc = pen_solve(&p, v, 0, NULL, NULL, NULL, 0, &r, &e)))
                    break;
                const double pm = r.p_max + (in->nose ? 0.5 * p.d : 0.0);
                fprintf(f, "%.10e,%.10e,%.10e,%.10e\n", p.d, v, pm, pm / p.d);
            }
        }
    }
    if (fclose(f) && !rc)
        return bad("error writing '%s'%s", o->curve, "");
    return rc ? fail(&e) : 0;
}

static int cmd_fit(struct pen_opts *o)
{
    struct spall_error e = {0};
    if (!o->model)
        return bad("fit needs --model poncelet|liu|mcg%s%s", "", "");
    if ((o->traj != NULL) == (o->points != NULL))
        return bad("fit needs exactly one of --trajectory FILE or --points FILE%s%s", "", "");
    struct pen_fit_input in;
    memset(&in, 0, sizeof in);
    in.base = o->p;
    in.nose = o->nose;
    struct pen_csv c;
    const char *path = o->traj ? o->traj : o->points;
    if (pen_csv_read(path, &c, &e))
        return fail(&e);
    int rc = 0, k0 = 0, k1 = 0, k2 = 0;
    double *buf = NULL;
    if (o->traj) {
        if (!o->have_d || !o->have_v0) {
            rc = bad("a trajectory fit (approach a) needs --diameter (or --radius) and --v0%s%s", "", "");
            goto done;
        }
        if ((rc = col(&c, "t", path, &k0)) || (rc = col(&c, "P", path, &k1)))
            goto done;
        in.kind = PEN_FIT_TRAJECTORY;
        in.v0 = o->v0;
    } else {
        if ((rc = col(&c, "d", path, &k0)) || (rc = col(&c, "v0", path, &k1)) ||
            (rc = col(&c, "P_max", path, &k2)))
            goto done;
        in.kind = PEN_FIT_POINTS;
    }
    in.n = c.n_rows;
    buf = malloc(4 * in.n * sizeof *buf);
    if (!buf) {
        rc = bad("out of memory%s%s", "", "");
        goto done;
    }
    double *a0 = buf, *a1 = buf + in.n, *a2 = buf + 2 * in.n, *res = buf + 3 * in.n;
    for (size_t i = 0; i < in.n; i++) {
        a0[i] = c.data[i * c.n_cols + (size_t)k0];
        a1[i] = c.data[i * c.n_cols + (size_t)k1];
        a2[i] = o->points ? c.data[i * c.n_cols + (size_t)k2] : 0.0;
    }
    if (o->traj)
        in.t = a0, in.P = a1;
    else
        in.d = a0, in.v0s = a1, in.pmax = a2;
    /* approach (b): every point carries its own d; the parameter set needs a
     * valid one, so it takes the first point's unless --diameter or --radius was given */
    if (o->points && !o->have_d && in.n > 0)
        in.base.d = a0[0];
    struct pen_fit_result fr;
    if (pen_fit(&in, &fr, res, &e)) {
        rc = fail(&e);
        goto done;
    }
    printf("fit of %s, approach %s, %zu rows from %s: %s after %d iterations\n",
           pen_model_name(in.base.model), o->traj ? "(a) one trajectory" : "(b) P_max points",
           in.n, path, fr.converged ? "converged" : "NOT converged", fr.iterations);
    printf("%-8s %14s %14s %30s\n", "coef", "value", "std. error", "95 % confidence interval");
    for (int k = 0; k < fr.n_coef; k++)
        printf("%-8s %14.6g %14.4g      [%12.6g, %12.6g]\n", fr.names[k], fr.value[k],
               fr.std_err[k], fr.ci_lo[k], fr.ci_hi[k]);
    if (fr.n_coef > 1) {
        printf("correlation:");
        for (int k = 0; k < fr.n_coef; k++)
            for (int l = k + 1; l < fr.n_coef; l++)
                printf("  %s-%s %+.4f", fr.names[k], fr.names[l], fr.corr[k][l]);
        printf("\n");
    }
    printf("residuals (%s): rms %.4g, max |r| %.4g, chi^2 %.4g, %d degrees of freedom\n",
           o->traj ? "P_model - P [m]" : "(P_max,model - P_max)/d [1]", fr.rms, fr.max_abs,
           fr.chisq, fr.dof);
    if (o->csv) {
        FILE *f = NULL;
        if ((rc = write_open(o->csv, &f)))
            goto done;
        if (o->traj) {
            fprintf(f, "t,P_data,P_model,residual\n");
            for (size_t i = 0; i < in.n; i++)
                fprintf(f, "%.10e,%.10e,%.10e,%.10e\n", a0[i], a1[i], a1[i] + res[i], res[i]);
        } else {
            fprintf(f, "d,v0,P_max_data,P_max_model,residual_over_d\n");
            for (size_t i = 0; i < in.n; i++)
                fprintf(f, "%.10e,%.10e,%.10e,%.10e,%.10e\n", a0[i], a1[i], a2[i],
                        a2[i] + res[i] * a0[i], res[i]);
        }
        if (fclose(f))
            rc = bad("error writing '%s'%s", o->csv, "");
        if (!rc)
            rc = plot_fit(o, &in, a0, a1, a2, res);
    }
    if (!rc && o->curve) {
        /* reuse the residual buffer for the sorted diameters */
        if (o->points) {
            memcpy(res, a0, in.n * sizeof *res);
            qsort(res, in.n, sizeof *res, cmp_dbl);
        }
        rc = write_curve(o, &in, &fr.fitted, res);
    }
done:
    free(buf);
    pen_csv_free(&c);
    return rc;
}

static int cmd_sweep(struct pen_opts *o)
{
    struct spall_error e = {0};
    if (!o->model || !o->vrange || !o->dlist || !o->csv)
        return bad("sweep needs --model, --v0 FROM:TO:STEP, --diameter D1[,D2,...] (or --radius) "
                   "and --csv%s%s", "", "");
    double v_from = 0, v_to = 0, v_step = 0;
    char tail = 0;
    if (sscanf(o->vrange, "%lf:%lf:%lf%c", &v_from, &v_to, &v_step, &tail) != 3 ||
        !(v_from > 0) || !(v_to >= v_from) || !(v_step > 0) || (v_to - v_from) / v_step > 1e6)
        return bad("--v0 '%s' must be FROM:TO:STEP with 0 < FROM <= TO, STEP > 0%s", o->vrange,
                   "");
    double ds[PEN_MAX_D];
    int nd = 0;
    const char *s = o->dlist;
    while (*s) {
        char *end = NULL;
        if (nd == PEN_MAX_D)
            return bad("%s lists more than 64 values%s", o->d_is_radius ? "--radius" : "--diameter", "");
        ds[nd] = strtod(s, &end);
        if (end == s || !(ds[nd] > 0) || !isfinite(ds[nd]) || (*end && *end != ','))
            return bad("%s '%s' must be a comma-separated list of lengths > 0",
                       o->d_is_radius ? "--radius" : "--diameter", o->dlist);
        if (o->d_is_radius)
            ds[nd] *= 2.0;
        nd++;
        s = *end ? end + 1 : end;
    }
    FILE *f = NULL;
    int rc = 0;
    const long nv = (long)floor((v_to - v_from) / v_step * (1.0 + 1e-12)) + 1;
    /* P_max/d for the figure: one row of nv values per diameter, then v0 */
    double *fig = malloc((size_t)(nd + 1) * (size_t)nv * sizeof *fig);
    if (!fig)
        return bad("out of memory%s%s", "", "");
    double *fig_v = fig + (size_t)nd * (size_t)nv;
    for (int k = 0; k < nd && !rc; k++) {
        struct pen_params p = o->p;
        p.d = ds[k];
        double re_worst = 0.0;
        for (long iv = 0; iv < nv && !rc; iv++) {
            const double v = v_from + (double)iv * v_step;
            struct pen_result r;
            if (pen_solve(&p, v, 0, NULL, NULL, NULL, o->ode, &r, &e)) {
                rc = fail(&e);
                break;
            }
            if (!f) {
                if ((rc = write_open(o->csv, &f)))
                    break;
                fprintf(f, "# spall penetrate sweep, model %s\n", pen_model_name(p.model));
                fprintf(f, "d,v0,T_f,P_max,P_max_nose,P_max_over_d%s\n",
                        p.model == PEN_MCG ? ",Re" : "");
            }
            fprintf(f, "%.10e,%.10e,%.10e,%.10e,%.10e,%.10e", p.d, v, r.t_f, r.p_max,
                    r.p_max + 0.5 * p.d, r.p_max / p.d);
            fig[(size_t)k * (size_t)nv + (size_t)iv] = r.p_max / p.d;
            fig_v[iv] = v;
            if (p.model == PEN_MCG)
                fprintf(f, ",%.10e", r.re_max);
            fprintf(f, "\n");
            if (r.re_max > re_worst)
                re_worst = r.re_max;
        }
        if (!rc)
            warn_re(&p, v_to, re_worst);
    }
    if (f && fclose(f) && !rc)
        rc = bad("error writing '%s'%s", o->csv, "");
    if (!rc)
        printf("wrote %s (%d diameter(s))\n", o->csv, nd);
    if (!rc) {
        struct plot_series ser[PEN_MAX_D];
        char labels[PEN_MAX_D][32];
        for (int k = 0; k < nd; k++) {
            snprintf(labels[k], sizeof labels[k], "d = %.3g um", ds[k] * 1e6);
            ser[k] = (struct plot_series){labels[k], fig_v, fig + (size_t)k * (size_t)nv,
                                          (size_t)nv, PLOT_LINE};
        }
        char title[64], path[1024];
        snprintf(title, sizeof title, "%s: P_max / d vs impact velocity",
                 pen_model_name(o->p.model));
        struct plot_spec spec = {title, "impact velocity v0 [m/s]", "P_max / d [1]", 0, 0,
                                 ser, (size_t)nd, NULL, 0};
        png_path(o->csv, path, sizeof path);
        if (plot_png(path, &spec, &e))
            rc = fail(&e);
        else
            printf("wrote %s\n", path);
    }
    free(fig);
    return rc;
}

int cli_penetrate(int argc, char **argv)
{
    if (argc < 2 || strcmp(argv[1], "-h") == 0 || strcmp(argv[1], "--help") == 0) {
        pen_usage(argc < 2 ? stderr : stdout);
        return argc < 2 ? 2 : 0;
    }
    for (int k = 2; k < argc; k++)
        if (strcmp(argv[k], "-h") == 0 || strcmp(argv[k], "--help") == 0) {
            pen_usage(stdout);
            return 0;
        }
    struct pen_opts o;
    memset(&o, 0, sizeof o);
    o.p.edot0 = 1.0e7;
    const char *mode = argv[1];
    struct spall_error e = {0};
    int is_fit = strcmp(mode, "fit") == 0, is_sweep = strcmp(mode, "sweep") == 0;
    if (!is_fit && !is_sweep && pen_model_from_name(mode, &o.p.model, &e))
        return bad("unknown mode '%s'; expected poncelet, liu, mcg, fit or sweep%s", mode, "");
    int rc = parse_opts(argc, argv, 2, &o);
    if (rc)
        return rc;
    if ((is_fit || is_sweep) && o.model && pen_model_from_name(o.model, &o.p.model, &e))
        return fail(&e);
    if (!(o.p.rho_p > 0) || !(o.p.rho_t > 0))
        return bad("densities missing: give --rho-projectile/--projectile and --rho-target/--target%s%s", "", "");
    /* like `spall run`: results are never replaced silently, and the check
     * comes before anything is computed or written */
    const char *outs[3] = {o.csv, o.curve, NULL};
    char png[1024];
    if (o.csv && (is_fit || is_sweep)) {
        png_path(o.csv, png, sizeof png);
        outs[2] = png;
    }
    for (int k = 0; k < 3 && !o.overwrite; k++)
        if (outs[k] && access(outs[k], F_OK) == 0)
            return bad("'%s' exists; give --overwrite to replace it%s", outs[k], "");
    if (is_fit) {
        /* initial guesses where none given */
        if (!(o.p.cd > 0)) o.p.cd = 0.5;
        if (!(o.p.R > 0)) o.p.R = 1.0e7;
        if (!(o.p.cv > 0)) o.p.cv = 1.0e3;
        if (!(o.p.sigma0 > 0)) o.p.sigma0 = 1.0e7;
        if (!(o.p.eta > 0)) o.p.eta = 0.05;
        return cmd_fit(&o);
    }
    if (is_sweep)
        return cmd_sweep(&o);
    return cmd_model(&o);
}
