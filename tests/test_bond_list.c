/* Tests for src/core/bond_list.c on a triangular lattice plate: shells,
 * reverse index, pre-crack and counts. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include "core/bond_list.h"
#include "core/geometry.h"
#include "core/lattice_gen.h"
#include "core/particles.h"
#include "spall/error.h"

#include <math.h>
#include <omp.h>
#include <stdbool.h>
#include <stdlib.h>
#include <string.h>

static const double R0 = 2e-3;
#define NX 30
#define NY 20

/** NX x NY triangular plate (even rows x = 0..NX-1, odd rows shifted r0/2). */
static struct particles *plate(void)
{
    struct spall_error err = {0};
    struct particles *p = NULL;
    assert_int_equal(particles_create(&p, 2, 0, &err), SPALL_OK);
    double h = R0 * sqrt(3.0) / 2.0;
    const double lo[3] = {0, 0, 0}, hi[3] = {(NX - 0.5) * R0, (NY - 1) * h, 0};
    struct geom *box = geom_box(lo, hi);
    struct lattice_spec s = {.kind = LATTICE_TRIANGULAR, .spacing = R0};
    size_t n = 0;
    assert_int_equal(lattice_fill(p, &s, box, 0, &n, &err), SPALL_OK);
    assert_int_equal(n, NX * NY);
    geom_destroy(&box);
    return p;
}

static struct bond_list *two_shells(const struct particles *p)
{
    struct spall_error err = {0};
    const double lo[2] = {0.99 * R0, 0.99 * sqrt(3.0) * R0};
    const double hi[2] = {1.01 * R0, 1.01 * sqrt(3.0) * R0};
    struct bond_list *bl = NULL;
    assert_int_equal(bond_list_build_shells(&bl, p, 2, lo, hi, &err), SPALL_OK);
    return bl;
}

static void test_shells_coordination(void **state)
{
    (void)state;
    struct particles *p = plate();
    struct bond_list *bl = two_shells(p);
    size_t c = (NY / 2) * NX + NX / 2; /* interior site */
    int n_type[2] = {0, 0};
    for (size_t k = bl->offset[c]; k < bl->offset[c + 1]; k++) {
        int t = bl->type[k];
        assert_true(t == 0 || t == 1);
        n_type[t]++;
        double expect = t == 0 ? R0 : sqrt(3.0) * R0;
        assert_true(fabs(bl->rest[k] - expect) < 1e-12 * R0);
        assert_int_equal(bl->state[k], 0);
        if (k > bl->offset[c])
            assert_true(bl->partner[k - 1] < bl->partner[k]);
    }
    assert_int_equal(n_type[0], 6);
    assert_int_equal(n_type[1], 6);
    /* Nearest-neighbour bonds of the patch: NY(NX-1) + (NY-1)(2NX-1). */
    size_t nn = NY * (NX - 1) + (NY - 1) * (2 * NX - 1);
    size_t n_t0 = 0;
    for (size_t k = 0; k < bl->offset[bl->n]; k++)
        n_t0 += bl->type[k] == 0;
    assert_int_equal(n_t0, 2 * nn);

    /* The plain radius build equals shell 0 alone. */
    struct spall_error err = {0};
    struct bond_list *b1 = NULL;
    assert_int_equal(bond_list_build(&b1, p, 1.01 * R0, &err), SPALL_OK);
    assert_int_equal(bond_list_count(b1), nn);
    for (size_t k = 0; k < b1->offset[b1->n]; k++) {
        assert_int_equal(b1->type[k], 0);
        assert_true(fabs(b1->rest[k] - R0) < 1e-12 * R0);
    }
    size_t m = b1->offset[b1->n];
    assert_int_equal(bond_list_bytes(b1),
                     sizeof *b1 + (b1->n + 1) * sizeof(size_t) + m * (4 + 8 + 1 + 1));
    bond_list_destroy(&b1);
    assert_null(b1);
    bond_list_destroy(&bl);
    particles_destroy(&p);
}

