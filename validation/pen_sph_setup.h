/**
 * @file pen_sph_setup.h
 * @brief General deck builder and runner of the axisymmetric SPH
 *        penetration model (issue 7 items 3-4): a rigid sphere of any
 *        diameter, density and speed into a soft elastic-plastic-
 *        hydrodynamic target ([Meng2021] sec. 4.3-4.5), and the validation
 *        case "pen-sph-sebs" (steel into 40 vol% SEBS, item 4c).
 *
 * At d = 7.38 um with the gelatin target this is the gelatin deck of
 * validation/pen_sph.c (pen_sph_deck calls it); for other d every length
 * is scaled by d / 7.38 um: graded spacing dx1 for
 * r <= 8 um and z >= -100 um, then 2, 4, 8 dx1 out to r = 144 um (x width)
 * and z = -250 um (x depth), those lengths times d / 7.38 um; every
 * level's edges are rounded up to multiples of the next level's spacing.
 * The sphere starts 0.25 um x d / 7.38 um above the surface.
 */
#ifndef SPALL_VALIDATION_PEN_SPH_SETUP_H
#define SPALL_VALIDATION_PEN_SPH_SETUP_H

#include <stddef.h>

struct spall_error;
struct vreport;

/** Target material and its SPH numerics (SI). */
struct pen_sph_target {
    const char *name; /**< material key in the deck (letters, digits, '_') */
    double rho;       /**< density [kg/m^3] */
    double E, nu;     /**< Young's modulus [Pa], Poisson's ratio */
    double A, B, n;   /**< yield A + B ep^n [Pa], [Pa], [1] */
    double fail;      /**< von Mises failure stress [Pa]; <= 0: no failure */
    double c0, S;     /**< Mie-Grueneisen C_k form: sound speed [m/s], Hugoniot slope */
    double gamma;     /**< Grueneisen Gamma (0 in the thesis' C_k form) */
    double av_a, av_b; /**< artificial viscosity (q_a, q_b) */
    double av_length;  /**< AV length [m] instead of h (viscosity_length); 0: h */
    int av_balsara;    /**< 1: AV times Balsara's switch (viscosity_switch) */
    double xsph;      /**< XSPH alpha_cs */
};

/** Rigid spherical projectile. */
struct pen_sph_shot {
    double d;     /**< diameter [m] */
    double rho_p; /**< density [kg/m^3] (mass rho_p pi d^3 / 6) */
    double v0;    /**< impact speed [m/s] (downwards) */
};

/** Discretisation and run length. */
struct pen_sph_grid {
    double dx1_d;        /**< finest spacing as a fraction of d (0.1 = d/10) */
    double width;        /**< scales the two outer radial levels (1 = the gelatin deck) */
    double depth;        /**< scales the four level depths (1 = the gelatin deck) */
    double t_end;        /**< end time [s] (a validation run stops earlier, at rest) */
    double cavity_depth; /**< depth of the cavity measurement [m]; 0: 15 um x d / 7.38 um */
    int k_first_contact; /**< 1: the impactor's penalty stiffness is frozen at first contact
                          *   (`stiffness_dt: first_contact`, as the gelatin deck); 0: per
                          *   step (the SEBS case's numbers were measured so) */
    double t_rebound;    /**< > 0: do not stop at P_max; run on to this time after contact
                          *   (or t_end) and measure the rebound; 0: stop at rest */
    int surface_contact; /**< 1: the sphere's contact surface pushed out by dx1/2
                          *   (impactor key `contact_offset`), so that the gel's
                          *   particle surfaces, not centres, meet radius d/2; 0: on
                          *   centres (effective radius d/2 - dx1/2, the cases' decks) */
};

/** 10 wt% gelatin of [Meng2021] Tab. 4.3 with modulus @p E; AV (0.5, 0.2),
 *  XSPH 0.015 (sec. 4.4.1). */
