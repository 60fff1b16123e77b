/* Tests for src/core/geometry.c: primitives, composites, bounds, clone and
 * pre-crack cuts. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include "core/geometry.h"

#include <math.h>
#include <string.h>

static bool in2(const struct geom *g, double x, double y)
{
    const double p[3] = {x, y, 0.0};
    return geom_contains(g, p, 2);
}

static bool in3(const struct geom *g, double x, double y, double z)
{
    const double p[3] = {x, y, z};
    return geom_contains(g, p, 3);
}

static void test_box(void **state)
{
    (void)state;
    const double lo[3] = {0, 0, 0}, hi[3] = {2, 1, 3};
    struct geom *g = geom_box(lo, hi);
    assert_non_null(g);
    assert_true(in2(g, 1.0, 0.5));
    assert_true(in2(g, 2.0, 1.0)); /* corner */
    assert_true(in2(g, 0.0, 0.3)); /* face */
    /* A face point computed with rounding: 10 * 0.1 != 1 exactly in general. */
    double yf = 0.0;
    for (int k = 0; k < 10; k++)
        yf += 0.1;
    assert_true(in2(g, 1.0, yf));
    assert_false(in2(g, 2.0 + 1e-6, 0.5));
    assert_false(in2(g, -1e-6, 0.5));
    assert_true(in3(g, 1.0, 0.5, 3.0));
    assert_false(in3(g, 1.0, 0.5, 3.001));
    /* 2D ignores z entirely. */
    assert_true(in2(g, 1.0, 0.5) && geom_contains(g, (const double[3]){1.0, 0.5, 99.0}, 2));
    double blo[3], bhi[3];
    assert_true(geom_bounds(g, 3, blo, bhi));
    assert_true(blo[0] == 0.0 && bhi[0] == 2.0 && bhi[1] == 1.0 && bhi[2] == 3.0);
    geom_destroy(&g);
    assert_null(g);
}

static void test_sphere_and_cylinder(void **state)
{
    (void)state;
    const double c[3] = {1, 1, 1};
    struct geom *s = geom_sphere(c, 0.5);
    assert_true(in3(s, 1.5, 1.0, 1.0)); /* on the surface */
    assert_true(in3(s, 1.2, 1.2, 1.2));
    assert_false(in3(s, 1.3, 1.3, 1.3)); /* |d| = 0.52 */
    assert_true(in2(s, 1.0, 0.5));
    assert_false(in2(s, 1.4, 1.4));
    double lo[3], hi[3];
    assert_true(geom_bounds(s, 3, lo, hi));
    assert_true(fabs(lo[2] - 0.5) < 1e-15 && fabs(hi[0] - 1.5) < 1e-15);
    geom_destroy(&s);

    /* 3D finite cylinder along a skew axis. */
    const double p0[3] = {0, 0, 0}, p1[3] = {0, 0, 2};
    struct geom *cy = geom_cylinder(p0, p1, 1.0);
    assert_true(in3(cy, 0.5, 0.5, 1.0));
    assert_true(in3(cy, 1.0, 0.0, 2.0)); /* rim */
    assert_false(in3(cy, 0.8, 0.8, 1.0));
    assert_false(in3(cy, 0.0, 0.0, 2.01));
    assert_false(in3(cy, 0.0, 0.0, -0.01));
    /* 2D: a disc of `radius` around p0 regardless of p1. */
    assert_true(in2(cy, 0.6, 0.6));
    assert_false(in2(cy, 0.8, 0.8));
    assert_true(geom_bounds(cy, 2, lo, hi));
    assert_true(lo[0] == -1.0 && hi[1] == 1.0);
    geom_destroy(&cy);

    const double q0[3] = {0, 0, 0}, q1[3] = {1, 1, 1};
    struct geom *sk = geom_cylinder(q0, q1, 0.1);
    assert_true(in3(sk, 0.5, 0.5, 0.5));
    assert_true(in3(sk, 0.55, 0.5, 0.5));
    assert_false(in3(sk, 0.7, 0.5, 0.5));
    assert_false(in3(sk, 1.05, 1.05, 1.05));
    geom_destroy(&sk);
}

