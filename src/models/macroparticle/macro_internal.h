/**
 * @file macro_internal.h
 * @brief Private state and inline kernels of the macro-particle model.
 */
#ifndef SPALL_MACRO_INTERNAL_H
#define SPALL_MACRO_INTERNAL_H

#include "core/bond_list.h"
#include "models/macroparticle/macro_calib.h"
#include "models/macroparticle/macro_pair.h"

#include <math.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

struct neighbor_list;
struct neighbor_pairs;
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
    double *xb[3];         /**< positions at the last build (the list is built from them) */
    int64_t *pgid;         /**< per slot: the partner's global id (rows ascend in it) */
    struct bond_list mbl;  /**< the list lent to a migration (macro_par.c) */
    struct bond_list ckbl; /**< the owned rows of the list, as a checkpoint sees them */
    int32_t *ck_gid;       /**< per slot: the partner's gid, for a distributed checkpoint */
    size_t n_half;         /**< its slots */
    double *dr0;           /**< per full-list slot: plastic offset [m] */
    double *kappa;         /**< per slot: accumulated plastic slip [m] */
    uint8_t *engaged;      /**< per slot: 1 once the pair was inside its yield surface */
    bool pstate_read;      /**< the three above were read from a checkpoint (else they stay
                                zero in an elastic run, and a rebuild need not carry them) */
    long n_calls;          /**< force evaluations so far (random-stream counter) */
    /* the once-per-pair loop (macro_half.c): its pair list is made again
     * after each change of the neighbour list (half_ok cleared by
     * macro_adopt_pairs and a restart) */
    bool pair_full;        /**< deck pair_loop: full (both ends evaluate a pair) */
    bool half_ok;          /**< the arrays below describe the current list */
    struct neighbor_pairs *hnew; /**< the pair table of the last one-rank build, not yet
                                      taken by the loop (NULL: none; half_fill makes it) */
    size_t half_pairs, half_pair_cap; /**< pairs, allocated pairs */
    size_t *hoff;          /**< per owned row + 1: its pairs are [hoff[i], hoff[i+1]) */
    int32_t *hpi, *hpj;    /**< per pair: the end that computes it and the partner */
    size_t *hps, *hprs;    /**< per pair: its slot in row hpi and in row hpj (SIZE_MAX:
                                a ghost's row), plastic runs only */
    uint32_t *pid;         /**< per slot of the owned rows: its pair (< 2^32 pairs) */
    int32_t *hreach;       /**< one rank, where the threads' row ranges meet: [0, n) per
                                row the largest partner of the rows up to it (-1: none),
                                [n, 2n) the smallest of the rows from it on (INT32_MAX) */
    size_t *goff;          /**< 3D, per group of four owned rows + 1: its first step in
                                gidx and gpid (macro_half_rows.c) */
    int32_t *gidx;         /**< per step of a group, four lanes (one a row): the partner
                                of the row's slot (a row that has ended: the row itself) */
    uint32_t *gpid;        /**< the same: the slot's pair (a row that has ended: the zero
                                pair, index half_pairs) */
    size_t g_cap;          /**< allocated lanes of gidx and gpid */
    double *pc;            /**< per pair: c = -f/r (the force on hpi along x_j - x_i);
                                +0 when it does not count; one more, the zero pair: +0 */
    double *pphi;          /**< per pair: half its energy, 0.5 phi (each end's share);
                                +0 when it does not count; the zero pair's +0 */
    double *pwp;           /**< per pair: half its plastic work of this call (plastic runs) */
    double *pfl;           /**< 3 per pair: pairwise Langevin force on hpi (pairwise damping) */
    size_t n_builds;
    /* per-particle outputs of the last force evaluation */
    double *epot;          /**< J (rows below epot_lazy: not written, see there) */
    size_t epot_lazy;      /**< the once-per-pair loop in 3D left epot of its owned rows
                                [0, epot_lazy) unwritten (0: none): row i's energy is
                                macro_half_epot (its pairs' 0.5 phi summed over its slots
                                in list order, as pass 2 summed them: the same bits)
                                until the next force call; macro_half_epot_sync writes
                                them before the list or the particles' layout changes
                                and before a checkpoint */
    double *sig;           /**< 6 per particle: virial xx yy zz xy yz xz (times volume) */
    double *wdiss;         /**< per particle dissipated energy [J] (Langevin + plastic) */
    /* strain gauge */
    size_t *lo_idx, *hi_idx, *mid_idx;
    size_t n_lo, n_hi, n_mid;  /**< owned members (all of them on one rank) */
    size_t n_lo_all, n_hi_all, n_mid_all; /**< members over all ranks */
    uint8_t *gflag;        /**< per particle: 1 low layer, 2 high layer, 4 middle band
                                (travels with it; the index lists follow, macro_par.c) */
    double gauge0, spread0;
    double volume;         /**< sum of particle volumes [m^3] */
    bool initialised;
};

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

/* macro_restart.c */
struct field_state;
int macro_register_state(struct model *m, struct sim *sim, struct field_state *fs,
                         struct spall_error *err);
