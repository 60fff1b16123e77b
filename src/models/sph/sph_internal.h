/**
 * @file sph_internal.h
 * @brief State of the SPH model ([Meng2021] chapter 3) shared by its files:
 *        sph_options.c (deck), sph_model.c (life cycle), sph_rates.c (pair loops),
 *        sph_material.c (EOS, Jaumann rate, yield, failure),
 *        sph_tlsph.c (total-Lagrangian variant).  Not a public interface.
 */
#ifndef SPALL_SPH_INTERNAL_H
#define SPALL_SPH_INTERNAL_H

#include "core/bond_list.h"
#include "models/sph/sph.h"
#include "models/sph/sph_kernels.h"
#include "models/sph/sph_options.h"

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

struct neighbor_list;
struct particles;
struct sim;
struct spall_error;

/** Read-only per-particle data the fused pair loop gathers over j: the
 *  model's own arrays, or real + mirrored ghost particles (symmetry). */
struct sph_pair_src {
    size_t n_all;
    const double *x[3], *v[3], *h, *rho, *c, *m2, *dx, *sr[6], *R[6];
};
struct sph_sym;
struct model;

/** The axisymmetric variant of the updated form (sph_axisym.c). */
struct sph_axisym_state {
    double *axl, *axl_s;   /**< axis weight lambda and its sweep scratch (per particle) */
    size_t builds;         /**< n_builds when the axis weights were last solved */
    double surface_z;      /**< initial top surface (cavity depth origin) */
};

/** The penalty interface between bodies or materials (sph_interface.c;
 *  the arrays are NULL when model.interface is none). */
struct sph_iface_state {
    size_t *off;           /**< n + 1: interface partners of i are idx[off[i] ..) */
    int32_t *idx;
    size_t cap;
    double *c0;            /**< per material: rest sound speed */
    double *e, *w;         /**< per particle: half its pairs' energy, sum k (1/mu_i + 1/mu_j) */
    uint32_t *np;          /**< per particle: pairs in contact */
    double energy;         /**< penalty energy [J] */
    size_t pairs;          /**< pairs in contact at the last force evaluation */
    double omega2;         /**< largest contact omega^2 (stable step) */
    size_t n_alloc;        /**< particles the per-particle arrays hold */
};

/** One formulation of the model ([Meng2021] ch. 3 updated Lagrangian;
 *  total Lagrangian, sph_tlsph*.c): what the model's hooks call for the
 *  particles on it.  A run holds one, or both when its bodies are split by
 *  formulation (sph_forms.c; TLSPH first: its stage writes the reference
 *  forces before the updated form and the interface add theirs). */
struct sph_formulation {
    const char *name;      /**< its model.formulation value */
    /** Lists at set-up: the current list with skin, or the reference list. */
    int (*init)(struct model *m, struct sim *s, struct spall_error *err);
    /** Rates and forces of its particles; @p lfdt > 0: the leapfrog's
     *  state advance by lfdt between the velocity gradient and the forces. */
    int (*rates)(struct model *m, struct sim *s, double lfdt, struct spall_error *err);
    /** End of a step (NULL: nothing). */
    int (*end_step)(struct model *m, struct sim *s, struct spall_error *err);
};
extern const struct sph_formulation sph_form_updated; /* sph_rates.c */
extern const struct sph_formulation sph_form_total;   /* sph_tlsph_ref.c */
struct sph_tl;
/** What the total-Lagrangian formulation keeps between steps (sph_tlsph*.c):
 *  m->tl, NULL in a run without TLSPH bodies, so that the updated form's
 *  model carries none of it. */
