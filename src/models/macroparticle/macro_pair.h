/**
 * @file macro_pair.h
 * @brief The macro-particle pair law and its random forces as pure inline
 *        functions (public: the model's loops and the unit tests use the same
 *        code): the Mie pair with a C1 taper and the counter-based Gaussian
 *        stream of the Langevin thermostat.
 */
#ifndef SPALL_MACRO_PAIR_H
#define SPALL_MACRO_PAIR_H

#include "core/mathconst.h"

#include <Random123/philox.h>
#include <math.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

/** Pair constants of one material (one material per run: mixed pairs use
 *  material 0's shape; see macro_model.c). */
struct macro_pair {
    double D, p, q, r0;
    double r_on, r_c;   /**< taper start and cut-off [m] */
    double e_y;         /**< yield elastic stretch [m] (INFINITY: elastic) */
    int ip, iq;         /**< p, q when both are integers <= 32 (fast powers), else 0 */
    double h;           /**< hardening in stretch units, t/(1-t) */
};

/* ---- Mie pair with a C1 taper --------------------------------------------------- */

/** s^n for an integer n >= 0 by binary powering. */
static inline double macro_ipow(double s, int n)
{
    double r = 1.0, b = s;
    while (n) {
        if (n & 1)
            r *= b;
        b *= b;
        n >>= 1;
    }
    return r;
}

/** The cubic switch of macro_mie applied to the plain Mie energy @p pe and
 *  force @p pf at r > r_on (one place for the pair loop and macro_mie). */
static inline void macro_taper(const struct macro_pair *w, double r, double *pe, double *pf)
{
    double e = *pe, f = *pf;
    const double L = w->r_c - w->r_on, t = (r - w->r_on) / L;
    const double S = 1.0 - t * t * (3.0 - 2.0 * t), dS = -6.0 * t * (1.0 - t) / L;
    f = f * S - e * dS;
    e *= S;
    *pe = e;
    *pf = f;
}

/** Mie energy and force magnitude -dphi/dr at distance r for the shifted
 *  elastic coordinate; smooth cubic switch S(r) between r_on and r_c (the
 *  product phi S and its derivative vanish at r_c). */
static inline void macro_mie(const struct macro_pair *w, double r, double *phi, double *fr)
{
    const double s = w->r0 / r;
    double sp, sq;
    if (w->ip > 0) { /* integer exponents (all of Table 1): no pow() */
        sp = macro_ipow(s, w->ip);
        sq = macro_ipow(s, w->iq);
    } else {
        sp = pow(s, w->p);
        sq = pow(s, w->q);
    }
    const double a = w->D / (w->q - w->p);
    double e = a * (w->p * sq - w->q * sp);
    double f = a * w->p * w->q * (sq - sp) / r; /* -dphi/dr: > 0 repulsive */
    if (r > w->r_on)
        macro_taper(w, r, &e, &f);
    *phi = e;
    *fr = f;
}

/* ---- the same pair law over a chunk of pairs ---------------------------------- */

/* Forced inline: the pair loops' kernels are cloned per CPU level
 * (MACRO_CLONES); a call out of a clone would run the baseline code. */
#if defined(__GNUC__)
#define MACRO_PAIR_INLINE static inline __attribute__((always_inline))
#else
#define MACRO_PAIR_INLINE static inline
#endif

/** Most pairs a chunk of the pair loops (macro_forces.c: a row's slots,
 *  macro_half.c: consecutive pairs): the once-per-pair loop's arrays of a
 *  chunk (3 x 2 kB) stay in L1; 256 rather than 64 pairs a call spread the
 *  kernels' set-up over more pairs (1.1e6 instructions a step fewer on the
 *  race deck of bench/macro_vs_lammps.sh, docs/performance.md). */
#define MACRO_CHUNK 256

/** out[k] = s[k]^n for k < nb, n >= 1, by the multiplications of macro_ipow
 *  in the same order (the same bits), with n the same for every k so that
 *  the loops over k vectorise. */