static void test_reverse(void **state)
{
    (void)state;
    struct particles *p = plate();
    struct bond_list *bl = two_shells(p);
    struct spall_error err = {0};
    size_t bytes0 = bond_list_bytes(bl);
    assert_int_equal(bond_list_build_reverse(bl, &err), SPALL_OK);
    assert_non_null(bl->reverse);
    assert_int_equal(bond_list_bytes(bl), bytes0 + bl->offset[bl->n] * sizeof(size_t));
    for (size_t i = 0; i < bl->n; i++) {
        for (size_t k = bl->offset[i]; k < bl->offset[i + 1]; k++) {
            size_t r = bl->reverse[k];
            size_t j = (size_t)bl->partner[k];
            assert_true(r >= bl->offset[j] && r < bl->offset[j + 1]);
            assert_int_equal(bl->partner[r], (int32_t)i);
            assert_int_equal(bl->reverse[r], k);
            assert_true(bl->rest[r] == bl->rest[k]); /* bit for bit */
            assert_int_equal(bl->type[r], bl->type[k]);
        }
    }
    /* Same list on 1 and 2 threads. */
    int saved = omp_get_max_threads();
    omp_set_num_threads(1);
    struct bond_list *b1 = two_shells(p);
    omp_set_num_threads(2);
    struct bond_list *b2 = two_shells(p);
    omp_set_num_threads(saved);
    size_t m = b1->offset[b1->n];
    assert_memory_equal(b1->offset, b2->offset, (b1->n + 1) * sizeof(size_t));
    assert_memory_equal(b1->partner, b2->partner, m * sizeof(int32_t));
    assert_memory_equal(b1->rest, b2->rest, m * sizeof(double));
    assert_memory_equal(b1->type, b2->type, m);
    bond_list_destroy(&b1);
    bond_list_destroy(&b2);
    bond_list_destroy(&bl);
    particles_destroy(&p);
}

/** Independent reference: does the bond a-b cross y = yc at x in [xa, xb]? */
static bool crosses_line(double x1, double y1, double x2, double y2, double yc, double xa,
                         double xb)
{
    if ((y1 - yc) * (y2 - yc) > 0 || y1 == y2)
        return false;
    double x = x1 + (yc - y1) / (y2 - y1) * (x2 - x1);
    return x >= xa && x <= xb;
}

static void test_precrack(void **state)
{
    (void)state;
    struct particles *p = plate();
    struct bond_list *bl = two_shells(p);
    struct spall_error err = {0};
    assert_int_equal(bond_list_build_reverse(bl, &err), SPALL_OK);
    double h = R0 * sqrt(3.0) / 2.0;
    double yc = (NY / 2 - 0.5) * h; /* between rows NY/2-1 and NY/2 */
    double xa = -R0, xb = 12.3 * R0;  /* from outside the left edge to the middle */
    struct precrack pc = {.dim = 2, .a = {xa, yc, 0}, .b = {xb, yc, 0}};
    size_t cut = bond_list_apply_precrack(bl, p, &pc);

    size_t expect = 0, expect_nn = 0;
    for (size_t i = 0; i < bl->n; i++) {
        for (size_t k = bl->offset[i]; k < bl->offset[i + 1]; k++) {
            size_t j = (size_t)bl->partner[k];
            bool x = crosses_line(p->x0[0][i], p->x0[1][i], p->x0[0][j], p->x0[1][j], yc, xa, xb);
            uint8_t want = x ? (BOND_BROKEN | BOND_PRECUT) : 0;
            assert_int_equal(bl->state[k], want);               /* none not crossing */
            assert_int_equal(bl->state[bl->reverse[k]], want);  /* both halves */
            if (x && j > i) {
                expect++;
                expect_nn += bl->type[k] == 0;
            }
        }
    }
    assert_int_equal(cut, expect);
    /* Nearest bonds across the line with crossing x <= 12.3 r0: the crossing
     * points of one row pair sit every r0/2 from x = 0.25 r0: 0.25..12.25 -> 25. */
    assert_int_equal(expect_nn, 25);
    assert_true(expect > expect_nn); /* second-shell bonds are cut too */
    assert_int_equal(bond_list_count_broken(bl), cut);
    /* Applying the same crack again finds the same bonds, the count of broken
     * bonds does not change. */
    assert_int_equal(bond_list_apply_precrack(bl, p, &pc), cut);
    assert_int_equal(bond_list_count_broken(bl), cut);
    bond_list_destroy(&bl);

    /* Full-width crack, nearest neighbours only: all 2 NX - 1 links cut. */
    struct bond_list *b1 = NULL;
    assert_int_equal(bond_list_build(&b1, p, 1.01 * R0, &err), SPALL_OK);
    struct precrack full = {.dim = 2, .a = {-R0, yc, 0}, .b = {NX * R0, yc, 0}};
    assert_int_equal(bond_list_apply_precrack(b1, p, &full), 2 * NX - 1);
    assert_int_equal(bond_list_count_broken(b1), 2 * NX - 1);
    assert_int_equal(bond_list_count(b1), NY * (NX - 1) + (NY - 1) * (2 * NX - 1));
    bond_list_destroy(&b1);
    particles_destroy(&p);
}