struct sph_tlsph {
    struct sph_tl *ref;    /**< reference list, pair constants, B0^-1 and the packed
                                blocks (sph_tlsph_data.h; rebuilt by a re-reference) */
    double jmin, kmax;     /**< smallest det F, largest distortion (last step) */
    size_t rerefs;         /**< reference updates so far (sph_tlsph_reref.c) */
    long reref_step;       /**< step of the last reference update (0: none) */
    double t_reref;        /**< wall seconds spent in reference updates */
    size_t hgrown;         /**< h growths (x1.2) at reference updates */
    struct bond_list *halo; /**< distributed runs: the reference list as bonds (sph_localize.c) */
    size_t n_half;         /**< its half-bonds (migration keeps the count) */
    size_t pairs_all;      /**< pairs of the whole body's reference list (its serial count) */
};
struct sph_clamp;
struct deck_node;


struct model {
    struct sim *sim; /**< borrowed */
    struct sph_options opt; /**< deck options (sph_options.h) */
    const struct sph_formulation *forms[2]; /**< the run's formulations, in call order */
    int n_forms;
    struct sph_loops loops; /**< pair loops the options (or a test) chose */
    int dim;
    double alpha;          /**< kernel alpha_d */
    double qmax;           /**< kernel support / h */
    size_t n_mat;
    struct sph_material *mat;

    /* per particle (SoA) */
    double *h, *dx;        /**< smoothing length, initial spacing */
    double *m2;            /**< mass per thickness (2D) or mass */
    double *rho, *e;       /**< density, specific internal energy */
    double *S[6];          /**< deviatoric stress */
    double *P;             /**< pressure (compression positive) */
    double *ep, *T;        /**< equivalent plastic strain, temperature */
    uint8_t *failed;
    double *c;             /**< sound speed */
    double *drho, *de, *dh, *dS[6];       /**< rates of step n+1 */
    double *rho_n, *e_n, *h_n, *S_n[6];   /**< state at step n (PC) */
    double *drho_n, *de_n, *dh_n, *dS_n[6]; /**< rates at step n */
    double *L[9];          /**< velocity gradient dv^a/dx^b, [a*3+b] */
    double *Bi[9];         /**< inverse CSPM matrix (identity on fallback) */
    double *sig[6];        /**< total stress (tension positive) + artificial stress */
    double *R[6];          /**< artificial stress tensor R_i */
    double *Rs[6];         /**< scratch of the R smoothing (sph_as_smooth.c) */
    double *sr[6];         /**< sigma / rho^2 (fused pair loop, sph_fused.c) */
    double *xv[3];         /**< XSPH velocity correction (the drift velocity, sph_drift_velocity) */
    double *x_build[3];    /**< positions at the last neighbour build */
    double *h_build;       /**< h at the last neighbour build, where h changes between
                                builds and a list is found again off its build step
                                (sph_h_build_kept; NULL otherwise) */
    double *wp;            /**< plastic work per particle [J] */

