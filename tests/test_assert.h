/**
 * @file test_assert.h
 * @brief Double-precision comparison for the cmocka tests.  Include after
 *        <cmocka.h>.
 *
 * cmocka's assert_float_equal casts its operands and the tolerance to float,
 * so a check written at 1e-12 is really made at float precision (~1e-7); the
 * tests use assert_near instead.
 */
#ifndef SPALL_TEST_ASSERT_H
#define SPALL_TEST_ASSERT_H

#include <math.h>

/** |a - b| <= tol in double precision; prints both values on failure. */
#define assert_near(a, b, tol)                                                                     \
    do {                                                                                           \
        const double a_ = (a), b_ = (b), tol_ = (tol);                                             \
        if (!(fabs(a_ - b_) <= tol_)) {                                                            \
            print_error("%s = %.15e, %s = %.15e: |difference| %.3e > %.3e\n", #a, a_, #b, b_,       \
                        fabs(a_ - b_), tol_);                                                      \
            fail();                                                                                \
        }                                                                                          \
    } while (0)

#endif
