/*
 * Unit tests of the analytical penetration models (src/penetration):
 * closed forms against hand-derived limits, input checking, the CSV reader
 * and the fit's input checks.  Validation against the thesis lives in
 * validation/pen_*.c.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include "core/mathconst.h"
#include "spall/error.h"
#include "spall/penetration.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>


static struct pen_params gel(void)
{
    struct pen_params p = {0};
    p.model = PEN_PONCELET;
    p.d = 7.38e-6, p.rho_p = 1850, p.rho_t = 1030, p.cd = 0.375, p.R = 21e6, p.edot0 = 1e7;
    return p;
}

/* V(0) = v0, P(0) = 0, V(T_f) = 0, and energy: for small v0 the resistance
 * dominates, P_max -> M v0^2 / (2 C) (B -> 0 limit of Eq. 4.6). */
static void test_poncelet_limits(void **state)
{
    (void)state;
    struct pen_params p = gel();
    struct spall_error e = {0};
    struct pen_result r;
    double t[2] = {0.0, 1.0}, P[2], V[2];
    assert_int_equal(pen_poncelet(&p, 1290.0, 2, t, P, V, &r, &e), SPALL_OK);
    assert_true(fabs(V[0] - 1290.0) < 1e-9 * 1290.0);
    assert_true(fabs(P[0]) < 1e-18);
    assert_true(V[1] == 0.0 || fabs(V[1]) < 1e-9);
    assert_true(fabs(P[1] - r.p_max) < 1e-12 * r.p_max);
    const double v0 = 0.1;
    assert_int_equal(pen_poncelet(&p, v0, 0, NULL, NULL, NULL, &r, &e), SPALL_OK);
    const double C = p.R * SPALL_PI * p.d * p.d / 4.0;
    const double lim = pen_mass(&p) * v0 * v0 / (2.0 * C);
    assert_true(fabs(r.p_max / lim - 1.0) < 1e-6);
}

/* Liu with C_v = 0 and edot0 -> infinity is Poncelet with R = sigma0. */
static void test_liu_reduces_to_poncelet(void **state)
{
    (void)state;
    struct pen_params p = gel(), l = gel();
    l.model = PEN_LIU;
    l.cv = 0.0;
    l.sigma0 = p.R;
    l.edot0 = 1e30;
    struct spall_error e = {0};
    struct pen_result rp, rl;
    assert_int_equal(pen_solve(&p, 800.0, 0, NULL, NULL, NULL, 0, &rp, &e), SPALL_OK);
    assert_int_equal(pen_solve(&l, 800.0, 0, NULL, NULL, NULL, 0, &rl, &e), SPALL_OK);
    assert_true(rl.closed_form);
    assert_true(fabs(rl.p_max / rp.p_max - 1.0) < 1e-10);
    assert_true(fabs(rl.t_f / rp.t_f - 1.0) < 1e-10);
}

/* Liu with a strong viscous term (b^2 > 4ac) has no atan closed form: the
 * ODE is used; check it against the log form of the same integrals,
 * with D = b^2 - 4ac > 0 and L(v) = ln((2av + b - sqrt D) / (2av + b + sqrt D)):
 * T_f = M (L(v0) - L(0)) / sqrt D,
 * P_max = M [ln(F(v0) / F(0)) / (2a) - b (L(v0) - L(0)) / (2a sqrt D)]. */
static void test_liu_fallback(void **state)
{
    (void)state;
    struct pen_params l = gel();
    l.model = PEN_LIU;
    l.cd = 0.4;
    l.cv = 1.0e6; /* b^2 >> 4ac */
    l.sigma0 = 1.0e5;
    struct spall_error e = {0};
    struct pen_result r;
    const double v0 = 300.0;
    assert_int_equal(pen_solve(&l, v0, 0, NULL, NULL, NULL, 0, &r, &e), SPALL_OK);
    assert_false(r.closed_form);
    const double A = SPALL_PI * l.d * l.d / 4.0, M = pen_mass(&l);
    const double a = 0.5 * l.cd * l.rho_t * A + A * l.sigma0 / (l.d * l.d * l.edot0 * l.edot0);
    const double b = l.cv * A, c = l.sigma0 * A, sd = sqrt(b * b - 4.0 * a * c);
    const double dl = log((2 * a * v0 + b - sd) / (2 * a * v0 + b + sd)) - log((b - sd) / (b + sd));
    const double tf = M * dl / sd;
    const double pm = M * (log((a * v0 * v0 + b * v0 + c) / c) / (2 * a) - b * dl / (2 * a * sd));
    assert_true(fabs(r.t_f / tf - 1.0) < 1e-8);
    assert_true(fabs(r.p_max / pm - 1.0) < 1e-8);
}

