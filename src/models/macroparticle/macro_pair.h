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

/** Mie energy and force magnitude -dphi/dr at distance r for the shifted
 *  elastic coordinate; smooth cubic switch S(r) between r_on and r_c (the
 *  product phi S and its derivative vanish at r_c). */
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
    if (r > w->r_on) {
        const double L = w->r_c - w->r_on, t = (r - w->r_on) / L;
        const double S = 1.0 - t * t * (3.0 - 2.0 * t), dS = -6.0 * t * (1.0 - t) / L;
        f = f * S - e * dS;
        e *= S;
    }
    *phi = e;
    *fr = f;
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
