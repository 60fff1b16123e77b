/**
 * @file lattice_model.c
 * @brief Hybrid lattice particle model (HLPM, [Wang2010]): quasi-particles on a
 *        lattice joined by breakable axial springs (Eqs. 1, 15) and, on the
 *        triangular lattice, angular springs (alpha-beta model, Eq. 17).
 *
 * Deck keys (copied to docs/decks.md):
 *
 *   model:
 *     type: lattice
 *     law: linear | lennard_jones | piecewise_linear | softening
 *           (softening: bilinear cohesive law with per-bond damage,
 *           lattice_softening.h; material keys tensile_strength | onset_strain
 *           and fracture_energy | failure_strain)
 *           axial law (default linear; [Wang2010] Eq. 15, Eq. 1, "polynomial")
 *     layers: 1 | 2
 *           axial neighbour shells (seed Fig. 3a/3b).  Default: 1 for chain,
 *           triangular and fcc; 2 for square and sc, which need their diagonals
 *           (layers: 1 is refused there: no shear stiffness).
 *     second_layer_ratio: k2/k1 for a two-layer triangular lattice
 *           (default 1/sqrt3: equal bar modulus k*l; k1 + 3 k2 still gives E)
 *     angular: auto | on | off
 *           angular springs (triangular, layers 1 only).  auto: on iff the
 *           material's nu differs from 1/3 (by more than 1e-3).  nu < 1/3:
 *           alpha-beta angular springs; nu in (1/3, 1): triangle-area springs
 *           (lattice_calib.c); off refuses nu != 1/3.  The paper's
 *           alpha-beta-gamma model is `lattice: type: triple_honeycomb`.
 *
 *   materials:
 *     <name>:
 *       density: [kg/m^3]                (read by the core)
 *       youngs_modulus: [Pa] > 0         required (piecewise_linear: optional,
 *                                        taken from the curve's first slope; if
 *                                        given it must agree within 1%)
 *       poisson_ratio:                   required except on the chain.
 *                                        triangular alpha-beta: (-1, 1/3];
 *                                        area springs: (1/3, 1); triple
 *                                        honeycomb (alpha-beta-gamma): [1/3, 1);
 *                                        central-force lattices: their Cauchy
 *                                        value within 1e-3 (1/3 for triangular
 *                                        with layers 2 or angular off and
 *                                        square; 1/4 for sc and fcc, Voigt)
 *       tensile_strength: [Pa] > 0       } linear law: exactly one of them;
 *       failure_strain: > 0              } eps_max = sigma_TS / E (Eq. 26).
 *                                          lennard_jones: failure_strain only,
 *                                          optional (default: break at the
 *                                          force peak r_d, Eq. 4)
 *       compressive_failure_strain: > 0  optional; default: never breaks in
 *                                        compression
 *       angular_failure: [dphi_c, dphi_t] optional [rad], both > 0: an angular
 *                                        spring breaks when dphi < -dphi_c or
 *                                        dphi > dphi_t (Eq. 17)
 *       exponents: [p, q]                lennard_jones only, required,
 *                                        q > p >= 1 (Eq. 1)
 *       curve: [[strain, stress], ...]   piecewise_linear only, required;
 *                                        starts at [0, 0], strictly increasing
 *                                        strain, first slope > 0; the bond
 *                                        breaks beyond the last strain
 *
 * A bond between materials a and b uses the series stiffness
 * 2 k_a k_b / (k_a + k_b) and the smaller failure strains (piecewise linear:
 * the curve of the material with the smaller last strain); an angular spring
 * uses the constants of its centre particle's material.
 *
 * Fields: fracture_density (Eq. 27: broken / original bonds, pre-cut bonds
 * count as broken), strain_energy [J], stress [Pa] (virial, tension
 * positive; 1D xx; 2D xx yy xy; 3D xx yy zz xy yz xz).  History columns:
 * bonds_broken (during the run, each bond once; pre-cut bonds excluded) and
 * fracture_fraction (all broken bonds / all bonds).
 */
#include "models/lattice/lattice_calib.h"
#include "models/lattice/lattice_honeycomb.h"
#include "models/lattice/lattice_internal.h"
#include "models/lattice/lattice_softening.h"

#include "core/bond_list.h"
#include "models/lattice/lattice_thermal.h"
#include "core/fields.h"
#include "core/particles.h"
#include "core/sim.h"
#include "core/options.h"
#include "core/parallel/comm.h"
#include "core/model.h"
#include "core/parallel/decomp.h"
#include "core/parallel/psum.h"
#include "core/parallel/setup_dist.h"
#include "spall/error.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>