/* bond_list_compact_rest: the same doubles through the index, a table of
 * the distinct values only, 2 B per half-bond in the byte count; a list
 * with more distinct values than an index holds keeps its doubles. */
static void test_compact_rest(void **state)
{
    (void)state;
    struct spall_error err = {0};
    struct particles *p = plate();
    struct bond_list *bl = two_shells(p);
    const size_t m = bl->offset[bl->n];
    double *before = malloc(m * sizeof *before);
    assert_non_null(before);
    memcpy(before, bl->rest, m * sizeof *before);
    const size_t bytes = bond_list_bytes(bl);
    assert_int_equal(bond_list_compact_rest(bl, &err), SPALL_OK);
    assert_null(bl->rest);
    assert_non_null(bl->rest_idx);
    assert_true(bl->n_rest >= 2 && bl->n_rest < m / 4); /* regular: few values */
    for (size_t k = 0; k < m; k++) {
        const double r = bond_rest(bl, k);
        assert_memory_equal(&r, &before[k], sizeof r); /* bit for bit */
        for (size_t q = 0; q < bl->n_rest; q++) /* each value once in the table */
            if (q != bl->rest_idx[k])
                assert_true(memcmp(&bl->rest_tab[q], &r, sizeof r) != 0);
    }
    assert_int_equal(bond_list_bytes(bl), bytes - m * 6 + bl->n_rest * sizeof(double));
    assert_int_equal(bond_list_compact_rest(bl, &err), SPALL_OK); /* again: nothing to do */

    /* localize keeps the index: particle 5's row and the first 40 particles */
    size_t keep[40];
    int64_t new_of_old[NX * NY];
    for (size_t i = 0; i < NX * NY; i++)
        new_of_old[i] = i < 40 ? (int64_t)i : -1;
    for (size_t i = 0; i < 40; i++)
        keep[i] = i;
    struct bond_rows rows;
    assert_int_equal(bond_list_localize(bl, keep, 40, 1, new_of_old, &rows, &err), SPALL_OK);
    assert_int_equal(rows.n_half, bl->offset[1]);
    double *kept = bond_rows_gather(&rows, before, sizeof *before);
    assert_non_null(kept);
    for (size_t k = 0; k < rows.n_half; k++) {
        const double r = bond_rest(bl, k);
        assert_memory_equal(&r, &kept[k], sizeof r);
    }
    free(kept);
    bond_rows_free(&rows);
    bond_list_destroy(&bl);

    /* more distinct lengths than a 16-bit index holds: the doubles stay */
    struct particles *q = NULL;
    assert_int_equal(particles_create(&q, 2, 0, &err), SPALL_OK);
    const double lo[3] = {0, 0, 0}, hi[3] = {120 * R0, 120 * R0, 0};
    struct geom *box = geom_box(lo, hi);
    struct lattice_spec sp = {.kind = LATTICE_TRIANGULAR, .spacing = R0};
    size_t nq = 0;
    assert_int_equal(lattice_fill(q, &sp, box, 0, &nq, &err), SPALL_OK);
    geom_destroy(&box);
    assert_int_equal(bond_list_build(&bl, q, 1.01 * R0, &err), SPALL_OK);
    const size_t mq = bl->offset[bl->n];
    assert_true(mq > 65536);
    for (size_t k = 0; k < mq; k++)
        bl->rest[k] = R0 * (1.0 + 1e-9 * (double)k);
    assert_int_equal(bond_list_compact_rest(bl, &err), SPALL_OK);
    assert_null(bl->rest_idx);
    assert_non_null(bl->rest);
    assert_true(bond_rest(bl, mq - 1) == R0 * (1.0 + 1e-9 * (double)(mq - 1)));
    bond_list_destroy(&bl);
    particles_destroy(&q);
    free(before);
    particles_destroy(&p);
}

/* bond_list_localize: rows kept in keep's order with their partners
 * renumbered, states, types and rest lengths along, ghosts' rows empty;
 * bond_rows_gather hands a per-half-bond array the same rows, and
 * bond_rows_take (in its place when ascending) too.  Ascending
 * keep (both set-ups: compacted in place) and a shuffled one (copied)
 * against the rows read off the untouched list. */
