/*
 * Tests of the lamina failure rules of the peridynamics model: the
 * mixed-mode (Benzeggagh-Kenane) factor of matrix bonds (pd_mixed.c) under
 * pure transverse tension, pure in-plane shear and a rigid rotation, and the
 * fiber-parallel matrix-crack twins (pd_plane.c).
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include "core/bond_list.h"
#include "core/mathconst.h"
#include "core/particles.h"
#include "core/sim.h"
#include "io/deck.h"
#include "io/deck_build.h"
#include "core/model.h"
#include "models/peridynamics/pd.h"
#include "spall/error.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static struct sim *build_ok(const char *opts, double theta)
{
    char yaml[1024];
    snprintf(yaml, sizeof yaml,
             "model: {type: peridynamics, variant: pdlm%s}\n"
             "materials:\n  t700: {density: 1550, fiber_modulus: 130e9, transverse_modulus: "
             "8.5e9, shear_modulus: 4.5e9, major_poisson_ratio: 0.3, fiber_angle: %g, "
             "matrix_fracture_energy: 300, mode2_fracture_energy: 800, fiber_fracture_energy: "
             "6.0e4}\n"
             "lattice: {type: triangular, spacing: 1.0e-3, thickness: 1.0e-4, angle: %g}\n"
             "geometry:\n  p: {box: {min: [-0.0061, -0.0061], max: [0.0061, 0.0061]}}\n"
             "body: {geometry: p, material: t700}\nrun: {steps: 1}\n",
             opts, theta, theta);
    struct deck *d = NULL;
    struct spall_error err = {0};
    struct sim *s = NULL;
    int rc = deck_load_string(&d, "test", yaml, &err);
    if (!rc) {
        struct run_output ro;
        rc = deck_build_sim(d, &s, &ro, &err);
    }
    deck_destroy(&d);
    if (rc)
        fprintf(stderr, "%s\n", err.msg);
    assert_int_equal(rc, 0);
    return s;
}

/* x = R (I + H) x0: H in material axes (1 = fiber at theta), then a rigid
 * rotation by rot */
static void deform(struct sim *s, double theta, double e22, double g12, double rot)
{
    struct particles *p = s->p;
    double c = cos(theta), sn = sin(theta), cr = cos(rot), sr = sin(rot);
    for (size_t i = 0; i < p->n; i++) {
        double X = p->x0[0][i], Y = p->x0[1][i];
        double a = c * X + sn * Y, b = -sn * X + c * Y; /* material coordinates */
        double a1 = a + g12 * b, b1 = b + e22 * b;      /* simple shear + transverse stretch */
        double x = c * a1 - sn * b1, y = sn * a1 + c * b1;
        p->x[0][i] = cr * x - sr * y;
        p->x[1][i] = sr * x + cr * y;
    }
}

/* The mixed-mode state of particle i through the model's public view. */
static bool mixed_on(const struct model *m)
{
    double beta, g;
    return pd_mixed_state(m, 0, &beta, &g);
}
static double mixed_beta(const struct model *m, size_t i)
{
    double beta, g;
    (void)pd_mixed_state(m, i, &beta, &g);
    return beta;
}
static double mixed_g(const struct model *m, size_t i)
{
    double beta, g;
    (void)pd_mixed_state(m, i, &beta, &g);
    return g;
}

static void test_mixed_mode_factor(void **state)
{
    (void)state;
    const double th = 45.0 * SPALL_PI / 180.0;
    struct sim *s = build_ok("", 45.0);
    struct model *m = s->model;
    assert_true(mixed_on(m));
    size_t i = pd_patch_particle(m, s, 0);
    const double gmax = sqrt(800.0 / 300.0);
    /* transverse tension: pure mode I */
    deform(s, th, 1e-3, 0.0, 0.0);
    pd_mixed_update(m, s);
    assert_true(mixed_beta(m, i) < 1e-9);
    assert_true(fabs(mixed_g(m, i) - 1.0) < 1e-9);
    /* in-plane shear: pure mode II, s0 x sqrt(G_IIc / G_Ic) (simple shear has
     * E22 = g^2/2: beta = 1 - O(1e-6)) */
    deform(s, th, 0.0, 2e-3, 0.0);
    pd_mixed_update(m, s);
    assert_true(mixed_beta(m, i) > 1.0 - 1e-4);
    assert_true(fabs(mixed_g(m, i) - gmax) < 1e-4);
    /* transverse compression + shear: compression does not open, mode II */
    deform(s, th, -1e-3, 1e-3, 0.0);
    pd_mixed_update(m, s);
    assert_true(mixed_beta(m, i) > 1.0 - 1e-4);
    /* equal energies: beta = 1/2, G_c = G_Ic + (G_IIc - G_Ic)/4 (eta = 2) */
    double e22 = 1e-3, q22 = 8.5e9 / (1.0 - 0.09 * 8.5 / 130.0);
    double g = e22 * sqrt(q22 / 4.5e9); /* w_II = G12 g^2 / 2 = Q22 e22^2 / 2 */
    deform(s, th, e22, g, 0.0);
    pd_mixed_update(m, s);
    printf("  mixed mode: beta %.4f (small-strain 0.5), g %.4f\n", mixed_beta(m, i), mixed_g(m, i));
    assert_true(fabs(mixed_beta(m, i) - 0.5) < 0.01);
    /* a rigid rotation of 30 deg changes nothing (Green strain) */
    double b0 = mixed_beta(m, i);
    deform(s, th, e22, g, 0.5236);
    pd_mixed_update(m, s);
    assert_true(fabs(mixed_beta(m, i) - b0) < 1e-9);
    sim_destroy(&s);
    /* off: no factors */
    s = build_ok(", mixed_mode: off", 45.0);
    assert_false(mixed_on(s->model)); /* and no per-particle factors */
    sim_destroy(&s);
}

