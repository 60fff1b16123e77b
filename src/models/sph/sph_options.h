/**
 * @file sph_options.h
 * @brief The deck options of the SPH model (`model:` of a `type: sph`
 *        deck), one struct per concern, parsed and cross-checked by
 *        sph_options.c; docs/decks.md lists the keys.  Private to the
 *        model's folder (included by sph_internal.h).
 */
#ifndef SPALL_SPH_OPTIONS_H
#define SPALL_SPH_OPTIONS_H

#include "models/sph/sph_kernels.h"

#include <stdbool.h>

struct deck_node;
struct sph_clamp;
struct spall_error;

/** 2D stress state ([Meng2021] sec. 3.3; the beam is plane stress). */
enum sph_plane { SPH_PLANE_STRESS, SPH_PLANE_STRAIN, SPH_PLANE_AXISYMMETRIC /* sph_axisym.c */ };
enum sph_density { SPH_DENSITY_CONTINUITY, SPH_DENSITY_SUMMATION };
/** Coupling of bodies (sph_interface.c): kernel sums across them (none), or
 *  sums inside each body / material and a penalty between them. */
enum sph_iface { SPH_IFACE_NONE, SPH_IFACE_BODIES, SPH_IFACE_MATERIALS };

/** Defaults of the TLSPH det F guard (model.det_f_range, max_distortion;
 *  sph_tlsph.c).  MACHDYN deletes particles outside 0.2 < det F < 2; these
 *  only stop a run whose reference configuration is no longer usable. */
#define SPH_DET_F_MIN 0.1
#define SPH_DET_F_MAX 10.0
#define SPH_MAX_DISTORTION 100.0

/** Discretisation: kernel, smoothing length, density and gradient forms,
 *  2D stress state (keys kernel, h_factor, skin, variable_h, density, cspm,
 *  plane; [Meng2021] secs. 3.1-3.3). */
struct sph_opt_kernel {
    enum sph_kernel kernel;
    double h_factor;        /**< h = h_factor * dx */
    double skin;            /**< neighbour skin / h */
    bool variable_h;        /**< dh/dt = (h/dim) div v */
    enum sph_density density;
    bool cspm;              /**< corrected velocity gradient (Eqs. 3.10-3.11); always on
                                 with plane: axisymmetric */
    enum sph_plane plane;
};

/** Stabilisation of the updated form: artificial viscosity, artificial
 *  stress and XSPH (keys viscosity*, artificial_stress*, xsph; [Meng2021]
 *  sec. 2.4).  TLSPH bodies read only the AV. */
struct sph_opt_visc {
    double av_a, av_b;      /**< Monaghan AV q_a, q_b */
    double av_length;       /**< AV length in mu_ij [m] (0: h_ij, Eq. 2.21) */
    bool av_balsara;        /**< AV times the Balsara shear switch (not with symmetry planes) */
    double as_zeta;         /**< artificial stress zeta (0: off) */
    double as_n;            /**< exponent n (4) */
    bool as_smooth;         /**< R_i kernel-averaged over i's neighbours (sph_as_smooth.c) */
    double xsph;            /**< XSPH alpha_cs (0: off) */
};

/** Time integration (keys time_integration, adaptive_dt). */
struct sph_opt_time {
    bool leapfrog;          /**< staggered leapfrog state update (sph_leapfrog.c) */
    bool adaptive_dt;       /**< Eq. 3.38 every step (sph_time_scheme) */
};

/** Total-Lagrangian formulation (keys formulation, body_formulation,
 *  hourglass, det_f_range, max_distortion, reference_update; sph_tlsph*.c). */
struct sph_opt_tlsph {
    bool total_lagrangian;  /**< some (or every) body is TLSPH (sph_tlsph.c) */
    bool split_forms;       /**< TLSPH bodies with interface: bodies: particles split
                                 by formulation (m->form, sph_forms.c) */
    double hourglass;       /**< hourglass coefficient kappa */
    double det_f_range[2];  /**< guard: det F outside stops the run */
    double max_distortion;  /**< guard: (|F|^2/dim)/J^(2/dim) above stops the run */
    long reref_every;       /**< re-reference every N steps (0: off; sph_tlsph_reref.c) */
    double reref_distortion; /**< re-reference when the distortion exceeds it (0: off) */
    double reref_isotropy;  /**< at a re-reference: grow h where the neighbourhood's
                                 isotropy is below */
};

/** Interfaces between bodies or materials (keys interface,
 *  interface_stiffness, interface_distance; sph_interface.c). */
struct sph_opt_iface {
    enum sph_iface kind;
    double stiffness;       /**< penalty factor eta (default 1) */
    double distance;        /**< contact distance factor f: d = f (dx_i + dx_j)/2 */
};

/** Boundaries: rigid wall, symmetry planes (keys wall, symmetry; the clamp
 *  is its own object, sph_clamp.c). */
struct sph_opt_bound {
    bool wall;              /**< rigid half-space wall (penalty) */
    double wall_point[3], wall_normal[3]; /**< normal points into the body side */
    double wall_stiffness;  /**< penalty k = factor m (c/dx)^2 */
    bool symmetry[3];       /**< mirror plane x_d = 0 (ghost particles, sph_symmetry.c) */
};

/** Every option of an SPH run. */
struct sph_options {
    struct sph_opt_kernel kern;
    struct sph_opt_visc visc;
    struct sph_opt_time time;
    struct sph_opt_tlsph tl;
    struct sph_opt_iface iface;
    struct sph_opt_bound bound;
    double cavity_depth;    /**< axisymmetric diagnostic: depth of the cavity-diameter
                                 history (0: off; sph_axisym.c) */
};

/** Which pair loops run: not options but what the options need (the
 *  velocity gradient before the force pass: leapfrog, artificial-stress
 *  smoothing, Balsara's switch, the clamp), and what the verification
 *  forces through sph_set_split_loops (sph.h): the fused and the two-pass
 *  loops, the pipelined and the staged TLSPH sweep solve the same
 *  equations, and the tests compare them. */
struct sph_loops {
    bool split_pairs;       /**< the two-pass loops of sph_rates.c */
    bool tl_split;          /**< TLSPH: stages one after the other, not pipelined */
    bool scalar_rows;       /**< fused loop: the scalar rows, not the vector rows */
};

/** What sph_options_parse reads besides the options. */
struct sph_parsed {
    struct sph_options opt;
    struct sph_loops loops;
    int run_form;           /**< the model's formulation (1: total, type tlsph) before the
                                 per-body overrides */
    struct sph_clamp *clamp; /**< model.clamp (NULL: none); the caller owns it */
};

/** Parse and cross-check the `model:` mapping @p params (NULL: defaults)
 *  of a @p dim-dimensional run of the plug-in whose formulation is
 *  @p base_form (0: sph, updated; 1: tlsph, total) into @p out; removed
 *  keys are refused naming their replacement. */
int sph_options_parse(const struct deck_node *params, int dim, int base_form,
                      struct sph_parsed *out, struct spall_error *err);

#endif
