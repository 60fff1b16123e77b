/**
 * @file sph_model.c
 * @brief SPH for elastic-plastic solids ([Meng2021] chapter 3): deck, life
 *        cycle, predictor-corrector state update, diagnostics.
 *
 * Deck keys (copied to docs/decks.md):
 *   model:
 *     type: sph
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
 *     formulation: updated | total            total: TLSPH (sph_tlsph.c), reference
 *                                             kernel, no AS/XSPH (default updated)
 *     body_formulation: {name: updated | total}  per body (bodies[].name) override of
 *                                             formulation (sph_forms.c); mixed runs need
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

#include "core/fields.h"
#include "core/neighbor.h"
#include "core/particles.h"
#include "core/sim.h"
#include "core/options.h"
#include "core/model.h"
#include "spall/error.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

size_t sph_state_arrays(struct model *m, double **a[SPH_N_ARRAYS])
{
    size_t k = 0;
    a[k++] = &m->h;
    a[k++] = &m->dx;
    a[k++] = &m->m2;
    a[k++] = &m->rho;
    a[k++] = &m->e;
    a[k++] = &m->P;
    a[k++] = &m->ep;
    a[k++] = &m->T;
    a[k++] = &m->c;
    a[k++] = &m->drho;
    a[k++] = &m->de;
    a[k++] = &m->dh;
    a[k++] = &m->rho_n;
    a[k++] = &m->e_n;
    a[k++] = &m->h_n;
    a[k++] = &m->drho_n;
    a[k++] = &m->de_n;
    a[k++] = &m->dh_n;
    a[k++] = &m->wp;
    for (int c = 0; c < 6; c++) {
        a[k++] = &m->S[c];
        a[k++] = &m->dS[c];
        a[k++] = &m->S_n[c];
        a[k++] = &m->dS_n[c];
        a[k++] = &m->sig[c];
        a[k++] = &m->R[c];
        a[k++] = &m->Rs[c];
        a[k++] = &m->sr[c];
    }
    for (int c = 0; c < 9; c++) {
        a[k++] = &m->L[c];
        a[k++] = &m->Bi[c];
    }
    a[k++] = &m->axl;
    a[k++] = &m->axl_s;
    for (int c = 0; c < 3; c++) {
        a[k++] = &m->xv[c];
        a[k++] = &m->x_build[c];
    }
    return k;
}

static void sph_destroy(struct model **pm)
{
    if (!pm || !*pm)
        return;
    struct model *m = *pm;
    double **a[SPH_N_ARRAYS];
    size_t na = sph_state_arrays(m, a);
    for (size_t k = 0; k < na; k++)
        free(*a[k]);
    free(m->failed);
    free(m->if_off);
    free(m->if_idx);
    free(m->if_c0);
    free(m->if_e);
    free(m->if_w);
    free(m->if_np);
    free(m->body_total);
    free(m->form);
    free(m->mat);
    sph_symmetry_destroy(&m->sym);
    sph_tlsph_destroy(&m->tl);
    sph_clamp_destroy(&m->clamp);
    neighbor_list_destroy(&m->nl);
    free(m);
    *pm = NULL;
}

static int sph_create(struct model **out, struct sim *sim, const struct deck_node *params,
                      struct spall_error *err)
{
    static const char *const kernels[] = {"cubic_spline",  "gaussian",   "quintic_spline",
                                          "wendland",      "double_cosine", "hyperbolic", NULL};
    static const char *const dens[] = {"continuity", "summation", NULL};
    static const char *const planes[] = {"stress", "strain", "axisymmetric", NULL};
    static const char *const forms[] = {"updated", "total", NULL};
    static const char *const syms[] = {"none", "x", "y", "xy", NULL};
    static const char *const tints[] = {"predictor_corrector", "leapfrog", NULL};
    static const char *const keys[] = {"type", "kernel", "h_factor", "density", "cspm",
                                       "viscosity", "viscosity_length", "viscosity_switch",
                                       "artificial_stress", "artificial_stress_n",
                                       "artificial_stress_smoothing",
                                       "xsph", "variable_h", "plane", "skin", "adaptive_dt",
                                       "formulation", "hourglass",
                                       "wall", "symmetry",
                                       "cavity_depth", "time_integration", "interface",
                                       "interface_stiffness", "interface_distance", "clamp",
                                       "body_formulation", "det_f_range", "max_distortion",
                                       "reference_update", NULL};
    static const char *const ifaces[] = {"none", "bodies", "materials", NULL};
    static const char *const avsw[] = {"none", "balsara", NULL};
    *out = NULL;
    if (sim->dim < 2)
        return spall_error_set(err, SPALL_ERR_INPUT,
                               "the sph model runs in 2D and 3D; use a 2D or 3D lattice");
    struct sph_options o;
    memset(&o, 0, sizeof o);
    o.kernel = SPH_KERNEL_WENDLAND;
    o.h_factor = 1.5;
    o.cspm = false;
    o.av_a = o.av_b = 1.0;
    o.as_n = 4.0;
    o.plane = SPH_PLANE_STRAIN;
    o.skin = 0.2;
    o.wall_stiffness = 1.0;
    o.hourglass = 0.1;
    o.det_f_range[0] = SPH_DET_F_MIN;
    o.det_f_range[1] = SPH_DET_F_MAX;
    o.max_distortion = SPH_MAX_DISTORTION;
    o.iface_stiffness = 1.0;
    o.iface_distance = 1.0;
    bool adaptive = true;
    int run_form = 0; /* model.formulation, before the per-body overrides */
    if (params) {
        int kern = 3, den = 0, pl = 1, form = 0, sym = 0, tint = 0, ifc = 0, avs = 0, rc;
        double av[2] = {o.av_a, o.av_b};
        /* pair_loop was a verification switch; tests now set it through
         * sph_set_split_loops (sph.h) */
        if (deck_peek(params, "pair_loop"))
            return deck_error_key(err, params, "pair_loop",
                                  "pair_loop is no longer a deck key: spall picks the fused "
                                  "or the two-pass loops from the other options (same "
                                  "equations); remove it");
        if ((rc = deck_enum(params, "kernel", false, kernels, &kern, err)) ||
            (rc = deck_double(params, "h_factor", false, 0.5, 4.0, &o.h_factor, err)) ||
            (rc = deck_enum(params, "density", false, dens, &den, err)) ||
            (rc = deck_bool(params, "cspm", false, &o.cspm, err)) ||
            (rc = deck_vector(params, "viscosity", false, 2, 2, av, err)) ||
            (rc = deck_double(params, "viscosity_length", false, 0.0, INFINITY, &o.av_length,
                              err)) ||
            (rc = deck_enum(params, "viscosity_switch", false, avsw, &avs, err)) ||
            (rc = deck_double(params, "artificial_stress", false, 0.0, 10.0, &o.as_zeta, err)) ||
            (rc = deck_double(params, "artificial_stress_n", false, 1.0, 20.0, &o.as_n, err)) ||
            (rc = deck_bool(params, "artificial_stress_smoothing", false, &o.as_smooth, err)) ||
            (rc = deck_double(params, "xsph", false, 0.0, 1.0, &o.xsph, err)) ||
            (rc = deck_bool(params, "variable_h", false, &o.variable_h, err)) ||
            (rc = deck_enum(params, "plane", false, planes, &pl, err)) ||
            (rc = deck_double(params, "skin", false, 0.0, 2.0, &o.skin, err)) ||
            (rc = deck_bool(params, "adaptive_dt", false, &adaptive, err)) ||
            (rc = deck_enum(params, "formulation", false, forms, &form, err)) ||
            (rc = deck_double(params, "hourglass", false, 0.0, 10.0, &o.hourglass, err)) ||
            (rc = deck_vector(params, "det_f_range", false, 2, 2, o.det_f_range, err)) ||
            (rc = deck_double(params, "max_distortion", false, 1.0, INFINITY, &o.max_distortion,
                              err)) ||
            (rc = deck_enum(params, "symmetry", false, syms, &sym, err)) ||
            (rc = deck_double(params, "cavity_depth", false, 0.0, INFINITY, &o.cavity_depth,
                              err)) ||
            (rc = deck_enum(params, "time_integration", false, tints, &tint, err)) ||
            (rc = deck_enum(params, "interface", false, ifaces, &ifc, err)) ||
            (rc = deck_double(params, "interface_stiffness", false, 1e-3, 10.0,
                              &o.iface_stiffness, err)) ||
            (rc = deck_double(params, "interface_distance", false, 0.5, 2.0, &o.iface_distance,
                              err)))
            return rc;
        o.iface = (enum sph_iface)ifc;
        o.av_balsara = avs == 1;
        if (!(o.det_f_range[0] >= 0.0 && o.det_f_range[0] < 1.0 && o.det_f_range[1] > 1.0))
            return deck_error_key(err, params, "det_f_range",
                                  "det_f_range [%g, %g]; expected [lo, hi] with 0 <= lo < 1 < hi",
                                  o.det_f_range[0], o.det_f_range[1]);
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
        run_form = form;
        if (any_total && !all_total && ifc == SPH_IFACE_NONE)
            return deck_error_key(err, params, "body_formulation",
                                  "bodies of formulation total and updated must not share "
                                  "kernel sums: this run mixes them, so it needs "
                                  "interface: bodies (or materials), a penalty between them");
        form = any_total ? 1 : 0;
        /* the switch needs the velocity gradient before the force pass:
         * sph_axisym.c, TLSPH's stage 1 (sph_tlsph.c) and the two-pass
         * loops of sph_rates.c have it there, the fused loop does not */
        if (o.av_balsara && pl != 2 && !all_total && sym)
            return deck_error_key(err, params, "viscosity_switch",
                                  "viscosity_switch: balsara in the updated form needs the "
                                  "two-pass loops, which symmetry planes do not have: model "
                                  "the whole body instead of using symmetry");
        o.split_forms = any_total && ifc != SPH_IFACE_NONE;
        /* the ghosts of symmetry planes have their own neighbour list,
         * which the interface split does not see */
        if (ifc && sym)
            return deck_error_key(err, params, "interface",
                                  "interface works without symmetry planes");
        o.leapfrog = tint == 1;
        /* the leapfrog advances the state between the gradient and the force
         * pass (sph_leapfrog.c): it needs the two-pass loops */
        o.split_pairs = o.leapfrog;
        /* the smoothing of R sits between the passes of sph_rates.c */
        if (o.as_smooth && (sym || pl == 2))
            return deck_error_key(err, params, "artificial_stress_smoothing",
                                  "artificial_stress_smoothing works with the two-pass loops "
                                  "only: not with symmetry planes or plane: axisymmetric");
        o.split_pairs = o.split_pairs || o.as_smooth;
        /* Balsara's switch, Cartesian updated form (alone or beside TLSPH
         * bodies, whose switch is TLSPH's stage 1): sph_rates.c pass C */
        o.split_pairs = o.split_pairs || (o.av_balsara && pl != 2 && !all_total);
        o.symmetry[0] = sym == 1 || sym == 3;
        o.symmetry[1] = sym == 2 || sym == 3;
        if (sym == 3 && sim->dim < 3)
            return deck_error_key(err, params, "symmetry",
                                  "symmetry xy needs 3D (in 2D use x or y)");
        if (sym && pl == 2)
            return deck_error_key(err, params, "symmetry",
                                  "symmetry planes do not apply to plane: axisymmetric (the "
                                  "axis is already a symmetry line)");
        if (o.leapfrog && (sym || pl == 2))
            return deck_error_key(err, params, "time_integration",
                                  "leapfrog works with the two-pass loops only: not with "
                                  "symmetry planes or plane: axisymmetric");
        if (sym && (form == 1 || o.cspm || den == 1))
            return deck_error_key(err, params, "symmetry",
                                  "symmetry planes work with the fused loop only: updated "
                                  "formulation, continuity density, no cspm");
        o.total_lagrangian = form == 1;
        if ((rc = sph_tlsph_reref_parse(params, &o, err))) /* sph_tlsph_reref.c */
            return rc;
        if (av[0] < 0.0 || av[1] < 0.0)
            return deck_error_key(err, params, "viscosity",
                                  "viscosity [%g, %g]; expected [q_a, q_b] both >= 0", av[0],
                                  av[1]);
        o.av_a = av[0];
        o.av_b = av[1];
        o.kernel = (enum sph_kernel)(kern + 1);
        o.density = (enum sph_density)den;
        o.plane = (enum sph_plane)pl;
        const struct deck_node *w = deck_get(params, "wall");
        if (w) {
            static const char *const wk[] = {"point", "normal", "stiffness", NULL};
            if ((rc = deck_expect_map(w, "a mapping with point and normal", err)) ||
                (rc = deck_vector(w, "point", true, (size_t)sim->dim, (size_t)sim->dim,
                                  o.wall_point, err)) ||
                (rc = deck_vector(w, "normal", true, (size_t)sim->dim, (size_t)sim->dim,
                                  o.wall_normal, err)) ||
                (rc = deck_double(w, "stiffness", false, 1e-3, 4.0, &o.wall_stiffness, err)) ||
                (rc = deck_check_unused(w, "model.wall", wk, err)))
                return rc;
            double nn = 0.0;
            for (int d = 0; d < 3; d++)
                nn += o.wall_normal[d] * o.wall_normal[d];
            if (!(nn > 0.0))
                return deck_error_key(err, w, "normal", "wall normal is zero");
            for (int d = 0; d < 3; d++)
                o.wall_normal[d] /= sqrt(nn);
            o.wall = true;
        }
        if ((rc = deck_check_unused(params, "model", keys, err)))
            return rc;
        /* sph_axisym.c has its own pair loops without these options */
        if (o.plane == SPH_PLANE_AXISYMMETRIC &&
            (sim->dim != 2 || o.as_zeta > 0.0 || o.total_lagrangian ||
             o.density == SPH_DENSITY_SUMMATION))
            return deck_error_key(err, params, "plane",
                                  "plane: axisymmetric is 2D (x = r, y = z) and takes no "
                                  "artificial_stress, summation density or total formulation");
        /* a ring can only meet a plane normal to the axis all round */
        if (o.plane == SPH_PLANE_AXISYMMETRIC && o.wall && fabs(o.wall_normal[0]) > 1e-12)
            return deck_error_key(err, deck_get(params, "wall"), "normal",
                                  "plane: axisymmetric takes only a wall normal to the axis "
                                  "(normal [0, +-1])");
        if (o.plane == SPH_PLANE_AXISYMMETRIC)
            o.cspm = true; /* always corrected there (sph_axisym.c) */
        if (o.cavity_depth > 0.0 && o.plane != SPH_PLANE_AXISYMMETRIC)
            return deck_error_key(err, params, "cavity_depth",
                                  "cavity_depth needs plane: axisymmetric");
    }
    struct sph_clamp *clamp = NULL;
    const struct deck_node *cl = params ? deck_get(params, "clamp") : NULL;
    if (cl) {
        /* sph_clamp.c hooks into the two-pass loops of sph_rates.c only */
        if (o.symmetry[0] || o.symmetry[1] || o.plane == SPH_PLANE_AXISYMMETRIC ||
            o.total_lagrangian)
            return deck_error_key(err, params, "clamp",
                                  "clamp works with the updated formulation's two-pass loops "
                                  "only: not with symmetry planes, plane: axisymmetric or "
                                  "formulation: total (TLSPH needs none: a plain fixed "
                                  "group clamps it, docs/validation.md sph-plate)");
        int rc = sph_clamp_parse(cl, sim->dim, &clamp, err);
        if (rc)
            return rc;
        o.split_pairs = true;
    }
    struct model *m = calloc(1, sizeof *m);
    if (!m) {
        sph_clamp_destroy(&clamp);
        return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory creating the sph model");
    }
    m->clamp = clamp;
    m->sim = sim;
    m->opt = o;
    if (o.split_forms) {
        int rc = sph_forms_parse(params, run_form, &m->body_total, &m->n_bodies, err);
        if (rc) {
            sph_destroy(&m);
            return rc;
        }
    }
    m->dim = sim->dim;
    m->alpha = sph_kernel_alpha(o.kernel, sim->dim);
    m->qmax = sph_kernel_support(o.kernel);
    m->opt.adaptive_dt = adaptive;
    *out = m;
    return SPALL_OK;
}

