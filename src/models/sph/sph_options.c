/**
 * @file sph_options.c
 * @brief The `model:` keys of an SPH deck (sph_options.h: one struct per
 *        concern), their defaults and the checks between them: which
 *        combinations the pair loops support, which keys need which
 *        formulation.
 *
 * Deck keys (copied to docs/decks.md):
 *   model:
 *     type: sph | tlsph                       the updated (sph) or total (tlsph) Lagrangian
 *                                             formulation: two models sharing these keys
 *     kernel: cubic_spline | gaussian | quintic_spline | wendland |
 *             double_cosine | hyperbolic      (Fig. 3.1 types 1-6; default wendland)
 *     h_factor: h / dx (default 1.5)
 *     density: continuity | summation         (Eq. 3.18 / Eq. 3.15; default continuity)
 *     cspm: true | false                      corrected gradients (default false): velocity
 *                                             gradient and, paired with it, the stress
 *                                             terms of momentum and energy
 *     viscosity: [q_a, q_b]                   Monaghan AV (default [1, 1])
 *     viscosity_length: L                     [m] length in the AV's mu_ij instead of
 *                                             h_ij (default 0: h_ij, Eq. 2.21); adds an AV dt bound
 *     viscosity_switch: none | balsara        AV times Balsara's shear switch (every
 *                                             form but symmetry planes; default none)
 *     artificial_stress: zeta                 Monaghan-Gray (default 0: off)
 *     artificial_stress_n: n                  (default 4)
 *     artificial_stress_smoothing: false      R_i averaged over the kernel
 *                                             (sph_as_smooth.c; default false)
 *     xsph: alpha_cs                          (default 0)
 *     variable_h: false                       dh/dt = -(h/(d rho)) drho/dt
 *     plane: stress | strain                  2D only (default strain)
 *     skin: fraction of the support added to the neighbour radius (default 0.2)
 *     adaptive_dt: true                       Eq. 3.38 every step (dt_factor = c_s, default 0.3)
 *     time_integration: predictor_corrector | leapfrog   (sph_leapfrog.c; default
 *                                             predictor_corrector, Eqs. 3.35-3.37)
 *     body_formulation: {name: updated | total}  per body (bodies[].name) override of
 *                                             the model's formulation (sph_forms.c); mixed runs need
 *                                             interface: bodies | materials
 *     hourglass: kappa                        TLSPH hourglass coefficient (default 0.1)
 *     det_f_range: [lo, hi]                   TLSPH guard: a particle's det F outside stops
 *                                             the run, naming it (default [0.1, 10])
 *     max_distortion: k                       TLSPH guard on (|F|^2/dim)/J^(2/dim) (default 100)
 *     reference_update: {every: N, distortion: k, isotropy: s}  TLSPH re-referencing
 *                                             (sph_tlsph_reref.c): reference := current
 *                                             configuration every N steps and/or when the
 *                                             distortion exceeds k (1 < k < max_distortion);
 *                                             h grows where the new neighbourhood's isotropy
 *                                             is below s (default 0.2); default off
 *     clamp: {group: g, point: [...], normal: [...]}
 *           mirrored clamp (sph_clamp.c): the fixed group g behind the plane
 *           takes -v and the stress of its mirror images during force calls
 *     wall: {point: [...], normal: [...], stiffness: 1}  rigid frictionless half-space, normal
 *           into the body; penalty k = stiffness m (c0/dx)^2 closer than dx/2
 *     interface: none | bodies | materials    (sph_interface.c; default none) kernel sums
 *                                             inside each body (material) only, bodies
 *                                             (materials) touch through a frictionless
 *                                             penalty at d = (dx_i + dx_j)/2
 *     interface_stiffness: eta                penalty k = eta min(rho0 dx^dim) (c0max/d)^2
 *                                             (default 1)
 *     interface_distance: f                   d = f (dx_i + dx_j)/2 (default 1)
 *   materials.<name>: density, youngs_modulus + poisson_ratio (or
 *     bulk_modulus + shear_modulus), eos: linear | mie_gruneisen |
 *     mie_gruneisen_ck with sound_speed, hugoniot_slope, gruneisen,
 *     reference_pressure; yield: elastic | perfect | power | johnson_cook with
 *     yield_stress (perfect), yield_a, yield_b, yield_n (power, JC), jc_c,
 *     jc_m, melt_temperature, room_temperature (293), reference_strain_rate
 *     (1), specific_heat, taylor_quinney (0.9); failure: none | stress |
 *     plastic_strain with failure_value, failed_tension (false: a failed
 *     particle carries no tension); rate_model: none | cowper_symonds
 *     with cs_d [1/s], cs_q (perfect / power yield and stress failure scaled
 *     by 1 + (epdot/D)^(1/q)).
 */
