/**
 * @file exact_sum.c
 * @brief Exact fixed-point accumulation of doubles (exact_sum.h).
 *
 * A finite double is m 2^e with an integer m < 2^53 and e >= -1074, so
 * every double is an integer multiple of 2^-1074: the sum of any doubles
 * is an integer in those units, held here in base 2^32.  A term lands on
 * three consecutive digits (53 bits shifted by up to 31); digits are int64
 * so that carries can wait (each add changes a digit by less than 2^33, so
 * 2^28 adds stay far below 2^63).
 */
#include "core/exact_sum.h"

#include <math.h>
#include <string.h>

#define LOW32 XSUM_LOW32

void xsum_init(struct xsum *a)
{
    memset(a, 0, sizeof *a);
}

void xsum_normalize(struct xsum *a)
{
    int64_t carry = 0;
    for (int k = 0; k < XSUM_DIGITS - 1; k++) {
        int64_t v = a->w[k] + carry;
        /* floor division by 2^32 without shifting a negative value */
        int64_t low = (int64_t)((uint64_t)v & LOW32);
        carry = (v - low) / (INT64_C(1) << 32);
        a->w[k] = low;
    }
    a->w[XSUM_DIGITS - 1] += carry; /* the top digit keeps the sign */
    a->w[XSUM_ADDS] = 0;
}

void xsum_merge(struct xsum *a, const struct xsum *b)
{
    struct xsum t = *b;
    xsum_normalize(&t);
    xsum_normalize(a);
    for (int k = 0; k < XSUM_DIGITS; k++)
        a->w[k] += t.w[k];
    for (int k = XSUM_PINF; k <= XSUM_NAN; k++)
        a->w[k] += t.w[k];
    a->w[XSUM_ADDS] = 2; /* digits below 2^33: as after two adds */
}

double xsum_round(struct xsum *a)
{
    const int64_t pinf = a->w[XSUM_PINF], ninf = a->w[XSUM_NINF];
    if (a->w[XSUM_NAN] || (pinf && ninf))
        return NAN;
    if (pinf || ninf)
        return pinf ? INFINITY : -INFINITY;
    xsum_normalize(a);
    /* magnitude in non-negative digits: negate a negative sum and carry */
    struct xsum t = *a;
    const int neg = t.w[XSUM_DIGITS - 1] < 0;
    if (neg) {
        for (int k = 0; k < XSUM_DIGITS; k++)
            t.w[k] = -t.w[k];
        xsum_normalize(&t);
    }
    if (t.w[XSUM_DIGITS - 1] > (int64_t)LOW32) /* at least 2^1038 */
        return neg ? -INFINITY : INFINITY;
    int h = XSUM_DIGITS - 1;
    while (h >= 0 && t.w[h] == 0)
        h--;
    if (h < 0)
        return 0.0;
    /* the top 64 bits from digits h, h-1, h-2 (zero below digit 0), the
     * leading one at bit 63, and every lower bit folded into a sticky bit
     * 0 so that the conversion to double rounds once and correctly */
    const uint64_t d2 = (uint64_t)t.w[h];
    const uint64_t d1 = h >= 1 ? (uint64_t)t.w[h - 1] : 0;
    const uint64_t d0 = h >= 2 ? (uint64_t)t.w[h - 2] : 0;
    uint64_t u = d2 << 32 | d1;
    int lz = 0;
    while (!(u & (UINT64_C(1) << 63))) {
        u <<= 1;
        lz++;
    }
    uint64_t rest = d0;
    if (lz) {
        u |= d0 >> (32 - lz);
        rest = d0 & ((UINT64_C(1) << (32 - lz)) - 1);
    }
    for (int k = h - 3; k >= 0 && !rest; k--)
        rest = (uint64_t)t.w[k];
    if (rest)
        u |= 1;
    /* u counts units of 2^(32 (h - 1) - 1074 - lz) */
    double r = ldexp((double)u, 32 * (h - 1) - 1074 - lz);
    return neg ? -r : r;
}
