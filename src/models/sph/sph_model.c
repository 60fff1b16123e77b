/**
 * @file sph_model.c
 * @brief SPH for elastic-plastic solids ([Meng2021] chapter 3): deck, life
 *        cycle, predictor-corrector state update, diagnostics.
 *
 * The deck keys are parsed by sph_options.c (listed there and in
 * docs/decks.md).
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
    a[k++] = &m->ax.axl;
    a[k++] = &m->ax.axl_s;
    for (int c = 0; c < 3; c++) {
        a[k++] = &m->xv[c];
        a[k++] = &m->x_build[c];
    }
    if (sph_h_build_kept(&m->opt)) /* last: the other arrays keep their slots */
        a[k++] = &m->h_build;
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
    sph_ul_release(m);
    free(m->ifs.off);
    free(m->ifs.idx);
    free(m->ifs.c0);
    free(m->ifs.e);
    free(m->ifs.w);
    free(m->ifs.np);
    free(m->ck_gid);
    free(m->ck_tlgid);
    free(m->ck_tlup);
    free(m->ck_igid);
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

/* Both plug-ins (sph: updated, tlsph: total Lagrangian) are built here:
 * they share the kernels, EOS, strength models, interfaces and the state,
 * and differ in their formulation's table of hooks (sph_internal.h,
 * sph_form_updated / sph_form_total) and their own keys; @p base_form is
 * the plug-in's formulation, which model.body_formulation can override
 * per body. */
static int sph_create(struct model **out, struct sim *sim, const struct deck_node *params,
                      int base_form, struct spall_error *err)
{
    *out = NULL;
    if (sim->dim < 2)
        return spall_error_set(err, SPALL_ERR_INPUT,
                               "the sph model runs in 2D and 3D; use a 2D or 3D lattice");
    struct sph_parsed in; /* sph_options.c */
    int rc = sph_options_parse(params, sim->dim, base_form, &in, err);
    if (rc)
        return rc;
    struct sph_options o = in.opt;
    struct sph_clamp *clamp = in.clamp;
    struct model *m = calloc(1, sizeof *m);
    if (!m) {
        sph_clamp_destroy(&clamp);
        return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory creating the sph model");
    }
    m->clamp = clamp;
    m->sim = sim;
    m->opt = o;
    m->loops = in.loops;
    if (o.tl.split_forms) {
        rc = sph_forms_parse(params, in.run_form, &m->body_total, &m->n_bodies, err);
        if (rc) {
            sph_destroy(&m);
            return rc;
        }
    }
    /* the formulations' tables (sph_internal.h), TLSPH first */
    if (o.tl.total_lagrangian)
        m->forms[m->n_forms++] = &sph_form_total;
    if (!o.tl.total_lagrangian || o.tl.split_forms)
        m->forms[m->n_forms++] = &sph_form_updated;
    m->dim = sim->dim;
    m->alpha = sph_kernel_alpha(o.kern.kernel, sim->dim);
    m->qmax = sph_kernel_support(o.kern.kernel);
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
        m->h[i] = m->opt.kern.h_factor * m->dx[i];
        m->m2[i] = p->mass[i] / t;
        m->rho[i] = mt->rho0;
        m->T[i] = mt->Troom;
    }
    if (m->opt.kern.plane == SPH_PLANE_AXISYMMETRIC)
        sph_axisym_init(m, s); /* ring masses */
    int rc = m->clamp ? sph_clamp_init(m, s, err) : SPALL_OK;
    if (rc)
        return rc;
    /* bodies split by formulation (sph_forms.c): m->form first, then the
     * TLSPH reference list, then the current list of the updated bodies
     * and the interface */
    if (m->opt.tl.split_forms && (rc = sph_forms_init(m, s, err)))
        return rc;
    for (int k = 0; k < m->n_forms; k++)
        if ((rc = m->forms[k]->init(m, s, err)))
            return rc;
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
    /* sph_clamp.c: mirrored clamp around the force call (distributed: the
     * engine's place hook did this before the rebuild test and the halo) */
    if (m->clamp && !sim->par)
        sph_clamp_begin(m, sim);
    int rc = lfdt > 0.0 ? sph_compute_rates_kick(m, sim, lfdt, err) : sph_compute_rates(m, sim, err);
    if (m->clamp)
        sph_clamp_end(m, sim);
    if (!rc && m->opt.iface.kind != SPH_IFACE_NONE)
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
    if (!(m->opt.visc.xsph > 0.0))
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
    const double lav = m->opt.visc.av_length, h = m->h[i];
    double d2 = 0.0;
    for (int a = 0; a < 3; a++)
        for (int b = 0; b < 3; b++) {
            const double dab = 0.5 * (m->L[a * 3 + b][i] + m->L[b * 3 + a][i]);
            d2 += dab * dab;
        }
    const struct sph_opt_visc *vo = &m->opt.visc;
    const double vvis = (lav / h) * (vo->av_a * m->c[i] + vo->av_b * lav * sqrt(d2));
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
        if ((m->opt.kern.cspm || m->opt.tl.total_lagrangian) && !m->opt.time.leapfrog) {
            double nb = 0.0;
            for (int a = 0; a < 3; a++)
                nb = fmax(nb, fabs(m->Bi[a * 3][i]) + fabs(m->Bi[a * 3 + 1][i]) +
                                  fabs(m->Bi[a * 3 + 2][i]));
            if (nb > 1.0)
                dt /= nb;
        }
        if (m->opt.visc.av_length > 0.0)
            dt = fmin(dt, sph_av_length_dt(m, i));
        if (dt < best)
            best = dt;
    }
    if (m->opt.iface.kind != SPH_IFACE_NONE)
        best = fmin(best, sph_interface_stable_dt(m));
    return best;
}