/* Clift-Gauvin: Stokes limit 24/Re at small Re, ~0.4-0.45 near Re = 1e4. */
static void test_clift_gauvin(void **state)
{
    (void)state;
    assert_true(fabs(pen_cd_clift_gauvin(1e-4) * 1e-4 / 24.0 - 1.0) < 1e-3);
    const double c = pen_cd_clift_gauvin(1e4);
    assert_true(c > 0.35 && c < 0.5);
    struct pen_params p = gel();
    p.model = PEN_MCG;
    p.eta = 0.045;
    p.R = 25e6;
    /* F(0) is the resistance alone */
    assert_true(fabs(pen_force(&p, 0.0) / (p.R * SPALL_PI * p.d * p.d / 4.0) - 1.0) < 1e-14);
    struct spall_error e = {0};
    struct pen_result r;
    assert_int_equal(pen_solve(&p, 500.0, 0, NULL, NULL, NULL, 0, &r, &e), SPALL_OK);
    assert_false(r.closed_form);
    assert_true(fabs(r.re_max - 1030.0 * 500.0 * 7.38e-6 / 0.045) < 1e-9);
}

static void test_bad_params(void **state)
{
    (void)state;
    struct spall_error e = {0};
    struct pen_result r;
    struct pen_params p = gel();
    p.R = -1.0;
    assert_int_equal(pen_solve(&p, 100.0, 0, NULL, NULL, NULL, 0, &r, &e), SPALL_ERR_INPUT);
    assert_non_null(strstr(e.msg, "R"));
    p = gel();
    assert_int_equal(pen_solve(&p, 0.0, 0, NULL, NULL, NULL, 0, &r, &e), SPALL_ERR_INPUT);
    assert_non_null(strstr(e.msg, "v0"));
    p.d = NAN;
    assert_int_equal(pen_solve(&p, 10.0, 0, NULL, NULL, NULL, 0, &r, &e), SPALL_ERR_INPUT);
    enum pen_model m;
    assert_int_equal(pen_model_from_name("modified-cg", &m, &e), SPALL_OK);
    assert_int_equal(m, PEN_MCG);
    assert_int_equal(pen_model_from_name("bogus", &m, &e), SPALL_ERR_INPUT);
    assert_non_null(strstr(e.msg, "bogus"));
}

static void write_file(const char *path, const char *text)
{
    FILE *f = fopen(path, "w");
    assert_non_null(f);
    fputs(text, f);
    fclose(f);
}

static void test_csv(void **state)
{
    (void)state;
    const char *path = "test_penetration_tmp.csv";
    struct pen_csv c;
    struct spall_error e = {0};
    write_file(path, "# comment\n\n t , P \n1e-9, 2e-6\n2e-9,3e-6\n");
    assert_int_equal(pen_csv_read(path, &c, &e), SPALL_OK);
    assert_int_equal(c.n_rows, 2);
    assert_int_equal(c.n_cols, 2);
    assert_int_equal(pen_csv_column(&c, "P"), 1);
    assert_int_equal(pen_csv_column(&c, "x"), -1);
    assert_true(c.data[3] == 3e-6);
    pen_csv_free(&c);
    write_file(path, "t,P\n1,2\n3,abc\n");
    assert_int_equal(pen_csv_read(path, &c, &e), SPALL_ERR_INPUT);
    assert_non_null(strstr(e.msg, ":3:"));
    write_file(path, "t,P\n1\n");
    assert_int_equal(pen_csv_read(path, &c, &e), SPALL_ERR_INPUT);
    assert_non_null(strstr(e.msg, ":2:"));
    write_file(path, "t,P\n");
    assert_int_equal(pen_csv_read(path, &c, &e), SPALL_ERR_INPUT);
    assert_non_null(strstr(e.msg, "no data"));
    remove(path);
    assert_int_equal(pen_csv_read(path, &c, &e), SPALL_ERR_INPUT);
}