#include "models/sph/sph_internal.h"

#include "core/options.h"
#include "spall/error.h"

#include <limits.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

/* Deck keys that were switches between two code paths solving the same
 * equations: verification, not physics.  Tests reach both paths through
 * sph_set_split_loops (sph.h); a deck that still names one is told why. */
static const struct {
    const char *key, *why;
} removed_keys[] = {
    {"formulation", "model.formulation is no longer a key: the two SPH formulations are two "
                    "models, type: sph (updated Lagrangian) and type: tlsph (total "
                    "Lagrangian); model.body_formulation still sets single bodies"},
    {"pair_loop", "pair_loop is no longer a deck key: spall picks the fused or the two-pass "
                  "loops from the other options (same equations); remove it"},
};

static int refuse_removed(const struct deck_node *params, struct spall_error *err)
{
    for (size_t k = 0; k < sizeof removed_keys / sizeof removed_keys[0]; k++)
        if (deck_peek(params, removed_keys[k].key))
            return deck_error_key(err, params, removed_keys[k].key, "%s", removed_keys[k].why);
    return SPALL_OK;
}

/* model.reference_update {every, distortion, isotropy} (sph_tlsph_reref.c):
 * TLSPH runs only, after total_lagrangian and max_distortion are known. */
static int parse_reref(const struct deck_node *params, struct sph_opt_tlsph *o,
                       struct spall_error *err)
{
    static const char *const keys[] = {"every", "distortion", "isotropy", NULL};
    const struct deck_node *r = deck_get(params, "reference_update");
    if (!r)
        return SPALL_OK;
    int rc = deck_expect_map(r, "a mapping with every: N and/or distortion: k", err);
    if (rc)
        return rc;
    if (!o->total_lagrangian)
        return deck_error_key(err, params, "reference_update",
                              "reference_update re-references total-Lagrangian bodies; this "
                              "run has none (type: tlsph or body_formulation)");
    long every = 0;
    double k = 0.0, iso = 0.2;
    if ((rc = deck_long(r, "every", false, 1, LONG_MAX, &every, err)) ||
        (rc = deck_double(r, "distortion", false, 1.0, INFINITY, &k, err)) ||
        (rc = deck_double(r, "isotropy", false, 0.0, 1.0, &iso, err)) ||
        (rc = deck_check_unused(r, "model.reference_update", keys, err)))
        return rc;
    const bool has_k = deck_peek(r, "distortion") != NULL;
    if (!every && !has_k)
        return deck_error_key(err, params, "reference_update",
                              "reference_update names no trigger; expected every: N (steps) "
                              "and/or distortion: k (> 1)");
    if (has_k && !(k > 1.0))
        return deck_error_key(err, r, "distortion",
                              "distortion %g; expected k > 1 (1 is an undistorted F: it would "
                              "re-reference every step)",
                              k);
    if (has_k && !(k < o->max_distortion))
        return deck_error_key(err, r, "distortion",
                              "distortion %g; expected k < max_distortion (%g): the det F guard "
                              "would stop the run before the update",
                              k, o->max_distortion);
    o->reref_every = every;
    o->reref_isotropy = iso;
    o->reref_distortion = has_k ? k : 0.0;
    return SPALL_OK;
}

