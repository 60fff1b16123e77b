/* Tests for src/core/exact_sum.c: correct rounding (against IEEE addition,
 * which is correctly rounded for two terms, and the exact error of a
 * two-term sum), independence of the order and of the split into merged
 * partial sums, cancellation, overflow, subnormals, non-finite terms and
 * carries over many terms. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include "core/exact_sum.h"

#include <float.h>
#include <math.h>
#include <string.h>

static uint64_t rng_next(uint64_t *s)
{
    /* xorshift64*: a fixed, portable stream */
    *s ^= *s >> 12;
    *s ^= *s << 25;
    *s ^= *s >> 27;
    return *s * UINT64_C(2685821657736338717);
}

/* A double of random sign, mantissa and exponent in [2^-emax, 2^emax]. */
static double rnd(uint64_t *s, int emax)
{
    uint64_t r = rng_next(s);
    double m = 1.0 + (double)(r >> 12) * 0x1p-52;
    int e = (int)(rng_next(s) % (uint64_t)(2 * emax + 1)) - emax;
    return (r & 1 ? -1.0 : 1.0) * ldexp(m, e);
}

static double xsum_of(const double *v, size_t n)
{
    struct xsum a;
    xsum_init(&a);
    for (size_t i = 0; i < n; i++)
        xsum_add(&a, v[i]);
    return xsum_round(&a);
}

static int same_bits(double a, double b)
{
    return memcmp(&a, &b, sizeof a) == 0;
}

static void test_two_terms_round_like_ieee(void **state)
{
    (void)state;
    uint64_t s = 12345;
    for (int t = 0; t < 200000; t++) {
        /* exponents close together (rounding in the last bits) and far apart */
        int emax = t % 3 == 0 ? 1000 : (t % 3 == 1 ? 60 : 4);
        double v[2] = {rnd(&s, emax), rnd(&s, emax)};
        double want = v[0] + v[1];
        double got = xsum_of(v, 2);
        if (!same_bits(got, want))
            fail_msg("%a + %a: xsum %a, IEEE %a", v[0], v[1], got, want);
    }
}

static void test_exact_error_of_two_sum(void **state)
{
    (void)state;
    uint64_t s = 777;
    for (int t = 0; t < 100000; t++) {
        double a = rnd(&s, 40), b = rnd(&s, 40);
        /* Knuth's TwoSum: a + b = sum + err exactly */
        double sum = a + b, bb = sum - a, err = (a - (sum - bb)) + (b - bb);
        double v[3] = {a, b, -sum};
        double got = xsum_of(v, 3);
        if (!same_bits(got, err) && !(got == 0.0 && err == 0.0))
            fail_msg("%a + %a - %a: xsum %a, exact %a", a, b, sum, got, err);
    }
}

static void test_order_and_split_independent(void **state)
{
    (void)state;
    enum { N = 20000 };
    static double v[N], w[N];
    uint64_t s = 99;
    for (size_t i = 0; i < N; i++)
        v[i] = rnd(&s, i % 2 ? 300 : 8);
    const double ref = xsum_of(v, N);
    /* reversed */
    for (size_t i = 0; i < N; i++)
        w[i] = v[N - 1 - i];
    assert_true(same_bits(xsum_of(w, N), ref));
    /* shuffled (Fisher-Yates) */
    for (size_t i = N - 1; i > 0; i--) {
        size_t j = (size_t)(rng_next(&s) % (i + 1));
        double t = w[i];
        w[i] = w[j];
        w[j] = t;
    }
    assert_true(same_bits(xsum_of(w, N), ref));
    /* split into uneven chunks, merged (threads, ranks) */
    struct xsum total, part;
    xsum_init(&total);
    size_t at = 0;
    while (at < N) {
        size_t len = 1 + (size_t)(rng_next(&s) % 3000);
        xsum_init(&part);
        for (size_t i = at; i < at + len && i < N; i++)
            xsum_add(&part, w[i]);
        xsum_merge(&total, &part);
        at += len;
    }
    assert_true(same_bits(xsum_round(&total), ref));
    /* rounding does not change the value: rounding twice gives the same */
    assert_true(same_bits(xsum_round(&total), ref));
}