static void test_halfspace_bounds(void **state)
{
    (void)state;
    const double pt[3] = {0.5, 0, 0}, nrm[3] = {2, 0, 0}; /* x <= 0.5 */
    struct geom *h = geom_halfspace(pt, nrm);
    assert_true(in2(h, 0.5, 7.0));
    assert_true(in2(h, -100.0, 7.0));
    assert_false(in2(h, 0.5001, 0.0));
    double lo[3], hi[3];
    assert_false(geom_bounds(h, 2, lo, hi));

    const double blo[3] = {0, 0, 0}, bhi[3] = {1, 2, 0};
    struct geom *kids[2] = {geom_box(blo, bhi), h};
    struct geom *x = geom_combine(GEOM_INTERSECTION, kids, 2);
    assert_non_null(x);
    assert_true(geom_bounds(x, 2, lo, hi));
    assert_true(lo[0] == 0.0 && hi[0] == 1.0 && hi[1] == 2.0);
    assert_true(in2(x, 0.25, 1.0));
    assert_false(in2(x, 0.75, 1.0));
    /* A union with an unbounded child is unbounded. */
    struct geom *hc = geom_halfspace(pt, nrm);
    const double slo[3] = {5, 5, 0}, shi[3] = {6, 6, 0};
    struct geom *u_kids[2] = {geom_box(slo, shi), hc};
    struct geom *u = geom_combine(GEOM_UNION, u_kids, 2);
    assert_false(geom_bounds(u, 2, lo, hi));
    assert_true(in2(u, 5.5, 5.5) && in2(u, 0.0, 9.0) && !in2(u, 3.0, 3.0));
    geom_destroy(&u);
    geom_destroy(&x);
    /* Invalid composite: children destroyed, NULL returned (ASan checks leaks). */
    struct geom *bad[1] = {geom_box(blo, bhi)};
    assert_null(geom_combine(GEOM_BOX, bad, 1));
    assert_null(bad[0]);
}

static void test_plate_with_holes(void **state)
{
    (void)state;
    const double lo[3] = {0, 0, 0}, hi[3] = {10, 4, 0};
    const double c1[3] = {3, 2, 0}, c2[3] = {7, 2, 0}, top[3] = {0, 0, 1};
    struct geom *kids[3] = {geom_box(lo, hi), geom_cylinder(c1, top, 1.0),
                            geom_sphere(c2, 1.0)};
    struct geom *plate = geom_combine(GEOM_DIFFERENCE, kids, 3);
    assert_non_null(plate);
    assert_false(in2(plate, 3.0, 2.0));
    assert_false(in2(plate, 3.9, 2.0));
    assert_false(in2(plate, 7.5, 2.5));
    assert_true(in2(plate, 3.0, 3.5));
    assert_true(in2(plate, 5.0, 2.0));
    assert_true(in2(plate, 10.0, 4.0));
    assert_false(in2(plate, 10.5, 2.0));
    double blo[3], bhi[3];
    assert_true(geom_bounds(plate, 2, blo, bhi));
    assert_true(bhi[0] == 10.0 && bhi[1] == 4.0);
    geom_destroy(&plate);
}

static void test_polygon_concave(void **state)
{
    (void)state;
    /* L-shape: unit square [0,2]x[0,2] minus the top-right quadrant. */
    const double xy[] = {0, 0, 2, 0, 2, 1, 1, 1, 1, 2, 0, 2};
    struct geom *L = geom_polygon(xy, 6);
    assert_non_null(L);
    assert_true(in2(L, 0.5, 0.5));
    assert_true(in2(L, 1.5, 0.5));
    assert_true(in2(L, 0.5, 1.5));
    assert_false(in2(L, 1.5, 1.5)); /* the notch */
    assert_false(in2(L, 2.5, 0.5));
    assert_true(in2(L, 1.5, 1.0)); /* on the inner edge */
    assert_true(in2(L, 1.0, 1.5));
    assert_true(in2(L, 1.0, 1.0)); /* reflex vertex */
    assert_true(in2(L, 0.0, 1.0)); /* ray through a vertex y = 1 */
    assert_false(in2(L, -0.5, 1.0));
    double lo[3], hi[3];
    assert_true(geom_bounds(L, 2, lo, hi));
    assert_true(lo[0] == 0.0 && hi[0] == 2.0 && hi[1] == 2.0);

    struct geom *c = geom_clone(L);
    assert_non_null(c);
    assert_ptr_not_equal(c->poly, L->poly);
    assert_int_equal(c->n_poly, 6);
    assert_memory_equal(c->poly, xy, sizeof xy);
    geom_destroy(&L);
    assert_true(in2(c, 0.5, 1.5) && !in2(c, 1.5, 1.5)); /* survives the original */
    geom_destroy(&c);
}

