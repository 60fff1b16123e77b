/**
 * @file pd_internal.h
 * @brief State of the peridynamics model shared by pd_model.c (life cycle,
 *        deck, fields), pd_forces.c (hot loop, breaking, energies) and
 *        pd_calib.c (micromoduli, critical stretches, patch test).
 *        Not part of the public interface.
 */
#ifndef SPALL_PD_INTERNAL_H
#define SPALL_PD_INTERNAL_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include "core/bond_list.h"
#include "core/mathconst.h"
#include "models/peridynamics/pd.h"
#include "models/peridynamics/pd_lps.h"

struct bond_list;
struct sim;
struct spall_error;

#define PD_MAX_MAT 8 /* bond type = (ma * n_mat + mb) * 2 + fiber must fit in uint8 */

/** Variants (deck `model.variant`). */
enum pd_variant {
    PD_PMB, /**< continuum PMB with a horizon delta = m dx (Silling & Askari 2005) */
    PD_PDLM /**< lattice variant of [PDLM2019]: triangular lattice, nearest neighbours */
};

/** How fiber bonds are chosen in an orthotropic lamina. */
enum pd_fiber_model {
    PD_FIBER_LATTICE, /**< bonds parallel to the fiber (rotated lattice, [PDLM2019]) */
    PD_FIBER_ANGULAR  /**< c(phi) = c_m + c_f cos^2n(phi): arbitrary fiber angles */
};

/** Quasi-static option (deck `model.quasi_static`). */
enum pd_quasi { PD_QS_OFF, PD_QS_ADR };

struct pd_options {
    enum pd_variant variant;
    bool lps;                /**< formulation lps or eps: linear peridynamic solid (pd_lps.c) */
    bool eps;                /**< formulation eps: with deviatoric plasticity (pd_eps.c) */
    enum pd_plane plane;
    double horizon_factor;   /**< m: delta = m dx (PMB) */
    bool partial_volume;     /**< beta_ij for bonds cut by the horizon */
    bool break_late;         /**< a bond past s0 acts once more (PDLAMMPS order) */
    bool full_bonds;         /**< bond_storage full: no compact families (pd_compact.c) */
    bool family_at_delta;    /**< family ends at delta, not delta + dx/2 (PDLAMMPS rule) */
    bool cell_volumes;       /**< partial_volume_rule cell: beta = cut cell fraction (pd_cellvol.c) */
    bool surface_correction; /**< energy method (Madenci & Oterkus 2014 sec. 4.2) */
    enum pd_quasi quasi;
    enum pd_fiber_model fiber_model;
    int fiber_power;         /**< n of cos^2n (angular fiber model) */
    bool mixed_mode;         /**< laminae: matrix bonds by the BK mixed-mode G_c (pd_mixed.c) */
    double bk_exponent;      /**< Benzeggagh-Kenane exponent eta */
    bool fiber_plane;        /**< matrix_crack: fiber_plane (pd_plane.c) */
};

/** Law of the bonds between two materials (deck `model.interfaces`, pd_interface.c). */
struct pd_interface {
    char a[64], b[64];  /**< material names */
    double s0;          /**< critical stretch (0: from G, or the default) */
    double G;           /**< fracture energy [J/m^2] (0: none) */
    double stiffness;   /**< factor on the pair's micromodulus (formulation bond) */
};

struct model {
    struct sim *sim; /**< borrowed */
    struct pd_options opt;
    int dim;
    double dx;       /**< lattice spacing */
    double delta;    /**< horizon [m] */
    size_t n_mat;
    struct pd_material *mat;
    double s0_tab[256];      /**< critical stretch per bond type; INFINITY: never breaks */

