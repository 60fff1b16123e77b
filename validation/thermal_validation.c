/**
 * @file thermal_validation.c
 * @brief Validation cases "thermal-conduction" and "thermal-expansion" of the
 *        thermal lattice ([Wang2010] sec. 2.2, Eqs. 19-21; lattice_thermal.h).
 *
 * thermal-conduction: a chain of 101 particles (r0 = 1 mm) at T0 = 300 K whose
 * first particle is held at T1 = 400 K.  A semi-infinite bar with a fixed end
 * temperature has T(x, t) = T0 + (T1 - T0) erfc(x / (2 sqrt(a t))),
 * a = k / (rho C).  At t = 0.1 s, sqrt(a t) = 10 r0, so the 100 mm chain is
 * semi-infinite to erfc(5) = 1.5e-12, and the lattice's second-order error,
 * ~ r0^2 / (12 (2 sqrt(a t))^2) relative, is about 0.02 %.  Checked: T at
 * x = 5, 10 and 20 mm, error / (T1 - T0) < 2 % (the tolerance).
 * No expansion (alpha = 0), so nothing moves.
 *
 * thermal-expansion: a free 20 x 10 mm alpha-beta plate (nu = 0.25) heated
 * uniformly by a power density P_d for 2 ms (dT = P_d t / (rho C) = 100 K,
 * alpha = 1e-5 /K).  Every bond's rest length scales by 1 + alpha dT, so the
 * stress-free state is a uniform strain alpha dT in x and y.  Measured: the
 * least-squares slopes du_x/dx and du_y/dy over all particles; reference
 * alpha (T_mean - T_ref) from the temperature field; tolerance 1 % (issue).
 * The heating is slow (2 ms = 50 periods of the plate's lowest mode), so the
 * dynamic lag of the strain behind the ramp, ~ 1 / (omega t), is ~ 0.3 %.
 */
#include "validation/thermal_cases.h"

#include "validation/lattice_cases.h"
#include "validation/validation.h"

#include "core/fields.h"
#include "core/particles.h"
#include "core/sim.h"
#include "core/parallel/comm.h"
#include "spall/error.h"
#include "validation/vpar.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static int temperatures(const struct sim *s, double **T, struct spall_error *err)
{
    const struct field_desc *f = field_registry_find(s->fields, "temperature");
    if (!f)
        return spall_error_set(err, SPALL_ERR_INTERNAL, "no temperature field registered");
    double *own = malloc((s->p->n_owned ? s->p->n_owned : 1) * sizeof *own);
    if (own)
        field_gather_f64(f, s->p->n_owned, own);
    /* the whole run's temperatures by global id (one rank: the same array) */
    int rc = own ? SPALL_OK
                 : spall_error_set(err, SPALL_ERR_NOMEM, "out of memory in thermal validation");
    if (s->par)
        rc = par_agree(rc, err);
    *T = rc ? NULL : vpar_whole(s, own, err);
    free(own);
    return rc ? rc : (*T ? SPALL_OK : err->code);
}

static int run_to(struct sim *s, double t_end, struct spall_error *err)
{
    int rc = SPALL_OK;
    while (s->t < t_end - 1e-12 * t_end && !rc)
        rc = sim_step(s, err);
    return rc;
}

#define COND_T0 300.0
#define COND_T1 400.0
#define COND_RHO 1000.0
#define COND_C 4000.0
#define COND_K 4000.0 /* a = 1e-3 m^2/s */
#define COND_T_END 0.1