static int sph_init(struct model *m, struct sim *s, struct spall_error *err)
{
    struct particles *p = s->p;
    const size_t n = p->n_owned, cap = p->cap > n ? p->cap : n;
    for (size_t k = 0; k < s->n_materials; k++)
        if (k >= m->n_mat || !m->mat[k].parsed)
            return spall_error_set(err, SPALL_ERR_INPUT, "material '%s' has no sph parameters",
                                   s->materials[k].name);
    double **a[SPH_N_ARRAYS];
    size_t na = sph_state_arrays(m, a);
    for (size_t k = 0; k < na; k++) {
        *a[k] = calloc(cap ? cap : 1, sizeof(double));
        if (!*a[k])
            return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory (sph state)");
    }
    m->failed = calloc(cap ? cap : 1, 1);
    if (!m->failed)
        return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory (sph state)");
    const double t = s->dim == 2 ? s->thickness : 1.0;
    for (size_t i = 0; i < n; i++) {
        const struct sph_material *mt = &m->mat[p->material[i]];
        double area_or_vol = p->volume[i] / t;
        m->dx[i] = s->dim == 2 ? sqrt(area_or_vol) : cbrt(area_or_vol);
        m->h[i] = m->opt.h_factor * m->dx[i];
        m->m2[i] = p->mass[i] / t;
        m->rho[i] = mt->rho0;
        m->T[i] = mt->Troom;
    }
    if (m->opt.plane == SPH_PLANE_AXISYMMETRIC)
        sph_axisym_init(m, s); /* ring masses */
    int rc = m->clamp ? sph_clamp_init(m, s, err) : SPALL_OK;
    if (rc)
        return rc;
    if (m->opt.split_forms) {
        /* bodies split by formulation (sph_forms.c): the TLSPH reference
         * list, then the current list of the updated bodies and the
         * interface */
        if ((rc = sph_forms_init(m, s, err)) || (rc = sph_tlsph_init(m, s, err)) ||
            (rc = sph_neighbors_update(m, s, true, err)))
            return rc;
    } else {
        rc = m->opt.total_lagrangian ? sph_tlsph_init(m, s, err)
                                     : sph_neighbors_update(m, s, true, err);
        if (rc)
            return rc;
    }
    sph_update_pressure(m, s, SPH_FORM_ALL);
    return SPALL_OK;
}

