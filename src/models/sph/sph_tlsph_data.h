/**
 * @file sph_tlsph_data.h
 * @brief Private to the total-Lagrangian SPH files (sph_tlsph.c, the hot
 *        sweep; sph_tlsph_ref.c, the reference configuration): the packed
 *        per-particle blocks, the pair constants and the CPU versions.
 */
#ifndef SPALL_SPH_TLSPH_DATA_H
#define SPALL_SPH_TLSPH_DATA_H

#include "models/sph/sph_internal.h"

#include <stdbool.h>
#include <stddef.h>
#include <string.h>

/* The hot sweep in two versions, picked once at load time by the CPU
 * (GCC function multi-versioning, an ifunc): x86-64-v3 (AVX2, FMA) and the
 * build's baseline.  Every thread runs the same version, so the results
 * stay bitwise thread independent; FMA contraction changes the rounding
 * against the baseline version (docs/performance.md, "TLSPH speed: how
 * the sweep is built").  SPALL_NO_CLONES builds the baseline only. */
#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__) && defined(__linux__) &&     \
    !defined(SPALL_NO_CLONES)
#define TL_CLONES __attribute__((target_clones("arch=x86-64-v3", "default")))
#define TL_CLONED 1
#else
#define TL_CLONES
#endif
#if defined(__GNUC__)
#define TL_INLINE static inline __attribute__((always_inline))
#else
#define TL_INLINE static inline
#endif

#ifdef TL_CLONED
/* Four doubles as one value (GCC vector extension), used by the x86-64-v3
 * version only (t->wide: the baseline version would run it as two SSE
 * halves through memory, 1.8x slower); never passed by value (-Wpsabi);
 * loaded from any 8-byte boundary. */
#define TL_HAVE_V4 1
typedef double tl_v4 __attribute__((vector_size(4 * sizeof(double))));
static inline void tl_madd4(tl_v4 *acc, const double *p, const double *q, double x)
{
    tl_v4 a, b;
    memcpy(&a, p, sizeof a);
    memcpy(&b, q, sizeof b);
    *acc += (a + b) * x; /* *acc += (p + q) x, lane by lane */
}
#endif

/* Reference-configuration constants of a pair (rebuilt only on a re-reference).
 * X_i - X_j is gathered from the packed block instead (x0 shares its cache
 * line with v and V0): the pair stream was the stall of pass 1. */
struct tl_pair {
    double F;    /**< (dW/dr) / r of the reference kernel */
    double hg;   /**< kappa (E_i + E_j)/2 V0_i V0_j W / |X_ij|^2 */
};

/* The pairs [k0, k1) of a row: partner nb[k], constants pair[k] (the
 * reference row's upper part; a distributed run also evaluates single
 * pairs in the partner's orientation, sph_tlsph_par.c). */
struct tl_span {
    size_t k0, k1;
    const int32_t *nb;
    const struct tl_pair *pair;
};

/* What a pair loop gathers from partner j, packed in one block per
 * particle (4 cache lines) instead of 26 separate arrays: the SoA layout
 * spilled the array pointers and touched a line per array and partner.
 * Refreshed each step from the SoA state (O(N)). */
enum { TL_Q = 0, TL_FD = 9, TL_X = 18, TL_V = 21, TL_C = 24, TL_RHO, TL_H, TL_M, TL_VOL,
       TL_X0 = 29, TL_STRIDE = 32 };

/* What only particle i itself reads and writes, one block instead of 13
 * arrays (13 streams in the sweep): B0^-1; the stage-2 accumulators (force
 * and sum f_ij . v_ij) into which the lower rows scatter; the stress power
 * P : dF/dt; Balsara's factor f (model.viscosity_switch, read by the rows
 * of i's partners, written in i's stage 1 like Q). */
enum { TL_BI = 0, TL_ACC = 9, TL_FV = 12, TL_PW = 13, TL_SW = 14, TL_SELF = 16 };

struct sph_tl {
    struct neighbor_list *nl; /**< reference-configuration list (fixed) */
    double *self;         /**< per particle, TL_SELF doubles: B0^-1, accumulators, P : dF/dt */
    double *pk;           /**< per particle, TL_STRIDE doubles (TL_Q ...) */
    struct tl_pair *pair; /**< per listed pair, same index as the neighbour list */
    size_t *up;           /**< per particle: first list index of row i with j > i */
    size_t band;          /**< max |j - i| over the list: the pipeline's lag */
    bool wide;            /**< the CPU runs the x86-64-v3 version (TL_CLONES) */
    /* distributed runs only (sph_localize.c; NULL otherwise) */
    int32_t *rown;        /**< per listed pair: its row's particle (a pair's reverse row) */
    struct tl_pair *prev; /**< per listed pair (i, j): the constants of (j, i) in j's row */
    double *halo;         /**< TL_HALO doubles per particle: stage-1 values for the ghosts */
    int64_t *rgid;        /**< per listed pair: the partner's global id (the rows are
                               renumbered after each spatial ghost build, sph_localize.c) */
};

/* What a ghost needs of its owner's stage 1: the packed block up to TL_H
 * (Q, Fd, x, v, c, rho, h) and Balsara's factor. */
enum { TL_HALO = TL_H + 2 };

#endif