    struct sph_sym *sym;   /**< symmetry-plane ghosts (NULL: none) */
    struct sph_tlsph *tl;  /**< total-Lagrangian state (sph_tlsph*.c; NULL: no TLSPH body) */
    struct sph_clamp *clamp; /**< mirrored clamp (sph_clamp.c; NULL: none) */
    struct neighbor_list *nl;
    double nl_radius;
    /** the whole body's h_max at the last build: the interface split keeps
     *  the pairs within nl_radius - qmax nl_hmax of contact, and a partition,
     *  migration or restart between builds (variable h) must split with the
     *  build's value, not the h_max of the moment (sph_ulpar.c) */
    double nl_hmax;
    size_t n_builds;
    double t_neighbor;     /**< wall seconds spent building neighbour lists */
    size_t cspm_fallbacks; /**< particles whose CSPM matrix was singular (total) */
    size_t n_pairs;
    struct sph_iface_state ifs; /**< interface between bodies (sph_interface.c) */
    struct sph_axisym_state ax; /**< plane: axisymmetric (sph_axisym.c) */
    struct {
        double energy;     /**< penalty energy [J] */
        double force[3];   /**< total force [N] */
    } wall;                /**< the rigid wall (model.wall; sph_rates.c) */
    /* formulation per body (sph_forms.c) */
    uint8_t *body_total;   /**< per deck body: 1 = TLSPH */
    size_t n_bodies;
    uint8_t *form;         /**< per particle SPH_FORM_*: a run whose bodies are split
                                by formulation (NULL: one formulation, no split) */
    size_t n_total;        /**< particles on TLSPH when form is set (the whole body's) */
    size_t ul_pairs_all;   /**< distributed: the current list's pairs of the whole body at
                                its last build (sph_ulpar.c) */
    struct bond_list *ulmig; /**< distributed updated form: the empty bond list a
                                  migration is lent (sph_ulpar.c; NULL: none) */
    size_t ul_half;        /**< its half-bonds (none) */
    struct bond_list *ulview; /**< distributed updated form: the neighbour list seen as
                                   bonds (rows aliased, own zero states), the
                                   partition's work 1 + partners (sph_halo_bonds) */
    /* restart state (sph_restart.c) */
    struct bond_list ck_list;  /**< the owned rows of the neighbour list as bonds */
    struct bond_list ck_iface; /**< the owned rows of the interface list as bonds */
    int32_t *ck_gid, *ck_igid; /**< distributed runs: their partners by global id */
    struct bond_list ck_tl;    /**< distributed re-referencing TLSPH: the owned reference rows */
    int32_t *ck_tlgid;         /**< ... their partners by global id */
    int64_t *ck_tlup;          /**< ... each row's split in the serial list */
    int64_t ck_tlband;         /**< ... the serial list's band (max |gid_i - gid_j|) */
    int64_t sym_ghosts;        /**< symmetry planes: mirror ghosts of the last build (the
                                    whole body's, also on several ranks) */
    bool sym_restore;          /**< a checkpoint was loaded: the next force call rebuilds
                                    the ghosts and list of the last build
                                    (sph_symmetry_restore; on several ranks the list
                                    after the partition, sph_symmetry_list) */
    bool ulview_own;       /**< the view owns its rows (sph_ul_view_held: a serial
                                list with symmetry-plane images, which it leaves out) */
};

/** Formulation of a particle (m->form), and SPH_FORM_ALL for loops that
 *  run over every particle of a mixed run. */
enum { SPH_FORM_UPDATED = 0, SPH_FORM_TOTAL = 1, SPH_FORM_ALL = 2 };

/** Particle i belongs to the other formulation than @p mine: the loops of
 *  @p mine skip it.  Always false when the run has one formulation. */
static inline bool sph_skip(const struct model *m, size_t i, int mine)
{
    return m->form && mine != SPH_FORM_ALL && m->form[i] != mine;
}

#define SPH_N_ARRAYS 105
/** TLSPH bodies behind an interface whose reference updates grow h
 *  (reference_update with isotropy > 0, fixed h): the kernel list's trim
 *  reads each particle's h at the build, which a later re-reference may
 *  have grown, so a partition, migration, re-reference or restart that
 *  finds the list of the last build again off its build step trims with
 *  m->h_build and splits with the build's h_max (sph_ulpar.c); only such
 *  runs keep (and checkpoint) them. */
static inline bool sph_h_build_kept(const struct sph_options *o)
{
    return o->tl.split_forms && (o->tl.reref_every || o->tl.reref_distortion > 0.0) &&
           o->tl.reref_isotropy > 0.0 && !o->kern.variable_h;
}
/* sph_report.c: the model_ops entries that only read the state */
struct model_energy;
void sph_energy(const struct model *m, const struct sim *sim, struct model_energy *out);
size_t sph_history(const struct model *m, const struct sim *sim, const char **names,
                   double *values);
void sph_describe(const struct model *m, const struct sim *sim, char *buf, size_t len);
size_t sph_interactions(const struct model *m, const struct sim *sim);
/** Every per-particle double array of the model (sph_model.c): allocation,
 *  release and the restart state (sph_restart.c) walk the same list. */
