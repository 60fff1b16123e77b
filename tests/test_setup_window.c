/* Tests for the distributed set-up's lattice windows (core/lattice_gen.h
 * lattice_fill_window, lattice_split_layers) and the global-id offsets of
 * core/parallel/setup_dist.h: every rank's window, simulated here for 1-5
 * ranks, holds exactly the serial sites [gid_first, gid_first + n) in the
 * serial order; the blocks tile the body with the offsets of the counts;
 * every site within the halo of a block is in its window. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include "core/geometry.h"
#include "core/lattice_gen.h"
#include "core/parallel/setup_dist.h"
#include "core/particles.h"
#include "spall/error.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static const double R0 = 1e-3;

struct fill_case {
    enum lattice_kind kind;
    int dim;
    double angle;
    double lo[3], hi[3]; /* box in r0; a disc cut when round */
    bool round;
};

static struct geom *region_of(const struct fill_case *c)
{
    double l[3], h[3];
    for (int d = 0; d < 3; d++) {
        l[d] = c->lo[d] * R0;
        h[d] = c->hi[d] * R0;
    }
    struct geom *box = geom_box(l, h);
    if (!c->round)
        return box;
    double ctr[3] = {0.5 * (l[0] + h[0]), 0.5 * (l[1] + h[1]), 0.5 * (l[2] + h[2])};
    struct geom *parts[2] = {box, geom_sphere(ctr, 0.5 * (h[0] - l[0]))};
    return geom_combine(GEOM_INTERSECTION, parts, 2);
}

static void check_case(const struct fill_case *c, double halo)
{
    struct spall_error err = {0};
    const struct lattice_spec spec = {c->kind, R0, {0, 0, 0}, c->angle};
    struct geom *g = region_of(c);
    struct particles *serial = NULL;
    size_t n_serial = 0;
    assert_int_equal(particles_create(&serial, c->dim, 0, &err), SPALL_OK);
    assert_int_equal(lattice_fill(serial, &spec, g, 0, &n_serial, &err), SPALL_OK);
    assert_true(n_serial > 20);
    for (int size = 1; size <= 5; size++) {
        size_t *own = calloc((size_t)size, sizeof *own);
        int64_t *first = calloc((size_t)size + 1, sizeof *first);
        int64_t *start = calloc((size_t)size, sizeof *start);
        for (int r = 0; r < size; r++) {
            struct particles *p = NULL;
            assert_int_equal(particles_create(&p, c->dim, 0, &err), SPALL_OK);
            struct lattice_window w = {r, size, halo, 0, 0, 0, 0, 0};
            assert_int_equal(lattice_fill_window(p, &spec, g, 0, &w, &err), SPALL_OK);
            assert_int_equal(w.n_total, n_serial);
            /* the window is a run of the serial order */
            assert_true(w.gid_first >= 0);
            assert_true((size_t)w.gid_first + p->n <= n_serial);
            assert_true(w.n_below + w.n_own <= p->n);
            for (size_t i = 0; i < p->n; i++)
                for (int d = 0; d < c->dim; d++)
                    assert_true(p->x0[d][i] == serial->x0[d][(size_t)w.gid_first + i]);
            own[r] = w.n_own;
            start[r] = w.gid_first + (int64_t)w.n_below;
            /* every serial site within the halo of a site of the block
             * is in the window */
            const size_t a = (size_t)start[r], b = a + w.n_own;
            for (size_t j = 0; j < n_serial; j++) {
                if (j >= (size_t)w.gid_first && j < (size_t)w.gid_first + p->n)
                    continue;
                for (size_t i = a; i < b; i++) {
                    double r2 = 0.0;
                    for (int d = 0; d < c->dim; d++) {
                        double dx = serial->x0[d][j] - serial->x0[d][i];
                        r2 += dx * dx;
                    }
                    assert_true(sqrt(r2) > halo);
                }
            }
            particles_destroy(&p);
        }
        /* the offsets of the counts are where the blocks start: the blocks
         * tile [0, n) in rank order */
        par_setup_offsets(own, size, first);
        assert_int_equal(first[size], (int64_t)n_serial);
        for (int r = 0; r < size; r++)
            assert_int_equal(first[r], start[r]);
        free(own);
        free(first);
        free(start);
    }
    particles_destroy(&serial);
    geom_destroy(&g);
}