int sph_options_parse(const struct deck_node *params, int dim, int base_form,
                      struct sph_parsed *out, struct spall_error *err)
{
    static const char *const kernels[] = {"cubic_spline",  "gaussian",   "quintic_spline",
                                          "wendland",      "double_cosine", "hyperbolic", NULL};
    static const char *const dens[] = {"continuity", "summation", NULL};
    static const char *const planes[] = {"stress", "strain", "axisymmetric", NULL};
    static const char *const syms[] = {"none", "x", "y", "xy", NULL};
    static const char *const tints[] = {"predictor_corrector", "leapfrog", NULL};
    static const char *const keys[] = {"type", "kernel", "h_factor", "density", "cspm",
                                       "viscosity", "viscosity_length", "viscosity_switch",
                                       "artificial_stress", "artificial_stress_n",
                                       "artificial_stress_smoothing",
                                       "xsph", "variable_h", "plane", "skin", "adaptive_dt",
                                       "hourglass",
                                       "wall", "symmetry",
                                       "cavity_depth", "time_integration", "interface",
                                       "interface_stiffness", "interface_distance", "clamp",
                                       "body_formulation", "det_f_range", "max_distortion",
                                       "reference_update", NULL};
    static const char *const ifaces[] = {"none", "bodies", "materials", NULL};
    static const char *const avsw[] = {"none", "balsara", NULL};
    memset(out, 0, sizeof *out);
    struct sph_options o;
    struct sph_loops *loops = &out->loops;
    memset(&o, 0, sizeof o);
    o.kern.kernel = SPH_KERNEL_WENDLAND;
    o.kern.h_factor = 1.5;
    o.kern.cspm = false;
    o.visc.av_a = o.visc.av_b = 1.0;
    o.visc.as_n = 4.0;
    o.kern.plane = SPH_PLANE_STRAIN;
    o.kern.skin = 0.2;
    o.bound.wall_stiffness = 1.0;
    o.tl.hourglass = 0.1;
    o.tl.det_f_range[0] = SPH_DET_F_MIN;
    o.tl.det_f_range[1] = SPH_DET_F_MAX;
    o.tl.max_distortion = SPH_MAX_DISTORTION;
    o.iface.stiffness = 1.0;
    o.iface.distance = 1.0;
    bool adaptive = true;
    o.tl.total_lagrangian = base_form == 1;
    out->run_form = base_form;
    int rc = SPALL_OK;
    if (params) {
        int kern = 3, den = 0, pl = 1, form = base_form, sym = 0, tint = 0, ifc = 0, avs = 0;
        double av[2] = {o.visc.av_a, o.visc.av_b};
        if ((rc = refuse_removed(params, err)))
            return rc;
        if ((rc = deck_enum(params, "kernel", false, kernels, &kern, err)) ||
            (rc = deck_double(params, "h_factor", false, 0.5, 4.0, &o.kern.h_factor, err)) ||
            (rc = deck_enum(params, "density", false, dens, &den, err)) ||
            (rc = deck_bool(params, "cspm", false, &o.kern.cspm, err)) ||
            (rc = deck_vector(params, "viscosity", false, 2, 2, av, err)) ||
            (rc = deck_double(params, "viscosity_length", false, 0.0, INFINITY, &o.visc.av_length,
                              err)) ||
            (rc = deck_enum(params, "viscosity_switch", false, avsw, &avs, err)) ||
            (rc = deck_double(params, "artificial_stress", false, 0.0, 10.0, &o.visc.as_zeta,
                              err)) ||
            (rc = deck_double(params, "artificial_stress_n", false, 1.0, 20.0, &o.visc.as_n,
                              err)) ||
            (rc = deck_bool(params, "artificial_stress_smoothing", false, &o.visc.as_smooth,
                            err)) ||
            (rc = deck_double(params, "xsph", false, 0.0, 1.0, &o.visc.xsph, err)) ||
            (rc = deck_bool(params, "variable_h", false, &o.kern.variable_h, err)) ||
            (rc = deck_enum(params, "plane", false, planes, &pl, err)) ||
            (rc = deck_double(params, "skin", false, 0.0, 2.0, &o.kern.skin, err)) ||
            (rc = deck_bool(params, "adaptive_dt", false, &adaptive, err)) ||
            (rc = deck_double(params, "hourglass", false, 0.0, 10.0, &o.tl.hourglass, err)) ||
            (rc = deck_vector(params, "det_f_range", false, 2, 2, o.tl.det_f_range, err)) ||
            (rc = deck_double(params, "max_distortion", false, 1.0, INFINITY, &o.tl.max_distortion,
                              err)) ||
            (rc = deck_enum(params, "symmetry", false, syms, &sym, err)) ||
            (rc = deck_double(params, "cavity_depth", false, 0.0, INFINITY, &o.cavity_depth,
                              err)) ||
            (rc = deck_enum(params, "time_integration", false, tints, &tint, err)) ||
            (rc = deck_enum(params, "interface", false, ifaces, &ifc, err)) ||
            (rc = deck_double(params, "interface_stiffness", false, 1e-3, 10.0,
                              &o.iface.stiffness, err)) ||
            (rc = deck_double(params, "interface_distance", false, 0.5, 2.0, &o.iface.distance,
                              err)))
            return rc;
        o.iface.kind = (enum sph_iface)ifc;
        o.visc.av_balsara = avs == 1;
        if (!(o.tl.det_f_range[0] >= 0.0 && o.tl.det_f_range[0] < 1.0 && o.tl.det_f_range[1] > 1.0))
            return deck_error_key(err, params, "det_f_range",
                                  "det_f_range [%g, %g]; expected [lo, hi] with 0 <= lo < 1 < hi",
                                  o.tl.det_f_range[0], o.tl.det_f_range[1]);
        /* model.body_formulation (sph_forms.c): form becomes 1 when any
         * body is TLSPH; a mixed run needs the interface between bodies */
        uint8_t *body_total = NULL;
        size_t n_bodies = 0;
        if ((rc = sph_forms_parse(params, form, &body_total, &n_bodies, err)))
            return rc;
        bool any_total = false, all_total = true;
        for (size_t k = 0; k < n_bodies; k++) {
            any_total = any_total || body_total[k];
            all_total = all_total && body_total[k];
        }
        free(body_total); /* parsed again into the model once it exists */
        out->run_form = form;
        if (any_total && !all_total && ifc == SPH_IFACE_NONE)
            return deck_error_key(err, params, "body_formulation",
                                  "bodies of formulation total and updated must not share "
                                  "kernel sums: this run mixes them, so it needs "
                                  "interface: bodies (or materials), a penalty between them");
        form = any_total ? 1 : 0;
        /* the switch needs the velocity gradient before the force pass:
         * sph_axisym.c, TLSPH's stage 1 (sph_tlsph.c) and the two-pass
         * loops of sph_rates.c have it there, the fused loop does not */
        if (o.visc.av_balsara && pl != 2 && !all_total && sym)
            return deck_error_key(err, params, "viscosity_switch",
                                  "viscosity_switch: balsara in the updated form needs the "
                                  "two-pass loops, which symmetry planes do not have: model "
                                  "the whole body instead of using symmetry");
        o.tl.split_forms = any_total && ifc != SPH_IFACE_NONE;
        /* the ghosts of symmetry planes have their own neighbour list,
         * which the interface split does not see */
        if (ifc && sym)
            return deck_error_key(err, params, "interface",
                                  "interface works without symmetry planes");
        o.time.leapfrog = tint == 1;
        /* the leapfrog advances the state between the gradient and the force
         * pass (sph_leapfrog.c): it needs the two-pass loops */
        loops->split_pairs = o.time.leapfrog;
        /* the smoothing of R sits between the passes of sph_rates.c */
        if (o.visc.as_smooth && (sym || pl == 2))
            return deck_error_key(err, params, "artificial_stress_smoothing",
                                  "artificial_stress_smoothing works with the two-pass loops "
                                  "only: not with symmetry planes or plane: axisymmetric");
        loops->split_pairs = loops->split_pairs || o.visc.as_smooth;
        /* Balsara's switch, Cartesian updated form (alone or beside TLSPH
         * bodies, whose switch is TLSPH's stage 1): sph_rates.c pass C */
        loops->split_pairs = loops->split_pairs || (o.visc.av_balsara && pl != 2 && !all_total);
        o.bound.symmetry[0] = sym == 1 || sym == 3;
        o.bound.symmetry[1] = sym == 2 || sym == 3;
        if (sym == 3 && dim < 3)
            return deck_error_key(err, params, "symmetry",
                                  "symmetry xy needs 3D (in 2D use x or y)");
        if (sym && pl == 2)
            return deck_error_key(err, params, "symmetry",
                                  "symmetry planes do not apply to plane: axisymmetric (the "
                                  "axis is already a symmetry line)");
        if (o.time.leapfrog && (sym || pl == 2))
            return deck_error_key(err, params, "time_integration",
                                  "leapfrog works with the two-pass loops only: not with "
                                  "symmetry planes or plane: axisymmetric");
        if (sym && (form == 1 || o.kern.cspm || den == 1))
            return deck_error_key(err, params, "symmetry",
                                  "symmetry planes work with the fused loop only: updated "
                                  "formulation, continuity density, no cspm");
        o.tl.total_lagrangian = form == 1;
        if ((rc = parse_reref(params, &o.tl, err)))
            return rc;
        if (av[0] < 0.0 || av[1] < 0.0)
            return deck_error_key(err, params, "viscosity",
                                  "viscosity [%g, %g]; expected [q_a, q_b] both >= 0", av[0],
                                  av[1]);
        o.visc.av_a = av[0];
        o.visc.av_b = av[1];
        o.kern.kernel = (enum sph_kernel)(kern + 1);
        o.kern.density = (enum sph_density)den;
        o.kern.plane = (enum sph_plane)pl;
        const struct deck_node *w = deck_get(params, "wall");
        if (w) {
            static const char *const wk[] = {"point", "normal", "stiffness", NULL};
            if ((rc = deck_expect_map(w, "a mapping with point and normal", err)) ||
                (rc = deck_vector(w, "point", true, (size_t)dim, (size_t)dim,
                                  o.bound.wall_point, err)) ||
                (rc = deck_vector(w, "normal", true, (size_t)dim, (size_t)dim,
                                  o.bound.wall_normal, err)) ||
                (rc = deck_double(w, "stiffness", false, 1e-3, 4.0, &o.bound.wall_stiffness,
                                  err)) ||
                (rc = deck_check_unused(w, "model.wall", wk, err)))
                return rc;
            double nn = 0.0;
            for (int d = 0; d < 3; d++)
                nn += o.bound.wall_normal[d] * o.bound.wall_normal[d];
            if (!(nn > 0.0))
                return deck_error_key(err, w, "normal", "wall normal is zero");
            for (int d = 0; d < 3; d++)
                o.bound.wall_normal[d] /= sqrt(nn);
            o.bound.wall = true;
        }
        if ((rc = deck_check_unused(params, "model", keys, err)))
            return rc;
        /* sph_axisym.c has its own pair loops without these options */
        if (o.kern.plane == SPH_PLANE_AXISYMMETRIC &&
            (dim != 2 || o.visc.as_zeta > 0.0 || o.tl.total_lagrangian ||
             o.kern.density == SPH_DENSITY_SUMMATION))
            return deck_error_key(err, params, "plane",
                                  "plane: axisymmetric is 2D (x = r, y = z) and takes no "
                                  "artificial_stress, summation density or total formulation");
        /* a ring can only meet a plane normal to the axis all round */
        if (o.kern.plane == SPH_PLANE_AXISYMMETRIC && o.bound.wall &&
            fabs(o.bound.wall_normal[0]) > 1e-12)
            return deck_error_key(err, deck_get(params, "wall"), "normal",
                                  "plane: axisymmetric takes only a wall normal to the axis "
                                  "(normal [0, +-1])");
        if (o.kern.plane == SPH_PLANE_AXISYMMETRIC)
            o.kern.cspm = true; /* always corrected there (sph_axisym.c) */
        if (o.cavity_depth > 0.0 && o.kern.plane != SPH_PLANE_AXISYMMETRIC)
            return deck_error_key(err, params, "cavity_depth",
                                  "cavity_depth needs plane: axisymmetric");
    }
    const struct deck_node *cl = params ? deck_get(params, "clamp") : NULL;
    if (cl) {
        /* sph_clamp.c hooks into the two-pass loops of sph_rates.c only */
        if (o.bound.symmetry[0] || o.bound.symmetry[1] ||
            o.kern.plane == SPH_PLANE_AXISYMMETRIC || o.tl.total_lagrangian)
            return deck_error_key(err, params, "clamp",
                                  "clamp works with the updated formulation's two-pass loops "
                                  "only: not with symmetry planes, plane: axisymmetric or "
                                  "type: tlsph (TLSPH needs none: a plain fixed "
                                  "group clamps it, docs/validation.md sph-plate)");
        if ((rc = sph_clamp_parse(cl, dim, &out->clamp, err)))
            return rc;
        loops->split_pairs = true;
    }
    o.time.adaptive_dt = adaptive;
    out->opt = o;
    return SPALL_OK;
}