int lattice_model_new(struct model **out, struct sim *sim, const struct lattice_options *opt,
                      struct spall_error *err)
{
    *out = NULL;
    struct model *m = calloc(1, sizeof *m);
    if (!m)
        return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory creating the lattice model");
    m->sim = sim;
    m->opt = *opt;
    m->lp.law = opt->law;
    *out = m;
    return SPALL_OK;
}

int lattice_model_set_material(struct model *m, int index, struct lattice_material *mt,
                               struct spall_error *err)
{
    if (index < 0)
        return spall_error_set(err, SPALL_ERR_INTERNAL, "material index %d", index);
    if ((size_t)index >= m->n_mat) {
        struct lattice_material *q = realloc(m->mat, ((size_t)index + 1) * sizeof *q);
        if (!q)
            return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory for materials");
        memset(q + m->n_mat, 0, ((size_t)index + 1 - m->n_mat) * sizeof *q);
        m->mat = q;
        m->n_mat = (size_t)index + 1;
    }
    lattice_curve_free(&m->mat[index].curve);
    m->mat[index] = *mt;
    m->mat[index].parsed = true;
    memset(&mt->curve, 0, sizeof mt->curve); /* ownership moved */
    return SPALL_OK;
}

static void lattice_destroy(struct model **pm)
{
    if (!pm || !*pm)
        return;
    struct model *m = *pm;
    for (size_t k = 0; k < m->n_mat; k++)
        lattice_curve_free(&m->mat[k].curve);
    free(m->mat);
    free(m->curves);
    free(m->pair);
    free(m->mat_k_phi);
    free(m->mat_k_area);
    free(m->mat_dphi_c);
    free(m->mat_dphi_t);
    bond_list_destroy(&m->bl);
    free(m->ang_b);
    free(m->ang_phi0);
    free(m->ang_state);
    free(m->ang_buf);
    free(m->diss);
    free(m->kappa);
    free(m->half_buf);
    free(m->half_st);
    free(m->half_runs);
    lattice_thermal_destroy(&m->th);
    free(m->ifc);
    free(m);
    *pm = NULL;
}

/* ---- deck ------------------------------------------------------------------ */

static int lattice_create(struct model **out, struct sim *sim, const struct deck_node *params,
                          struct spall_error *err)
{
    static const char *const laws[] = {"linear", "lennard_jones", "piecewise_linear",
                                       "softening", NULL};
    static const char *const angs[] = {"auto", "on", "off", NULL};
    static const char *const keys[] = {"type", "law", "layers", "second_layer_ratio", "angular",
                                       "thermal", "interfaces", NULL};
    struct lattice_options opt = {LATTICE_LAW_LINEAR, 0, -1, 0.0};
    *out = NULL;
    if (params) {
        int law = 0, ang = 0, rc;
        long layers = 0;
        if ((rc = deck_enum(params, "law", false, laws, &law, err)) ||
            (rc = deck_long(params, "layers", false, 1, 2, &layers, err)) ||
            (rc = deck_double_pos(params, "second_layer_ratio", false, &opt.second_layer_ratio,
                                  err)) ||
            (rc = deck_enum(params, "angular", false, angs, &ang, err)) ||
            (rc = deck_check_unused(params, "model", keys, err)))
            return rc;
        opt.law = (enum lattice_law)law;
        opt.layers = (int)layers;
        opt.angular = ang == 0 ? -1 : ang == 1 ? 1 : 0;
        /* lattice-dependent checks with a dummy material of the Cauchy nu */
        struct lattice_calib c;
        memset(&c, 0, sizeof c);
        c.kind = sim->lattice.kind;
        c.layers = opt.layers;
        c.angular = opt.angular;
        c.second_layer_ratio = opt.second_layer_ratio;
        c.E = 1.0;
        c.nu = (c.kind == LATTICE_SC || c.kind == LATTICE_FCC) ? 0.25 : 1.0 / 3.0;
        c.r0 = sim->lattice.spacing > 0.0 ? sim->lattice.spacing : 1.0;
        c.thickness = 1.0;
        if (opt.angular == 1)
            c.nu = 0.2;
        if (lattice_calibrate(&c, err)) {
            const char *key = deck_peek(params, "layers") ? "layers" : "angular";
            if (opt.second_layer_ratio > 0.0 && (opt.layers != 2 || c.kind != LATTICE_TRIANGULAR))
                key = "second_layer_ratio";
            char msg[SPALL_ERROR_MSG_LEN];
            snprintf(msg, sizeof msg, "%s", err->msg);
            deck_error_key(err, params, key, "%s", msg);
            err->code = SPALL_ERR_PHYSICS;
            return SPALL_ERR_PHYSICS;
        }
    }
    int rc = lattice_model_new(out, sim, &opt, err);
    const struct deck_node *th = params ? deck_get(params, "thermal") : NULL;
    if (!rc && th && (rc = lattice_thermal_parse_options(*out, th, err)))
        lattice_destroy(out);
    if (!rc && params && (rc = lattice_interfaces_parse(*out, params, err)))
        lattice_destroy(out);
    return rc;
}