static void test_cancellation_and_ranges(void **state)
{
    (void)state;
    double a[] = {1e300, 1.0, -1e300};
    assert_true(same_bits(xsum_of(a, 3), 1.0));
    double b[] = {DBL_MAX, DBL_MAX, -DBL_MAX}; /* the partial sum exceeds DBL_MAX */
    assert_true(same_bits(xsum_of(b, 3), DBL_MAX));
    double c[] = {DBL_MAX, DBL_MAX};
    assert_true(isinf(xsum_of(c, 2)) && xsum_of(c, 2) > 0);
    double c2[] = {-DBL_MAX, -DBL_MAX};
    assert_true(isinf(xsum_of(c2, 2)) && xsum_of(c2, 2) < 0);
    double d[] = {DBL_TRUE_MIN, DBL_TRUE_MIN, 3 * DBL_TRUE_MIN};
    assert_true(same_bits(xsum_of(d, 3), 5 * DBL_TRUE_MIN));
    double e[] = {DBL_MIN, -DBL_TRUE_MIN};
    assert_true(same_bits(xsum_of(e, 2), DBL_MIN - DBL_TRUE_MIN));
    /* ten times fl(0.1) is 1 + 5.55e-17 exactly, which rounds to 1 (the
     * running double sum gives 0.9999999999999999) */
    double f[10];
    for (int i = 0; i < 10; i++)
        f[i] = 0.1;
    assert_true(same_bits(xsum_of(f, 10), 1.0));
    double g[] = {-0.75, 0.25, -1e-20};
    assert_true(same_bits(xsum_of(g, 3), -0.5 - 1e-20));
    assert_true(same_bits(xsum_of(NULL, 0), 0.0));
    double z[] = {-0.0, 0.0};
    assert_true(xsum_of(z, 2) == 0.0);
}

static void test_non_finite_terms(void **state)
{
    (void)state;
    double a[] = {1.0, INFINITY, 2.0};
    assert_true(isinf(xsum_of(a, 3)) && xsum_of(a, 3) > 0);
    double b[] = {1.0, -INFINITY};
    assert_true(isinf(xsum_of(b, 2)) && xsum_of(b, 2) < 0);
    double c[] = {INFINITY, -INFINITY};
    assert_true(isnan(xsum_of(c, 2)));
    double d[] = {1.0, NAN, 3.0};
    assert_true(isnan(xsum_of(d, 3)));
    /* merged: one part infinite, the other finite */
    struct xsum p, q;
    xsum_init(&p);
    xsum_init(&q);
    xsum_add(&p, 5.0);
    xsum_add(&q, -INFINITY);
    xsum_merge(&p, &q);
    assert_true(isinf(xsum_round(&p)) && xsum_round(&p) < 0);
}

static void test_many_terms_carry(void **state)
{
    (void)state;
    /* past the adds at which carries are propagated (2^28), with terms
     * whose bits straddle two digits, and negative terms */
    struct xsum a;
    xsum_init(&a);
    const long n = (1L << 28) + 1000;
    const double x = 0x1.fffffffffffffp+31; /* 53 ones spanning three digits */
    for (long i = 0; i < n; i++)
        xsum_add(&a, i % 2 ? x : -0.5 * x);
    /* exactly (n/2) (x/2); one IEEE product of the two (both exact
     * doubles) is that value correctly rounded, as the sum must be */
    assert_true(same_bits(xsum_round(&a), (double)(n / 2) * (0.5 * x)));
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_two_terms_round_like_ieee),
        cmocka_unit_test(test_exact_error_of_two_sum),
        cmocka_unit_test(test_order_and_split_independent),
        cmocka_unit_test(test_cancellation_and_ranges),
        cmocka_unit_test(test_non_finite_terms),
        cmocka_unit_test(test_many_terms_carry),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
