/* Tests for src/core/lattice_gen.c: site counts, nearest distances, shells,
 * ordering, rotation, site volumes and errors. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include "core/geometry.h"
#include "core/lattice_gen.h"
#include "core/mathconst.h"
#include "core/particles.h"
#include "spall/error.h"

#include <math.h>
#include <string.h>

static const double R0 = 1e-3; /* 1 mm, SI */

/** Fill a box lo..hi (in units of r0) and return the particle set. */
static struct particles *fill_box(enum lattice_kind kind, int dim, const double lo[3],
                                  const double hi[3], double angle, size_t *added)
{
    struct spall_error err = {0};
    struct particles *p = NULL;
    assert_int_equal(particles_create(&p, dim, 0, &err), SPALL_OK);
    double l[3], h[3];
    for (int d = 0; d < 3; d++) {
        l[d] = lo[d] * R0;
        h[d] = hi[d] * R0;
    }
    struct geom *box = geom_box(l, h);
    struct lattice_spec s = {.kind = kind, .spacing = R0, .origin = {0, 0, 0}, .angle = angle};
    int rc = lattice_fill(p, &s, box, 3, added, &err);
    assert_int_equal(rc, SPALL_OK);
    assert_int_equal(p->n, *added);
    geom_destroy(&box);
    return p;
}

static double min_pair_distance(const struct particles *p)
{
    double best = INFINITY;
    for (size_t i = 0; i < p->n; i++)
        for (size_t j = i + 1; j < p->n; j++) {
            double r2 = 0;
            for (int d = 0; d < p->dim; d++) {
                double dx = p->x[d][j] - p->x[d][i];
                r2 += dx * dx;
            }
            best = fmin(best, r2);
        }
    return sqrt(best);
}

static void test_counts(void **state)
{
    (void)state;
    size_t n;
    const double z[3] = {0, 0, 0};
    /* Chain: 0..10 r0 -> 11 sites. */
    struct particles *p = fill_box(LATTICE_CHAIN, 1, z, (const double[3]){10, 0, 0}, 0.0, &n);
    assert_int_equal(n, 11);
    assert_true(p->x[0][10] == 10 * R0);
    particles_destroy(&p);
    /* Triangular, 10 rows: even rows x = 0..9, odd rows x = 0.5..9.5 -> 100. */
    double h = sqrt(3.0) / 2.0;
    p = fill_box(LATTICE_TRIANGULAR, 2, z, (const double[3]){9.5, 9 * h, 0}, 0.0, &n);
    assert_int_equal(n, 100);
    assert_int_equal(p->material[0], 3);
    particles_destroy(&p);
    /* Width 9: odd rows lose their last site -> 95. */
    p = fill_box(LATTICE_TRIANGULAR, 2, z, (const double[3]){9, 9 * h, 0}, 0.0, &n);
    assert_int_equal(n, 95);
    particles_destroy(&p);
    p = fill_box(LATTICE_SQUARE, 2, z, (const double[3]){7, 4, 0}, 0.0, &n);
    assert_int_equal(n, 8 * 5);
    particles_destroy(&p);
    p = fill_box(LATTICE_SC, 3, z, (const double[3]){4, 4, 4}, 0.0, &n);
    assert_int_equal(n, 125);
    particles_destroy(&p);
    /* FCC cube of 3 cells: (n+1)^3 corners + 3 n^2 (n+1) face centres = 172. */
    double a = 3 * sqrt(2.0);
    p = fill_box(LATTICE_FCC, 3, z, (const double[3]){a, a, a}, 0.0, &n);
    assert_int_equal(n, 172);
    particles_destroy(&p);
}

static void test_nearest_distance(void **state)
{
    (void)state;
    const enum lattice_kind kinds[] = {LATTICE_CHAIN, LATTICE_TRIANGULAR, LATTICE_SQUARE,
                                       LATTICE_SC, LATTICE_FCC};
    const double lo[3] = {-2.3, -2.3, -2.3}, hi[3] = {3.1, 3.1, 3.1};
    for (size_t k = 0; k < sizeof kinds / sizeof kinds[0]; k++) {
        size_t n;
        int dim = lattice_kind_dim(kinds[k]);
        struct particles *p = fill_box(kinds[k], dim, lo, hi, 0.0, &n);
        assert_true(n > 5);
        double dmin = min_pair_distance(p);
        assert_true(fabs(dmin - R0) <= 1e-12 * R0);
        particles_destroy(&p);
    }
}