/* one particle pushed off its fiber row: its 2 matrix bonds to the next row
 * break by stretch; fiber_plane also breaks their 2 zigzag neighbours */
static void test_fiber_plane(void **state)
{
    (void)state;
    size_t broken[2];
    for (int fp = 0; fp < 2; fp++) {
        struct sim *s = build_ok(fp ? ", matrix_crack: fiber_plane, mixed_mode: off"
                                    : ", mixed_mode: off", 0.0);
        struct model *m = s->model;
        struct particles *p = s->p;
        struct spall_error err = {0};
        size_t i = pd_patch_particle(m, s, 0);
        for (size_t q = 0; q < p->n; q++)
            for (int d = 0; d < 2; d++) {
                p->x[d][q] = p->x0[d][q];
                p->f[d][q] = 0.0;
            }
        p->x[1][i] -= 0.1e-3; /* 10 % of the spacing: far past s0_m, fiber bonds intact */
        assert_int_equal(s->ops->compute_forces(m, s, &err), 0);
        assert_int_equal(s->ops->end_step(m, s, &err), 0);
        broken[fp] = bond_list_count_broken(pd_bonds(m));
        sim_destroy(&s);
    }
    /* refused outside the PDLM lattice, with the deck position */
    {
        struct deck *d = NULL;
        struct spall_error err = {0};
        struct sim *s = NULL;
        const char *yaml = "model: {type: peridynamics, matrix_crack: fiber_plane}\n"
                           "materials:\n  m: {density: 1000, youngs_modulus: 1e9}\n"
                           "lattice: {type: square, spacing: 1.0e-3}\n"
                           "geometry:\n  p: {box: {min: [0, 0], max: [0.005, 0.005]}}\n"
                           "body: {geometry: p, material: m}\nrun: {steps: 1}\n";
        int rc = deck_load_string(&d, "test", yaml, &err);
        if (!rc) {
            struct run_output ro;
            rc = deck_build_sim(d, &s, &ro, &err);
        }
        deck_destroy(&d);
        sim_destroy(&s);
        assert_int_not_equal(rc, 0);
        assert_non_null(strstr(err.msg, "fiber_plane needs variant pdlm"));
    }
    printf("  fiber plane: %zu bonds broken without, %zu with\n", broken[0], broken[1]);
    assert_int_equal(broken[0], 2);
    assert_int_equal(broken[1], 4);
}

/* E_x of a lamina with fibers at theta: the paper's way (PDLM, lattice
 * rotated by theta) and the angle-dependent micromodulus (PMB family,
 * c = c_m + c_f cos^2n(phi), unrotated square lattice), against the
 * classical 1/E(theta) = c^4/E1 + s^4/E2 + (1/G12 - 2 nu12/E1) c^2 s^2 with
 * each model's achieved constants */
static double ex_of(const char *yaml)
{
    struct deck *d = NULL;
    struct spall_error err = {0};
    struct sim *s = NULL;
    int rc = deck_load_string(&d, "test", yaml, &err);
    if (!rc) {
        struct run_output ro;
        rc = deck_build_sim(d, &s, &ro, &err);
    }
    deck_destroy(&d);
    if (rc)
        fprintf(stderr, "%s\n", err.msg);
    assert_int_equal(rc, 0);
    struct model *m = s->model;
    double C[3][3], S[3][3], a[4];
    assert_int_equal(pd_calibrate_ortho(m, s, 0, a, &err), 0);
    pd_patch_stiffness(m, s, pd_patch_particle(m, s, 0), 0.0, C);
    assert_int_equal(pd_invert3(C, S), 0);
    const struct pd_material *mt = pd_material_get(m, 0);
    double c = cos(mt->fiber_angle), sn = sin(mt->fiber_angle);
    double cls = 1.0 / (pow(c, 4) / a[0] + pow(sn, 4) / a[1] +
                        (1.0 / a[2] - 2.0 * a[3] / a[0]) * c * c * sn * sn);
    printf("    E_x %.4g GPa (classical with achieved E1 %.4g, E2 %.4g, G12 %.4g, nu12 %.3f: "
           "%.4g GPa)\n", 1e-9 / S[0][0], a[0] * 1e-9, a[1] * 1e-9, a[2] * 1e-9, a[3],
           cls * 1e-9);
    assert_true(fabs(1.0 / S[0][0] / cls - 1.0) < 0.03);
    sim_destroy(&s);
    return 1.0 / S[0][0];
}

