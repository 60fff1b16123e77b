/* Tests for src/core/neighbor.c: the cell list must equal the brute-force
 * twin exactly (same CSR), for any thread count and in degenerate cases. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include "core/neighbor.h"
#include "spall/error.h"

#include <math.h>
#include <omp.h>
#include <stdbool.h>
#include <stdlib.h>
#include <string.h>

/** Seeded 64-bit LCG (Knuth MMIX constants) -> uniform in [0,1). */
static double lcg_next(uint64_t *s)
{
    *s = *s * 6364136223846793005ULL + 1442695040888963407ULL;
    return (double)(*s >> 11) * (1.0 / 9007199254740992.0);
}

struct pts {
    size_t n;
    double *x[3];
};

static struct pts pts_alloc(size_t n)
{
    struct pts p = {.n = n};
    for (int d = 0; d < 3; d++) {
        p.x[d] = calloc(n ? n : 1, sizeof(double));
        assert_non_null(p.x[d]);
    }
    return p;
}

static void pts_free(struct pts *p)
{
    for (int d = 0; d < 3; d++)
        free(p->x[d]);
}

static void assert_same_list(const struct neighbor_list *a, const struct neighbor_list *b)
{
    assert_int_equal(a->n, b->n);
    assert_memory_equal(a->offset, b->offset, (a->n + 1) * sizeof *a->offset);
    size_t m = a->offset[a->n];
    if (m)
        assert_memory_equal(a->idx, b->idx, m * sizeof *a->idx);
}

/** Rows ascending, no self, and j in row i <=> i in row j. */
static void assert_well_formed(const struct neighbor_list *nl)
{
    for (size_t i = 0; i < nl->n; i++) {
        for (size_t k = nl->offset[i]; k < nl->offset[i + 1]; k++) {
            int32_t j = nl->idx[k];
            assert_true(j >= 0 && (size_t)j < nl->n && (size_t)j != i);
            if (k > nl->offset[i])
                assert_true(nl->idx[k - 1] < j);
            bool back = false;
            for (size_t q = nl->offset[j]; q < nl->offset[j + 1]; q++)
                back |= (size_t)nl->idx[q] == i;
            assert_true(back);
        }
    }
}

/** The half-stencil builder on @p threads threads: the CSR of @p ref, and
 *  a pair table that lists each pair once, (i, j < i) in the order of the
 *  rows' upper parts, with every slot pointing at its pair. */
static void check_pairs(const struct neighbor_list *ref, int dim, const struct pts *p,
                        double radius, int threads)
{
    struct spall_error err = {0};
    struct neighbor_list *nl = NULL, *nl2 = NULL;
    struct neighbor_pairs pp;
    int saved = omp_get_max_threads();
    omp_set_num_threads(threads);
    assert_int_equal(neighbor_list_build_pairs(&nl, &pp, dim, p->n, p->x, radius, &err), SPALL_OK);
    assert_int_equal(neighbor_list_build_pairs(&nl2, NULL, dim, p->n, p->x, radius, &err),
                     SPALL_OK);
    omp_set_num_threads(saved);
    assert_same_list(ref, nl);
    assert_same_list(ref, nl2);
    assert_int_equal(2 * pp.n_pairs, nl->offset[nl->n]);
    assert_int_equal(pp.first[0], 0);
    for (size_t i = 0; i < nl->n; i++) {
        size_t q = pp.first[i];
        for (size_t s = nl->offset[i]; s < nl->offset[i + 1]; s++) {
            const size_t j = (size_t)nl->idx[s], pq = pp.slot_pair[s];
            if (j > i) { /* the upper part: i's pairs, in order */
                assert_int_equal(pq, q);
                assert_int_equal(pp.partner[q], j);
                q++;
            } else { /* a pair of j's, whose partner is i */
                assert_true(pq >= pp.first[j] && pq < pp.first[j + 1]);
                assert_int_equal(pp.partner[pq], i);
            }
        }
        assert_int_equal(q, pp.first[i + 1]);
    }
    neighbor_pairs_free(&pp);
    assert_null(pp.first);
    neighbor_list_destroy(&nl);
    neighbor_list_destroy(&nl2);
}

/** Build with the cell list on 1, 2 and 3 threads and by brute force; all
 *  equal (the half-stencil builder too, also on 5 threads: the grid's and
 *  the ordering's blocks split unevenly, some empty for small n). */