static void test_rotated_triangular(void **state)
{
    (void)state;
    struct spall_error err = {0};
    struct particles *p = NULL;
    assert_int_equal(particles_create(&p, 2, 0, &err), SPALL_OK);
    const double c[3] = {0.2 * R0, -0.1 * R0, 0};
    struct geom *disc = geom_sphere(c, 12 * R0);
    struct lattice_spec s = {.kind = LATTICE_TRIANGULAR, .spacing = R0, .origin = {0, 0, 0},
                             .angle = 0.3};
    size_t n = 0;
    assert_int_equal(lattice_fill(p, &s, disc, 0, &n, &err), SPALL_OK);
    assert_true(fabs(min_pair_distance(p) - R0) <= 1e-12 * R0);
    /* Site count ~ disc area / cell area (boundary effects a few %). */
    double expect = SPALL_PI * 144.0 / (sqrt(3.0) / 2.0);
    assert_true(fabs((double)n - expect) < 0.05 * expect);
    /* The origin is a site, and the lattice is rotated: the site at
     * r0 (cos 0.3, sin 0.3) exists. */
    bool origin = false, rotated = false;
    for (size_t i = 0; i < p->n; i++) {
        origin |= hypot(p->x[0][i], p->x[1][i]) < 1e-12 * R0;
        rotated |= hypot(p->x[0][i] - R0 * cos(0.3), p->x[1][i] - R0 * sin(0.3)) < 1e-12 * R0;
    }
    assert_true(origin && rotated);
    /* Every site is inside the disc. */
    for (size_t i = 0; i < p->n; i++) {
        const double x[3] = {p->x[0][i], p->x[1][i], 0};
        assert_true(geom_contains(disc, x, 2));
    }
    geom_destroy(&disc);
    particles_destroy(&p);
}

static void test_row_major_order(void **state)
{
    (void)state;
    size_t n;
    const double lo[3] = {0, 0, 0}, hi[3] = {4, 4, 4};
    struct particles *p = fill_box(LATTICE_FCC, 3, lo, hi, 0.0, &n);
    for (size_t i = 1; i < p->n; i++) {
        double dz = p->x[2][i] - p->x[2][i - 1], dy = p->x[1][i] - p->x[1][i - 1];
        double dx = p->x[0][i] - p->x[0][i - 1];
        /* (z, y, x) strictly increasing lexicographically: x fastest. */
        assert_true(dz > 0 || (dz == 0 && (dy > 0 || (dy == 0 && dx > 0))));
    }
    particles_destroy(&p);
}

/** Count neighbours of the site nearest the centre within each shell. */
static void check_shells(enum lattice_kind kind, int n_shells)
{
    size_t n;
    int dim = lattice_kind_dim(kind);
    const double lo[3] = {-4.2, -4.2, -4.2}, hi[3] = {4.2, 4.2, 4.2};
    struct particles *p = fill_box(kind, dim, lo, hi, 0.0, &n);
    struct lattice_spec s = {.kind = kind, .spacing = R0};
    size_t c = 0;
    double best = INFINITY;
    for (size_t i = 0; i < p->n; i++) {
        double r2 = 0;
        for (int d = 0; d < dim; d++)
            r2 += p->x[d][i] * p->x[d][i];
        if (r2 < best) {
            best = r2;
            c = i;
        }
    }
    for (int sh = 1; sh <= n_shells; sh++) {
        double rs = lattice_shell_distance(&s, sh);
        assert_true(rs > 0.0);
        if (sh > 1)
            assert_true(rs > lattice_shell_distance(&s, sh - 1));
        int count = 0;
        for (size_t j = 0; j < p->n; j++) {
            double r2 = 0;
            for (int d = 0; d < dim; d++) {
                double dx = p->x[d][j] - p->x[d][c];
                r2 += dx * dx;
            }
            if (j != c && fabs(sqrt(r2) - rs) < 1e-9 * R0)
                count++;
        }
        assert_int_equal(count, lattice_shell_count(kind, sh));
    }
    particles_destroy(&p);
}