static void check_localize(const size_t *keep, size_t n_keep, size_t n_owned)
{
    struct spall_error err = {0};
    struct particles *p = plate();
    struct bond_list *ref = two_shells(p), *bl = two_shells(p);
    const size_t m = ref->offset[ref->n];
    int64_t new_of_old[NX * NY];
    for (size_t i = 0; i < NX * NY; i++)
        new_of_old[i] = -1;
    for (size_t k = 0; k < n_keep; k++)
        new_of_old[keep[k]] = (int64_t)k;
    double *slot = malloc(m * sizeof *slot); /* a model's array: its old slot */
    assert_non_null(slot);
    for (size_t s = 0; s < m; s++)
        slot[s] = (double)s;
    struct bond_rows rows;
    assert_int_equal(bond_list_localize(bl, keep, n_keep, n_owned, new_of_old, &rows, &err),
                     SPALL_OK);
    double *got = bond_rows_gather(&rows, slot, sizeof *slot);
    assert_non_null(got);
    /* bond_rows_take: the same rows, in place when ascending */
    assert_true(m <= UINT16_MAX);
    uint16_t *taken = malloc(m * sizeof *taken);
    assert_non_null(taken);
    for (size_t s = 0; s < m; s++)
        taken[s] = (uint16_t)s;
    taken = bond_rows_take(&rows, taken, sizeof *taken);
    assert_non_null(taken);
    assert_int_equal(bl->n, n_keep);
    assert_null(bl->reverse);
    size_t w = 0;
    for (size_t k = 0; k < n_keep; k++) {
        assert_int_equal(bl->offset[k], w);
        if (k < n_owned)
            for (size_t s = ref->offset[keep[k]]; s < ref->offset[keep[k] + 1]; s++, w++) {
                assert_int_equal(bl->partner[w], new_of_old[ref->partner[s]]);
                assert_int_equal(bl->state[w], ref->state[s]);
                assert_int_equal(bl->type[w], ref->type[s]);
                assert_true(bond_rest(bl, w) == bond_rest(ref, s));
                assert_true(got[w] == (double)s);
                assert_int_equal(taken[w], (uint16_t)s);
            }
        assert_int_equal(bl->offset[k + 1], w); /* a ghost's row is empty */
    }
    assert_int_equal(w, rows.n_half);
    free(taken);
    free(got);
    free(slot);
    bond_rows_free(&rows);
    bond_list_destroy(&bl);
    bond_list_destroy(&ref);
    particles_destroy(&p);
}

static void test_localize(void **state)
{
    (void)state;
    size_t keep[NX * NY];
    size_t n = 0;
    for (size_t i = 3; i < NX * NY; i += 3) /* owned: every third, ascending */
        keep[n++] = i;
    const size_t n_owned = n;
    keep[n++] = 1; /* ghosts, any order */
    keep[n++] = 0;
    check_localize(keep, n, n_owned);
    for (size_t k = 0; k + 1 < n_owned; k += 2) { /* not ascending: copied */
        const size_t t = keep[k];
        keep[k] = keep[k + 1];
        keep[k + 1] = t;
    }
    check_localize(keep, n, n_owned);
    check_localize(keep, 0, 0); /* nothing kept */
}

/* bond_list_build_compact: the bonds of bond_list_build and the index and
 * table bond_list_compact_rest makes of its doubles, without the doubles
 * ever existing; bond_list_expand_rest gives the doubles back.  With more
 * distinct lengths than an index holds (a jittered plate) the doubles, bit
 * for bit those of bond_list_build. */
static void same_bonds(const struct bond_list *a, const struct bond_list *b)
{
    assert_int_equal(a->n, b->n);
    assert_memory_equal(a->offset, b->offset, (a->n + 1) * sizeof *a->offset);
    const size_t m = a->offset[a->n];
    assert_memory_equal(a->partner, b->partner, m * sizeof *a->partner);
    for (size_t k = 0; k < m; k++)
        assert_int_equal(b->state[k], 0);
    assert_null(b->type);
}

/* splitmix64's finaliser: neighbouring sites get unrelated jitters */
static uint64_t mix64(uint64_t z)
{
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
}