    struct bond_list *bl;    /**< family (type = (ma*n_mat+mb)*2 + fiber) */
    double *coef;            /**< per half-bond: c V_i V_j beta G / xi [N/m]; NULL when compact */
    /* compact families (pd_compact.c): bl->rest, bl->type and coef never built; a
     * 16-bit row per half-bond of a table of the distinct triples; read them
     * through pd_rest, pd_coef, pd_type */
    uint16_t *kind;          /**< per half-bond: row of the table, or NULL (arrays kept) */
    double *k_rest, *k_coef; /**< per row: reference length, coefficient */
    uint8_t *k_type;         /**< per row: bond type */
    size_t n_kind;
    size_t *n_init;          /**< per particle: bonds at t = 0 after pre-cracks (all types) */
    size_t *n_init_f;        /**< fiber bonds at t = 0 */
    double *diss;            /**< per particle: energy released by its broken bonds [J] */
    /* adaptive dynamic relaxation (Kilic & Madenci 2010) */
    double *f_prev[3];
    double adr_damping;    /**< ADR coefficient c_n [1/s] for the engine (pd_damping) */
    bool adr_estimated;    /**< adr_damping holds an estimate (else the engine keeps its own) */
    size_t n_half;
    /* mixed-mode matrix failure (pd_mixed.c): per particle factor on s0_m */
    double *mm_g;            /**< sqrt(G_c(beta_i) / G_Ic); 1 for isotropic particles */
    double *mm_beta;         /**< mode-II energy share beta_i of the last step */
    uint8_t mm_type[256];    /**< 1: matrix bond of a lamina with G_IIc != G_Ic */
    /* fiber-parallel matrix cracks (pd_plane.c) */
    uint8_t *twin;           /**< per half-bond: row slot of its zigzag neighbour on the
                                  same interface (PD_NO_TWIN: none) */
    uint8_t *fresh;          /**< per half-bond: broken by stretch this step */
    double *tw_gid;          /**< per particle, PD_PLANE_SLOTS: gids its twins name (scratch) */
    size_t tw_cap;           /**< particles tw_gid holds */
    bool mixed;              /**< some bond type uses the mixed-mode threshold */
    bool ortho;              /**< some material is orthotropic */
    struct pd_lps lps;       /**< formulation lps (pd_lps.c) */
    /* the once-per-bond loop (pd_half.c): what the row check found for the
     * list of generation half_gen with half_n owned rows */
    bool half_known;         /**< false: check the rows again (new list) */
    unsigned long half_gen;
    size_t half_n;
    size_t half_ring;        /**< ring entries per thread (power of 2); 0: rows unsuited */
    uint8_t *half_flags;     /**< per owned row: irregular, clean (pd_half.c) */
    double *half_buf;        /**< the threads' rings of row sums, all zero between calls */
    size_t half_buf_len;     /**< doubles in half_buf */
    bool half_off;           /**< pd_set_row_loop: the split kernel only */
    bool half_used;          /**< the last force call took the once-per-bond loop */
    struct pd_interface *ifc; /**< material-pair bond laws (pd_interface.c) */
    size_t n_ifc;
    bool initialised;
};

/** formulation eps, serial: the slot of the reverse half of half-bond @p s. */
static inline size_t pd_eps_rev(const struct model *m, size_t s)
{
    const size_t j = (size_t)m->bl->partner[s];
    return m->bl->offset[j] + (m->lps.rloc8 ? m->lps.rloc8[s] : m->lps.rloc[s]);
}
/** Reference length, coefficient and type of half-bond @p s in either layout. */
static inline double pd_rest(const struct model *m, size_t s)
{
    return m->kind ? m->k_rest[m->kind[s]] : m->bl->rest[s];
}
static inline double pd_coef(const struct model *m, size_t s)
{
    return m->kind ? m->k_coef[m->kind[s]] : m->coef[s];
}
static inline unsigned pd_type(const struct model *m, size_t s)
{
    return m->kind ? m->k_type[m->kind[s]] : m->bl->type[s];
}
/** The rest lengths, omega beta and types of formulation lps / eps in either
 *  storage, taken out of the model once per loop (a byte store in a loop
 *  would make the compiler reload them through m): row r = pd_lps_row(s). */
struct pd_lps_bonds {
    const uint16_t *kind;    /**< per half-bond row of the table, or NULL: r = s */
    const double *rest, *ob; /**< per row */
    const uint8_t *type;     /**< per row */
};
static inline struct pd_lps_bonds pd_lps_bonds(const struct model *m)
{
    if (m->kind)
        return (struct pd_lps_bonds){m->kind, m->k_rest, m->k_coef, m->k_type};
    return (struct pd_lps_bonds){NULL, m->bl->rest, m->lps.ob, m->bl->type};
}
static inline size_t pd_lps_row(const struct pd_lps_bonds *b, size_t s)
{
    return b->kind ? b->kind[s] : s;
}
/** omega beta of half-bond @p s (formulation lps / eps): in compact storage
 *  the table's coefficient column holds it (pd_lps_init, pd_lps.c). */