static int sph_register_fields(struct model *m, struct sim *sim, struct field_registry *reg,
                               struct spall_error *err)
{
    (void)sim;
    int rc;
    double **sc[6], **scn[6], **dscn[6];
    for (int c = 0; c < 6; c++) {
        sc[c] = &m->S[c];
        scn[c] = &m->S_n[c];
        dscn[c] = &m->dS_n[c];
    }
    double **r1[1] = {&m->rho}, **p1[1] = {&m->P}, **e1[1] = {&m->e}, **ep1[1] = {&m->ep},
           **t1[1] = {&m->T};
    if ((rc = field_registry_add_f64(reg, "density", "kg/m^3", 1, r1, FIELD_OUTPUT | FIELD_DEFAULT,
                                     err)) ||
        (rc = field_registry_add_f64(reg, "pressure", "Pa", 1, p1, FIELD_OUTPUT | FIELD_DEFAULT,
                                     err)) ||
        (rc = field_registry_add_f64(reg, "internal_energy", "J/kg", 1, e1, FIELD_OUTPUT, err)) ||
        (rc = field_registry_add_f64(reg, "plastic_strain", "1", 1, ep1,
                                     FIELD_OUTPUT | FIELD_DEFAULT, err)) ||
        (rc = field_registry_add_f64(reg, "temperature", "K", 1, t1, FIELD_OUTPUT, err)) ||
        (rc = field_registry_add_f64_parity(reg, "deviatoric_stress", "Pa", 6, sc, FIELD_OUTPUT,
                                            FIELD_SYMTENSOR, err)) ||
        /* Not output: the predictor-corrector's copies of the stress
         * state between its two stages (sph_advance_state), registered for
         * their parity so that sim_reflect_particle mirrors them with S
         * (the axis reflection of sph_axisym.c acts between the stages).
         * The other odd arrays (dS, sig, L, Bi, R, xv) are recomputed by
         * the force call from the reflected state before they are read. */
        (rc = field_registry_add_f64_parity(reg, "deviatoric_stress_n", "Pa", 6, scn, 0,
                                            FIELD_SYMTENSOR, err)) ||
        (rc = field_registry_add_f64_parity(reg, "deviatoric_stress_rate_n", "Pa/s", 6, dscn, 0,
                                            FIELD_SYMTENSOR, err)))
        return rc;
    struct field_desc d;
    memset(&d, 0, sizeof d);
    strcpy(d.name, "failed");
    strcpy(d.unit, "1");
    d.ncomp = 1;
    d.type = FIELD_U8;
    d.flags = FIELD_OUTPUT;
    d.comp[0] = (void **)&m->failed;
    return field_registry_add(reg, &d, err);
}