static void test_shells(void **state)
{
    (void)state;
    check_shells(LATTICE_CHAIN, 3);
    check_shells(LATTICE_TRIANGULAR, 5);
    check_shells(LATTICE_SQUARE, 4);
    check_shells(LATTICE_SC, 4);
    check_shells(LATTICE_FCC, 4);
    struct lattice_spec s = {.kind = LATTICE_FCC, .spacing = R0};
    assert_true(fabs(lattice_shell_distance(&s, 2) - sqrt(2.0) * R0) < 1e-18);
    assert_int_equal(lattice_shell_count(LATTICE_TRIANGULAR, 1), 6);
    assert_int_equal(lattice_shell_count(LATTICE_SC, 2), 12);
    assert_int_equal(lattice_shell_count(LATTICE_FCC, 2), 6);
    assert_int_equal(lattice_shell_count(LATTICE_SQUARE, 0), 0);
}

static void test_site_volume(void **state)
{
    (void)state;
    struct lattice_spec s = {.kind = LATTICE_TRIANGULAR, .spacing = R0};
    double v = lattice_site_volume(&s, 2.0 * R0 / sqrt(3.0));
    assert_true(fabs(v - R0 * R0 * R0) <= 1e-14 * R0 * R0 * R0);
    s.kind = LATTICE_SQUARE;
    assert_true(lattice_site_volume(&s, 2 * R0) == 2 * R0 * R0 * R0);
    s.kind = LATTICE_CHAIN;
    assert_true(lattice_site_volume(&s, 3e-6) == R0 * 3e-6);
    s.kind = LATTICE_SC;
    assert_true(lattice_site_volume(&s, 0) == R0 * R0 * R0);
    s.kind = LATTICE_FCC;
    assert_true(fabs(lattice_site_volume(&s, 0) - R0 * R0 * R0 / sqrt(2.0)) < 1e-14 * R0 * R0 * R0);
}

static void test_names(void **state)
{
    (void)state;
    for (int k = LATTICE_CHAIN; k <= LATTICE_FCC; k++)
        assert_int_equal(lattice_kind_from_name(lattice_kind_name((enum lattice_kind)k)), k);
    assert_int_equal(lattice_kind_from_name("hexagonal"), -1);
    assert_int_equal(lattice_kind_dim(LATTICE_FCC), 3);
    assert_int_equal(lattice_kind_dim(LATTICE_SQUARE), 2);
    assert_int_equal(lattice_kind_dim(LATTICE_CHAIN), 1);
}

static void test_errors(void **state)
{
    (void)state;
    struct spall_error err = {0};
    struct particles *p = NULL;
    assert_int_equal(particles_create(&p, 2, 0, &err), SPALL_OK);
    struct lattice_spec s = {.kind = LATTICE_TRIANGULAR, .spacing = R0};
    /* A box between sites. */
    const double lo[3] = {0.1 * R0, 0.1 * R0, 0}, hi[3] = {0.2 * R0, 0.2 * R0, 0};
    struct geom *tiny = geom_box(lo, hi);
    size_t n = 99;
    assert_int_equal(lattice_fill(p, &s, tiny, 0, &n, &err), SPALL_ERR_INPUT);
    assert_non_null(strstr(err.msg, "contains no lattice site"));
    assert_int_equal(n, 0);
    assert_int_equal(p->n, 0);
    /* Unbounded region. */
    const double pt[3] = {0, 0, 0}, nrm[3] = {0, 1, 0};
    struct geom *h = geom_halfspace(pt, nrm);
    spall_error_clear(&err);
    assert_int_equal(lattice_fill(p, &s, h, 0, &n, &err), SPALL_ERR_INPUT);
    assert_non_null(strstr(err.msg, "unbounded"));
    /* Bad spacing, and a 3D lattice into 2D particles. */
    s.spacing = -1.0;
    assert_int_equal(lattice_fill(p, &s, tiny, 0, &n, &err), SPALL_ERR_INPUT);
    s.spacing = R0;
    s.kind = LATTICE_FCC;
    assert_int_equal(lattice_fill(p, &s, tiny, 0, &n, &err), SPALL_ERR_INPUT);
    geom_destroy(&tiny);
    geom_destroy(&h);
    particles_destroy(&p);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_counts),          cmocka_unit_test(test_nearest_distance),
        cmocka_unit_test(test_rotated_triangular), cmocka_unit_test(test_row_major_order),
        cmocka_unit_test(test_shells),          cmocka_unit_test(test_site_volume),
        cmocka_unit_test(test_names),           cmocka_unit_test(test_errors),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