static size_t check_all_equal(int dim, const struct pts *p, double radius)
{
    struct spall_error err = {0};
    struct neighbor_list *brute = NULL, *c1 = NULL, *c2 = NULL, *c3 = NULL;
    assert_int_equal(neighbor_list_build_brute(&brute, dim, p->n, p->x, radius, &err), SPALL_OK);
    int saved = omp_get_max_threads();
    omp_set_num_threads(1);
    assert_int_equal(neighbor_list_build(&c1, dim, p->n, p->x, radius, &err), SPALL_OK);
    omp_set_num_threads(2);
    assert_int_equal(neighbor_list_build(&c2, dim, p->n, p->x, radius, &err), SPALL_OK);
    omp_set_num_threads(3);
    assert_int_equal(neighbor_list_build(&c3, dim, p->n, p->x, radius, &err), SPALL_OK);
    omp_set_num_threads(saved);
    assert_same_list(brute, c1);
    assert_same_list(brute, c2);
    assert_same_list(brute, c3);
    assert_well_formed(c1);
    for (int t = 1; t <= 5; t += t < 3 ? 1 : 2)
        check_pairs(brute, dim, p, radius, t);
    size_t m = c1->offset[c1->n];
    neighbor_list_destroy(&brute);
    neighbor_list_destroy(&c1);
    neighbor_list_destroy(&c2);
    neighbor_list_destroy(&c3);
    assert_null(c2);
    return m;
}

static void test_random_vs_brute(void **state)
{
    (void)state;
    uint64_t seed = 12345;
    const size_t n = 2000;
    for (int dim = 1; dim <= 3; dim++) {
        struct pts p = pts_alloc(n);
        for (size_t i = 0; i < n; i++)
            for (int d = 0; d < dim; d++)
                p.x[d][i] = -0.3 + 1.7 * lcg_next(&seed);
        /* Radius giving ~10 neighbours on average in each dimension. */
        const double radius[4] = {0, 10.0 * 1.7 / (2 * n), 0.05, 0.13};
        size_t m = check_all_equal(dim, &p, radius[dim]);
        assert_true(m > n); /* the test actually found pairs */
        /* And a radius larger than the whole cloud: everybody sees everybody. */
        if (dim == 2) {
            struct pts q = pts_alloc(300);
            for (size_t i = 0; i < 300; i++)
                for (int d = 0; d < 2; d++)
                    q.x[d][i] = p.x[d][i];
            assert_int_equal(check_all_equal(2, &q, 10.0), 300 * 299);
            pts_free(&q);
        }
        pts_free(&p);
    }
}

static void test_triangular_lattice(void **state)
{
    (void)state;
    const double r0 = 1e-3, h = r0 * sqrt(3.0) / 2.0;
    const size_t nx = 40, ny = 30;
    struct pts p = pts_alloc(nx * ny);
    for (size_t j = 0; j < ny; j++)
        for (size_t i = 0; i < nx; i++) {
            p.x[0][j * nx + i] = ((double)i + 0.5 * (double)(j % 2)) * r0;
            p.x[1][j * nx + i] = (double)j * h;
        }
    struct spall_error err = {0};
    struct neighbor_list *nl = NULL;
    assert_int_equal(neighbor_list_build(&nl, 2, p.n, p.x, 1.01 * r0, &err), SPALL_OK);
    for (size_t j = 1; j + 1 < ny; j++)
        for (size_t i = 1; i + 1 < nx; i++) {
            size_t s = j * nx + i;
            assert_int_equal(nl->offset[s + 1] - nl->offset[s], 6);
        }
    /* Corner (0,0) has 2 neighbours: (1,0) and (0,1). */
    assert_int_equal(nl->offset[1] - nl->offset[0], 2);
    assert_int_equal(nl->idx[0], 1);
    assert_int_equal(nl->idx[1], (int32_t)nx);
    /* Bonds of a triangular nx x ny patch: 3 nx ny - 2 nx - 2 ny + 1 (each
     * row nx-1, each row pair 2nx-1 links). */
    size_t bonds = ny * (nx - 1) + (ny - 1) * (2 * nx - 1);
    assert_int_equal(nl->offset[p.n], 2 * bonds);
    neighbor_list_destroy(&nl);
    check_all_equal(2, &p, 1.01 * r0);
    /* Exactly r0 is excluded (strict <) only where rounding keeps it >= r0;
     * the x-row neighbours sit at exactly r0 and must be absent. */
    assert_int_equal(neighbor_list_build(&nl, 2, p.n, p.x, r0, &err), SPALL_OK);
    for (size_t k = nl->offset[1]; k < nl->offset[2]; k++)
        assert_true(nl->idx[k] != 0 && nl->idx[k] != 2);
    neighbor_list_destroy(&nl);
    /* pairs at exactly the radius, on the cell edges: all builders agree */
    check_all_equal(2, &p, r0);
    pts_free(&p);
}