size_t sph_state_arrays(struct model *m, double **a[SPH_N_ARRAYS]);
/* sph_restart.c */
struct field_state;
int sph_register_state(struct model *m, struct sim *s, struct field_state *fs,
                       struct spall_error *err);

/* sph_forms.c */
/** Formulation of every deck body: @p run_form (the model: 1 for tlsph) unless
 *  model.body_formulation names the body (bodies[].name); *body_total has
 *  *n_bodies entries (free it). */
int sph_forms_parse(const struct deck_node *params, int run_form, uint8_t **body_total,
                    size_t *n_bodies, struct spall_error *err);
/** m->form of every particle from its body. */
int sph_forms_init(struct model *m, struct sim *s, struct spall_error *err);
/** One run-log line: the formulation of every body and the particle counts. */
void sph_forms_describe(const struct model *m, const struct sim *s, char *buf, size_t len);

/* sph_rates.c */
/** Largest squared displacement of an owned particle since the last
 *  neighbour build (x - x_build): the skin test of sph_neighbors_update and
 *  sph_symmetry_update. */
double sph_max_move2(const struct model *m, const struct particles *p);
/** All rates of the current state: drho, de, dS, accelerations into sim->p->f. */
int sph_compute_rates(struct model *m, struct sim *s, struct spall_error *err);
/** Leapfrog (sph_leapfrog.c): the velocity gradient of the current state,
 *  the state advanced by @p dt with it, then the forces of the new state. */
int sph_compute_rates_kick(struct model *m, struct sim *s, double dt, struct spall_error *err);

/** Principal-axes artificial stress R_i of particle i from m->sig (Eqs. 2.25-2.27). */
void sph_artificial_stress(struct model *m, size_t i);

/* sph_as_smooth.c */

/* sph_fused.c */
/** One-pass rates (no CSPM, continuity density): same equations as the
 *  split passes of sph_compute_rates, one gather per pair. */
int sph_rates_fused(struct model *m, struct sim *s, struct spall_error *err);

/* sph_symmetry.c */
/** Refresh the mirrored ghosts (and the neighbour list over real + ghost
 *  particles when particles moved more than half the skin); fill @p src. */
int sph_symmetry_update(struct model *m, struct sim *s, struct sph_pair_src *src,
                        struct spall_error *err);
/** Free the ghost state; sets *sym to NULL. */
void sph_symmetry_destroy(struct sph_sym **sym);
/** After a checkpoint was loaded: the ghosts and the real + ghost list of
 *  the last build, found again at the build positions (m->x_build) with
 *  the list radius of that build, exactly as sph_symmetry_update made them
 *  then (not counted as a build). */
int sph_symmetry_restore(struct model *m, struct sim *s, struct spall_error *err);
/** Mirror ghosts of the last build (0 before the first). */
size_t sph_symmetry_ghosts(const struct model *m);
/** Distributed (sph_ulpar.c): the neighbour list over the held (owned and
 *  spatial ghost) particles and the images of those near a plane, at the
 *  build positions x_build with the radius m->nl_radius, images in
 *  ascending (source gid, mask); @p moved: an engine rebuild (the first
 *  one marks the ghosts built, as sph_symmetry_update's first call).
 *  Sets m->sym_ghosts to the whole body's image count (collective); after
 *  a checkpoint's load the list is the checkpointed build's, checked
 *  against the saved count. */
int sph_symmetry_list(struct model *m, struct sim *s, bool moved, struct spall_error *err);
/** Distributed: the images refreshed from their sources (after the halo
 *  of the fused loop); fill @p src. */
void sph_symmetry_src(struct model *m, struct sim *s, struct sph_pair_src *src);
/** Has the list over real and mirrored particles been built (the serial
 *  first force call builds it)? */
bool sph_symmetry_built(const struct model *m);