/* The force call; @p lfdt > 0: the leapfrog's, which advances the state by
 * lfdt between the velocity gradient and the forces (sph_leapfrog.c). */
static int forces(struct model *m, struct sim *sim, double lfdt, struct spall_error *err)
{
    if (m->clamp)
        sph_clamp_begin(m, sim); /* sph_clamp.c: mirrored clamp around the force call */
    int rc = lfdt > 0.0 ? sph_compute_rates_kick(m, sim, lfdt, err) : sph_compute_rates(m, sim, err);
    if (m->clamp)
        sph_clamp_end(m, sim);
    if (!rc && m->opt.iface != SPH_IFACE_NONE)
        sph_interface_forces(m, sim);
    return rc;
}

static int sph_forces(struct model *m, struct sim *sim, struct spall_error *err)
{
    return forces(m, sim, 0.0, err);
}

static int sph_forces_kick(struct model *m, struct sim *sim, double dt, struct spall_error *err)
{
    return forces(m, sim, dt, err);
}

/* XSPH: particles drift with v + xv (xv of the last force call). */
static bool sph_drift_velocity(const struct model *m, const struct sim *sim, const double *u[3])
{
    if (!(m->opt.xsph > 0.0))
        return false; /* xv = 0 * sum: no stream to add */
    for (int d = 0; d < sim->dim; d++)
        u[d] = m->xv[d];
    return true;
}