struct pen_sph_target pen_sph_target_gelatin(double E);
/** 40 vol% SEBS of [Meng2021] Tab. 4.3 with modulus @p E (40-50 MPa);
 *  AV (2, 1), XSPH 0.08 (sec. 4.5.1, Fig. 4.21-4.22). */
struct pen_sph_target pen_sph_target_sebs(double E);

/** Gap between the sphere's tip and the surface at t = 0 [m]. */
double pen_sph_setup_gap(const struct pen_sph_shot *s);

/** Write the YAML deck into @p buf (no header comments, no output block).
 *  SPALL_ERR_INPUT if a parameter is not finite and positive where it must
 *  be, or if @p len is too small. */
int pen_sph_setup_deck(char *buf, size_t len, const struct pen_sph_target *t,
                       const struct pen_sph_shot *s, const struct pen_sph_grid *g,
                       struct spall_error *err);

/** One run's results. */
struct pen_sph_outcome {
    double pmax, t_pmax; /**< deepest tip depth [m], its time after contact [s] */
    double p_end, v_end; /**< tip depth [m] and speed [m/s] at the end */
    double d1max, d2max; /**< largest cavity diameters at cavity_depth [m] */
    double balance;      /**< energy balance / kinetic energy input (at the last step) */
    int at_rest;         /**< 1 if the sphere stopped (V <= 0) before t_end */
    /* rebound (grid t_rebound > 0 only): */
    int rebounded;       /**< 1 if V turned upward after P_max */
    double t_rev;        /**< time V turned upward, after contact [s] */
    double v_reb, t_reb; /**< peak upward speed after t_rev [m/s] and its time [s] */
    double recovery;     /**< tip recovery at the end, pmax - p_end [m] */
    size_t n;            /**< particles */
    double secs;         /**< wall time of the run [s] */
    double *t, *P;       /**< tip depth history, every 10 steps (owned) */
    size_t nh;
};

/** Build the deck (distributed under mpirun when @p r's case runs
 *  distributed, vpar.h; @p r may be NULL: one rank), run until the sphere comes to rest (V <= 0 after
 *  contact) or t_end; with g->t_rebound > 0 run on past rest to
 *  min(t_rebound after contact, t_end) and fill the rebound fields.
 *  P = depth of the tip below the initial surface, t counted from first
 *  contact.  Free with pen_sph_outcome_free. */
int pen_sph_setup_run(struct vreport *r, const struct pen_sph_target *t,
                      const struct pen_sph_shot *s, const struct pen_sph_grid *g,
                      struct pen_sph_outcome *o, struct spall_error *err);
void pen_sph_outcome_free(struct pen_sph_outcome *o);

/** Richardson extrapolation of three results @p f at spacings @p h (h[0] >
 *  h[1] > h[2], any ratios): f = f_inf + C h^p fitted through the three
 *  points (p by bisection on (f0 - f1)/(f1 - f2) = (h0^p - h1^p)/(h1^p -
 *  h2^p), p in [0.05, 20]).  SPALL_ERR_INPUT, with the cause in @p err, if
 *  the h are not decreasing and positive, or if the sequence does not
 *  converge monotonically (the differences change sign or do not shrink as
 *  any p in that range would make them): then no estimate exists. */
int pen_richardson(const double h[3], const double f[3], double *p, double *f_inf,
                   struct spall_error *err);

/** "pen-sph-sebs": the five steel-into-SEBS cases of [Meng2021] sec. 4.5 at
 *  E = 40 and 50 MPa against the Modified-CG model (R = 25 MPa,
 *  eta = 4.5e-2 Pa s) with the d/2 nose, 15 % (validation/pen_sph_sebs.c). */
int pen_case_sph_sebs(struct vreport *r, struct spall_error *err);
/** "pen-sph-sebs-convergence": two SEBS shots at d/10, d/15, d/20 with the AV
 *  length fixed at 0.13 d and the contact on particle surfaces. */
int pen_case_sph_sebs_convergence(struct vreport *r, struct spall_error *err);

#endif