/* sph_clamp.c */
/** Parse model.clamp {group, point, normal}. */
int sph_clamp_parse(const struct deck_node *node, int dim, struct sph_clamp **out,
                    struct spall_error *err);
/** Find the mirror image of every clamp particle near the plane. */
int sph_clamp_init(struct model *m, struct sim *s, struct spall_error *err);
/** Before a force call: clamp particles take -v and the mirrored position of their image. */
void sph_clamp_begin(const struct model *m, struct sim *s);
/** Distributed: the same before the rebuild test and the halo of every
 *  force call (par_spatial_model.place), the images' x and v from their
 *  owners (collective). */
int sph_clamp_place(struct model *m, struct sim *s, struct spall_error *err);
/** Distributed: which clamp pairs have their clamp particle or their
 *  mirror among this rank's owned particles (after every partition and
 *  migration). */
int sph_clamp_localize(struct model *m, struct sim *s, struct spall_error *err);
/** Mirror-consistent stress of the clamp particles (after the stress pass;
 *  distributed: the images' values from their owners, collective). */
int sph_clamp_stress(const struct model *m, struct sim *s, struct spall_error *err);
/** After a force call: clamp particles back at rest at their reference positions. */
void sph_clamp_end(const struct model *m, struct sim *s);
/** Free; sets *pc to NULL. */
void sph_clamp_destroy(struct sph_clamp **pc);

/* sph_tlsph.c */
/** Reference neighbour list and corrected reference gradients (B0^-1). */
int sph_tlsph_init(struct model *m, struct sim *s, struct spall_error *err);
/** TLSPH rates: F, L, PK1 forces, energy, stress rates; with @p lfdt > 0
 *  the leapfrog's state advance by lfdt between L and the forces. */
int sph_tlsph_rates(struct model *m, struct sim *s, double lfdt, struct spall_error *err);
/** The reference list, pair constants and B0^-1 of configuration @p X with
 *  volumes m / @p rho (NULL: the materials' rho0); sph_tlsph_init passes
 *  p->x0, a re-reference the current x and rho.  F = I on @p X. */
int sph_tlsph_reference(struct model *m, struct sim *s, double *const X[3], const double *rho,
                        struct spall_error *err);
/** Free the TLSPH state; sets *tl to NULL. */
void sph_tlsph_destroy(struct sph_tlsph **tl);

/* sph_ulpar.c (distributed updated form on spatial ghosts, core/parallel/spatial.h) */
/** Drop the listed pairs beyond qmax max(h_i, h_j) + @p skin_abs at the
 *  positions @p x and smoothing lengths @p h of the build (sph_rates.c). */
void sph_neighbors_trim(struct model *m, double *const x[3], const double *h, double skin_abs);
/** The per-particle values a pair loop reads of its partners, by loop. */
enum sph_halo_set {
    SPH_HALO_DENSITY, /**< before the velocity gradient: rho, h */
    SPH_HALO_SPLIT,   /**< before pass_forces: rho, c, h, sigma (+ R, B^-1, L as used) */
    SPH_HALO_AS_SMOOTH, /**< before the smoothing of R: rho, h, R */
    SPH_HALO_FUSED,   /**< before the fused loop: rho, c, h, sigma / rho^2 (+ R) */
    SPH_HALO_AXI_GRADIENT, /**< axisymmetric, before the gradient: rho, h, m2 */
    SPH_HALO_AXI_FORCES    /**< axisymmetric, before the forces: rho, h, m2, c, lambda,
                                sigma, the (r, z) block of B^-1 (+ L) */
};
/** Hand the ghosts their owners' values of @p set (collective). */
int sph_par_halo(struct model *m, struct sim *s, enum sph_halo_set set, struct spall_error *err);
/** The same for @p w arrays of one's choice (a[k]: the address of array k). */
int sph_par_halo_arrays(struct sim *s, double **const *a, int w, struct spall_error *err);
/** The interface's energy (summed in gid order, the serial order), contact
 *  count and largest omega^2 of the whole body from this rank's
 *  (collective; sph_interface_forces). */