/* ---- init -------------------------------------------------------------------- */

/** Pair table from the per-material constants (symmetric by construction). */
static void build_pair_table(struct model *m)
{
    const size_t nm = m->n_mat;
    for (size_t a = 0; a < nm; a++)
        for (size_t b = a; b < nm; b++)
            for (int t = 0; t < LATTICE_MAX_TYPES; t++) {
                const struct lattice_material *A = &m->mat[a], *B = &m->mat[b];
                struct lattice_bond_law w;
                memset(&w, 0, sizeof w);
                w.k = a == b ? A->k[t] : 2.0 * A->k[t] * B->k[t] / (A->k[t] + B->k[t]);
                if (!(w.k > 0.0) || !isfinite(w.k))
                    w.k = 0.0;
                double et = fmin(A->eps_t, B->eps_t), ec = fmin(A->eps_c, B->eps_c);
                w.curve = (int)(B->eps_t < A->eps_t ? b : a);
                double s_min;
                if (m->lp.law == LATTICE_LAW_LJ) {
                    double sd = lattice_lj_peak_stretch(m->lp.p, m->lp.q);
                    if (!(A->eps_t_given || B->eps_t_given))
                        et = sd - 1.0;
                    /* |dF/dr| grows in compression: bound it at the compressive
                     * limit, or (none) at a compression as large as the tensile
                     * failure strain */
                    s_min = isfinite(ec) ? 1.0 - ec : 1.0 - fmin(et, 0.5);
                    s_min = fmax(s_min, 0.5);
                    w.dfdr_max = w.k * lattice_lj_slope(m->lp.p, m->lp.q, s_min);
                } else if (m->lp.law == LATTICE_LAW_PWL) {
                    const struct lattice_curve *cv = &m->mat[w.curve].curve;
                    double smax = 1.0;
                    for (size_t k = 0; k + 1 < cv->n; k++)
                        smax = fmax(smax, fabs(cv->slope[k]));
                    w.dfdr_max = w.k * smax;
                } else if (m->lp.law == LATTICE_LAW_SOFT) {
                    /* the softening branch's slope may be steeper than k */
                    w.e0 = fmin(A->eps_0, B->eps_0);
                    w.dfdr_max = w.k * fmax(1.0, w.e0 / (et - w.e0));
                } else {
                    w.dfdr_max = w.k;
                }
                w.t_lim = isfinite(et) ? 1.0 + et : INFINITY;
                w.c_lim = isfinite(ec) ? 1.0 - ec : -INFINITY;
                m->pair[(a * nm + b) * LATTICE_MAX_TYPES + (size_t)t] = w;
                m->pair[(b * nm + a) * LATTICE_MAX_TYPES + (size_t)t] = w;
            }
    lattice_interfaces_apply(m); /* model.interfaces (lattice_interface.c) */
}

void lattice_model_override(struct model *m, double k1, double k_phi)
{
    m->mat[0].k[0] = k1;
    m->mat[0].k_phi = k_phi;
    m->mat_k_phi[0] = k_phi;
    build_pair_table(m);
}

/** Angles between consecutive first-shell bonds (sorted by reference angle)
 *  that are adjacent in the triangular lattice (60 deg apart; anything wider
 *  than 90 deg, e.g. the 180 deg gap at a free edge, is not a lattice angle). */
