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
#include <string.h>

/** Digits of 32 bits: weight of digit k is 2^(32 k - 1074); 66 digits
 *  reach 2^1038, beyond the largest finite double. */
#define XSUM_DIGITS 66
/** Words of an accumulator: the digits, then the counts of +inf, -inf and
 *  NaN terms, then the adds since the last carry propagation. */
#define XSUM_WORDS (XSUM_DIGITS + 4)

struct xsum {
    int64_t w[XSUM_WORDS];
};

/* word indices after the digits */
#define XSUM_PINF XSUM_DIGITS
#define XSUM_NINF (XSUM_DIGITS + 1)
#define XSUM_NAN (XSUM_DIGITS + 2)
#define XSUM_ADDS (XSUM_DIGITS + 3)
/* adds before the carries must be propagated: each add changes a digit by
 * less than 2^33, so 2^28 adds stay far below 2^63 */
#define XSUM_MAX_ADDS (INT64_C(1) << 28)
#define XSUM_LOW32 UINT64_C(0xffffffff)

/** Empty accumulator (sum 0). */
void xsum_init(struct xsum *a);
/** Propagate the carries (the integer value is unchanged); xsum_add and
 *  xsum_merge call it when needed, callers only before merging words by
 *  hand (an MPI reduction). */
void xsum_normalize(struct xsum *a);
/** Add one term (any double: NaN and infinities are counted, and the
 *  result follows IEEE rules for them).  Inline: it sits in the loops over
 *  all particles (damping work every step).
 *
 * A finite x is m 2^(e - 1075) with an integer m < 2^53 and e = max(biased
 * exponent, 1): its bits start at offset e - 1 from 2^-1074, so it lands on
 * digits k = off / 32 to k + 2. */
static inline void xsum_add(struct xsum *a, double x)
{
    uint64_t bits;
    memcpy(&bits, &x, sizeof bits);
    const int neg = (int)(bits >> 63);
    const int ebits = (int)((bits >> 52) & 0x7ff);
    uint64_t m = bits & ((UINT64_C(1) << 52) - 1);
    if (ebits == 0x7ff) { /* infinity or NaN: counted, not summed */
        a->w[m ? XSUM_NAN : (neg ? XSUM_NINF : XSUM_PINF)]++;
        return;
    }
    if (ebits)
        m |= UINT64_C(1) << 52;
    if (!m)
        return;
    const int off = ebits ? ebits - 1 : 0;
    const int k = off >> 5, sh = off & 31;
    const uint64_t lo = (m & XSUM_LOW32) << sh; /* < 2^64 */
    const uint64_t hi = (m >> 32) << sh;        /* < 2^53 */
    const int64_t d0 = (int64_t)(lo & XSUM_LOW32);
    const int64_t d1 = (int64_t)((lo >> 32) + (hi & XSUM_LOW32));
    const int64_t d2 = (int64_t)(hi >> 32);
    if (neg) {
        a->w[k] -= d0;
        a->w[k + 1] -= d1;
        a->w[k + 2] -= d2;
    } else {
        a->w[k] += d0;
        a->w[k + 1] += d1;
        a->w[k + 2] += d2;
    }
    if (++a->w[XSUM_ADDS] >= XSUM_MAX_ADDS)
        xsum_normalize(a);
}

/** a += b (b unchanged): merging partial sums of any split. */
void xsum_merge(struct xsum *a, const struct xsum *b);
/** The exact sum rounded to the nearest double (ties to even); +-inf when
 *  it exceeds the double range or an infinite term was added, NaN after a
 *  NaN or both infinities.  Results below 2^-1022 (subnormal) may be
 *  rounded twice.  @p a is normalised in place; its value is unchanged. */
double xsum_round(struct xsum *a);

#endif
