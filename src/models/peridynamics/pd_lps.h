/**
 * @file pd_lps.h
 * @brief Linear peridynamic solid (LPS, ordinary state-based, [Silling2007])
 *        inside the peridynamics model (deck `model.formulation: lps`).  Internal to
 *        src/models/peridynamics: the shared model state is in pd_internal.h.
 */
#ifndef SPALL_PD_LPS_H
#define SPALL_PD_LPS_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "models/peridynamics/pd.h"

struct model;
struct sim;
struct spall_error;
struct pd_cellvol;
struct deck_node;

/** Influence function omega(xi) (deck `model.influence`). */
enum pd_influence {
    PD_OMEGA_ONE,    /**< omega = 1 ([Silling2007]; Peridigm's default) */
    PD_OMEGA_INVERSE /**< omega = delta / |xi| (LAMMPS peri/lps uses 1/|xi|) */
};

/** Per-particle constants and state of the LPS formulation. */
struct pd_lps {
    enum pd_influence influence;
    bool cubic;     /**< influence_correction cubic: omega (1 + gamma P(n)) (pd_lps.c) */
    double gamma;   /**< its gamma (0 without the correction) */
    struct pd_cellvol *cell; /**< partial_volume_rule cell, during pd_lps_init only */
    double *wvol;   /**< weighted volume m_i = sum omega beta |xi|^2 V_j [m^5] */
    double *theta;  /**< dilatation of the last force call */
    double *alpha;  /**< deviatoric coefficient d (d + 2) mu / m_i */
    double *bcoef;  /**< coefficient of |xi| theta in the scalar force: d k / m_i - alpha / d */
    double *ob;     /**< per half-bond: omega(xi) beta(xi) */
    bool surface;   /**< surface_correction true (pd_lps_surface.c) */
    bool pals;      /**< surface_correction position_aware (pd_lps_pals.c) */
    double *afac;   /**< per particle: factor on alpha of the surface correction; NULL: 1 */
    /* surface_correction position_aware (pd_lps_pals.c); NULL otherwise */
    double *pw;     /**< per half-bond i->j: omega_ij, sigma_ij, omega_ji, sigma_ji */
    double *pp;     /**< per particle (owned and ghosts): theta and P of the call */
    /* formulation eps (pd_eps.c); NULL for lps */
    double *ep;     /**< per half-bond: plastic deviatoric extension e^dp [m] */
    double *hs;     /**< per particle (owned and ghosts): theta, return-map scale and d k
                         theta / m_i of the call (pd_lps_kernel.c) */
    uint16_t *rloc; /**< per half-bond i->j: the place of j->i in j's row (serial; NULL
                         once distributed, or where rloc8 holds it) */
    uint8_t *rloc8; /**< the same in a byte where no family has more than 256 bonds */
    /* distributed eps only (pd_localize.c; NULL otherwise) */
    double *epr;    /**< per half-bond i->j: i's copy of e^dp of j->i, kept by the same update */
};

/** Allocate and fill the LPS arrays (after the bond list and materials). */
int pd_lps_init(struct model *m, struct sim *sim, struct spall_error *err);
/** Weighted volumes and coefficients from the current intact family (after
 *  pre-cracks: a pre-cut bond is not part of the family). */
void pd_lps_weights(struct model *m, const struct sim *sim);
void pd_lps_free(struct pd_lps *L);
/** Forces with fused breaking (critical stretch; pd_lps_kernel.c), with eps'
 *  plastic return map where the model has its state. */
int pd_lps_forces(struct model *m, struct sim *sim, struct spall_error *err);
/** surface_correction: factors on omega and alpha near free surfaces (pd_lps_surface.c). */
int pd_lps_surface_init(struct model *m, struct sim *sim, struct spall_error *err);
/* pd_lps_pals.c: surface_correction position_aware ([Mitchell2015]) */
/** Deck `model.surface_correction` (true, false, position_aware) into m's
 *  options once the formulation is known; refuses position_aware without lps. */
int pd_surface_opts(struct model *m, const struct deck_node *params, struct spall_error *err);
/** Influence functions omega, sigma of every half-bond (after pd_lps_init's ob). */
int pd_lps_pals_init(struct model *m, struct sim *sim, struct spall_error *err);
/** Forces (and breaking) of the position-aware LPS. */
int pd_lps_pals_forces(struct model *m, struct sim *sim, struct spall_error *err);
/** break_order next_step of rows [i0, i1) with the position-aware force state. */
void pd_lps_pals_break_rows(struct model *m, const struct sim *sim, size_t i0, size_t i1);
/** Gershgorin bound of its linearised stiffness (as pd_lps_stable_dt). */
double pd_lps_pals_stable_dt(const struct model *m, const struct sim *sim);
/** Energy [J] and stress [Pa] of particle @p i (as pd_lps_particle_eval). */
void pd_lps_pals_particle_eval(const struct model *m, const struct sim *sim, size_t i,
                               double *energy, double *stress);
/** break_order next_step: drop the bonds past s0 after this step's forces. */
void pd_lps_break_late(struct model *m, const struct sim *sim);
/** The same for the rows of particles [i0, i1) (the force passes break the
 *  owned rows themselves, on the lengths they compute). */
void pd_lps_break_rows(struct model *m, const struct sim *sim, size_t i0, size_t i1);
/** Gershgorin bound of the linearised LPS stiffness: dt < 2 sqrt(m_i / R_i). */
double pd_lps_stable_dt(const struct model *m, const struct sim *sim);
/** Energy [J] and stress [Pa] of particle @p i from the current positions. */
void pd_lps_particle_eval(const struct model *m, const struct sim *sim, size_t i,
                          double *energy, double *stress);

/* pd_eps.c: elastic-plastic LPS (model.formulation: eps) */
/** Allocate the plastic extension state (after pd_lps_init) and the reverse slots;
 *  nothing in a window of the distributed set-up (pd_eps_localized makes it). */
int pd_eps_init(struct model *m, struct sim *sim, struct spall_error *err);
/** After pd_localize of a window: the zero plastic state of the rank's @p nh
 *  half-bonds (e^dp, the reverse halves' e^dp) and its @p n particles'
 *  halo values. */
int pd_eps_localized(struct pd_lps *L, size_t nh, size_t n, struct spall_error *err);
/** c_d of the J2 criterion s : s <= c_d sigma_Y^2: 2/3 in 3D, 1/2 in 2D. */
double pd_eps_cd(int dim);
/** Equivalent plastic strain of particle @p i from its plastic extension state. */
double pd_eps_plastic_strain(const struct model *m, const struct sim *sim, size_t i);

#endif
