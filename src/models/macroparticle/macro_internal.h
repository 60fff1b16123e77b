/**
 * @file macro_internal.h
 * @brief Private state and inline kernels of the macro-particle model.
 */
#ifndef SPALL_MACRO_INTERNAL_H
#define SPALL_MACRO_INTERNAL_H

#include "models/macroparticle/macro_calib.h"

#include <math.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

struct neighbor_list;
struct spall_error;
struct sim;

enum macro_damping { MACRO_DAMP_NONE, MACRO_DAMP_ABSOLUTE, MACRO_DAMP_PAIRWISE };

/** Per-material input (deck). */
struct macro_material {
    bool parsed;
    double atom_mass;   /**< kg */
    double e0;          /**< J per atom */
    double p, q;        /**< Mie exponents */
    double theta_d;     /**< Debye temperature [K] */
    double yield_strain;/**< pair elastic stretch / r0 at yield (0 = elastic) */
    double hardening;   /**< plastic tangent / elastic pair stiffness, in [0, 1) */
    double e_target;    /**< calibration lattice: target E_[100] [Pa] (0: Eq. 15) */
};

/** Pair constants of one material (one material per run: mixed pairs use
 *  material 0's shape; see macro_model.c). */
struct macro_pair {
    double D, p, q, r0;
    double r_on, r_c;   /**< taper start and cut-off [m] */
    double e_y;         /**< yield elastic stretch [m] (INFINITY: elastic) */
    int ip, iq;         /**< p, q when both are integers <= 32 (fast powers), else 0 */
    double h;           /**< hardening in stretch units, t/(1-t) */
};

struct model {
    struct sim *sim;
    /* options */
    double cutoff_ratio;   /**< r_c / r0 */
    double taper_ratio;    /**< r_on / r0 */
    double skin_ratio;     /**< skin / r0 */
    enum macro_damping damping;
    double temperature;    /**< K */
    double gamma;          /**< absolute coefficient [kg/s] (0: from Debye) */
    double mu;             /**< pairwise coefficient [kg/s] (0: from Debye) */
    double zeta_cg, eta_cg;
    int axis;              /**< loading axis for the history's strain */
    enum macro_calibration calibration; /**< how D is set (macro_calib.h) */
    /* materials */
    struct macro_material *mat;
    size_t n_mat;
    struct macro_calib cal; /**< material 0 at the lattice spacing */
    struct macro_pair pp;
    double gamma_used, mu_used;
    /* neighbours */
    struct neighbor_list *nl;
    struct neighbor_list *nl0; /**< reference nearest neighbours (x0, 1.1 r0): slip fields */
    double *xb[3];         /**< positions at the last build */
    double *dr0;           /**< per full-list slot: plastic offset [m] */
    double *kappa;         /**< per slot: accumulated plastic slip [m] */
    uint8_t *engaged;      /**< per slot: 1 once the pair was inside its yield surface */
    long n_calls;          /**< force evaluations so far (random-stream counter) */
    size_t n_builds;
    /* per-particle outputs of the last force evaluation */
    double *epot;          /**< J */
    double *sig;           /**< 6 per particle: virial xx yy zz xy yz xz (times volume) */
    double *wdiss;         /**< per particle dissipated energy [J] (Langevin + plastic) */
    /* strain gauge */
    size_t *lo_idx, *hi_idx, *mid_idx;
    size_t n_lo, n_hi, n_mid;
    double gauge0, spread0;
    double volume;         /**< sum of particle volumes [m^3] */
    bool initialised;
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

/** Counter-based generator: a stateless hash of (seed, step, a, b, k)
 *  (SplitMix64 finaliser rounds), so a stream is a pure function of its key:
 *  reproducible and independent of the thread count and visiting order. */
static inline uint64_t macro_mix(uint64_t z)
{
    z += 0x9e3779b97f4a7c15ULL;
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
}

/** Three standard normal numbers for key (seed, step, a, b). */
static inline void macro_gauss3(uint64_t seed, uint64_t step, uint64_t a, uint64_t b,
                                double out[3])
{
    uint64_t h = macro_mix(seed ^ macro_mix(step ^ macro_mix(a ^ macro_mix(b))));
    double u[4];
    for (int k = 0; k < 4; k++) {
        h = macro_mix(h + (uint64_t)k);
        u[k] = ((double)(h >> 11) + 0.5) * (1.0 / 9007199254740992.0); /* (0, 1) */
    }
    const double tp = 6.283185307179586;
    double r1 = sqrt(-2.0 * log(u[0])), r2 = sqrt(-2.0 * log(u[2]));
    out[0] = r1 * cos(tp * u[1]);
    out[1] = r1 * sin(tp * u[1]);
    out[2] = r2 * cos(tp * u[3]);
}

/** Cubic elastic constants of the perfect FCC lattice of pair @p w. */
struct macro_fcc_constants {
    double c11, c12, c44; /**< Born term [Pa] */
    double pressure;      /**< residual pressure at r0 [Pa] (0 with the first shell only) */
    double e100, nu100;   /**< Young's modulus and Poisson's ratio along [100] */
    int neighbours;       /**< sites inside the cut-off */
};

/** Lattice sum over every FCC site inside w->r_c (macro_lattice.c). */
int macro_fcc_elastic(const struct macro_pair *w, struct macro_fcc_constants *out,
                      struct spall_error *err);

int macro_compute_forces(struct model *m, struct sim *sim, struct spall_error *err);
int macro_neighbors_update(struct model *m, struct sim *sim, bool force, struct spall_error *err);

#endif