int thermal_case_conduction(struct vreport *r, struct spall_error *err)
{
    static const char *deck =
        "title: thermal lattice, 1D conduction from a fixed-temperature end\n"
        "model:\n"
        "  type: lattice\n"
        "  law: linear\n"
        "  thermal: {boundary: [{group: hot, temperature: 400}]}\n"
        "materials:\n"
        "  bar: {density: 1000, youngs_modulus: 1.0e6, failure_strain: 1.0, specific_heat: 4000,\n"
        "        conductivity: 4000, initial_temperature: 300, reference_temperature: 300}\n"
        "lattice: {type: chain, spacing: 1.0e-3}\n"
        "geometry:\n"
        "  rod: {box: {min: [-0.0005], max: [0.1005]}}\n"
        "body: {geometry: rod, material: bar}\n"
        "groups:\n"
        "  hot: {box: {min: [-0.001], max: [0.0005]}}\n"
        "run: {end_time: 0.1}\n";
    struct sim *s = NULL;
    double *T = NULL, *xs = NULL, *ts = NULL, *te = NULL;
    double *x0 = NULL;
    int rc = vlat_build("thermal_conduction", deck, &s, err);
    if (rc)
        return rc;
    /* mpirun: partitioned; the measurement reads the whole bar by global id */
    if ((rc = vpar_distribute(r, s, err)) || (rc = run_to(s, COND_T_END, err)) ||
        (rc = temperatures(s, &T, err)) || !(x0 = vpar_whole(s, s->p->x0[0], err))) {
        rc = rc ? rc : err->code;
        goto done;
    }
    const size_t n = vpar_n(s);
    const double a = COND_K / (COND_RHO * COND_C), L = 2.0 * sqrt(a * s->t);
    const double xq[3] = {0.005, 0.010, 0.020};
    for (int q = 0; q < 3; q++) {
        size_t best = 0;
        for (size_t i = 0; i < n; i++)
            if (fabs(x0[i] - xq[q]) < fabs(x0[best] - xq[q]))
                best = i;
        double ref = COND_T0 + (COND_T1 - COND_T0) * erfc(x0[best] / L);
        char name[96];
        snprintf(name, sizeof name, "T at x = %.0f mm, t = %.2g s (error / (T1 - T0))",
                 1e3 * x0[best], s->t);
        /* error relative to the imposed temperature step */
        double meas_scaled = (T[best] - COND_T0) / (COND_T1 - COND_T0);
        double ref_scaled = (ref - COND_T0) / (COND_T1 - COND_T0);
        if ((rc = vreport_check(r, name, "1", ref_scaled, meas_scaled, 0.02, false,
                                "T0 + (T1 - T0) erfc(x / (2 sqrt(a t))), a = k / (rho C): "
                                "semi-infinite bar, fixed end temperature",
                                "2 % of the step (issue 3); discretisation error ~0.02 % at "
                                "sqrt(a t) = 10 r0",
                                err)))
            goto done;
        vreport_info(r, "x = %.4g m: T = %.4f K, analytical %.4f K (%+.3f %% of the step)",
                     x0[best], T[best], ref, 100.0 * (meas_scaled - ref_scaled));
    }
    /* profile for the report */
    xs = malloc(n * sizeof *xs);
    ts = malloc(n * sizeof *ts);
    te = malloc(n * sizeof *te);
    if (!xs || !ts || !te) {
        rc = spall_error_set(err, SPALL_ERR_NOMEM, "out of memory in thermal validation");
        goto done;
    }
    for (size_t i = 0; i < n; i++) {
        xs[i] = 1e3 * x0[i];
        ts[i] = T[i];
        te[i] = COND_T0 + (COND_T1 - COND_T0) * erfc(x0[i] / L);
    }
    const char *plot = "temperature profile at t = 0.1 s";
    if ((rc = vreport_series(r, plot, "x [mm]", "T [K]", "lattice", VSERIES_POINTS, xs, ts, n,
                             err)) ||
        (rc = vreport_series(r, plot, NULL, NULL, "erfc (analytical)", VSERIES_REF, xs, te, n,
                             err)))
        goto done;
done:
    free(T);
    free(x0);
    free(xs);
    free(ts);
    free(te);
    sim_destroy(&s);
    return rc;
}

/* least-squares slope of u_d against x0_d over the whole body: the
 * particles in global-id order (the serial order on any rank count) */
static double strain_fit(const double *x0, const double *x, size_t n)
{
    double mx = 0.0, mu = 0.0;
    for (size_t i = 0; i < n; i++) {
        mx += x0[i];
        mu += x[i] - x0[i];
    }
    mx /= (double)n;
    mu /= (double)n;
    double sxx = 0.0, sxu = 0.0;
    for (size_t i = 0; i < n; i++) {
        double dx = x0[i] - mx, du = x[i] - x0[i] - mu;
        sxx += dx * dx;
        sxu += dx * du;
    }
    return sxx > 0.0 ? sxu / sxx : NAN;
}

/* strain_fit of component @p d of the (possibly distributed) run */
static int whole_strain(const struct sim *s, int d, double *eps, struct spall_error *err)
{
    double *x0 = vpar_whole(s, s->p->x0[d], err);
    double *x = x0 ? vpar_whole(s, s->p->x[d], err) : NULL;
    if (x)
        *eps = strain_fit(x0, x, vpar_n(s));
    free(x0);
    free(x);
    return x ? SPALL_OK : err->code;
}