static void test_windows_2d(void **state)
{
    (void)state;
    const struct fill_case tri = {LATTICE_TRIANGULAR, 2, 0.0, {0, 0, 0}, {14, 9, 0}, false};
    check_case(&tri, 2.1 * R0);
    const struct fill_case rot = {LATTICE_TRIANGULAR, 2, 0.3, {0, 0, 0}, {12, 12, 0}, true};
    check_case(&rot, 3.2 * R0);
    const struct fill_case sq = {LATTICE_SQUARE, 2, 0.0, {0, 0, 0}, {10, 16, 0}, false};
    check_case(&sq, 6.1 * R0);
}

static void test_windows_3d_and_1d(void **state)
{
    (void)state;
    const struct fill_case fcc = {LATTICE_FCC, 3, 0.0, {0, 0, 0}, {4, 4, 6}, false};
    check_case(&fcc, 2.1 * R0);
    const struct fill_case sc = {LATTICE_SC, 3, 0.0, {0, 0, 0}, {5, 5, 5}, true};
    check_case(&sc, 2.0 * R0);
    const struct fill_case chain = {LATTICE_CHAIN, 1, 0.0, {0, 0, 0}, {40, 0, 0}, false};
    check_case(&chain, 2.1 * R0);
}

static void test_split_layers(void **state)
{
    (void)state;
    const size_t cnt[8] = {10, 10, 10, 10, 10, 10, 10, 10};
    size_t first[5];
    lattice_split_layers(cnt, 8, 4, first);
    const size_t want[5] = {0, 2, 4, 6, 8};
    for (int r = 0; r <= 4; r++)
        assert_int_equal(first[r], want[r]);
    /* more ranks than layers: empty blocks, still contiguous and ordered */
    size_t f2[7];
    lattice_split_layers(cnt, 3, 6, f2);
    assert_int_equal(f2[0], 0);
    assert_int_equal(f2[6], 3);
    for (int r = 0; r < 6; r++)
        assert_true(f2[r] <= f2[r + 1]);
    /* uneven layers: each block's count within one layer of N/P */
    const size_t odd[6] = {1, 30, 2, 2, 30, 1};
    size_t f3[3];
    lattice_split_layers(odd, 6, 2, f3);
    size_t a = 0;
    for (size_t l = f3[0]; l < f3[1]; l++)
        a += odd[l];
    assert_true(a <= 33 && a + 30 >= 33);
}

/* A second body's window: the particle limit counts the earlier bodies'
 * whole particles (n_prior), not the few of them in this rank's window,
 * and refuses exactly where the serial fill after them refuses. */
static void test_window_limit_counts_prior(void **state)
{
    (void)state;
    struct spall_error err = {0};
    const struct lattice_spec spec = {LATTICE_SQUARE, R0, {0, 0, 0}, 0.0};
    const struct fill_case c = {LATTICE_SQUARE, 2, 0.0, {0, 0, 0}, {9, 11, 0}, false};
    struct geom *g = region_of(&c);
    struct particles *serial = NULL;
    size_t n = 0;
    assert_int_equal(particles_create(&serial, 2, 0, &err), SPALL_OK);
    assert_int_equal(lattice_fill(serial, &spec, g, 0, &n, &err), SPALL_OK);
    for (size_t prior = 4; prior <= 6; prior++) {
        /* serially: prior particles of earlier bodies, then this body */
        struct particles *ps = NULL;
        assert_int_equal(particles_create(&ps, 2, 0, &err), SPALL_OK);
        ps->max_n = n + 5;
        const double pos[3] = {-1.0, -1.0, 0.0};
        for (size_t k = 0; k < prior; k++)
            assert_int_equal(particles_append(ps, pos, 0, NULL, &err), SPALL_OK);
        size_t added = 0;
        const int want = lattice_fill(ps, &spec, g, 0, &added, &err);
        assert_int_equal(want, prior <= 5 ? SPALL_OK : SPALL_ERR_INPUT);
        /* rank 1 of 3, its window empty of the earlier bodies */
        struct particles *p = NULL;
        assert_int_equal(particles_create(&p, 2, 0, &err), SPALL_OK);
        p->max_n = n + 5;
        struct lattice_window w = {1, 3, 2.1 * R0, prior, 0, 0, 0, 0};
        assert_int_equal(lattice_fill_window(p, &spec, g, 0, &w, &err), want);
        particles_destroy(&p);
        particles_destroy(&ps);
    }
    particles_destroy(&serial);
    geom_destroy(&g);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_windows_2d),
        cmocka_unit_test(test_windows_3d_and_1d),
        cmocka_unit_test(test_split_layers),
        cmocka_unit_test(test_window_limit_counts_prior),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