static inline double pd_ob(const struct model *m, size_t s)
{
    return m->kind ? m->k_coef[m->kind[s]] : m->lps.ob[s];
}

/* pd_compact.c */
/** Whether the built model could have compact families (false once it has
 *  them): run.log says why it has none. */
bool pd_compact_eligible(const struct model *m);
/** Whether pd_compact_build applies: the deck asks for nothing that needs
 *  per-half-bond arrays (known before any bond exists). */
bool pd_compact_predicted(const struct model *m);
/** The compact families built directly, one half-bond at a time, on a list
 *  from bond_list_build_compact, never holding the 8-byte lengths and
 *  coefficients (set-up peak memory): the table of the distinct triples in
 *  first-seen slot order.  Needs the material constants.  When the
 *  table overflows, leaves the arrays pd_build_coefficients expects (rest
 *  lengths and a zeroed type array) and m->kind NULL. */
int pd_compact_build(struct model *m, struct sim *sim, struct spall_error *err);

/** Bytes of one bond kind's key: rest length, coefficient (doubles), type. */
#define PD_KIND_KEY (2 * sizeof(double) + 1)

/** The model's kind arrays k_rest, k_coef, k_type (n_kind = @p nk) from a
 *  table of @p nk keys of PD_KIND_KEY bytes; @p tab is freed.  The arrays
 *  must be unset (NULL) on entry. */
int pd_kinds_from_table(struct model *m, unsigned char *tab, size_t nk,
                        struct spall_error *err);
/** A row of the compact families' table as the force kernels read it
 *  (bond-based pd_forces.c / pd_half.c and state-based pd_lps_kernel.c):
 *  one cache line for a half-bond's three doubles, the rest length, the
 *  k_coef column (the pair coefficient, or omega beta for lps / eps:
 *  pd_lps.c lps_build_kinds) and the breaking pre-test bound
 *  thr = s0 r PD_PRE with the thresholds of now. */
struct pd_kind_row {
    double rest, coef, thr;
    unsigned type;
};
/** The table for this force call (free it; NULL when the model keeps the
 *  per-half-bond arrays instead, m->kind NULL). */
int pd_kind_rows(const struct model *m, struct pd_kind_row **out, struct spall_error *err);
/** Bytes of the model's own arrays (families, coefficients, per-particle state)
 *  for @p n particles: the memory report of pd_describe. */
size_t pd_model_bytes(const struct model *m, size_t n);
/** Distributed set-up: the compact families' table the same on every rank
 *  (pd_setup_dist.c; collective). */
int pd_setup_tables(struct model *m, struct sim *sim, struct spall_error *err);

/* pd_interface.c */
struct deck_node;
/** Parse `model.interfaces` (names resolved at init). */
int pd_interfaces_parse(struct model *m, const struct deck_node *params,
                        struct spall_error *err);
/** Resolve the names and apply the laws to s0_tab and the pair coefficients
 *  (after the default table and the coefficients exist). */
int pd_interfaces_apply(struct model *m, struct sim *sim, struct spall_error *err);
/** Coefficient @p coef of a bond of @p type scaled as pd_interfaces_apply
 *  scales the coefficient array (for pd_compact_build). */
double pd_interface_scale(const struct model *m, const struct sim *sim, uint8_t type,
                          double coef);

/* pd_localize.c (distributed runs) */
struct model_energy;
int pd_localize(struct model *m, struct sim *sim, const size_t *keep, size_t n_keep,
                size_t n_owned, const int64_t *new_of_old, struct spall_error *err);
struct par_model_arrays;
int pd_migrate_arrays(struct model *m, struct par_model_arrays *a, struct spall_error *err);

/* pd_restart.c */
struct field_state;
int pd_register_state(struct model *m, struct sim *sim, struct field_state *fs,
                      struct spall_error *err);

/* pd_calib.c */
/** Stress of particle @p i (tension positive; 2D xx yy xy, 3D xx yy zz xy yz xz) and
 *  its strain energy [J] from the current positions (virial 1/2 sum F (x) xi / V_i). */
void pd_particle_eval(const struct model *m, const struct sim *sim, size_t i, double *energy,
                      double *stress);
/* pd_mixed.c */
/** Sets m->mm_type / m->mixed and allocates the per-particle arrays. */
int pd_mixed_init(struct model *m, struct sim *sim, struct spall_error *err);