/* viscosity_length L: an AV that does not shrink with h, so Eq. 3.38
 * alone no longer bounds the step.  Monaghan (1992) adds the AV's signal
 * speed q_a c + q_b max mu to c; with L in mu_ij the AV is L/h times that
 * (mu ~ L |D|, D the strain rate): a separate bound h / ((L/h)(q_a c +
 * q_b L |D|)).  Measured need: SEBS, AV (2, 1), L = 2.6 h blows up within
 * 150 steps at Eq. 3.38's step; with this bound it keeps the energy as at
 * half the step; factor 1/2 in the bound tripled the energy error; the
 * gelatin decks (L <= 1.7 h, AV (0.5, 0.2)) are not touched (docs/sph.md). */
static double sph_av_length_dt(const struct model *m, size_t i)
{
    const double lav = m->opt.av_length, h = m->h[i];
    double d2 = 0.0;
    for (int a = 0; a < 3; a++)
        for (int b = 0; b < 3; b++) {
            const double dab = 0.5 * (m->L[a * 3 + b][i] + m->L[b * 3 + a][i]);
            d2 += dab * dab;
        }
    const double vvis = (lav / h) * (m->opt.av_a * m->c[i] + m->opt.av_b * lav * sqrt(d2));
    return vvis > 0.0 ? h / vvis : INFINITY;
}