static void test_degenerate(void **state)
{
    (void)state;
    struct spall_error err = {0};
    struct neighbor_list *nl = NULL;
    /* n = 0 */
    struct pts p0 = pts_alloc(0);
    assert_int_equal(neighbor_list_build(&nl, 3, 0, p0.x, 1.0, &err), SPALL_OK);
    assert_int_equal(nl->n, 0);
    assert_int_equal(nl->offset[0], 0);
    check_pairs(nl, 3, &p0, 1.0, 1);
    neighbor_list_destroy(&nl);
    pts_free(&p0);
    /* All particles at one point: everybody's neighbour. */
    struct pts same = pts_alloc(120);
    for (size_t i = 0; i < 120; i++)
        same.x[0][i] = same.x[1][i] = same.x[2][i] = 0.25;
    assert_int_equal(check_all_equal(3, &same, 1e-9), 120 * 119);
    pts_free(&same);
    /* Huge spread: a dense cluster plus far outliers; the cell count is
     * capped, the result must still equal the brute force. */
    uint64_t seed = 7;
    struct pts far = pts_alloc(500);
    for (size_t i = 0; i < 500; i++)
        for (int d = 0; d < 3; d++)
            far.x[d][i] = lcg_next(&seed) * 1e-3;
    far.x[0][10] = 1e12;
    far.x[1][20] = -3e11;
    far.x[2][30] = 5e13;
    far.x[0][31] = 5e13; /* two outliers close to each other */
    far.x[2][31] = 5e13;
    far.x[0][30] = 5e13 + 1e-4;
    size_t m = check_all_equal(3, &far, 2e-4);
    assert_true(m > 0);
    pts_free(&far);
}

static void test_errors(void **state)
{
    (void)state;
    struct spall_error err = {0};
    struct neighbor_list *nl = NULL;
    struct pts p = pts_alloc(4);
    assert_int_equal(neighbor_list_build(&nl, 2, 4, p.x, 0.0, &err), SPALL_ERR_INPUT);
    assert_null(nl);
    assert_int_equal(neighbor_list_build(&nl, 4, 4, p.x, 1.0, &err), SPALL_ERR_INPUT);
    p.x[1][2] = NAN;
    assert_int_equal(neighbor_list_build(&nl, 2, 4, p.x, 1.0, &err), SPALL_ERR_INPUT);
    assert_non_null(strstr(err.msg, "particle 2"));
    assert_null(nl);
    struct neighbor_pairs pp;
    assert_int_equal(neighbor_list_build_pairs(&nl, &pp, 2, 4, p.x, 1.0, &err), SPALL_ERR_INPUT);
    assert_non_null(strstr(err.msg, "particle 2"));
    assert_null(nl);
    assert_null(pp.first);
    pts_free(&p);
    /* several non-finite coordinates, on two axes and in different threads'
     * blocks: every thread count names the one a single loop meets first
     * (axis x before y, then the lowest index) */
    struct pts q = pts_alloc(40);
    for (size_t i = 0; i < 40; i++)
        q.x[0][i] = q.x[1][i] = 0.1 * (double)i;
    q.x[1][3] = NAN;
    q.x[0][35] = INFINITY;
    q.x[0][25] = NAN;
    int saved = omp_get_max_threads();
    for (int t = 1; t <= 5; t++) {
        omp_set_num_threads(t);
        assert_int_equal(neighbor_list_build(&nl, 2, 40, q.x, 1.0, &err), SPALL_ERR_INPUT);
        assert_non_null(strstr(err.msg, "particle 25 has"));
        assert_int_equal(neighbor_list_build_pairs(&nl, &pp, 2, 40, q.x, 1.0, &err),
                         SPALL_ERR_INPUT);
        assert_non_null(strstr(err.msg, "particle 25 has"));
        assert_null(nl);
    }
    omp_set_num_threads(saved);
    pts_free(&q);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_random_vs_brute),
        cmocka_unit_test(test_triangular_lattice),
        cmocka_unit_test(test_degenerate),
        cmocka_unit_test(test_errors),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