static int build_angles(struct model *m, const struct particles *p, struct spall_error *err)
{
    struct bond_list *bl = m->bl;
    int rc = bond_list_build_reverse(bl, err);
    if (rc)
        return rc;
    size_t nh = m->n_half;
    m->ang_b = malloc((nh ? nh : 1) * sizeof *m->ang_b);
    m->ang_phi0 = calloc(nh ? nh : 1, sizeof *m->ang_phi0);
    m->ang_state = calloc(nh ? nh : 1, sizeof *m->ang_state);
    m->ang_buf = calloc(2 * (nh ? nh : 1), sizeof *m->ang_buf);
    if (!m->ang_b || !m->ang_phi0 || !m->ang_state || !m->ang_buf)
        return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory for angular springs");
    memset(m->ang_b, LATTICE_NO_ANGLE, nh ? nh : 1);
    for (size_t i = 0; i < bl->n; i++) {
        size_t s0 = bl->offset[i], len = bl->offset[i + 1] - s0;
        size_t loc[64];
        double th[64];
        size_t cnt = 0;
        for (size_t q = 0; q < len && cnt < 64; q++) {
            size_t s = s0 + q;
            if (bl->type[s] != 0)
                continue;
            size_t j = (size_t)bl->partner[s];
            th[cnt] = atan2(p->x0[1][j] - p->x0[1][i], p->x0[0][j] - p->x0[0][i]);
            loc[cnt++] = q;
        }
        for (size_t a = 1; a < cnt; a++) /* insertion sort by angle */
            for (size_t b = a; b > 0 && th[b] < th[b - 1]; b--) {
                double tt = th[b];
                th[b] = th[b - 1];
                th[b - 1] = tt;
                size_t tl = loc[b];
                loc[b] = loc[b - 1];
                loc[b - 1] = tl;
            }
        for (size_t a = 0; a < cnt && cnt > 1; a++) {
            size_t b = (a + 1) % cnt;
            double gap = th[b] - th[a];
            if (gap <= 0.0)
                gap += 2.0 * SPALL_PI;
            if (!(gap < 0.5 * SPALL_PI) || loc[b] > 254)
                continue;
            size_t sa = s0 + loc[a], sb = s0 + loc[b];
            size_t ja = (size_t)bl->partner[sa], jb = (size_t)bl->partner[sb];
            double ax = p->x0[0][ja] - p->x0[0][i], ay = p->x0[1][ja] - p->x0[1][i];
            double bx = p->x0[0][jb] - p->x0[0][i], by = p->x0[1][jb] - p->x0[1][i];
            m->ang_b[sa] = (uint8_t)loc[b];
            m->ang_phi0[sa] = atan2(ax * by - ay * bx, ax * bx + ay * by);
        }
    }
    return SPALL_OK;
}