static void test_clone_composite(void **state)
{
    (void)state;
    const double lo[3] = {0, 0, 0}, hi[3] = {1, 1, 1}, cc[3] = {0.5, 0.5, 0.5};
    struct geom *kids[2] = {geom_box(lo, hi), geom_sphere(cc, 0.25)};
    struct geom *g = geom_combine(GEOM_DIFFERENCE, kids, 2);
    struct geom *c = geom_clone(g);
    assert_non_null(c);
    assert_int_equal(c->kind, GEOM_DIFFERENCE);
    assert_int_equal(c->n_child, 2);
    assert_ptr_not_equal(c->child[0], g->child[0]);
    assert_int_equal(c->child[1]->kind, GEOM_SPHERE);
    assert_true(c->child[1]->radius == 0.25);
    /* Same answer on a grid of points. */
    for (int i = 0; i <= 20; i++)
        for (int j = 0; j <= 20; j++)
            for (int k = 0; k <= 20; k++) {
                const double p[3] = {i * 0.06 - 0.1, j * 0.06 - 0.1, k * 0.06 - 0.1};
                assert_int_equal(geom_contains(g, p, 3), geom_contains(c, p, 3));
            }
    geom_destroy(&g);
    geom_destroy(&c);
    assert_null(c);
}

static void test_precrack_2d(void **state)
{
    (void)state;
    struct precrack pc;
    memset(&pc, 0, sizeof pc);
    pc.dim = 2;
    pc.a[0] = 0.0, pc.a[1] = 0.0;
    pc.b[0] = 2.0, pc.b[1] = 0.0;
    const double p[3] = {1, -0.5, 0}, q[3] = {1.2, 0.5, 0};
    assert_true(precrack_cuts(&pc, p, q));
    assert_true(precrack_cuts(&pc, q, p));
    const double r[3] = {3, -0.5, 0}, s[3] = {3, 0.5, 0}; /* beyond the tip */
    assert_false(precrack_cuts(&pc, r, s));
    const double t[3] = {0.5, 0.1, 0}, u[3] = {1.5, 0.4, 0}; /* same side */
    assert_false(precrack_cuts(&pc, t, u));
    /* Touching: bond end on the crack, and crack tip on the bond. */
    const double v[3] = {1, 0, 0}, w[3] = {1, 1, 0};
    assert_true(precrack_cuts(&pc, v, w));
    const double tip0[3] = {2, -1, 0}, tip1[3] = {2, 1, 0};
    assert_true(precrack_cuts(&pc, tip0, tip1));
    /* Collinear overlap: a bond lying on the crack line is not cut. */
    const double c0[3] = {0.5, 0, 0}, c1[3] = {1.5, 0, 0}, c2[3] = {2.5, 0, 0};
    assert_false(precrack_cuts(&pc, c0, c1));
    assert_false(precrack_cuts(&pc, c1, c2));
    /* z is ignored in 2D. */
    const double pz[3] = {1, -0.5, 7}, qz[3] = {1, 0.5, -3};
    assert_true(precrack_cuts(&pc, pz, qz));
}

static void test_precrack_3d(void **state)
{
    (void)state;
    struct precrack pc;
    memset(&pc, 0, sizeof pc);
    pc.dim = 3;
    /* Rectangle in the plane z = 1: x in [0,2], y in [0,1]. */
    pc.origin[2] = 1.0;
    pc.e1[0] = 2.0;
    pc.e2[1] = 1.0;
    const double a[3] = {1, 0.5, 0.5}, b[3] = {1, 0.5, 1.5};
    assert_true(precrack_cuts(&pc, a, b));
    assert_true(precrack_cuts(&pc, b, a));
    const double c[3] = {1, 1.5, 0.5}, d[3] = {1, 1.5, 1.5}; /* outside in y */
    assert_false(precrack_cuts(&pc, c, d));
    const double e[3] = {1, 0.5, 1.2}, f[3] = {1, 0.5, 1.5}; /* above */
    assert_false(precrack_cuts(&pc, e, f));
    const double g[3] = {2, 1, 0.5}, h[3] = {2, 1, 1.5}; /* through a corner */
    assert_true(precrack_cuts(&pc, g, h));
    const double i[3] = {0.2, 0.5, 1.0}, j[3] = {1.2, 0.5, 1.0}; /* in the plane */
    assert_false(precrack_cuts(&pc, i, j));
    const double k[3] = {0.5, 0.5, 1.0}, l[3] = {0.5, 0.5, 2.0}; /* ends on it */
    assert_true(precrack_cuts(&pc, k, l));
    /* Oblique bond through the rectangle. */
    const double m[3] = {0.0, 0.0, 0.0}, n[3] = {1.0, 1.0, 2.0};
    assert_true(precrack_cuts(&pc, m, n));
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_box),
        cmocka_unit_test(test_sphere_and_cylinder),
        cmocka_unit_test(test_halfspace_bounds),
        cmocka_unit_test(test_plate_with_holes),
        cmocka_unit_test(test_polygon_concave),
        cmocka_unit_test(test_clone_composite),
        cmocka_unit_test(test_precrack_2d),
        cmocka_unit_test(test_precrack_3d),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