static void test_build_compact(void **state)
{
    (void)state;
    struct spall_error err = {0};
    struct particles *p = plate();
    const double radius = 1.01 * sqrt(3.0) * R0; /* two shells */
    struct bond_list *a = NULL, *b = NULL;
    assert_int_equal(bond_list_build(&a, p, radius, &err), SPALL_OK);
    const size_t m = a->offset[a->n];
    double *before = malloc(m * sizeof *before);
    assert_non_null(before);
    memcpy(before, a->rest, m * sizeof *before);
    assert_int_equal(bond_list_compact_rest(a, &err), SPALL_OK);
    assert_int_equal(bond_list_build_compact(&b, p, radius, &err), SPALL_OK);
    same_bonds(a, b);
    assert_null(b->rest);
    assert_int_equal(b->n_rest, a->n_rest);
    assert_memory_equal(b->rest_tab, a->rest_tab, a->n_rest * sizeof *a->rest_tab);
    assert_memory_equal(b->rest_idx, a->rest_idx, m * sizeof *a->rest_idx);
    assert_int_equal(bond_list_expand_rest(b, &err), SPALL_OK);
    assert_null(b->rest_idx);
    assert_null(b->rest_tab);
    assert_memory_equal(b->rest, before, m * sizeof *before);
    assert_int_equal(bond_list_expand_rest(b, &err), SPALL_OK); /* again: nothing to do */
    assert_memory_equal(b->rest, before, m * sizeof *before);
    bond_list_destroy(&a);
    bond_list_destroy(&b);
    free(before);

    /* shells: the types as well */
    const double slo[2] = {0.99 * R0, 0.99 * sqrt(3.0) * R0};
    const double shi[2] = {1.01 * R0, 1.01 * sqrt(3.0) * R0};
    a = two_shells(p);
    assert_int_equal(bond_list_compact_rest(a, &err), SPALL_OK);
    assert_int_equal(bond_list_build_shells_compact(&b, p, 2, slo, shi, &err), SPALL_OK);
    const size_t ms = a->offset[a->n];
    assert_memory_equal(a->offset, b->offset, (a->n + 1) * sizeof *a->offset);
    assert_memory_equal(a->partner, b->partner, ms * sizeof *a->partner);
    assert_memory_equal(a->type, b->type, ms * sizeof *a->type);
    assert_null(b->rest);
    assert_int_equal(b->n_rest, a->n_rest);
    assert_memory_equal(b->rest_tab, a->rest_tab, a->n_rest * sizeof *a->rest_tab);
    assert_memory_equal(b->rest_idx, a->rest_idx, ms * sizeof *a->rest_idx);
    assert_int_equal(bond_list_bytes(b), bond_list_bytes(a));
    bond_list_destroy(&a);
    bond_list_destroy(&b);
    particles_destroy(&p);

    struct particles *q = NULL;
    assert_int_equal(particles_create(&q, 2, 0, &err), SPALL_OK);
    const double lo[3] = {0, 0, 0}, hi[3] = {200 * R0, 200 * R0, 0};
    struct geom *box = geom_box(lo, hi);
    struct lattice_spec sp = {.kind = LATTICE_TRIANGULAR, .spacing = R0};
    size_t nq = 0;
    assert_int_equal(lattice_fill(q, &sp, box, 0, &nq, &err), SPALL_OK);
    geom_destroy(&box);
    for (size_t i = 0; i < nq; i++) /* hashed, in [0, 1e-5 R0): the same neighbours */
        for (int d = 0; d < 2; d++)
            q->x0[d][i] += 1e-5 * R0 * 0x1p-53 * (double)(mix64(2 * i + (size_t)d) >> 11);
    assert_int_equal(bond_list_build(&a, q, 1.01 * R0, &err), SPALL_OK);
    assert_int_equal(bond_list_build_compact(&b, q, 1.01 * R0, &err), SPALL_OK);
    const size_t mq = a->offset[a->n];
    assert_true(mq > 2 * 65536); /* each bond's two halves share a length */
    same_bonds(a, b);
    assert_null(b->rest_idx);
    assert_non_null(b->rest);
    assert_memory_equal(b->rest, a->rest, mq * sizeof *a->rest);
    bond_list_destroy(&a);
    bond_list_destroy(&b);
    particles_destroy(&q);
}

static void test_errors(void **state)
{
    (void)state;
    struct particles *p = plate();
    struct spall_error err = {0};
    struct bond_list *bl = NULL;
    const double lo[1] = {2 * R0}, hi[1] = {R0};
    assert_int_equal(bond_list_build_shells(&bl, p, 1, lo, hi, &err), SPALL_ERR_INPUT);
    assert_null(bl);
    assert_int_equal(bond_list_build_shells(&bl, p, 0, lo, hi, &err), SPALL_ERR_INPUT);
    assert_int_equal(bond_list_build(&bl, p, -1.0, &err), SPALL_ERR_INPUT);
    assert_null(bl);
    assert_int_equal(bond_list_count(NULL), 0);
    particles_destroy(&p);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_shells_coordination),
        cmocka_unit_test(test_reverse),
        cmocka_unit_test(test_precrack),
        cmocka_unit_test(test_compact_rest),
        cmocka_unit_test(test_localize),
        cmocka_unit_test(test_build_compact),
        cmocka_unit_test(test_errors),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