void sph_par_iface_totals(struct model *m, struct sim *s, double *energy, size_t *pairs,
                          double *omega2);
/** Doubles per ghost that sph_par_halo sends for @p set with the run's options. */
int sph_par_halo_width(const struct model *m, enum sph_halo_set set);
struct par_spatial_model;
/** model_ops.spatial_ghosts / spatial_rebuilt (> 0: a TLSPH run, no spatial ghosts). */
int sph_spatial_ghosts(struct model *m, struct par_spatial_model *sp);
int sph_spatial_rebuilt(struct model *m, struct sim *sim, bool moved, struct spall_error *err);
/** Every per-particle array of the model (sph_state_arrays) sized for @p n
 *  local particles, the rows kept; -1 when out of memory. */
int sph_resize_state(struct model *m, size_t n);
/** Each row of @p nl (a cell list over the owned particles, then the
 *  ghosts, each ascending in gid) in ascending partner gid, the serial
 *  order; partners from @p n_held on (symmetry-plane images) stay last;
 *  -1 when out of memory. */
struct neighbor_list;
int sph_rows_by_gid(struct neighbor_list *nl, size_t n_owned, size_t n_held,
                    const int64_t *gid);
/** localize (the list only: sph_localize gathers the arrays), migrate_arrays
 *  and migrated of the updated form. */
void sph_ul_localize(struct model *m);
struct par_model_arrays;
int sph_ul_migrate_arrays(struct model *m, struct sim *sim, struct par_model_arrays *a,
                          struct spall_error *err);
int sph_ul_migrated(struct model *m, size_t n, struct spall_error *err);
/** Free the migration's bond list and the list's bond view (sph_destroy). */
void sph_ul_release(struct model *m);
/** Point the bond view at the current neighbour list (runs on more than
 *  one rank only); -1 when out of memory. */
int sph_ul_view(struct model *m);
/** The same with the partners of index below @p n_held only, rows copied
 *  (the serial list over real and mirrored particles before the partition:
 *  the images are not particles); -1 when out of memory. */
int sph_ul_view_held(struct model *m, size_t n_held);

/* sph_localize.c (distributed runs, core/parallel/decomp.h) */
struct bond_list;
/** model_ops.localize: total-Lagrangian runs; refuses the rest. */
int sph_localize(struct model *m, struct sim *sim, const size_t *keep, size_t n_keep,
                 size_t n_owned, const int64_t *new_of_old, struct spall_error *err);
/** model_ops.halo_bonds: the TLSPH reference list as bonds. */
const struct bond_list *sph_halo_bonds(const struct model *m);
struct par_model_arrays;
/** model_ops.migrate_arrays and model_ops.migrated (rebalancing). */
int sph_migrate_arrays(struct model *m, struct par_model_arrays *a, struct spall_error *err);
int sph_migrated(struct model *m, struct sim *sim, struct spall_error *err);
/** The halo list lent to the partition made afresh from the reference rows
 *  (a checkpoint replaced them after the support check made it). */
int sph_tl_halo_refresh(struct model *m, struct spall_error *err);
/** After a distributed re-reference (sph_tlsph_reference): the halo list,
 *  the rows' split at the serial order, partner ids and scratch of the new
 *  reference rows, and the whole body's pair count. */
int sph_tl_par_rows(struct model *m, struct sim *sim, struct spall_error *err);
/** TLSPH bodies behind an interface (split_forms) on spatial ghosts: what
 *  the ghosts carry besides the updated form's arrays (the packed blocks)
 *  and the reference rows as the fixed partners every ghost build keeps
 *  (par_spatial_model.bonds); nothing without m->tl. */