static int lattice_init(struct model *m, struct sim *sim, struct spall_error *err)
{
    struct particles *p = sim->p;
    const struct lattice_spec *spec = &sim->lattice;
    m->dim = sim->dim;
    if (lattice_kind_dim(spec->kind) != sim->dim)
        return spall_error_set(err, SPALL_ERR_INPUT, "lattice model: %s lattice in a %dD run",
                               lattice_kind_name(spec->kind), sim->dim);
    size_t nm = sim->n_materials;
    if (nm == 0 || m->n_mat < nm)
        return spall_error_set(err, SPALL_ERR_INPUT,
                               "lattice model: material %zu has no parameters", m->n_mat);
    for (size_t k = 0; k < nm; k++)
        if (!m->mat[k].parsed)
            return spall_error_set(err, SPALL_ERR_INPUT,
                                   "lattice model: material '%s' has no parameters",
                                   sim->materials[k].name);
    m->n_mat = nm;
    /* law parameters */
    if (m->opt.law == LATTICE_LAW_LJ) {
        m->lp.p = m->mat[0].lj_p;
        m->lp.q = m->mat[0].lj_q;
        for (size_t k = 1; k < nm; k++)
            if (m->mat[k].lj_p != m->lp.p || m->mat[k].lj_q != m->lp.q)
                return spall_error_set(err, SPALL_ERR_INPUT,
                                       "lattice model: every material needs the same "
                                       "Lennard-Jones exponents ('%s' differs from '%s')",
                                       sim->materials[k].name, sim->materials[0].name);
    }
    m->curves = calloc(nm, sizeof *m->curves);
    m->pair = calloc(nm * nm * LATTICE_MAX_TYPES, sizeof *m->pair);
    m->mat_k_phi = calloc(nm, sizeof *m->mat_k_phi);
    m->mat_k_area = calloc(nm, sizeof *m->mat_k_area);
    m->mat_dphi_c = calloc(nm, sizeof *m->mat_dphi_c);
    m->mat_dphi_t = calloc(nm, sizeof *m->mat_dphi_t);
    m->diss = calloc(p->n ? p->n : 1, sizeof *m->diss);
    if (!m->curves || !m->pair || !m->mat_k_phi || !m->mat_k_area || !m->mat_dphi_c || !m->mat_dphi_t || !m->diss)
        return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory in the lattice model");
    /* spring constants per material */
    int layers = 0, angular = 0;
    for (size_t k = 0; k < nm; k++) {
        struct lattice_material *mt = &m->mat[k];
        struct lattice_calib c;
        memset(&c, 0, sizeof c);
        c.kind = spec->kind;
        c.layers = m->opt.layers;
        c.angular = m->opt.angular;
        c.second_layer_ratio = m->opt.second_layer_ratio;
        c.E = mt->E;
        c.nu = mt->nu;
        c.rho = sim->materials[k].density;
        c.r0 = spec->spacing;
        c.thickness = sim->thickness;
        int rc = lattice_calibrate(&c, err);
        if (rc) {
            spall_error_prefix(err, "material '%s': ", sim->materials[k].name);
            spall_error_default_key(err, "materials.%s", sim->materials[k].name);
            return rc;
        }
        mt->k[0] = c.honeycomb_used ? c.k_family[0] : c.k1;
        mt->k[1] = c.honeycomb_used ? c.k_family[1] : c.k2;
        mt->k[2] = c.k_family[2];
        mt->k_phi = c.k_phi;
        layers = c.layers_used;
        angular |= c.angular_used;
        m->curves[k] = mt->curve;
        m->mat_k_phi[k] = c.k_phi;
        mt->k_area = c.k_area;
        m->mat_k_area[k] = c.k_area;
        m->mat_dphi_c[k] = mt->dphi_c;
        m->mat_dphi_t[k] = mt->dphi_t;
        if (m->opt.law == LATTICE_LAW_SOFT && mt->gf > 0.0 &&
            (rc = lattice_soft_final_strain(&c, mt->eps_0, mt->gf, &mt->eps_t, err))) {
            spall_error_prefix(err, "material '%s': ", sim->materials[k].name);
            spall_error_default_key(err, "materials.%s", sim->materials[k].name);
            return rc;
        }
    }
    m->layers = layers;
    m->angular = angular && sim->dim == 2;
    m->lp.law = m->opt.law;
    m->lp.curves = m->curves;
    if (lattice_interfaces_resolve(m, sim, err))
        return err->code;
    build_pair_table(m);
    /* bonds: one shell per layer, +-5% around the shell distance (the
     * lattices' shells are at least 15% apart) */
    double lo[LATTICE_MAX_TYPES], hi[LATTICE_MAX_TYPES];
    for (int s = 0; s < layers; s++) {
        double d = lattice_shell_distance(spec, s + 1);
        lo[s] = 0.95 * d;
        hi[s] = 1.05 * d;
    }
    bond_list_destroy(&m->bl);
    /* rest lengths that never change (no thermal expansion) as an index
     * into their distinct values from the start: 6 B less per half-bond,
     * the same bits, and the set-up never holds the doubles */
    const bool fixed_rest = !lattice_thermal_enabled(m);
    int rc = fixed_rest ? bond_list_build_shells_compact(&m->bl, p, layers, lo, hi, err)
                        : bond_list_build_shells(&m->bl, p, layers, lo, hi, err);
    if (rc)
        return rc;
    m->half_known = false; /* a new list: lattice_half_ring checks its rows again */
    m->n_half = m->bl->offset[m->bl->n];
    if (m->opt.law == LATTICE_LAW_SOFT) {
        free(m->kappa);
        m->kappa = calloc(m->n_half ? m->n_half : 1, sizeof *m->kappa);
        if (!m->kappa)
            return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory for bond damage");
    }
    m->honeycomb = spec->kind == LATTICE_TRIPLE_HONEYCOMB;
    if (m->honeycomb) /* bond type = honeycomb family (alpha, beta, gamma) */
        lattice_honeycomb_retype(m->bl, p, spec);
    if (m->angular && (rc = build_angles(m, p, err)))
        return rc;
    if ((rc = lattice_thermal_init(m, sim, err)))
        return rc;
    m->initialised = true;
    return SPALL_OK;
}

static int lattice_precrack(struct model *m, struct sim *sim, const struct precrack *c,
                            size_t *n_cut, struct spall_error *err)
{
    if (!m->bl)
        return spall_error_set(err, SPALL_ERR_INTERNAL, "lattice pre-crack before init");
    *n_cut = bond_list_apply_precrack(m->bl, sim->p, c);
    return SPALL_OK;
}