/* Eq. 3.38 without c_s (the engine multiplies by run.dt_factor):
 * min_i h_i / (c_i + |v_i|), c_i the longitudinal sound speed; with
 * viscosity_length also the AV bound above. */
static double sph_stable_dt(const struct model *m, const struct sim *sim)
{
    const struct particles *p = sim->p;
    double best = INFINITY;
    for (size_t i = 0; i < p->n_owned; i++) {
        double v2 = 0.0;
        for (int d = 0; d < sim->dim; d++)
            v2 += p->v[d][i] * p->v[d][i];
        double dt = m->h[i] / (m->c[i] + sqrt(v2));
        /* corrected gradients (CSPM, TLSPH) scale the pair stiffness by up
         * to |B_i^-1| (2-3 at surfaces and corners): the highest frequency
         * grows by the same factor (measured: the TLSPH beam blows up at
         * c_s = 0.3 without this, runs at 0.1).  That was the weak
         * instability of the predictor-corrector (sph_leapfrog.c); the
         * leapfrog runs the TLSPH beam and the CSPM plate stably at the
         * plain limit (c_s = 0.5 and 0.3 measured), so it skips this. */
        if ((m->opt.cspm || m->opt.total_lagrangian) && !m->opt.leapfrog) {
            double nb = 0.0;
            for (int a = 0; a < 3; a++)
                nb = fmax(nb, fabs(m->Bi[a * 3][i]) + fabs(m->Bi[a * 3 + 1][i]) +
                                  fabs(m->Bi[a * 3 + 2][i]));
            if (nb > 1.0)
                dt /= nb;
        }
        if (m->opt.av_length > 0.0)
            dt = fmin(dt, sph_av_length_dt(m, i));
        if (dt < best)
            best = dt;
    }
    if (m->opt.iface != SPH_IFACE_NONE)
        best = fmin(best, sph_interface_stable_dt(m));
    return best;
}

