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

#define XSUM_PINF XSUM_DIGITS
#define XSUM_NINF (XSUM_DIGITS + 1)
#define XSUM_NAN (XSUM_DIGITS + 2)
#define XSUM_ADDS (XSUM_DIGITS + 3)
/* adds before the carries must be propagated (see the file comment) */
#define XSUM_MAX_ADDS (INT64_C(1) << 28)
#define LOW32 UINT64_C(0xffffffff)

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

void xsum_add(struct xsum *a, double x)
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
    /* x = m 2^(e - 1075) with e = max(ebits, 1): bit offset from 2^-1074 */
    const int off = ebits ? ebits - 1 : 0;
    const int k = off >> 5, sh = off & 31;
    const uint64_t lo = (m & LOW32) << sh; /* < 2^64 */
    const uint64_t hi = (m >> 32) << sh;   /* < 2^53 */
    const int64_t d0 = (int64_t)(lo & LOW32);
    const int64_t d1 = (int64_t)((lo >> 32) + (hi & LOW32));
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