static void test_fit_input(void **state)
{
    (void)state;
    struct pen_fit_input in;
    memset(&in, 0, sizeof in);
    in.kind = PEN_FIT_TRAJECTORY;
    in.base = gel();
    in.v0 = 1290.0;
    double t[2] = {1e-9, 2e-9}, P[2] = {1e-6, 2e-6};
    in.t = t, in.P = P, in.n = 2; /* 2 rows for 2 coefficients: too few */
    struct pen_fit_result f;
    struct spall_error e = {0};
    assert_int_equal(pen_fit(&in, &f, NULL, &e), SPALL_ERR_INPUT);
    assert_non_null(strstr(e.msg, "at least 3"));
    /* a Poncelet trajectory fit recovers its own coefficients */
    enum { N = 30 };
    double tt[N], PP[N];
    struct pen_result r;
    struct pen_params truth = gel();
    assert_int_equal(pen_solve(&truth, 1290.0, 0, NULL, NULL, NULL, 0, &r, &e), SPALL_OK);
    for (int i = 0; i < N; i++)
        tt[i] = r.t_f * (i + 1) / (N + 1);
    assert_int_equal(pen_solve(&truth, 1290.0, N, tt, PP, NULL, 0, &r, &e), SPALL_OK);
    in.t = tt, in.P = PP, in.n = N;
    in.base.cd = 1.0;
    in.base.R = 5e6;
    double res[N];
    assert_int_equal(pen_fit(&in, &f, res, &e), SPALL_OK);
    assert_int_equal(f.n_coef, 2);
    assert_true(fabs(f.value[0] / 0.375 - 1.0) < 1e-6);
    assert_true(fabs(f.value[1] / 21e6 - 1.0) < 1e-6);
    assert_true(f.max_abs < 1e-6 * r.p_max);
}

/* A square lattice (spacing 0.5 um) with a hole of radius 5 um and failed
 * particles out to 7 um: D1 ~ 10 um, D2 ~ 14 um within a spacing; one
 * stray particle on the axis does not close the cavity. */
static void test_cavity(void **state)
{
    (void)state;
    const double a = 0.5e-6;
    enum { NMAX = 200000 };
    double *x = malloc(3 * NMAX * sizeof *x), *y = x + NMAX, *z = y + NMAX;
    double *dxs = malloc(NMAX * sizeof *dxs);
    unsigned char *failed = malloc(NMAX);
    assert_non_null(x);
    assert_non_null(dxs);
    assert_non_null(failed);
    size_t n = 0;
    for (int k = -1; k <= 1; k++)
        for (int i = -30; i <= 30; i++)
            for (int j = -30; j <= 30; j++) {
                const double px = i * a, py = j * a, r = sqrt(px * px + py * py);
                if (r < 5.0e-6 + 0.5 * a)
                    continue;
                x[n] = px, y[n] = py, z[n] = -15e-6 + k * a, dxs[n] = a;
                failed[n] = r < 7.0e-6 + 0.5 * a;
                n++;
            }
    x[n] = 0.1e-6, y[n] = 0.0, z[n] = -15e-6, dxs[n] = a, failed[n] = 1; /* stray */
    n++;
    struct pen_cavity_opts o = {0.0, 0.0, 15e-6, 0.0, 2.0 * a, 0};
    double d1 = 0, d2 = 0;
    struct spall_error e = {0};
    assert_int_equal(pen_cavity_diameters(n, x, y, z, dxs, failed, &o, &d1, &d2, &e), SPALL_OK);
    assert_true(fabs(d1 - 10e-6) < 2.0 * a);
    assert_true(fabs(d2 - 14e-6) < 2.0 * a);
    assert_int_equal(pen_cavity_diameters(n, x, y, z, dxs, NULL, &o, &d1, &d2, &e), SPALL_OK);
    assert_true(d1 == d2);
    o.depth = 1.0; /* empty slab */
    assert_int_equal(pen_cavity_diameters(n, x, y, z, dxs, failed, &o, &d1, &d2, &e), SPALL_OK);
    assert_true(d1 == 0.0 && d2 == 0.0);
    o.slab = 0.0;
    assert_int_equal(pen_cavity_diameters(n, x, y, z, dxs, failed, &o, &d1, &d2, &e),
                     SPALL_ERR_INPUT);
    free(x);
    free(dxs);
    free(failed);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_poncelet_limits), cmocka_unit_test(test_liu_reduces_to_poncelet),
        cmocka_unit_test(test_clift_gauvin),    cmocka_unit_test(test_bad_params),
        cmocka_unit_test(test_csv),             cmocka_unit_test(test_fit_input),
        cmocka_unit_test(test_cavity),          cmocka_unit_test(test_liu_fallback),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