/* ---- fields ------------------------------------------------------------------ */

static void field_fracture_density(const void *ctx, size_t n, double *out)
{
    const struct model *m = ctx;
    const struct bond_list *bl = m->bl;
#pragma omp parallel for schedule(static)
    for (size_t i = 0; i < n; i++) {
        size_t nb = 0, len = bl->offset[i + 1] - bl->offset[i];
        for (size_t s = bl->offset[i]; s < bl->offset[i + 1]; s++)
            nb += (bl->state[s] & BOND_BROKEN) != 0;
        out[i] = len ? (double)nb / (double)len : 0.0; /* [Wang2010] Eq. 27 */
    }
}

static void field_strain_energy(const void *ctx, size_t n, double *out)
{
    const struct model *m = ctx;
#pragma omp parallel for schedule(static)
    for (size_t i = 0; i < n; i++)
        lattice_particle_eval(m, m->sim, i, &out[i], NULL);
}

static void field_stress(const void *ctx, size_t n, double *out)
{
    const struct model *m = ctx;
    const size_t nc = (size_t)field_symtensor_ncomp(m->dim);
#pragma omp parallel for schedule(static)
    for (size_t i = 0; i < n; i++)
        lattice_particle_eval(m, m->sim, i, NULL, &out[i * nc]);
}

static int lattice_register_fields(struct model *m, struct sim *sim, struct field_registry *reg,
                                   struct spall_error *err)
{
    int nc = field_symtensor_ncomp(sim->dim);
    int rc;
    if ((rc = field_registry_add_computed(reg, "fracture_density", "1", 1, FIELD_OUTPUT | FIELD_DEFAULT,
                           field_fracture_density, m, err)) ||
        (rc = field_registry_add_computed(reg, "strain_energy", "J", 1, FIELD_OUTPUT, field_strain_energy, m,
                           err)) ||
        (rc = field_registry_add_computed(reg, "stress", "Pa", nc, FIELD_OUTPUT | FIELD_DEFAULT, field_stress,
                           m, err)))
        return rc;
    return lattice_thermal_register_fields(m, reg, err);
}

/* ---- step hooks ------------------------------------------------------------------ */

static int lattice_forces(struct model *m, struct sim *sim, struct spall_error *err)
{
    return lattice_set_forces(m, sim, err);
}

/** Stable dt: see lattice_calib.c for the bound ([Wang2010] Eq. 25). */
static double lattice_stable_dt(const struct model *m, const struct sim *sim)
{
    const struct particles *p = sim->p;
    const struct bond_list *bl = m->bl;
    const size_t n = p->n, nm = m->n_mat;
    double *om = calloc(n ? n : 1, sizeof *om);
    if (!om)
        return 0.0;
    for (size_t i = 0; i < n; i++)
        for (size_t s = bl->offset[i]; s < bl->offset[i + 1]; s++) {
            size_t j = (size_t)bl->partner[s];
            om[i] += m->pair[((size_t)p->material[i] * nm + (size_t)p->material[j]) *
                                 LATTICE_MAX_TYPES + bl->type[s]].dfdr_max;
        }
    if (m->angular)
        for (size_t i = 0; i < n; i++) {
            double kp = m->mat_k_phi[p->material[i]];
            for (size_t s = bl->offset[i]; s < bl->offset[i + 1]; s++) {
                if (m->ang_b[s] == LATTICE_NO_ANGLE)
                    continue;
                size_t sb = bl->offset[i] + m->ang_b[s];
                double ia = 1.0 / bond_rest(bl, s), ib = 1.0 / bond_rest(bl, sb), g = ia + ib;
                om[i] += kp * g * g;
                om[bl->partner[s]] += kp * ia * g;
                om[bl->partner[sb]] += kp * ib * g;
                /* area share (lattice_calib.c): half the Gershgorin row */
                double ra = bond_rest(bl, s), rb = bond_rest(bl, sb);
                double A0 = 0.5 * ra * rb * sin(m->ang_phi0[s]);
                double ks = m->mat_k_area[p->material[i]] / 3.0, h = 0.5 * ks / (A0 * A0);
                om[i] += h * 0.5 * (ra + rb) * (ra + rb);
                om[bl->partner[s]] += h * 0.5 * rb * (ra + rb);
                om[bl->partner[sb]] += h * 0.5 * ra * (ra + rb);
            }
        }
    double w2 = 0.0;
    for (size_t i = 0; i < p->n_owned; i++)
        w2 = fmax(w2, om[i] / p->mass[i]);
    free(om);
    return w2 > 0.0 ? sqrt(2.0 / w2) : INFINITY;
}

