/* Tests for src/core/profile.c: the outer radius of a body of revolution
 * at a height (Taylor-bar mushroom profile, docs/performance.md). */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include "core/particles.h"
#include "core/profile.h"
#include "spall/error.h"

#include <math.h>
#include <string.h>

/* A cone r(z) = a - b z sampled in layers z_k = k dz: per layer the
 * surface particle at r(z_k) (at azimuth 0.3 k rad, so x and y both count)
 * and two interior ones at r/2 and 0. */
static const double CA = 6.0e-3, CB = 0.8, CDZ = 0.3e-3;
static double cone_r(double z) { return CA - CB * z; }

static struct particles *cone(size_t layers)
{
    struct particles *p = NULL;
    struct spall_error err = {0};
    assert_int_equal(particles_create(&p, 3, 3 * layers, &err), SPALL_OK);
    for (size_t k = 0; k < layers; k++) {
        const double z = (double)k * CDZ, r = cone_r(z), phi = 0.3 * (double)k;
        const double pts[3][3] = {{r * cos(phi), r * sin(phi), z},
                                  {0.5 * r * cos(phi + 1.0), 0.5 * r * sin(phi + 1.0), z},
                                  {0.0, 0.0, z}};
        for (int j = 0; j < 3; j++) {
            size_t idx;
            assert_int_equal(particles_append(p, pts[j], 0, &idx, &err), SPALL_OK);
        }
    }
    return p;
}

/* between layers, on a layer, and with bands of one to three layers: the
 * interpolated envelope is the cone's radius (+ offset), where the band
 * maximum would be the radius at the band's lowest layer */
static void test_cone_exact(void **state)
{
    (void)state;
    struct particles *p = cone(20);
    struct spall_error err = {0};
    const double off = 0.2e-3;
    const double z0s[4] = {0.5e-3, 1.0e-3, 0.9e-3, 2.45e-3}, ws[3] = {0.35e-3, 0.5e-3, 1.0e-3};
    for (int a = 0; a < 4; a++)
        for (int b = 0; b < 3; b++) {
            double r = 0.0;
            assert_int_equal(profile_radius(p, z0s[a], ws[b], off, &r, &err), SPALL_OK);
            assert_true(fabs(r - (cone_r(z0s[a]) + off)) < 1e-15);
        }
    /* the plain band maximum over [z0 - w, z0 + w) at z0 = 1 mm, w = 1 mm is
     * the radius at z = 0: 0.8 mm more than the cone there */
    double r = 0.0;
    assert_int_equal(profile_radius(p, 1.0e-3, 1.0e-3, 0.0, &r, &err), SPALL_OK);
    assert_true(cone_r(0.0) - r > 0.79e-3);
    particles_destroy(&p);
}

/* one band empty: the other band's outermost radius; ghosts ignored */
static void test_one_sided_and_owned(void **state)
{
    (void)state;
    struct particles *p = cone(10);
    struct spall_error err = {0};
    double r = 0.0;
    /* z0 = -0.1 mm: only the layer z = 0 lies in [z0, z0 + w) */
    assert_int_equal(profile_radius(p, -0.1e-3, 0.25e-3, 0.0, &r, &err), SPALL_OK);
    assert_true(fabs(r - cone_r(0.0)) < 1e-15);
    /* above the top layer (z = 2.7 mm): only that layer, below z0 */
    assert_int_equal(profile_radius(p, 2.8e-3, 0.25e-3, 0.0, &r, &err), SPALL_OK);
    assert_true(fabs(r - cone_r(2.7e-3)) < 1e-15);
    /* a far-out particle past n_owned (a ghost) does not count */
    size_t idx;
    const double far[3] = {0.05, 0.0, 0.5e-3};
    assert_int_equal(particles_append(p, far, 0, &idx, &err), SPALL_OK);
    assert_int_equal(profile_radius(p, 0.5e-3, 0.4e-3, 0.0, &r, &err), SPALL_OK);
    assert_true(r > 0.04);
    p->n_owned--;
    assert_int_equal(profile_radius(p, 0.5e-3, 0.4e-3, 0.0, &r, &err), SPALL_OK);
    assert_true(fabs(r - cone_r(0.5e-3)) < 1e-15);
    particles_destroy(&p);
}

/* 2D: an axisymmetric body in the half-plane x = r, y = z -- the same cone
 * as layers of three rings (r, r/2, 0); y is the height, |x| the radius;
 * 1D particles are refused */
static void test_axisymmetric_2d(void **state)
{
    (void)state;
    struct particles *p = NULL;
    struct spall_error err = {0};
    assert_int_equal(particles_create(&p, 2, 60, &err), SPALL_OK);
    for (size_t k = 0; k < 20; k++) {
        const double z = (double)k * CDZ, r = cone_r(z);
        const double pts[3][3] = {{r, z, 0.0}, {0.5 * r, z, 0.0}, {0.0, z, 0.0}};
        for (int j = 0; j < 3; j++) {
            size_t idx;
            assert_int_equal(particles_append(p, pts[j], 0, &idx, &err), SPALL_OK);
        }
    }
    const double z0s[3] = {0.5e-3, 1.0e-3, 2.45e-3};
    for (int a = 0; a < 3; a++) {
        double r = 0.0;
        assert_int_equal(profile_radius(p, z0s[a], 0.35e-3, 0.1e-3, &r, &err), SPALL_OK);
        assert_true(fabs(r - (cone_r(z0s[a]) + 0.1e-3)) < 1e-15);
    }
    particles_destroy(&p);
    assert_int_equal(particles_create(&p, 1, 4, &err), SPALL_OK);
    size_t idx;
    const double one[3] = {1e-3, 0.0, 0.0};
    assert_int_equal(particles_append(p, one, 0, &idx, &err), SPALL_OK);
    double r = -1.0;
    assert_int_equal(profile_radius(p, 0.0, 1e-3, 0.0, &r, &err), SPALL_ERR_INPUT);
    assert_non_null(strstr(err.msg, "1D"));
    assert_true(r == -1.0);
    particles_destroy(&p);
}

/* no particle in the bands, or a band half-width <= 0: an input error
 * naming the height */
static void test_errors(void **state)
{
    (void)state;
    struct particles *p = cone(5);
    struct spall_error err = {0};
    double r = -1.0;
    assert_int_equal(profile_radius(p, 0.05, 1e-3, 0.0, &r, &err), SPALL_ERR_INPUT);
    assert_non_null(strstr(err.msg, "0.05"));
    assert_int_equal(profile_radius(p, 0.5e-3, 0.0, 0.0, &r, &err), SPALL_ERR_INPUT);
    assert_true(r == -1.0);
    particles_destroy(&p);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_cone_exact),
        cmocka_unit_test(test_one_sided_and_owned),
        cmocka_unit_test(test_axisymmetric_2d),
        cmocka_unit_test(test_errors),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
