/* Tests for src/core/lattice_polar.c: the body-fitted rings (2D) and shells
 * (3D).  What a round body needs of them: every site of a layer at the
 * layer's radius (a round surface), volumes that tile the disc / ball
 * exactly, no site on the axis of an axisymmetric run, mirror symmetry, and
 * no two sites much closer than the spacing. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include "core/geometry.h"
#include "core/lattice_gen.h"
#include "core/lattice_polar.h"
#include "core/mathconst.h"
#include "core/particles.h"
#include "spall/error.h"

#include <math.h>
#include <string.h>

static const double DX = 0.5e-6; /* the deformable sphere's spacing, SI */

static struct particles *fill(enum lattice_kind kind, int dim, const double origin[3],
                              struct geom *region)
{
    struct spall_error err = {0};
    struct particles *p = NULL;
    assert_int_equal(particles_create(&p, dim, 0, &err), SPALL_OK);
    struct lattice_spec s = {.kind = kind, .spacing = DX};
    memcpy(s.origin, origin, sizeof s.origin);
    size_t added = 0;
    assert_int_equal(lattice_fill(p, &s, region, 2, &added, &err), SPALL_OK);
    assert_int_equal(added, p->n);
    geom_destroy(&region);
    return p;
}

static double site_volume(enum lattice_kind kind, const double origin[3],
                          const struct particles *p, size_t i)
{
    struct lattice_spec s = {.kind = kind, .spacing = DX};
    memcpy(s.origin, origin, sizeof s.origin);
    double pos[3] = {p->x[0][i], p->x[1][i], p->dim > 2 ? p->x[2][i] : 0.0};
    return lattice_site_volume_at(&s, pos, 1.0);
}

static double distance(const struct particles *p, size_t i, const double c[3])
{
    double r2 = 0.0;
    for (int d = 0; d < p->dim; d++)
        r2 += (p->x[d][i] - c[d]) * (p->x[d][i] - c[d]);
    return sqrt(r2);
}

/* Smallest distance between two sites over the smallest spacing allowed. */
static double min_pair_over_dx(const struct particles *p)
{
    double best = INFINITY;
    for (size_t i = 0; i < p->n; i++)
        for (size_t j = i + 1; j < p->n; j++) {
            double r2 = 0.0;
            for (int d = 0; d < p->dim; d++)
                r2 += (p->x[d][j] - p->x[d][i]) * (p->x[d][j] - p->x[d][i]);
            best = fmin(best, r2);
        }
    return sqrt(best) / DX;
}

/* A disc of radius 8 dx around an off-origin centre: 8 rings, every site at
 * its ring's radius (k + 1/2) dx, areas summing to pi R^2, mirror-symmetric
 * about both axes through the centre, none on the vertical axis. */
static void test_rings_disc(void **state)
{
    (void)state;
    const double c[3] = {3e-6, -2e-6, 0};
    const double R = 8.0 * DX;
    struct particles *p = fill(LATTICE_RINGS, 2, c, geom_sphere(c, R));
    long expect = 0;
    for (long k = 0; k < 8; k++) {
        long n = 2 * lround(SPALL_PI * ((double)k + 0.5));
        expect += n < 4 ? 4 : n;
    }
    assert_int_equal(p->n, (size_t)expect); /* 4 + 10 + 16 + 22 + 28 + 34 + 40 + 48 */
    assert_int_equal(expect, 202);
    double area = 0.0;
    for (size_t i = 0; i < p->n; i++) {
        double r = distance(p, i, c) / DX;
        assert_true(fabs(r - (floor(r) + 0.5)) < 1e-9);  /* on a ring */
        assert_true(fabs(p->x[0][i] - c[0]) > 0.05 * DX); /* off the axis */
        area += site_volume(LATTICE_RINGS, c, p, i);
        bool mirror_x = false, mirror_y = false;
        for (size_t j = 0; j < p->n; j++) {
            double ex = fabs(p->x[1][j] - p->x[1][i]), dxr = fabs((p->x[0][j] - c[0]) + (p->x[0][i] - c[0]));
            double ey = fabs(p->x[0][j] - p->x[0][i]), dyr = fabs((p->x[1][j] - c[1]) + (p->x[1][i] - c[1]));
            mirror_x |= ex < 1e-9 * DX && dxr < 1e-9 * DX;
            mirror_y |= ey < 1e-9 * DX && dyr < 1e-9 * DX;
        }
        assert_true(mirror_x && mirror_y);
    }
    assert_true(fabs(area - SPALL_PI * R * R) <= 1e-12 * SPALL_PI * R * R);
    double q = min_pair_over_dx(p);
    assert_true(q > 0.7 && q < 1.0); /* 0.707: the innermost ring of 4 */
    particles_destroy(&p);
}

/* The half-disc r >= 0 of an axisymmetric run, centre on the axis: exactly
 * half of every ring, and (times 2 pi r) the ring volumes sum to the
 * sphere's 4/3 pi R^3 within the midpoint rule's error. */