static void test_angle_models(void **state)
{
    (void)state;
    const char *mat = "materials:\n  t700: {density: 1550, fiber_modulus: 130e9, "
                      "transverse_modulus: 8.5e9, shear_modulus: 4.5e9, major_poisson_ratio: "
                      "0.3, fiber_angle: %g, matrix_fracture_energy: 300}\n";
    const double th[3] = {0.0, 45.0, 90.0};
    for (int k = 0; k < 3; k++) {
        char m1[512], y1[1536], y2[1536];
        snprintf(m1, sizeof m1, mat, th[k]);
        snprintf(y1, sizeof y1,
                 "model: {type: peridynamics, variant: pdlm}\n%s"
                 "lattice: {type: triangular, spacing: 1.0e-3, thickness: 1.0e-3, angle: %g}\n"
                 "geometry:\n  p: {box: {min: [-0.0061, -0.0061], max: [0.0061, 0.0061]}}\n"
                 "body: {geometry: p, material: t700}\nrun: {steps: 1}\n", m1, th[k]);
        snprintf(y2, sizeof y2,
                 "model: {type: peridynamics, fiber_model: angular}\n%s"
                 "lattice: {type: square, spacing: 1.0e-3, thickness: 1.0e-3}\n"
                 "geometry:\n  p: {box: {min: [-0.0101, -0.0101], max: [0.0101, 0.0101]}}\n"
                 "body: {geometry: p, material: t700}\nrun: {steps: 1}\n", m1);
        printf("  fiber %g deg, rotated PDLM lattice:\n", th[k]);
        double e1 = ex_of(y1);
        printf("  fiber %g deg, angular micromodulus (PMB, square lattice):\n", th[k]);
        double e2 = ex_of(y2);
        printf("  fiber %g deg: E_x rotated / angular = %.4f\n", th[k], e1 / e2);
        /* both are calibrated to Q11, Q22: the off-axis E_x differs only
         * through the achieved G12 and nu12 */
        assert_true(fabs(e1 / e2 - 1.0) < 0.15);
    }
}

/* mixed-mode factors and fiber-plane twins: 1 and 2 threads bitwise equal */
static void test_lamina_threads(void **state)
{
    (void)state;
    double *xs[2] = {NULL, NULL};
    size_t nb[2] = {0, 0}, n = 0;
    for (int t = 1; t <= 2; t++) {
        char yaml[1536];
        snprintf(yaml, sizeof yaml,
                 "model: {type: peridynamics, variant: pdlm, matrix_crack: fiber_plane}\n"
                 "materials:\n  t700: {density: 1550, fiber_modulus: 130e9, transverse_modulus: "
                 "8.5e9, shear_modulus: 4.5e9, major_poisson_ratio: 0.3, fiber_angle: 30, "
                 "matrix_fracture_energy: 300, mode2_fracture_energy: 800}\n"
                 "lattice: {type: triangular, spacing: 0.5e-3, thickness: 1.0e-4, angle: 30}\n"
                 "geometry:\n  p: {box: {min: [0, 0], max: [0.01, 0.006]}}\n"
                 "body: {geometry: p, material: t700}\n"
                 "groups:\n  b: {box: {min: [-1, -1], max: [1, 0.001]}}\n"
                 "  t: {box: {min: [-1, 0.005], max: [1, 1]}}\n"
                 "boundary_conditions:\n"
                 "  - {group: b, type: velocity, value: [0, -40]}\n"
                 "  - {group: t, type: velocity, value: [0, 40]}\n"
                 "run: {steps: 120, threads: %d}\n", t);
        struct deck *d = NULL;
        struct spall_error err = {0};
        struct sim *s = NULL;
        int rc = deck_load_string(&d, "test", yaml, &err);
        if (!rc) {
            struct run_output ro;
            rc = deck_build_sim(d, &s, &ro, &err);
        }
        deck_destroy(&d);
        if (rc)
            fprintf(stderr, "%s\n", err.msg);
        assert_int_equal(rc, 0);
        while (!sim_done(s))
            assert_int_equal(sim_step(s, &err), 0);
        n = s->p->n;
        xs[t - 1] = malloc(2 * n * sizeof(double));
        assert_non_null(xs[t - 1]);
        memcpy(xs[t - 1], s->p->x[0], n * sizeof(double));
        memcpy(xs[t - 1] + n, s->p->x[1], n * sizeof(double));
        nb[t - 1] = bond_list_count_broken(pd_bonds(s->model));
        sim_destroy(&s);
    }
    printf("  lamina threads: %zu bonds broken\n", nb[0]);
    assert_true(nb[0] > 0);
    assert_int_equal(nb[0], nb[1]);
    assert_memory_equal(xs[0], xs[1], 2 * n * sizeof(double));
    free(xs[0]);
    free(xs[1]);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_mixed_mode_factor),
        cmocka_unit_test(test_fiber_plane),
        cmocka_unit_test(test_angle_models),
        cmocka_unit_test(test_lamina_threads),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