void sph_tl_spatial_ghosts(struct model *m, struct par_spatial_model *sp);
/** After a ghost build (sph_spatial_rebuilt): the reference rows renumbered
 *  to the new local indices by their partners' global ids, the per-particle
 *  scratch sized for the n local particles, m->form of every local particle. */
int sph_tl_relayout(struct model *m, struct sim *sim, struct spall_error *err);

/* sph_tlsph_reref.c */
/** End of a step: re-reference when model.reference_update says so. */
int sph_tlsph_reref_step(struct model *m, struct sim *s, struct spall_error *err);

/* sph_axisym_vec.c: the axisymmetric pair sums as vector rows (Wendland
 * kernel, no Balsara switch); bitwise those of sph_axisym.c's loops */
#define SPH_AXI_TERMS 8
struct sph_axi_scratch {
    double *t;   /**< SPH_AXI_TERMS term arrays of cap entries */
    double *sg;  /**< +1 a pair, -1 an axis image */
    int32_t *cj; /**< partner of each entry */
    size_t cap;
};
/** Entries of the longest row (pairs, their images, the own image). */
size_t sph_axi_vec_cap(const struct model *m);
/** Allocate one thread's scratch; -1 when out of memory (free it anyway). */
int sph_axi_vec_alloc(struct sph_axi_scratch *sc, size_t cap);
void sph_axi_vec_free(struct sph_axi_scratch *sc);
/** pass_gradient_axi's sums of row i: G (rr rz zr zz) and the amounts to
 *  subtract from B (rr rz zr zz). */
void sph_axi_grad_row(const struct model *m, const struct particles *p, size_t i,
                      struct sph_axi_scratch *sc, double G[4], double Bs[4]);
/** pass_forces_axi's pair sums of row i: a_r, a_z, de, and the XSPH sums. */
void sph_axi_force_row(const struct model *m, const struct particles *p, size_t i,
                       struct sph_axi_scratch *sc, double out[5]);

/* sph_axisym.c */
/** Ring masses M = 2 pi r A rho0, planar masses, the surface; flags the sim. */
void sph_axisym_init(struct model *m, struct sim *s);
/** Axisymmetric (r, z) rates: planar sums with axis images + hoop terms. */
int sph_axisym_rates(struct model *m, struct sim *s, struct spall_error *err);
/** Cavity diameters D1, D2 at opt.cavity_depth (0 columns when off). */
size_t sph_axisym_history(const struct model *m, const struct sim *sim, const char **names,
                          double *values);
/* sph_interface.c */
/** Move the pairs of different groups (bodies or materials) out of the
 *  kernel neighbour list into the interface list (kept within d_ij +
 *  @p skin_abs); called at each neighbour-list build. */
int sph_interface_split(struct model *m, struct sim *s, double *const x[3], double skin_abs,
                        struct spall_error *err);
/** Stable step of the contact springs of the last evaluation (INFINITY: none). */
double sph_interface_stable_dt(const struct model *m);

/* sph_leapfrog.c */
/** Leapfrog: advance rho, h, S (with the radial return) and the stress
 *  power part of e over @p dt with the velocity gradient L just computed
 *  from the half-step velocities; P from the new density. */
void sph_leapfrog_advance(struct model *m, struct sim *s, double dt, int mine);
/** The same for particle i alone (the fused TLSPH pass, sph_tlsph.c). */
void sph_leapfrog_advance_one(struct model *m, size_t i, double dt);

/* sph_material.c */
/** The pressure a particle carries: a failed one no tension (P >= 0)
 *  unless its material has failed_tension (one rule for every update). */
static inline double sph_carried_pressure(const struct sph_material *mt, bool failed, double P)
{
    return failed && P < 0.0 && !mt->failed_tension ? 0.0 : P;
}
/** Balsara's switch ([Meng2021] Tab. 2.2 "BAL"): f = |div v| / (|div v| +
 *  |curl v| + 1e-4 c / h), -> 1 in compression, -> 0 in shear; the AV of a
 *  pair is scaled by (f_i + f_j) / 2.  @p div, @p curl are the magnitudes
 *  from the caller's velocity gradient (axisymmetric or Cartesian). */
