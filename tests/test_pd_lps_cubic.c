/*
 * Tests of the cubic influence correction of the linear peridynamic solid
 * (model.influence_correction: cubic, src/models/peridynamics/pd_lps.c):
 * on the square (2D, rotated by 30 degrees) and simple-cubic (3D) lattices
 * the two shear moduli C66 and (C11 - C12)/2 of an interior particle, which
 * differ by about 8 % (2D) without it, agree to 1e-6, and bulk and shear
 * match the input E and nu to 1e-6; the correction is refused on a lattice
 * that is not cubic and with pair forces.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include "core/fields.h"
#include "core/mathconst.h"
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

static void test_square_rotated(void **state)
{
    (void)state;
    const double E = 1e9, nu = 0.2, ang = 30.0;
    for (int corr = 0; corr < 2; corr++) {
        char buf[1024];
        snprintf(buf, sizeof buf,
                 "model: {type: peridynamics, formulation: lps%s}\n"
                 "materials:\n  m: {density: 1000, youngs_modulus: %g, poisson_ratio: %g}\n"
                 "lattice: {type: square, spacing: 1.0e-3, thickness: 1.0e-3, angle: %g}\n"
                 "geometry:\n  p: {circle: {center: [0, 0], radius: 0.012}}\n"
                 "body: {geometry: p, material: m}\nrun: {end_time: 1.0}\n",
                 corr ? ", influence_correction: cubic" : "", E, nu, ang);
        struct spall_error err = {0};
        struct sim *s = NULL;
        int rc = build(buf, &s, &err);
        if (rc)
            fprintf(stderr, "%s\n", err.msg);
        assert_int_equal(rc, 0);
        size_t i = pd_patch_particle(s->model, s, 0);
        double C[3][3];
        /* material axes = lattice axes */
        pd_patch_stiffness(s->model, s, i, ang * SPALL_PI / 180.0, C);
        const double c11 = E / (1 - nu * nu), c12 = nu * c11, c66 = E / (2 * (1 + nu));
        const double g1 = 0.5 * (C[0][0] - C[0][1]) / c66, g2 = C[2][2] / c66;
        printf("  square %s: C11 %+.2e, C12 %+.2e, (C11-C12)/2 %+.2e, C66 %+.2e (relative)\n",
               corr ? "corrected" : "as is", C[0][0] / c11 - 1, C[0][1] / c12 - 1, g1 - 1,
               g2 - 1);
        if (corr) {
            assert_true(fabs(C[0][0] / c11 - 1) < 1e-6);
            assert_true(fabs(C[0][1] / c12 - 1) < 1e-6);
            assert_true(fabs(g1 - 1) < 1e-6 && fabs(g2 - 1) < 1e-6);
        } else {
            assert_true(fabs(g1 - g2) > 0.05); /* the gap the correction removes */
        }
        sim_destroy(&s);
    }
}

static void test_sc(void **state)
{
    (void)state;
    const double E = 1e9, nu = 0.1;
    struct spall_error err = {0};
    struct sim *s = NULL;
    char buf[1024];
    snprintf(buf, sizeof buf,
             "model: {type: peridynamics, formulation: lps, influence: inverse, "
             "influence_correction: cubic}\n"
             "materials:\n  m: {density: 1000, youngs_modulus: %g, poisson_ratio: %g}\n"
             "lattice: {type: sc, spacing: 1.0e-3}\n"
             "geometry:\n  p: {box: {min: [0, 0, 0], max: [0.0105, 0.0105, 0.0105]}}\n"
             "body: {geometry: p, material: m}\nrun: {end_time: 1.0}\n",
             E, nu);
    int rc = build(buf, &s, &err);
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
    const struct field_desc *f = field_registry_find(s->fields, "stress");
    double *out = malloc(p->n * 6 * sizeof *out);
    assert_non_null(out);
    const double eps = 1e-7;
    double sx[6], sxy[6];
    for (int load = 0; load < 2; load++) {
        for (size_t i = 0; i < p->n; i++) {
            p->x[0][i] = p->x0[0][i] * (1 + (load == 0 ? eps : 0)) +
                         (load == 1 ? 0.5 * eps * p->x0[1][i] : 0);
            p->x[1][i] = p->x0[1][i] + (load == 1 ? 0.5 * eps * p->x0[0][i] : 0);
            p->x[2][i] = p->x0[2][i];
        }
        field_gather_f64(f, p->n, out);
        for (int a = 0; a < 6; a++)
            (load == 0 ? sx : sxy)[a] = out[c * 6 + (size_t)a] / eps;
    }
    free(out);
    const double K = E / (3 * (1 - 2 * nu)), mu = E / (2 * (1 + nu));
    printf("  sc corrected: C11 %+.2e, C12 %+.2e, C44 %+.2e (relative)\n",
           sx[0] / (K + 4 * mu / 3) - 1, sx[1] / (K - 2 * mu / 3) - 1, sxy[3] / mu - 1);
    assert_true(fabs(sx[0] / (K + 4 * mu / 3) - 1) < 1e-6);
    assert_true(fabs(sx[1] / (K - 2 * mu / 3) - 1) < 1e-6);
    assert_true(fabs(sxy[3] / mu - 1) < 1e-6);
    sim_destroy(&s);
}

static void test_refused(void **state)
{
    (void)state;
    static const char *const decks[] = {
        "model: {type: peridynamics, formulation: lps, influence_correction: cubic}\n"
        "materials:\n  m: {density: 1000, youngs_modulus: 1.0e9, poisson_ratio: 0.3}\n"
        "lattice: {type: triangular, spacing: 1.0e-3, thickness: 1.0e-3}\n",
        "model: {type: peridynamics, influence_correction: cubic}\n"
        "materials:\n  m: {density: 1000, youngs_modulus: 1.0e9}\n"
        "lattice: {type: square, spacing: 1.0e-3, thickness: 1.0e-3}\n"};
    static const char *const want[] = {"square, sc and fcc", "formulation lps or eps"};
    for (int k = 0; k < 2; k++) {
        char buf[1024];
        snprintf(buf, sizeof buf,
                 "%sgeometry:\n  p: {box: {min: [0, 0], max: [0.01, 0.01]}}\n"
                 "body: {geometry: p, material: m}\nrun: {end_time: 1.0}\n",
                 decks[k]);
        struct spall_error err = {0};
        struct sim *s = NULL;
        assert_int_not_equal(build(buf, &s, &err), 0);
        printf("  refused: %s\n", err.msg);
        assert_non_null(strstr(err.msg, want[k]));
        assert_null(s);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_square_rotated),
        cmocka_unit_test(test_sc),
        cmocka_unit_test(test_refused),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