#define EXP_ALPHA 1.0e-5
#define EXP_T_REF 293.15

int thermal_case_expansion(struct vreport *r, struct spall_error *err)
{
    /* P_d = rho C dT / t = 1000 * 1000 * 100 / 2e-3 */
    static const char *deck =
        "title: thermal lattice, free expansion of a uniformly heated plate\n"
        "model: {type: lattice, law: linear}\n"
        "materials:\n"
        "  solid: {density: 1000, youngs_modulus: 1.0e9, poisson_ratio: 0.25, failure_strain: 1.0,\n"
        "          specific_heat: 1000, conductivity: 1.0, thermal_expansion: 1.0e-5,\n"
        "          power_density: 5.0e10}\n"
        "lattice: {type: triangular, spacing: 1.0e-3}\n"
        "geometry:\n"
        "  plate: {box: {min: [0, 0], max: [0.0201, 0.0101]}}\n"
        "body: {geometry: plate, material: solid}\n"
        "run: {end_time: 2.0e-3}\n";
    struct sim *s = NULL;
    double *T = NULL, *tt = NULL, *ex = NULL, *eref = NULL;
    int rc = vlat_build("thermal_expansion", deck, &s, err);
    if (!rc && (rc = vpar_distribute(r, s, err))) /* mpirun: strains of the whole body */
        sim_destroy(&s);
    if (rc)
        return rc;
    long nmax = (long)ceil(2.0e-3 / s->dt) + 2, k = 0;
    tt = malloc((size_t)nmax * sizeof *tt);
    ex = malloc((size_t)nmax * sizeof *ex);
    eref = malloc((size_t)nmax * sizeof *eref);
    if (!tt || !ex || !eref) {
        rc = spall_error_set(err, SPALL_ERR_NOMEM, "out of memory in thermal validation");
        goto done;
    }
    const double dT_rate = 5.0e10 / (1000.0 * 1000.0); /* K/s */
    while (s->t < 2.0e-3 * (1.0 - 1e-12) && k < nmax) {
        if ((rc = sim_step(s, err)))
            goto done;
        if (s->step % 20 == 0) {
            tt[k] = 1e3 * s->t;
            double e = 0.0;
            if ((rc = whole_strain(s, 0, &e, err)))
                goto done;
            ex[k] = 1e6 * e;
            eref[k++] = 1e6 * EXP_ALPHA * dT_rate * s->t;
        }
    }
    if ((rc = temperatures(s, &T, err)))
        goto done;
    double tm = 0.0, exx = 0.0, eyy = 0.0;
    for (size_t i = 0; i < vpar_n(s); i++)
        tm += T[i];
    tm /= (double)vpar_n(s);
    if ((rc = whole_strain(s, 0, &exx, err)) || (rc = whole_strain(s, 1, &eyy, err)))
        goto done;
    const double ref = EXP_ALPHA * (tm - EXP_T_REF);
    const char *src = "alpha (T_mean - T_ref): stress-free state of a free body whose bond rest "
                      "lengths all scale by 1 + alpha dT ([Wang2010] Eq. 21)";
    const char *note = "1 % (issue 3); dynamic lag of the slow heating ramp ~0.3 %";
    if ((rc = vreport_check(r, "free thermal strain eps_xx", "1", ref, exx, 0.01,
                            true, src, note, err)) ||
        (rc = vreport_check(r, "free thermal strain eps_yy", "1", ref, eyy, 0.01,
                            true, src, note, err)))
        goto done;
    vreport_info(r, "T_mean = %.4f K (expected %.4f K from P_d t / (rho C)); eps_xx = %.6g, "
                 "eps_yy = %.6g, alpha dT = %.6g",
                 tm, EXP_T_REF + dT_rate * s->t, exx, eyy, ref);
    const char *plot = "strain vs time under uniform heating";
    if ((rc = vreport_series(r, plot, "time [ms]", "strain [1e-6]", "eps_xx (lattice)",
                             VSERIES_LINE, tt, ex, (size_t)k, err)) ||
        (rc = vreport_series(r, plot, NULL, NULL, "alpha dT(t)", VSERIES_REF, tt, eref, (size_t)k,
                             err)))
        goto done;
done:
    free(T);
    free(tt);
    free(ex);
    free(eref);
    sim_destroy(&s);
    return rc;
}