static void test_rings_half_disc(void **state)
{
    (void)state;
    const double c[3] = {0, 4e-6, 0};
    const double R = 7.0 * DX;
    struct geom *parts[2] = {geom_sphere(c, R), NULL};
    const double lo[3] = {0, 0, -1}, hi[3] = {1e-5, 1e-5, 1};
    parts[1] = geom_box(lo, hi);
    struct particles *p = fill(LATTICE_RINGS, 2, c, geom_combine(GEOM_INTERSECTION, parts, 2));
    size_t full = 0;
    for (long k = 0; k < 7; k++) {
        long n = 2 * lround(SPALL_PI * ((double)k + 0.5));
        full += (size_t)(n < 4 ? 4 : n);
    }
    assert_int_equal(2 * p->n, full);
    double vol = 0.0;
    for (size_t i = 0; i < p->n; i++) {
        assert_true(p->x[0][i] > 0.1 * DX);
        vol += 2.0 * SPALL_PI * p->x[0][i] * site_volume(LATTICE_RINGS, c, p, i);
    }
    double ball = 4.0 / 3.0 * SPALL_PI * R * R * R;
    assert_true(fabs(vol - ball) < 0.01 * ball);
    particles_destroy(&p);
}

/* A ball of radius 6 dx on shells: every site on its shell, volumes summing
 * to 4/3 pi R^3 exactly, quasi-uniform spacing. */
static void test_shells_ball(void **state)
{
    (void)state;
    const double c[3] = {1e-6, 2e-6, -3e-6};
    const double R = 6.0 * DX;
    struct particles *p = fill(LATTICE_SHELLS, 3, c, geom_sphere(c, R));
    long expect = 0;
    for (long k = 0; k < 6; k++) {
        double m = (double)k + 0.5;
        expect += lround(4.0 * SPALL_PI * m * m + SPALL_PI / 3.0);
    }
    assert_int_equal(p->n, (size_t)expect);
    double vol = 0.0, sum[3] = {0, 0, 0};
    for (size_t i = 0; i < p->n; i++) {
        double r = distance(p, i, c) / DX;
        assert_true(fabs(r - (floor(r) + 0.5)) < 1e-9);
        vol += site_volume(LATTICE_SHELLS, c, p, i);
        for (int d = 0; d < 3; d++)
            sum[d] += p->x[d][i] - c[d];
    }
    double ball = 4.0 / 3.0 * SPALL_PI * R * R * R;
    assert_true(fabs(vol - ball) <= 1e-12 * ball);
    /* The ball's sites are nearly centred (a spiral is not exactly symmetric). */
    for (int d = 0; d < 3; d++)
        assert_true(fabs(sum[d]) / (double)p->n < 0.05 * DX);
    double q = min_pair_over_dx(p);
    assert_true(q > 0.75 && q < 1.0); /* 0.752: the spiral of the 4-site shell */
    particles_destroy(&p);
}

static void test_names_and_errors(void **state)
{
    (void)state;
    assert_int_equal(lattice_kind_from_name("rings"), LATTICE_RINGS);
    assert_int_equal(lattice_kind_from_name("shells"), LATTICE_SHELLS);
    assert_int_equal(lattice_kind_dim(LATTICE_RINGS), 2);
    assert_int_equal(lattice_kind_dim(LATTICE_SHELLS), 3);
    assert_true(lattice_kind_is_polar(LATTICE_RINGS) && !lattice_kind_is_polar(LATTICE_SQUARE));
    struct spall_error err = {0};
    struct particles *p = NULL;
    assert_int_equal(particles_create(&p, 2, 0, &err), SPALL_OK);
    struct lattice_spec s = {.kind = LATTICE_SHELLS, .spacing = DX};
    const double c[3] = {0, 0, 0};
    struct geom *g = geom_sphere(c, 4 * DX);
    size_t n = 7;
    assert_int_equal(lattice_fill(p, &s, g, 0, &n, &err), SPALL_ERR_INPUT); /* 3D into 2D */
    assert_int_equal(n, 0);
    /* A region between the origin and the first ring holds no site. */
    s.kind = LATTICE_RINGS;
    geom_destroy(&g);
    g = geom_sphere(c, 0.4 * DX);
    assert_int_equal(lattice_fill(p, &s, g, 0, &n, &err), SPALL_ERR_INPUT);
    assert_non_null(strstr(err.msg, "contains no lattice site"));
    /* Unbounded region. */
    const double nrm[3] = {0, 1, 0};
    struct geom *h = geom_halfspace(c, nrm);
    assert_int_equal(lattice_fill(p, &s, h, 0, &n, &err), SPALL_ERR_INPUT);
    assert_non_null(strstr(err.msg, "unbounded"));
    /* A body far from the centre needs too many rings. */
    geom_destroy(&g);
    const double far[3] = {1e3, 0, 0};
    g = geom_sphere(far, 1e-6);
    assert_int_equal(lattice_fill(p, &s, g, 0, &n, &err), SPALL_ERR_INPUT);
    assert_non_null(strstr(err.msg, "from the lattice origin"));
    assert_int_equal(p->n, 0);
    geom_destroy(&g);
    geom_destroy(&h);
    particles_destroy(&p);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_rings_disc),
        cmocka_unit_test(test_rings_half_disc),
        cmocka_unit_test(test_shells_ball),
        cmocka_unit_test(test_names_and_errors),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