int macro_compute_forces(struct model *m, struct sim *sim, struct spall_error *err);
int macro_neighbors_update(struct model *m, struct sim *sim, bool force, struct spall_error *err);

/* The pair loops' vectorised kernels come in two versions picked once at
 * load time by the CPU (GCC function multi-versioning, as pd_forces.c):
 * x86-64-v3 (four doubles a vector) and the build's baseline; the files are
 * compiled without FP contraction (ISO C mode), so both round alike. */
#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__) && defined(__linux__) &&     \
    !defined(SPALL_NO_CLONES)
#define MACRO_CLONES __attribute__((target_clones("arch=x86-64-v3", "default")))
#else
#define MACRO_CLONES
#endif

/** Below this many particles a parallel region costs more than the pair
 *  loop (thousands of steps of a few hundred particles in the tests);
 *  results do not depend on it (each particle's sums run in a fixed order). */
#define MACRO_OMP_MIN 2048

/** Pair vectors x_j - x_i of the nb partners idx[k] of the particle at
 *  @p xi, their squared lengths and lengths (macro_forces.c). */
MACRO_CLONES void macro_chunk_geom(size_t nb, int dim, const double xi[3],
                                   double *const *restrict x, const int32_t *restrict idx,
                                   double *restrict gx, double *restrict gy, double *restrict gz,
                                   double *restrict r2, double *restrict r);

/* macro_half.c: each pair evaluated once, the sums in the order of the
 * full loop (the same bits) */
int macro_forces_half(struct model *m, struct sim *sim, struct spall_error *err);
void macro_half_free(struct model *m);
/** The list changed: the pair loop's arrays are made again at the next call
 *  (from @p pairs, the new list's table, when not NULL: taken over). */
void macro_half_invalidate(struct model *m, struct neighbor_pairs *pairs);
/** Owned row i's strain energy from the last force call's pair values
 *  (macro_half_rows.c). */
double macro_half_epot(const struct model *m, size_t i);
/** epot of the rows [0, m->epot_lazy) written (macro_half_epot), then
 *  epot_lazy = 0. */
void macro_half_epot_sync(struct model *m);
/** Owned particle i's strain energy of the last force call. */
static inline double macro_epot(const struct model *m, size_t i)
{
    return i < m->epot_lazy ? macro_half_epot(m, i) : m->epot[i];
}

/** The plastic update of one pair slot (Eq. 16, see macro_forces.c) at
 *  distance @p r; returns the elastic distance r - dr0 and adds the half of
 *  the plastic work that one end books to *wplast. */
static inline double macro_plastic_update(const struct macro_pair *w, double r, double *dr0,
                                          double *kap, uint8_t *eng, double *wplast)
{
    double el = r - w->r0 - *dr0;
    double lim = w->e_y + w->h * *kap;
    double a = fabs(el);
    if (!*eng) {
        /* a pair met at a large stretch (a second neighbour sliding in)
         * stays elastic until it enters the yield surface: it cannot be
         * "welded" at a wrong spacing */
        if (a <= lim)
            *eng = 1;
    } else if (r >= w->r_c) {
        /* separated: the pair forgets its plastic history */
        *dr0 = 0.0;
        *kap = 0.0;
        *eng = 0;
    } else if (a > lim) {
        double dd = (a - lim) / (1.0 + w->h);
        double sgn = el > 0.0 ? 1.0 : -1.0;
        *dr0 += sgn * dd;
        *kap += dd;
        double ph, fr;
        macro_mie(w, w->r0 + sgn * (lim + w->h * dd), &ph, &fr);
        *wplast += 0.5 * fabs(fr) * dd; /* half per end of the pair */
    }
    return r - *dr0;
}

/* macro_par.c: distributed runs (core/parallel/spatial.h) */
struct par_spatial_model;
int macro_list_build(struct model *m, struct sim *sim, bool count, struct spall_error *err);
int macro_localize(struct model *m, struct sim *sim, const size_t *keep, size_t n_keep,
                   size_t n_owned, const int64_t *new_of_old, struct spall_error *err);
int macro_spatial_ghosts(struct model *m, struct par_spatial_model *sp);
int macro_spatial_rebuilt(struct model *m, struct sim *sim, bool moved, struct spall_error *err);
struct par_model_arrays;
int macro_migrate_arrays(struct model *m, struct par_model_arrays *a, struct spall_error *err);
void macro_par_release(struct model *m);
/** Slip vectors and normals (3 per owned particle, either may be NULL) of
 *  a distributed run, equal to the one-rank values: the reference
 *  neighbours come from a ghost set built on the reference positions.
 *  Collective (every rank writes the frame); errors agreed. */
int macro_slip_par(const struct model *m, const struct sim *sim, double *slip, double *normal,
                   struct spall_error *err);
/** Replace the pair list and its per-pair state (partner gids, plastic
 *  offsets, hardening, engagement flags) by new ones, freeing the old. */
void macro_adopt_pairs(struct model *m, struct neighbor_list *nl, int64_t *pgid, double *dr0,
                       double *kappa, uint8_t *engaged);

#endif