/* [Meng2021] Eqs. 3.35-3.38: predictor-corrector (or the leapfrog) and
 * adaptive dt with c_s = 0.3 (run.dt_factor, parsed after the model, wins) */
static void sph_time_scheme(const struct model *m, struct time_scheme *ts)
{
    ts->integrator = m->opt.leapfrog ? INTEGRATOR_LEAPFROG : INTEGRATOR_PREDICTOR_CORRECTOR;
    ts->adaptive_dt = m->opt.adaptive_dt;
    ts->dt_factor = 0.3;
}

static int sph_end_step(struct model *m, struct sim *sim, struct spall_error *err)
{
    /* TLSPH re-referencing (model.reference_update): the step's state is complete */
    return sph_tlsph_reref_step(m, sim, err);
}

/* Predictor-corrector for rho, e, S, h (Eqs. 3.35-3.37 applied to the
 * state): stage 0 saves state_n and rate_n and predicts state_n + dt rate_n;
 * stage 1 corrects to state_n + dt/2 (rate_n + rate_n+1), then the radial
 * return.  (The leapfrog advances the state in its force call instead.) */
static int sph_advance_state(struct model *m, struct sim *sim, double dt, int stage,
                             struct spall_error *err)
{
    (void)err;
    const size_t n = sim->p->n_owned;
    const bool integ_rho = m->opt.density == SPH_DENSITY_CONTINUITY;
    /* Streams that hold exact zeros are skipped (the state loops are bound
     * by memory traffic once the state outgrows the cache): without
     * variable_h every rate path sets dh = 0, so h_n = h and h stays put. */
    const bool vh = m->opt.variable_h;
    /* One loop per group of a few arrays instead of one loop over all ~40:
     * the hardware prefetchers follow a handful of streams, not forty (the
     * loops were 6x slower per particle once the state left the cache).
     * Each value gets the same operations as before: bitwise the same. */
    if (stage == MODEL_STAGE_PREDICT) {
#pragma omp parallel for schedule(static)
        for (size_t i = 0; i < n; i++) {
            m->rho_n[i] = m->rho[i];
            m->drho_n[i] = m->drho[i];
            if (integ_rho)
                m->rho[i] += dt * m->drho[i];
        }
#pragma omp parallel for schedule(static)
        for (size_t i = 0; i < n; i++) {
            m->e_n[i] = m->e[i];
            m->de_n[i] = m->de[i];
            m->e[i] += dt * m->de[i];
        }
        if (vh) {
#pragma omp parallel for schedule(static)
            for (size_t i = 0; i < n; i++) {
                m->h_n[i] = m->h[i];
                m->dh_n[i] = m->dh[i];
                m->h[i] += dt * m->dh[i];
            }
        }
        for (int c = 0; c < 6; c++) {
            double *S = m->S[c], *dS = m->dS[c], *S_n = m->S_n[c], *dS_n = m->dS_n[c];
#pragma omp parallel for schedule(static)
            for (size_t i = 0; i < n; i++) {
                S_n[i] = S[i];
                dS_n[i] = dS[i];
                S[i] += dt * dS[i];
            }
        }
#pragma omp parallel for schedule(static)
        for (size_t i = 0; i < n; i++)
            sph_plastic_return(m, i, dt, false);
        return SPALL_OK;
    }
    const double hdt = 0.5 * dt;
#pragma omp parallel for schedule(static)
    for (size_t i = 0; i < n; i++) {
        if (integ_rho)
            m->rho[i] = m->rho_n[i] + hdt * (m->drho_n[i] + m->drho[i]);
        m->e[i] = m->e_n[i] + hdt * (m->de_n[i] + m->de[i]);
        if (vh)
            m->h[i] = m->h_n[i] + hdt * (m->dh_n[i] + m->dh[i]);
    }
    for (int c = 0; c < 6; c++) {
        double *S = m->S[c], *dS = m->dS[c], *S_n = m->S_n[c], *dS_n = m->dS_n[c];
#pragma omp parallel for schedule(static)
        for (size_t i = 0; i < n; i++)
            S[i] = S_n[i] + hdt * (dS_n[i] + dS[i]);
    }
#pragma omp parallel for schedule(static)
    for (size_t i = 0; i < n; i++)
        sph_plastic_return(m, i, dt, true);
    return SPALL_OK;
}

extern const struct model_fixture sph_fixtures[]; /* sph_fixture.c */
const struct model_ops sph_model_ops = {
    .name = "sph",
    .summary = "SPH for elastic-plastic solids: six kernels, CSPM, AV/AS/XSPH, JC, Mie-Grueneisen",
    .particle_volumes = true,
    .create = sph_create,
    .parse_material = sph_material_parse,
    .init = sph_init,
    .precrack = NULL,
    .register_fields = sph_register_fields,
    .register_state = sph_register_state,
    .compute_forces = sph_forces,
    .stable_dt = sph_stable_dt,
    .end_step = sph_end_step,
    .energy = sph_energy,
    .history = sph_history,
    .describe = sph_describe,
    .destroy = sph_destroy,
    .advance_state = sph_advance_state,
    .compute_forces_kick = sph_forces_kick,
    .drift_velocity = sph_drift_velocity,
    .time_scheme = sph_time_scheme,
    .interactions = sph_interactions,
    .fixtures = sph_fixtures,
};