/* [Meng2021] Eqs. 3.35-3.38: predictor-corrector (or the leapfrog) and
 * adaptive dt with c_s = 0.3 (run.dt_factor, parsed after the model, wins) */
static void sph_time_scheme(const struct model *m, struct time_scheme *ts)
{
    ts->integrator = m->opt.time.leapfrog ? INTEGRATOR_LEAPFROG : INTEGRATOR_PREDICTOR_CORRECTOR;
    ts->adaptive_dt = m->opt.time.adaptive_dt;
    ts->dt_factor = 0.3;
}

static int sph_end_step(struct model *m, struct sim *sim, struct spall_error *err)
{
    /* the step's state is complete (TLSPH: model.reference_update) */
    int rc = SPALL_OK;
    for (int k = 0; k < m->n_forms && !rc; k++)
        if (m->forms[k]->end_step)
            rc = m->forms[k]->end_step(m, sim, err);
    return rc;
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
    const bool integ_rho = m->opt.kern.density == SPH_DENSITY_CONTINUITY;
    /* Streams that hold exact zeros are skipped (the state loops are bound
     * by memory traffic once the state outgrows the cache): without
     * variable_h every rate path sets dh = 0, so h_n = h and h stays put. */
    const bool vh = m->opt.kern.variable_h;
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

/* The wall (model.wall) and the symmetry planes x_d = 0 (model.symmetry,
 * the particles on the positive side), for the frame index to draw. */
static size_t sph_planes(const struct model *m, const struct sim *sim, struct model_plane *out)
{
    const struct sph_opt_bound *b = &m->opt.bound;
    size_t k = 0;
    if (b->wall) {
        memset(&out[k], 0, sizeof out[k]);
        strcpy(out[k].name, "wall");
        for (int c = 0; c < 3; c++) {
            out[k].point[c] = b->wall_point[c];
            out[k].normal[c] = b->wall_normal[c];
        }
        k++;
    }
    for (int d = 0; d < sim->dim && d < 3 && k < MODEL_PLANES_MAX; d++) {
        if (!b->symmetry[d])
            continue;
        memset(&out[k], 0, sizeof out[k]);
        snprintf(out[k].name, sizeof out[k].name, "symmetry_%c", "xyz"[d]);
        out[k].normal[d] = 1.0;
        k++;
    }
    return k;
}

static int sph_create_updated(struct model **out, struct sim *sim,
                              const struct deck_node *params, struct spall_error *err)
{
    return sph_create(out, sim, params, 0, err);
}

static int sph_create_total(struct model **out, struct sim *sim, const struct deck_node *params,
                            struct spall_error *err)
{
    return sph_create(out, sim, params, 1, err);
}

/* sph_fixture.c: each plug-in's bodies for the model contract test */
extern const struct model_fixture sph_fixtures[], tlsph_fixtures[];

/* The hooks both plug-ins share: one implementation, two registry lines. */
#define SPH_SHARED_HOOKS \
    .particle_volumes = true, \
    .parse_material = sph_material_parse, \
    .init = sph_init, \
    .register_fields = sph_register_fields, \
    .register_state = sph_register_state, \
    .compute_forces = sph_forces, \
    .stable_dt = sph_stable_dt, \
    .end_step = sph_end_step, \
    .energy = sph_energy, \
    .history = sph_history, \
    .describe = sph_describe, \
    .destroy = sph_destroy, \
    .advance_state = sph_advance_state, \
    .compute_forces_kick = sph_forces_kick, \
    .drift_velocity = sph_drift_velocity, \
    .time_scheme = sph_time_scheme, \
    .interactions = sph_interactions, \
    .planes = sph_planes, \
    .localize = sph_localize, \
    .halo_bonds = sph_halo_bonds, \
    .migrate_arrays = sph_migrate_arrays, \
    .migrated = sph_migrated, \
    .spatial_ghosts = sph_spatial_ghosts, \
    .spatial_rebuilt = sph_spatial_rebuilt,

const struct model_ops sph_model_ops = {
    .name = "sph",
    .summary = "SPH for elastic-plastic solids, updated Lagrangian: six kernels, CSPM, "
               "AV/AS/XSPH, JC, Mie-Grueneisen",
    .create = sph_create_updated,
    .fixtures = sph_fixtures,
    SPH_SHARED_HOOKS
};

const struct model_ops tlsph_model_ops = {
    .name = "tlsph",
    .summary = "SPH for elastic-plastic solids, total Lagrangian (reference kernel, "
               "hourglass control, re-referencing): JC, Mie-Grueneisen",
    .create = sph_create_total,
    .fixtures = tlsph_fixtures,
    SPH_SHARED_HOOKS
};