/* pd_plane.c */
#define PD_NO_TWIN 255u   /* m->twin: the half-bond has no twin */
#define PD_PLANE_SLOTS 6  /* twins a particle names per step: a PDLM family has 6 bonds */
/** Twin table of the fiber-parallel matrix-crack rule (no-op when off). */
int pd_plane_init(struct model *m, struct sim *sim, struct spall_error *err);
/** Break the twins of this step's stretch-broken matrix bonds (any rank
 *  count: names the twins by gid through the halo; collective). */
int pd_plane_end_step(struct model *m, const struct sim *sim, struct spall_error *err);

/* pd_forces.c */
int pd_compute_forces(struct model *m, struct sim *sim, struct spall_error *err);
double pd_stable_dt(const struct model *m, const struct sim *sim);
/** Per-half-bond coefficients from the current c tables (beta, surface factor). */
int pd_build_coefficients(struct model *m, struct sim *sim, struct spall_error *err);
/** Directional surface-correction factors, 3 per particle (malloc'd), or
 *  NULL when the correction is off ([MadenciOterkus2014] Eq. 4.31). */
int pd_surface_factors(const struct model *m, const struct sim *sim, double **g,
                       struct spall_error *err);
/** Coefficient c V_i V_j beta corr / xi of half-bond @p s of particle @p i
 *  (@p g from pd_surface_factors); rest lengths in either storage. */
double pd_bond_coef(const struct model *m, const struct sim *sim, const double *g, size_t i,
                    size_t s);
/** Adaptive dynamic relaxation damping update (Kilic & Madenci 2010 Eq. 19):
 *  the new estimate in m->adr_damping, which the engine takes through the
 *  model's damping hook right after the force call. */
void pd_adr_update(struct model *m, const struct sim *sim);

/** Adds g (r (x) r0), symmetrised, to the Voigt stress sum @p sg (1D: xx;
 *  2D: xx yy xy; 3D: xx yy zz xy yz xz): the virial of one bond force g r
 *  over its reference vector r0, shared by the PMB and LPS stress
 *  recoveries. */
static inline void pd_add_bond_virial(double *sg, int dim, double g, const double r[3],
                                      const double r0[3])
{
    sg[0] += g * r[0] * r0[0];
    if (dim == 1)
        return;
    sg[1] += g * r[1] * r0[1];
    if (dim == 2) {
        sg[2] += 0.5 * g * (r[0] * r0[1] + r[1] * r0[0]);
        return;
    }
    sg[2] += g * r[2] * r0[2];
    sg[3] += 0.5 * g * (r[0] * r0[1] + r[1] * r0[0]);
    sg[4] += 0.5 * g * (r[1] * r0[2] + r[2] * r0[1]);
    sg[5] += 0.5 * g * (r[0] * r0[2] + r[2] * r0[0]);
}

/* The split bond kernels (pd_forces.c, pd_lps_kernel.c) -------------------- */

/** Vector loops in two versions picked once at load time by the CPU (GCC
 *  function multi-versioning, as sph_tlsph_data.h): x86-64-v3 (four
 *  doubles a vector) and the build's baseline.  The files are compiled
 *  without FP contraction (ISO C mode), so both versions round alike and
 *  the results do not depend on the CPU. */
#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__) && defined(__linux__) &&     \
    !defined(SPALL_NO_CLONES)
#define PD_CLONES __attribute__((target_clones("arch=x86-64-v3", "default")))
#else
#define PD_CLONES
#endif

/** Factor of the breaking pre-test e > s0 xi PD_PRE, which misses no
 *  half-bond of the exact test e / xi > s0: that needs e > s0 xi (1 -
 *  2^-53) in floating point. */
#define PD_PRE (1.0 - 1e-12)

/** A pre-test bound, or NaN when the half-bond is broken (state bit 0),
 *  without a branch: the bits of a quiet NaN or-ed into any double give a
 *  NaN. */
static inline double pd_thr_or_nan(double thr, uint8_t state)
{
    uint64_t b;
    memcpy(&b, &thr, sizeof b);
    b |= ((uint64_t)0 - (uint64_t)(state & BOND_BROKEN)) & UINT64_C(0x7ff8000000000000);
    memcpy(&thr, &b, sizeof thr);
    return thr;
}

#endif