static inline void macro_ipow_chunk(size_t nb, const double *restrict s, int n,
                                    double *restrict out)
{
    double b[MACRO_CHUNK];
    for (size_t k = 0; k < nb; k++) {
        out[k] = 1.0;
        b[k] = s[k];
    }
    while (n) {
        if (n & 1)
            for (size_t k = 0; k < nb; k++)
                out[k] *= b[k];
        n >>= 1;
        if (n)
            for (size_t k = 0; k < nb; k++)
                b[k] *= b[k];
    }
}

/** One distance of the exponents written out, 4-9 (@p lj false) or 6-12
 *  (@p lj true): macro_mie's energy and force without the switch, with
 *  macro_ipow's multiplications in its order (its first r = 1.0 * b is
 *  exact and left out), so the same bits.  GCC unrolls macro_ipow's loop
 *  only after the vectoriser has run, which would leave the chunk loops
 *  below scalar. */
MACRO_PAIR_INLINE void macro_mie_lane(double r0, double a, double p, double q, bool lj, double r,
                                      double *phi, double *fr)
{
    const double sk = r0 / r, s2 = sk * sk, s4 = s2 * s2, s8 = s4 * s4;
    const double spk = lj ? s2 * s4 : s4, sqk = lj ? s4 * s8 : sk * s8;
    *phi = a * (p * sqk - q * spk);
    *fr = a * p * q * (sqk - spk) / r;
}

/** 1: exponents 4-9 ([Saitoh]'s aluminium, every shipped material), 2: 6-12
 *  (Lennard-Jones), written out by macro_mie_lane; 0: others. */
static inline int macro_mie_fixed(const struct macro_pair *w)
{
    return w->ip == 4 && w->iq == 9 ? 1 : w->ip == 6 && w->iq == 12 ? 2 : 0;
}

/** macro_mie for nb <= MACRO_CHUNK distances r[k] in (0, r_c): energy
 *  phi[k] and force fr[k], bit for bit those of macro_mie (the same
 *  operations in the same order; the taper, rare in a crystal, in a scalar
 *  pass).  Loops without dependences between k, for the vectoriser.  At
 *  r[k] >= r_c (list slots the pair loop skips) the untapered values. */
MACRO_PAIR_INLINE void macro_mie_chunk(const struct macro_pair *w, size_t nb,
                                   const double *restrict r, double *restrict phi,
                                   double *restrict fr)
{
    double s[MACRO_CHUNK], sp[MACRO_CHUNK], sq[MACRO_CHUNK];
    const double r0 = w->r0, p = w->p, q = w->q, r_on = w->r_on, r_c = w->r_c;
    const double a = w->D / (q - p);
    const int fixed = macro_mie_fixed(w);
    /* exponents known here: one loop with the powers in registers; other
     * integer exponents power array by array, non-integer ones call pow() */
    if (fixed) {
        for (size_t k = 0; k < nb; k++)
            macro_mie_lane(r0, a, p, q, fixed == 2, r[k], &phi[k], &fr[k]);
    } else {
        for (size_t k = 0; k < nb; k++)
            s[k] = r0 / r[k];
        if (w->ip > 0) {
            macro_ipow_chunk(nb, s, w->ip, sp);
            macro_ipow_chunk(nb, s, w->iq, sq);
        } else {
            for (size_t k = 0; k < nb; k++) {
                sp[k] = pow(s[k], p);
                sq[k] = pow(s[k], q);
            }
        }
        for (size_t k = 0; k < nb; k++) {
            phi[k] = a * (p * sq[k] - q * sp[k]);
            fr[k] = a * p * q * (sq[k] - sp[k]) / r[k];
        }
    }
    /* the switch, for the few pairs in [r_on, r_c): a branch-free test of
     * the chunk first (vectorised), the scalar loop only when one is there */
    int any = 0;
    for (size_t k = 0; k < nb; k++)
        any |= (r[k] > r_on) & (r[k] < r_c);
    if (any)
        for (size_t k = 0; k < nb; k++)
            if (r[k] > r_on && r[k] < r_c)
                macro_taper(w, r[k], &phi[k], &fr[k]);
}