static int lattice_end_step(struct model *m, struct sim *sim, struct spall_error *err)
{
    /* Breaking is fused into the force loop (each half-bond decided by its
     * own particle's thread); the thermal lattice advances here. */
    return lattice_thermal_step(m, sim, sim_step_dt(sim), err);
}

static void lattice_energy_fn(const struct model *m, const struct sim *sim,
                              struct model_energy *out)
{
    /* exact sums: one value for any thread and rank count */
    par_bond_energy(m, sim, lattice_particle_eval, m->diss, &out->strain, &out->dissipated);
}

static size_t lattice_history(const struct model *m, const struct sim *sim, const char **names,
                              double *values)
{
    const struct bond_list *bl = m->bl;
    size_t broken_run = 0, broken_all = 0;
    size_t nh = bl->offset[sim->p->n_owned];
    for (size_t s = 0; s < nh; s++) {
        broken_all += (bl->state[s] & BOND_BROKEN) != 0;
        broken_run += bl->state[s] == BOND_BROKEN;
    }
    if (sim->par) { /* integer counts: exact in any order */
        uint64_t c[3] = {broken_run, broken_all, nh};
        par_sum_u64_array(c, 3);
        broken_run = (size_t)c[0];
        broken_all = (size_t)c[1];
        nh = (size_t)c[2];
    }
    names[0] = "bonds_broken";
    values[0] = 0.5 * (double)broken_run;
    names[1] = "fracture_fraction";
    values[1] = nh ? (double)broken_all / (double)nh : 0.0;
    return 2 + lattice_thermal_history(m, sim, names + 2, values + 2);
}

static void lattice_describe(const struct model *m, const struct sim *sim, char *buf,
                             size_t len)
{
    static const char *const lawn[] = {"linear", "lennard_jones", "piecewise_linear",
                                       "softening"};
    size_t w = 0;
#define PUT(...)                                                                                \
    do {                                                                                        \
        if (w < len)                                                                            \
            w += (size_t)snprintf(buf + w, len - w, __VA_ARGS__);                               \
    } while (0)
    double r0 = sim->lattice.spacing;
    PUT("lattice model (HLPM): %s lattice, r0 = %g m, thickness/area = %g, law %s, layers %d, "
        "angular springs %s\n", lattice_kind_name(sim->lattice.kind), r0, sim->thickness,
        lawn[m->opt.law], m->layers, m->angular ? "on" : "off");
    for (size_t k = 0; k < m->n_mat; k++) {
        const struct lattice_material *mt = &m->mat[k];
        PUT("  material '%s': E = %g Pa, nu = %g, k1 = %g N/m", sim->materials[k].name, mt->E,
            mt->nu, mt->k[0]);
        if (m->layers > 1 || m->honeycomb)
            PUT(m->honeycomb ? " (alpha), beta = gamma = %g N/m (triple honeycomb)"
                             : ", k2 = %g N/m", mt->k[1]);
        if (m->angular && mt->k_area > 0.0)
            PUT(", k_area = %g J (area springs)", mt->k_area);
        else if (m->angular)
            PUT(", k_phi = %g N m/rad^2 (seed Eq. 18 would give %g)", mt->k_phi,
                sim->lattice.kind == LATTICE_TRIANGULAR
                    ? lattice_paper_k_phi(mt->E, mt->nu, r0, sim->thickness) : 0.0);
        const struct lattice_bond_law *w0 = &m->pair[(k * m->n_mat + k) * LATTICE_MAX_TYPES];
        PUT(", eps_max = %g, compressive limit %g\n", w0->t_lim - 1.0,
            isfinite(w0->c_lim) ? 1.0 - w0->c_lim : INFINITY);
        if (m->opt.law == LATTICE_LAW_SOFT)
            PUT("    softening: onset strain e0 = %g, full separation ef = %g (%s), energy per "
                "first-shell bond k1 r0^2 e0 ef / 2 = %g J\n", w0->e0, w0->t_lim - 1.0,
                mt->gf > 0.0 ? "from fracture_energy" : "failure_strain", 0.5 * mt->k[0] * r0 *
                r0 * w0->e0 * (w0->t_lim - 1.0));
        if (m->opt.law == LATTICE_LAW_LJ) {
            double p = m->lp.p, q = m->lp.q, k1 = mt->k[0];
            double H = k1 * pow(r0, q + 1.0) / (q - p), G = H * pow(r0, p - q);
            double sd = lattice_lj_peak_stretch(p, q);
            double Fd = -k1 * r0 * (pow(sd, -q) - pow(sd, -p)) / (q - p);
            PUT("    Lennard-Jones p = %g, q = %g: G = %g, H = %g (SI, r0 shell), r_d = %g m "
                "(strain %g), peak force %g N, sigma_TS = F(r_d)/r0^2 = %g Pa (Eq. 4); "
                "lattice uniaxial estimate E F_d/(k1 r0) = %g Pa\n",
                p, q, G, H, sd * r0, sd - 1.0, Fd, Fd / (r0 * r0), mt->E * Fd / (k1 * r0));
        }
    }
    /* distributed: the whole body's limit (a rank's rows alone cannot give it) */
    PUT("  stable dt = %g s (sqrt2 / max Omega, [Wang2010] Eq. 25)\n",
        sim->par ? sim->dt_limit : lattice_stable_dt(m, sim));
#undef PUT
}

