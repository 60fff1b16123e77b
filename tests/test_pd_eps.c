/*
 * Tests of the elastic-plastic state-based model (model.formulation: eps,
 * src/models/peridynamics/pd_eps.c).
 *  - bar: a uniaxial-stress cycle (load to 3 eps_Y, unload through reverse
 *    yield) imposed as a homogeneous deformation on a 2D triangular plate
 *    (its fourth moment is isotropic, so the interior particle is the
 *    continuum point): sigma_xx of the interior particle against the
 *    analytical elastic-perfectly plastic bar (E up to sigma_Y, plateau,
 *    unloading with E, reverse yield at -sigma_Y), sigma_yy = 0, and the
 *    equivalent plastic strain field against the axial plastic strain.  The
 *    lateral strain follows the analytical bar (elastic -nu d eps, plastic
 *    -d eps: 2D deviatoric flow keeps the area).
 *  - no flow under a dilatation (3D): the isotropic part stays elastic.
 *  - the deck refuses yield_stress without formulation eps and eps without it.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include "core/fields.h"
#include "core/model.h"
#include "core/particles.h"
#include "core/sim.h"
#include "io/deck.h"
#include "io/deck_build.h"
#include "models/peridynamics/pd.h"
#include "spall/error.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static int build(const char *yaml, struct sim **s, struct spall_error *err)
{
    struct deck *d = NULL;
    *s = NULL;
    int rc = deck_load_string(&d, "test", yaml, err);
    if (rc)
        return rc;
    struct run_output ro;
    rc = deck_build_sim(d, s, &ro, err);
    deck_destroy(&d);
    return rc;
}

/* Impose x = diag(1 + ex, 1 + ey, 1 + ez) x0 everywhere, take one force call
 * (which advances the plastic state) and read the fields of particle c. */
static void strain_step(struct sim *s, double ex, double ey, double ez, size_t c, double *sig,
                        double *ep)
{
    struct particles *p = s->p;
    const double e[3] = {ex, ey, ez};
    for (int a = 0; a < s->dim; a++)
        for (size_t i = 0; i < p->n; i++) {
            p->x[a][i] = p->x0[a][i] * (1.0 + e[a]);
            p->f[a][i] = 0.0;
        }
    struct spall_error err = {0};
    assert_int_equal(s->ops->compute_forces(s->model, s, &err), SPALL_OK);
    const int nc = field_symtensor_ncomp(s->dim);
    double *out = malloc(p->n * (size_t)nc * sizeof *out);
    assert_non_null(out);
    const struct field_desc *fs = field_registry_find(s->fields, "stress");
    const struct field_desc *fp = field_registry_find(s->fields, "plastic_strain");
    assert_non_null(fs);
    assert_non_null(fp);
    field_gather_f64(fs, p->n, out);
    for (int k = 0; k < nc; k++)
        sig[k] = out[c * (size_t)nc + (size_t)k];
    field_gather_f64(fp, p->n, out);
    *ep = out[c];
    free(out);
}

static void test_bar_cycle(void **state)
{
    (void)state;
    const double E = 1.0e9, nu = 0.3, sy = 1.0e5, ey_ = sy / E;
    char buf[1024];
    snprintf(buf, sizeof buf,
             "model: {type: peridynamics, formulation: eps}\n"
             "materials:\n  m: {density: 1000, youngs_modulus: %g, poisson_ratio: %g, "
             "yield_stress: %g}\n"
             "lattice: {type: triangular, spacing: 1.0e-3, thickness: 1.0e-3}\n"
             "geometry:\n  p: {box: {min: [0, 0], max: [0.0205, 0.0205]}}\n"
             "body: {geometry: p, material: m}\nrun: {end_time: 1.0}\n",
             E, nu, sy);
    struct spall_error err = {0};
    struct sim *s = NULL;
    int rc = build(buf, &s, &err);
    if (rc)
        fprintf(stderr, "%s\n", err.msg);
    assert_int_equal(rc, 0);
    const size_t c = pd_patch_particle(s->model, s, 0);
    /* path: 0 -> 3 eps_Y -> 0 in steps of eps_Y / 10 */
    const int nup = 30, n = 60;
    double ex = 0.0, ey = 0.0, sref = 0.0, epref = 0.0, worst = 0.0, worst_yy = 0.0;
    double s_peak = 0.0, s_rev = 0.0, ep_peak = 0.0, epf_peak = 0.0;
    for (int k = 1; k <= n; k++) {
        const double dex = (k <= nup ? 1.0 : -1.0) * 0.1 * ey_;
        /* analytical bar: elastic trial, clipped at +-sigma_Y */
        double st = sref + E * dex;
        st = fmax(-sy, fmin(sy, st));
        const double del = (st - sref) / E, dpl = dex - del;
        ex += dex;
        ey += -nu * del - dpl;
        sref = st;
        epref += fabs(dpl);
        double sig[3], epf;
        strain_step(s, ex, ey, 0.0, c, sig, &epf);
        worst = fmax(worst, fabs(sig[0] - sref) / sy);
        worst_yy = fmax(worst_yy, fabs(sig[1]) / sy);
        if (k == nup) {
            s_peak = sig[0];
            ep_peak = epref;
            epf_peak = epf;
        }
        if (k == nup + 20) /* unloaded by 2 eps_Y: at reverse yield */
            s_rev = sig[0];
    }
    printf("  EPS bar: sigma at 3 eps_Y %.5g (sigma_Y %.5g), at reverse yield %.5g; plastic "
           "strain %.5g (ref %.5g); worst |sigma_xx - ref| %.3g sigma_Y, |sigma_yy| %.3g "
           "sigma_Y\n", s_peak, sy, s_rev, epf_peak, ep_peak, worst, worst_yy);
    assert_true(fabs(s_peak / sy - 1.0) < 0.01);
    assert_true(fabs(s_rev / sy + 1.0) < 0.01);
    assert_true(fabs(epf_peak / ep_peak - 1.0) < 0.01);
    assert_true(worst < 0.01);
    assert_true(worst_yy < 0.01);
    sim_destroy(&s);
}

