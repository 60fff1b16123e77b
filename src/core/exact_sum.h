/**
 * @file exact_sum.h
 * @brief Exact, order-independent sums of doubles (issue 20).
 *
 * Why: a floating-point sum depends on the order of its terms, so a sum
 * split over threads or MPI ranks differs from the serial one in the last
 * digits unless the serial order is reproduced (which moved every term to
 * one place).  This accumulator holds the sum of its terms exactly, as a
 * fixed-point integer spanning the whole double range (2^-1074 to beyond
 * 2^1024), in 32-bit digits stored in int64 words so that many terms can
 * be added before a carry must be propagated.  Integer addition is
 * associative, so partial accumulators of any split (threads, ranks) merge
 * into the same integer, and xsum_round() returns that exact value rounded
 * once to the nearest double (ties to even): the correctly rounded sum,
 * independent of the order and of the decomposition.
 *
 * The words are plain int64 and merge by element-wise addition, so an MPI
 * run reduces an accumulator with one MPI_Allreduce(MPI_INT64_T, MPI_SUM)
 * of XSUM_WORDS words (core/parallel/psum.h).
 *
 * Cost: an add is a few integer operations on three words (about 3x a
 * double add); the accumulator is 560 bytes.
 */
#ifndef SPALL_CORE_EXACT_SUM_H
#define SPALL_CORE_EXACT_SUM_H

#include <stddef.h>
#include <stdint.h>

/** Digits of 32 bits: weight of digit k is 2^(32 k - 1074); 66 digits
 *  reach 2^1038, beyond the largest finite double. */
#define XSUM_DIGITS 66
/** Words of an accumulator: the digits, then the counts of +inf, -inf and
 *  NaN terms, then the adds since the last carry propagation. */
#define XSUM_WORDS (XSUM_DIGITS + 4)

struct xsum {
    int64_t w[XSUM_WORDS];
};

/** Empty accumulator (sum 0). */
void xsum_init(struct xsum *a);
/** Add one term (any double: NaN and infinities are counted, and the
 *  result follows IEEE rules for them). */
void xsum_add(struct xsum *a, double x);
/** a += b (b unchanged): merging partial sums of any split. */
void xsum_merge(struct xsum *a, const struct xsum *b);
/** Propagate the carries (the integer value is unchanged); xsum_add and
 *  xsum_merge call it when needed, callers only before merging words by
 *  hand (an MPI reduction). */
void xsum_normalize(struct xsum *a);
/** The exact sum rounded to the nearest double (ties to even); +-inf when
 *  it exceeds the double range or an infinite term was added, NaN after a
 *  NaN or both infinities.  Results below 2^-1022 (subnormal) may be
 *  rounded twice.  @p a is normalised in place; its value is unchanged. */
double xsum_round(struct xsum *a);

#endif