/* Bonds counted once (pre-cut and broken ones included: they are still
 * visited every step for contact repulsion). */
static size_t lattice_interactions(const struct model *m, const struct sim *sim)
{
    (void)sim;
    return m->bl ? bond_list_count(m->bl) : 0;
}

/* Distributed set-up: the longest bond init makes, the outermost shell's
 * upper bound (layers not yet resolved: the second shell's, the most a
 * lattice has). */
static double lattice_setup_range(const struct model *m, const struct sim *sim)
{
    return 1.05 * lattice_shell_distance(&sim->lattice, m->opt.layers > 0 ? m->opt.layers : 2);
}

/* Distributed set-up: the compact rest lengths' table, the same on every rank */
static int lattice_setup_tables(struct model *m, struct sim *sim, struct spall_error *err)
{
    (void)sim;
    struct bond_list *bl = m->bl;
    return par_setup_merge_table((void **)&bl->rest_tab, sizeof(double), &bl->n_rest,
                                 bl->rest_idx, bl->rest_idx ? bl->offset[bl->n] : 0, err);
}

/* for fragments (core/fragments.h) */
static const struct bond_list *lattice_bonds(const struct model *m)
{
    return m->bl;
}

extern const struct model_fixture lattice_fixtures[]; /* lattice_fixture.c */
const struct model_ops lattice_model_ops = {
    .name = "lattice",
    .summary = "hybrid lattice particle model (HLPM): breakable axial/angular springs",
    .create = lattice_create,
    .parse_material = lattice_parse_material,
    .init = lattice_init,
    .precrack = lattice_precrack,
    .register_fields = lattice_register_fields,
    .compute_forces = lattice_forces,
    .stable_dt = lattice_stable_dt,
    .end_step = lattice_end_step,
    .energy = lattice_energy_fn,
    .history = lattice_history,
    .describe = lattice_describe,
    .destroy = lattice_destroy,
    .interactions = lattice_interactions,
    .bonds = lattice_bonds,
    .register_state = lattice_register_state,
    .localize = lattice_localize,
    .migrate_arrays = lattice_migrate_arrays,
    .migrated = lattice_migrated,
    .fixtures = lattice_fixtures,
    .setup_range = lattice_setup_range,
    .setup_tables = lattice_setup_tables,
    .bonds_within_bodies = true, /* bond_list_build_shells skips other bodies */
    .sets_forces = true,         /* lattice_set_forces */
};

const struct lattice_material *lattice_material_get(const struct model *m, int k)
{
    return &m->mat[k];
}

const struct lattice_bond_law *lattice_pair_law(const struct model *m, int ma, int mb, int type)
{
    return &m->pair[((size_t)ma * m->n_mat + (size_t)mb) * LATTICE_MAX_TYPES + (size_t)type];
}

struct bond_list *lattice_bond_list(struct model *m)
{
    return m->bl;
}

bool lattice_has_angles(const struct model *m)
{
    return m->angular;
}

double lattice_area_stiffness(const struct model *m, int k)
{
    return m->mat_k_area[k];
}

void lattice_set_angle_limits(struct model *m, int k, double dphi_c, double dphi_t)
{
    m->mat_dphi_c[k] = dphi_c;
    m->mat_dphi_t[k] = dphi_t;
}

uint8_t *lattice_angle_states(struct model *m, size_t *n)
{
    *n = m->n_half;
    return m->ang_state;
}