/** A pair's values in the once-per-pair loop (macro_half.c) from its energy
 *  e and force f at the elastic distance re, the distance rd and its square
 *  r2: half the energy *ph = 0.5 e (pass 2 adds it as the full loop adds
 *  0.5 phi, the same product) and *c = -f/rd, both +0 where the pair does
 *  not count (the full loop's tests, without short circuits for the
 *  vectoriser; NaN distances count; masks by bits, not a branch the
 *  vectoriser would have to keep around the division). */
MACRO_PAIR_INLINE void macro_pair_values(double r2, double rd, double re, double rlist2,
                                         double r_c, double e, double f, double *ph, double *c)
{
    const uint64_t ok = (uint64_t)(!(r2 >= rlist2) & (r2 != 0.0) & !(re >= r_c) & !(re <= 0.0));
    union { double d; uint64_t u; } ck = {.d = -f / rd}, pk = {.d = 0.5 * e};
    ck.u &= -ok;
    pk.u &= -ok;
    *c = ck.d;
    *ph = pk.d;
}

/** macro_pair_values of nb <= MACRO_CHUNK pairs at distances rd[k] (squared
 *  r2[k]) and elastic distances re[k], with macro_mie's e and f at re[k]
 *  (the same bits as macro_mie_chunk's): for the written-out exponents in
 *  one loop, the pairs in [r_on, r_c) then made again with the switch
 *  (macro_mie, scalar: rare in a crystal); for the others after
 *  macro_mie_chunk. */
MACRO_PAIR_INLINE void macro_mie_pairs(const struct macro_pair *w, size_t nb,
                                       const double *restrict r2, const double *restrict rd,
                                       const double *restrict re, double rlist2,
                                       double *restrict ph, double *restrict c)
{
    const double r_on = w->r_on, r_c = w->r_c;
    const int fixed = macro_mie_fixed(w);
    if (!fixed) {
        double fk[MACRO_CHUNK];
        macro_mie_chunk(w, nb, re, ph, fk);
        for (size_t k = 0; k < nb; k++)
            macro_pair_values(r2[k], rd[k], re[k], rlist2, r_c, ph[k], fk[k], &ph[k], &c[k]);
        return;
    }
    const double r0 = w->r0, p = w->p, q = w->q, a = w->D / (q - p);
    int any = 0;
    for (size_t k = 0; k < nb; k++) {
        double e, f;
        macro_mie_lane(r0, a, p, q, fixed == 2, re[k], &e, &f);
        any |= (re[k] > r_on) & (re[k] < r_c);
        macro_pair_values(r2[k], rd[k], re[k], rlist2, r_c, e, f, &ph[k], &c[k]);
    }
    if (any)
        for (size_t k = 0; k < nb; k++)
            if (re[k] > r_on && re[k] < r_c) {
                double e, f;
                macro_mie(w, re[k], &e, &f);
                macro_pair_values(r2[k], rd[k], re[k], rlist2, r_c, e, f, &ph[k], &c[k]);
            }
}

/** Three standard normal numbers for key (seed, step, a, b), from the
 *  counter-based Philox4x64-10 generator of Random123 ([Salmon2011]):
 *  one call maps the counter (step, a, b) under key seed to four 64-bit
 *  words, so a stream is a pure function of its key -- reproducible and
 *  independent of the thread count, the rank count and the visiting order,
 *  with nothing to save on a checkpoint but the step. */
static inline void macro_gauss3(uint64_t seed, uint64_t step, uint64_t a, uint64_t b,
                                double out[3])
{
    philox4x64_ctr_t ctr = {{step, a, b, 0}};
    philox4x64_key_t key = {{seed, 0x5370616c6c4d6163ULL /* "SpallMac" */}};
    philox4x64_ctr_t w = philox4x64(ctr, key);
    double u[4];
    for (int k = 0; k < 4; k++)
        u[k] = ((double)(w.v[k] >> 11) + 0.5) * (1.0 / 9007199254740992.0); /* (0, 1) */
    const double tp = SPALL_TWO_PI;
    double r1 = sqrt(-2.0 * log(u[0])), r2 = sqrt(-2.0 * log(u[2]));
    out[0] = r1 * cos(tp * u[1]);
    out[1] = r1 * sin(tp * u[1]);
    out[2] = r2 * cos(tp * u[3]);
}

#endif