static inline double sph_balsara_factor(double div, double curl, double c, double h)
{
    const double den = div + curl + 1e-4 * c / h;
    return den > 0.0 ? div / den : 1.0;
}
/** Balsara's factor of an updated-form particle i of a Cartesian run (plane
 *  strain / stress or 3D) from its velocity gradient m->L of this force
 *  call (sph_rates.c pass A): div = L_xx + L_yy (+ L_zz in 3D; the
 *  plane-stress thickness rate is left out, the AV acts in the plane),
 *  |curl| the full vorticity (in 2D only its z component is non-zero). */
static inline double sph_balsara_cartesian(const struct model *m, size_t i, int dim)
{
    const double div = m->L[0][i] + m->L[4][i] + (dim == 3 ? m->L[8][i] : 0.0);
    const double cx = m->L[7][i] - m->L[5][i], cy = m->L[2][i] - m->L[6][i];
    const double cz = m->L[3][i] - m->L[1][i];
    return sph_balsara_factor(fabs(div), sqrt(cx * cx + cy * cy + cz * cz), m->c[i], m->h[i]);
}
/** Pressure of every particle of formulation @p mine (SPH_FORM_*); failed
 *  particles carry no tension. */
void sph_update_pressure(struct model *m, struct sim *s, int mine);
/** Pressure and sound speed of particle i (what sph_update_pressure does per particle). */
void sph_update_pressure_one(struct model *m, size_t i);
/** Parse and check `materials:` entry @p index of an SPH run into m->mat
 *  (the model_ops parse_material hook, sph_material.c). */
int sph_material_parse(struct model *m, struct sim *sim, int index,
                       const struct deck_node *node, struct spall_error *err);
/** Jaumann stress rate of particle i from L (Eq. 3.28-3.30), and the plane-stress
 *  out-of-plane strain rate; also returns tr(D) (3D trace). */
void sph_stress_rate(const struct model *m, size_t i, double *trD);
/** Radial return (von Mises) and failure of particle i after S was advanced;
 *  @p commit: accumulate plastic strain, work and heat (corrector only). */
void sph_plastic_return(struct model *m, size_t i, double dt, bool commit);



/* Inverse of a dim x dim matrix held in row-major 3x3 storage (2D: the
 * 2x2 block, out[8] = 1); returns the determinant of the dim block.  Callers
 * decide what "singular" means for them before using out. */
static inline double sph_inverse(int dim, const double A[9], double out[9])
{
    if (dim == 2) {
        double det = A[0] * A[4] - A[1] * A[3];
        out[0] = A[4] / det;
        out[1] = -A[1] / det;
        out[3] = -A[3] / det;
        out[4] = A[0] / det;
        out[2] = out[5] = out[6] = out[7] = 0.0;
        out[8] = 1.0;
        return det;
    }
    double c0 = A[4] * A[8] - A[5] * A[7], c1 = A[5] * A[6] - A[3] * A[8],
           c2 = A[3] * A[7] - A[4] * A[6];
    double det = A[0] * c0 + A[1] * c1 + A[2] * c2, id = 1.0 / det;
    out[0] = c0 * id;
    out[1] = (A[2] * A[7] - A[1] * A[8]) * id;
    out[2] = (A[1] * A[5] - A[2] * A[4]) * id;
    out[3] = c1 * id;
    out[4] = (A[0] * A[8] - A[2] * A[6]) * id;
    out[5] = (A[2] * A[3] - A[0] * A[5]) * id;
    out[6] = c2 * id;
    out[7] = (A[1] * A[6] - A[0] * A[7]) * id;
    out[8] = (A[0] * A[4] - A[1] * A[3]) * id;
    return det;
}

#endif