/* A pure dilatation (3D, far past the shear yield strain) leaves e^dp = 0
 * and the pressure K theta. */
static void test_dilatation_elastic(void **state)
{
    (void)state;
    const double E = 1.0e9, nu = 0.25, K = E / (3 * (1 - 2 * nu));
    struct spall_error err = {0};
    struct sim *s = NULL;
    int rc = build("model: {type: peridynamics, formulation: eps}\n"
                   "materials:\n  m: {density: 1000, youngs_modulus: 1.0e9, poisson_ratio: "
                   "0.25, yield_stress: 1.0e5}\n"
                   "lattice: {type: sc, spacing: 1.0e-3}\n"
                   "geometry:\n  p: {box: {min: [0, 0, 0], max: [0.0105, 0.0105, 0.0105]}}\n"
                   "body: {geometry: p, material: m}\nrun: {end_time: 1.0}\n",
                   &s, &err);
    if (rc)
        fprintf(stderr, "%s\n", err.msg);
    assert_int_equal(rc, 0);
    struct particles *p = s->p;
    size_t c = 0;
    double best = INFINITY;
    for (size_t i = 0; i < p->n; i++) {
        double d2 = 0;
        for (int a = 0; a < 3; a++)
            d2 += pow(p->x0[a][i] - 0.005, 2);
        if (d2 < best) {
            best = d2;
            c = i;
        }
    }
    const double e = 1.0e-4; /* 10 x the uniaxial yield strain */
    double sig[6], epf;
    strain_step(s, e, e, e, c, sig, &epf);
    printf("  EPS 3D dilatation: sigma_xx / (3 K e) - 1 = %.3g, plastic strain %.3g\n",
           sig[0] / (3 * K * e) - 1, epf);
    assert_true(fabs(sig[0] / (3 * K * e) - 1) < 1e-3);
    assert_true(epf < 1e-9 * e);
    sim_destroy(&s);
}

static void refused(const char *model, const char *mat, const char *want)
{
    char buf[1024];
    snprintf(buf, sizeof buf,
             "model: {type: peridynamics, %s}\n"
             "materials:\n  m: {density: 1000, youngs_modulus: 1.0e9, %s}\n"
             "lattice: {type: square, spacing: 1.0e-3, thickness: 1.0e-3}\n"
             "geometry:\n  p: {box: {min: [0, 0], max: [0.01, 0.01]}}\n"
             "body: {geometry: p, material: m}\nrun: {end_time: 1.0}\n",
             model, mat);
    struct spall_error err = {0};
    struct sim *s = NULL;
    assert_int_not_equal(build(buf, &s, &err), 0);
    printf("  refused: %s\n", err.msg);
    assert_non_null(strstr(err.msg, want));
    assert_null(s);
}

static void test_deck(void **state)
{
    (void)state;
    refused("formulation: lps", "poisson_ratio: 0.3, yield_stress: 1.0e6", "formulation eps");
    refused("formulation: eps", "poisson_ratio: 0.3", "yield_stress");
    refused("formulation: eps", "yield_stress: 1.0e6", "poisson_ratio");
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_bar_cycle),
        cmocka_unit_test(test_dilatation_elastic),
        cmocka_unit_test(test_deck),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
