/**
 * @file macro_model.c
 * @brief Macro-particle model ([Saitoh] "MPM", spec/macroparticle.md): FCC
 *        macro-particles each standing for N_atom atoms, joined by a Mie pair
 *        potential whose depth comes from the cohesive energy (Eqs. 10-15),
 *        with optional Langevin forces (Eqs. 6-9, 17-22) and pair plasticity
 *        (Eq. 16).  Forces and neighbours: macro_forces.c.
 *
 * Deck keys (copied to docs/decks.md):
 *
 *   model:
 *     type: macroparticle
 *     cutoff: r_c / r0 (default 1.35: the nearest FCC shell only; the second
 *             shell sits at sqrt2 = 1.414)
 *     taper: r_on / r0 (default 1.2): phi is multiplied by a cubic switch
 *            from 1 at r_on to 0 at r_c, so force and energy are continuous
 *     skin: Verlet skin / r0 (default 0.1)
 *     damping: none | absolute | pairwise (default none)
 *     temperature: bath temperature T [K] (default 0: no random force)
 *     gamma: absolute coefficient [kg/s] (default zeta_cg m (pi/6) omega_D,
 *            m the atomic mass, omega_D = k_B theta_D / hbar; Eq. 20)
 *     mu: pairwise coefficient [kg/s] (same default)
 *     zeta_cg: coarse-graining factor of the dissipation (default 1)
 *     eta_cg: coarse-graining factor of the random force (default 1; the
 *             bath then holds eta_cg^2 T)
 *     axis: x | y | z: loading axis of the history's strain (default z)
 *     calibration: eq15 | lattice (default eq15).  eq15: the seed's well
 *             depth D = P_atom/6 (Eq. 13); the FCC crystal of these pairs is
 *             1.886 x stiffer along [100] than Eq. 15 says.  lattice: D scaled
 *             so that E_[100] of the FCC lattice (Cauchy-Born sum over every
 *             shell inside the cut-off) equals the material's youngs_modulus,
 *             default Eq. 15's E (macro_lattice.c)
 *     pair_loop: half | full (default half).  half: each pair evaluated
 *             once (macro_half.c); full: from both ends (the reference loop
 *             of macro_forces.c).  The same results, bit for bit.
 *
 *   materials:
 *     <name>:
 *       density: [kg/m^3]
 *       atomic_mass_u: atomic mass [u] (> 0, required)
 *       cohesive_energy_ev: cohesive energy per atom [eV] (> 0, required)
 *       exponents: [p, q], q > p > 0 (required; [Saitoh] uses [4, 9] for Al)
 *       debye_temperature: [K] (> 0; required only for Langevin defaults)
 *       yield_strain: pair elastic stretch at yield / r0 (> 0; optional,
 *                     turns plasticity on)
 *       hardening: plastic / elastic pair tangent in [0, 1) (default 0.1)
 *       youngs_modulus: target E_[100] [Pa] of calibration: lattice (> 0;
 *                       default Eq. 15's E; refused with calibration: eq15)
 *
 * The lattice must be fcc (3D): r0 = lattice.spacing.  One material per
 * run (the pair shape of material 0 is used; a second material is refused).
 *
 * Fields: stress [Pa] (virial, tension positive, xx yy zz xy yz xz),
 * strain_energy [J] (half the pair energies of the particle), plastic_slip
 * [m] (sum of the accumulated slip of its pairs, halved), centro_symmetry
 * [1] and slip_vector [m], slip_normal [1] (macro_slip.c).
 * History: strain (axial, from the mean positions of the end layers),
 * lateral_strain (RMS transverse spread of the middle half), stress_axial,
 * stress_nominal (axial virial / (V0 (1 + strain)) = axial force over the
 * reference section: the engineering stress of a tensile test),
 * stress_xx, stress_yy, stress_zz (specimen virial average, Pa),
 * kinetic_temperature [K], plastic_pairs, neighbor_builds.
 */
#include "core/mathconst.h"
#include "models/macroparticle/macro_internal.h"
#include "models/macroparticle/macro_slip.h"

#include "core/exact_sum.h"
#include "core/fields.h"
#include "core/neighbor.h"
#include "core/parallel/comm.h"
#include "core/parallel/decomp.h"
#include "core/parallel/psum.h"
#include "core/particles.h"
#include "core/sim.h"
#include "core/options.h"
#include "core/model.h"
#include "spall/error.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>


static void macro_destroy(struct model **pm)
{
    if (!pm || !*pm)
        return;
    struct model *m = *pm;
    macro_par_release(m);
    macro_half_free(m);
    free(m->mat);
    neighbor_list_destroy(&m->nl);
    neighbor_list_destroy(&m->nl0);
    for (int d = 0; d < 3; d++)
        free(m->xb[d]);
    free(m->dr0);
    free(m->kappa);
    free(m->engaged);
    free(m->pgid);
    free(m->ck_gid);
    free(m->epot);
    free(m->sig);
    free(m->wdiss);
    free(m->lo_idx);
    free(m->hi_idx);
    free(m->mid_idx);
    free(m->gflag);
    free(m);
    *pm = NULL;
}

static int macro_create(struct model **out, struct sim *sim, const struct deck_node *params,
                        struct spall_error *err)
{
    static const char *const keys[] = {"type", "cutoff", "taper", "skin", "damping",
                                       "temperature", "gamma", "mu", "zeta_cg", "eta_cg", "axis",
                                       "calibration", "pair_loop", NULL};
    static const char *const cals[] = {"eq15", "lattice", NULL};
    static const char *const loops[] = {"half", "full", NULL};
    static const char *const damps[] = {"none", "absolute", "pairwise", NULL};
    static const char *const axes[] = {"x", "y", "z", NULL};
    (void)sim;
    *out = NULL;
    struct model *m = calloc(1, sizeof *m);
    if (!m)
        return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory creating the macro model");
    m->sim = sim;
    m->cutoff_ratio = 1.35;
    m->taper_ratio = 1.2;
    m->skin_ratio = 0.1;
    m->zeta_cg = 1.0;
    m->eta_cg = 1.0;
    m->axis = 2;
    int damp = 0, ax = 2, cal = 0, loop = 0, rc = 0;
    if (params) {
        if ((rc = deck_double(params, "cutoff", false, 1.05, 3.0, &m->cutoff_ratio, err)) ||
            (rc = deck_double(params, "taper", false, 1.0, 3.0, &m->taper_ratio, err)) ||
            (rc = deck_double(params, "skin", false, 0.0, 1.0, &m->skin_ratio, err)) ||
            (rc = deck_enum(params, "damping", false, damps, &damp, err)) ||
            (rc = deck_double(params, "temperature", false, 0.0, INFINITY, &m->temperature, err)) ||
            (rc = deck_double(params, "gamma", false, 0.0, INFINITY, &m->gamma, err)) ||
            (rc = deck_double(params, "mu", false, 0.0, INFINITY, &m->mu, err)) ||
            (rc = deck_double_pos(params, "zeta_cg", false, &m->zeta_cg, err)) ||
            (rc = deck_double_pos(params, "eta_cg", false, &m->eta_cg, err)) ||
            (rc = deck_enum(params, "axis", false, axes, &ax, err)) ||
            (rc = deck_enum(params, "calibration", false, cals, &cal, err)) ||
            (rc = deck_enum(params, "pair_loop", false, loops, &loop, err)) ||
            (rc = deck_check_unused(params, "model", keys, err))) {
            macro_destroy(&m);
            return rc;
        }
        if (!(m->taper_ratio < m->cutoff_ratio)) {
            rc = deck_error_key(err, params, "taper", "taper %g must be below cutoff %g (both "
                                "in units of r0)", m->taper_ratio, m->cutoff_ratio);
            macro_destroy(&m);
            return rc;
        }
        if (m->temperature > 0.0 && damp == 0) {
            rc = deck_error_key(err, params, "temperature", "temperature %g K needs damping: "
                                "absolute or pairwise (fluctuation-dissipation, [Saitoh] "
                                "Eq. 9)", m->temperature);
            macro_destroy(&m);
            return rc;
        }
    }
    m->damping = (enum macro_damping)damp;
    m->axis = ax;
    m->pair_full = loop == 1;
    m->calibration = cal ? MACRO_CAL_LATTICE : MACRO_CAL_EQ15;
    *out = m;
    return SPALL_OK;
}

static int macro_parse_material(struct model *m, struct sim *sim, int index,
                                const struct deck_node *node, struct spall_error *err)
{
    static const char *const keys[] = {"density", "atomic_mass_u", "cohesive_energy_ev",
                                       "exponents", "debye_temperature", "yield_strain",
                                       "hardening", "youngs_modulus", NULL};
    char what[SPALL_NAME_LEN + 16];
    snprintf(what, sizeof what, "materials.%s", sim->materials[index].name);
    if (index != 0)
        return deck_error(err, node, "%s: the macro-particle model takes one material per run",
                          what);
    struct macro_material mt;
    memset(&mt, 0, sizeof mt);
    mt.hardening = 0.1;
    double mu_u = 0.0, e_ev = 0.0, pq[2] = {0, 0};
    int rc;
    if ((rc = deck_double_pos(node, "atomic_mass_u", true, &mu_u, err)) ||
        (rc = deck_double_pos(node, "cohesive_energy_ev", true, &e_ev, err)) ||
        (rc = deck_vector(node, "exponents", true, 2, 2, pq, err)) ||
        (rc = deck_double_pos(node, "debye_temperature", false, &mt.theta_d, err)) ||
        (rc = deck_double_pos(node, "yield_strain", false, &mt.yield_strain, err)) ||
        (rc = deck_double(node, "hardening", false, 0.0, 0.99, &mt.hardening, err)) ||
        (rc = deck_double_pos(node, "youngs_modulus", false, &mt.e_target, err)) ||
        (rc = deck_check_unused(node, what, keys, err)))
        return rc;
    if (mt.e_target > 0.0 && m->calibration != MACRO_CAL_LATTICE)
        return deck_error_key(err, node, "youngs_modulus", "youngs_modulus is the target of "
                              "model.calibration: lattice (eq15 takes E from Eq. 15)");
    if (!(pq[0] > 0.0) || !(pq[1] > pq[0]))
        return deck_error_key(err, node, "exponents", "exponents [%g, %g]; expected [p, q] with "
                              "q > p > 0 (attractive p, repulsive q)", pq[0], pq[1]);
    if (mt.yield_strain > 0.0 && !(mt.yield_strain < m->taper_ratio - 1.0)) {
        rc = deck_error_key(err, node, "yield_strain", "yield_strain %g must be below the taper "
                            "start %g (pair stretch / r0)", mt.yield_strain,
                            m->taper_ratio - 1.0);
        err->code = SPALL_ERR_PHYSICS;
        return SPALL_ERR_PHYSICS;
    }
    mt.atom_mass = mu_u * MACRO_AMU;
    mt.e0 = e_ev * MACRO_EV;
    mt.p = pq[0];
    mt.q = pq[1];
    mt.parsed = true;
    if (m->n_mat < 1) {
        m->mat = calloc(1, sizeof *m->mat);
        if (!m->mat)
            return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory for materials");
        m->n_mat = 1;
    }
    m->mat[0] = mt;
    return SPALL_OK;
}

/** End layers and middle band for the strain gauge (reference positions). */
static int gauge_init(struct model *m, const struct sim *sim, struct spall_error *err)
{
    const struct particles *p = sim->p;
    const size_t n = p->n_owned;
    const int a = m->axis;
    const double *z = p->x0[a];
    double lo = INFINITY, hi = -INFINITY;
    for (size_t i = 0; i < n; i++) {
        lo = z[i] < lo ? z[i] : lo;
        hi = z[i] > hi ? z[i] : hi;
    }
    m->lo_idx = malloc((n ? n : 1) * sizeof(size_t));
    m->hi_idx = malloc((n ? n : 1) * sizeof(size_t));
    m->mid_idx = malloc((n ? n : 1) * sizeof(size_t));
    if (!m->lo_idx || !m->hi_idx || !m->mid_idx)
        return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory for the strain gauge");
    const double tol = 0.25 * m->pp.r0, mid = 0.5 * (lo + hi), quarter = 0.25 * (hi - lo);
    m->n_lo = m->n_hi = m->n_mid = 0;
    free(m->gflag);
    m->gflag = calloc(p->n ? p->n : 1, 1);
    if (!m->gflag)
        return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory for the strain gauge");
    for (size_t i = 0; i < n; i++) {
        if (z[i] < lo + tol) {
            m->lo_idx[m->n_lo++] = i;
            m->gflag[i] |= 1;
        }
        if (z[i] > hi - tol) {
            m->hi_idx[m->n_hi++] = i;
            m->gflag[i] |= 2;
        }
        if (fabs(z[i] - mid) <= quarter) {
            m->mid_idx[m->n_mid++] = i;
            m->gflag[i] |= 4;
        }
    }
    m->n_lo_all = m->n_lo;
    m->n_hi_all = m->n_hi;
    m->n_mid_all = m->n_mid;
    return SPALL_OK;
}

/* Exact sum of z over the owned members of a gauge set (completed over
 * the ranks by the caller): the same mean on every rank count. */
static void layer_sum(struct xsum *acc, const double *z, const size_t *idx, size_t n)
{
    xsum_init(acc);
    for (size_t k = 0; k < n; k++)
        xsum_add(acc, z[idx[k]]);
}

/* The gauge: end layer means along the axis and the middle band's mean
 * transverse position (exact sums over all ranks; collective when
 * distributed), then the band's RMS spread about it. */
static void gauge_read(const struct model *m, const struct sim *sim, double *const x[3],
                       double *len, double *spread)
{
    const int dim = sim->dim, a = m->axis;
    struct xsum acc[5];
    double v[5] = {0, 0, 0, 0, 0};
    layer_sum(&acc[0], x[a], m->lo_idx, m->n_lo);
    layer_sum(&acc[1], x[a], m->hi_idx, m->n_hi);
    for (int d = 0; d < 3; d++)
        layer_sum(&acc[2 + d], d < dim && d != a ? x[d] : x[a], m->mid_idx,
                  d < dim && d != a ? m->n_mid : 0);
    par_xsum_finish(sim, acc, 5, v);
    double lo = m->n_lo_all ? v[0] / (double)m->n_lo_all : 0.0;
    double hi = m->n_hi_all ? v[1] / (double)m->n_hi_all : 0.0;
    *len = hi - lo;
    double c[3] = {0, 0, 0};
    for (int d = 0; d < dim; d++)
        if (d != a && m->n_mid_all)
            c[d] = v[2 + d] / (double)m->n_mid_all;
    struct xsum s2;
    xsum_init(&s2);
    for (size_t k = 0; k < m->n_mid; k++)
        for (int d = 0; d < dim; d++)
            if (d != a) {
                double u = x[d][m->mid_idx[k]] - c[d];
                xsum_add(&s2, u * u);
            }
    double s = 0.0;
    par_xsum_finish(sim, &s2, 1, &s);
    *spread = m->n_mid_all ? sqrt(s / (double)m->n_mid_all) : 0.0;
}

static int macro_init(struct model *m, struct sim *sim, struct spall_error *err)
{
    struct particles *p = sim->p;
    if (sim->dim != 3 || sim->lattice.kind != LATTICE_FCC)
        return spall_error_set(err, SPALL_ERR_INPUT, "macro-particle model: needs a 3D fcc "
                               "lattice ([Saitoh] packs macro-particles FCC), got %s in %dD",
                               lattice_kind_name(sim->lattice.kind), sim->dim);
    if (sim->n_materials != 1 || m->n_mat < 1 || !m->mat[0].parsed)
        return spall_error_set(err, SPALL_ERR_INPUT,
                               "macro-particle model: exactly one material with parameters");
    const struct macro_material *mt = &m->mat[0];
    struct macro_calib *c = &m->cal;
    memset(c, 0, sizeof *c);
    c->rho = sim->materials[0].density;
    c->atom_mass = mt->atom_mass;
    c->e0 = mt->e0;
    c->p = mt->p;
    c->q = mt->q;
    c->r0 = sim->lattice.spacing;
    c->mode = m->calibration;
    c->e_target = mt->e_target;
    c->taper = m->taper_ratio;
    c->cutoff = m->cutoff_ratio;
    int rc = macro_calibrate(c, err);
    if (rc)
        return rc;
    struct macro_pair *w = &m->pp;
    w->D = c->D;
    w->p = c->p;
    w->q = c->q;
    w->r0 = c->r0;
    w->r_on = m->taper_ratio * c->r0;
    w->r_c = m->cutoff_ratio * c->r0;
    w->e_y = mt->yield_strain > 0.0 ? mt->yield_strain * c->r0 : INFINITY;
    w->h = mt->hardening / (1.0 - mt->hardening);
    if (c->p == floor(c->p) && c->q == floor(c->q) && c->q <= 32.0) {
        w->ip = (int)c->p;
        w->iq = (int)c->q;
    }
    if (m->damping != MACRO_DAMP_NONE) {
        double def = 0.0;
        if (mt->theta_d > 0.0)
            def = m->zeta_cg * mt->atom_mass * (SPALL_PI / 6.0) * macro_debye_omega(mt->theta_d);
        double given = m->damping == MACRO_DAMP_ABSOLUTE ? m->gamma : m->mu;
        if (!(given > 0.0) && !(def > 0.0))
            return spall_error_set_key(err, SPALL_ERR_INPUT, "model.damping",
                                       "macro-particle model: damping %s needs "
                                       "%s [kg/s] or the material's debye_temperature",
                                       m->damping == MACRO_DAMP_ABSOLUTE ? "absolute" : "pairwise",
                                       m->damping == MACRO_DAMP_ABSOLUTE ? "gamma" : "mu");
        m->gamma_used = m->gamma > 0.0 ? m->gamma : def;
        m->mu_used = m->mu > 0.0 ? m->mu : def;
    }
    const size_t n = p->n;
    for (int d = 0; d < 3; d++) {
        m->xb[d] = calloc(n ? n : 1, sizeof(double));
        if (!m->xb[d])
            return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory (macro model)");
    }
    m->epot = calloc(n ? n : 1, sizeof *m->epot);
    m->sig = calloc(6 * (n ? n : 1), sizeof *m->sig);
    m->wdiss = calloc(n ? n : 1, sizeof *m->wdiss);
    if (!m->epot || !m->sig || !m->wdiss)
        return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory (macro model)");
    m->volume = 0.0;
    for (size_t i = 0; i < p->n_owned; i++)
        m->volume += p->volume[i];
    if ((rc = macro_neighbors_update(m, sim, true, err)) || (rc = gauge_init(m, sim, err)) ||
        (rc = neighbor_list_build_pairs(&m->nl0, NULL, 3, p->n_owned, p->x0, 1.1 * c->r0, err)))
        return rc;
    gauge_read(m, sim, p->x0, &m->gauge0, &m->spread0); /* set-up: one rank's view */
    m->initialised = true;
    return SPALL_OK;
}

/* ---- fields ---------------------------------------------------------------------- */

static void field_stress(const void *ctx, size_t n, double *out)
{
    const struct model *m = ctx;
    const double *vol = m->sim->p->volume;
    for (size_t i = 0; i < n; i++)
        for (int k = 0; k < 6; k++)
            out[6 * i + k] = m->sig[6 * i + k] / vol[i];
}

static void field_energy(const void *ctx, size_t n, double *out)
{
    const struct model *m = ctx;
    for (size_t i = 0; i < n; i++)
        out[i] = macro_epot(m, i);
}

static void field_slip(const void *ctx, size_t n, double *out)
{
    const struct model *m = ctx;
    for (size_t i = 0; i < n; i++) {
        double s = 0.0;
        for (size_t q = m->nl->offset[i]; q < m->nl->offset[i + 1]; q++)
            s += m->kappa[q];
        out[i] = 0.5 * s;
    }
}

static void field_csp(const void *ctx, size_t n, double *out)
{
    const struct model *m = ctx;
    macro_centro_symmetry(n, m->sim->p->x, m->nl, m->pp.r0, out);
}

/* slip threshold 0.25 r0: above elastic relative displacements (a few % of
 * r0), below a partial Burgers vector r0/sqrt3.  A distributed run holds
 * no reference list of the whole body (macro_localize drops it): it finds
 * the reference neighbours anew for each frame (macro_slip_par). */
static void slip_fields(const struct model *m, size_t n, double *slip, double *normal)
{
    if (m->nl0) {
        macro_slip_vectors(n, m->sim->p->x, m->sim->p->x0, m->nl0, 0.25 * m->pp.r0, slip, normal,
                           NULL);
        return;
    }
    struct spall_error err = {0};
    if (macro_slip_par(m, m->sim, slip, normal, &err)) {
        double *out = slip ? slip : normal; /* out of memory on some rank: no values */
        for (size_t i = 0; i < 3 * n; i++)
            out[i] = NAN;
    }
}

static void field_slip_vector(const void *ctx, size_t n, double *out)
{
    slip_fields(ctx, n, out, NULL);
}

static void field_slip_normal(const void *ctx, size_t n, double *out)
{
    slip_fields(ctx, n, NULL, out);
}

static int macro_register_fields(struct model *m, struct sim *sim, struct field_registry *reg,
                                 struct spall_error *err)
{
    (void)sim;
    int rc;
    if ((rc = field_registry_add_computed(reg, "stress", "Pa", 6, FIELD_OUTPUT | FIELD_DEFAULT, field_stress, m,
                           err)) ||
        (rc = field_registry_add_computed(reg, "strain_energy", "J", 1, FIELD_OUTPUT, field_energy, m, err)) ||
        (rc = field_registry_add_computed(reg, "plastic_slip", "m", 1, FIELD_OUTPUT, field_slip, m, err)) ||
        (rc = field_registry_add_computed(reg, "centro_symmetry", "1", 1, FIELD_OUTPUT, field_csp, m,
                                          err)) ||
        /* distributed: collective (every rank writes the frame) */
        (rc = field_registry_add_computed(reg, "slip_vector", "m", 3, FIELD_OUTPUT,
                                          field_slip_vector, m, err)) ||
        (rc = field_registry_add_computed(reg, "slip_normal", "1", 3, FIELD_OUTPUT,
                                          field_slip_normal, m, err)))
        return rc;
    return SPALL_OK;
}

/* ---- step hooks -------------------------------------------------------------------- */

static int macro_forces(struct model *m, struct sim *sim, struct spall_error *err)
{
    return macro_compute_forces(m, sim, err);
}

/** sqrt(2 / max(sum k / M)) with the stiffest pair curvature met down to a
 *  10 % compression (Mie stiffens steeply), 12 partners; and the damping
 *  limit M / (gamma or 12 mu). */
static double macro_stable_dt(const struct model *m, const struct sim *sim)
{
    const struct macro_pair *w = &m->pp;
    double kmax = 0.0;
    for (int k = 0; k <= 60; k++) {
        double r = w->r0 * (0.9 + (m->cutoff_ratio - 0.9) * k / 60.0), h = 1e-5 * w->r0;
        double e1, f1, e2, f2;
        macro_mie(w, r - h, &e1, &f1);
        macro_mie(w, r + h, &e2, &f2);
        double kk = fabs(f1 - f2) / (2.0 * h);
        kmax = kk > kmax ? kk : kmax;
    }
    double mmin = INFINITY;
    for (size_t i = 0; i < sim->p->n_owned; i++)
        mmin = sim->p->mass[i] < mmin ? sim->p->mass[i] : mmin;
    if (!isfinite(mmin) || !(kmax > 0.0))
        return INFINITY;
    double dt = sqrt(2.0 / (12.0 * kmax / mmin));
    double c = m->damping == MACRO_DAMP_ABSOLUTE ? m->gamma_used
               : m->damping == MACRO_DAMP_PAIRWISE ? 12.0 * m->mu_used : 0.0;
    if (c > 0.0 && mmin / c < dt)
        dt = mmin / c;
    return dt;
}

static int macro_end_step(struct model *m, struct sim *sim, struct spall_error *err)
{
    (void)m;
    (void)sim;
    (void)err;
    return SPALL_OK;
}

static void macro_energy_fn(const struct model *m, const struct sim *sim,
                            struct model_energy *out)
{
    /* exact sums: the same on every rank count (collective when distributed) */
    struct xsum acc[2];
    xsum_init(&acc[0]);
    xsum_init(&acc[1]);
    for (size_t i = 0; i < sim->p->n_owned; i++) {
        xsum_add(&acc[0], macro_epot(m, i));
        xsum_add(&acc[1], m->wdiss[i]);
    }
    double ew[2];
    par_xsum_finish(sim, acc, 2, ew);
    /* strain energy relative to the perfect bulk lattice (-6 D per
     * particle): a bulk particle at rest reads 0, a surface particle the
     * depth of its missing bonds (a constant for the run) */
    out->strain = ew[0] + 6.0 * m->pp.D * (double)par_n_global(sim);
    out->dissipated = ew[1];
}

static size_t macro_history(const struct model *m, const struct sim *sim, const char **names,
                            double *values)
{
    const struct particles *p = sim->p;
    const int a = m->axis;
    /* exact sums and integer counts: history.csv does not depend on the
     * rank count (collectives when distributed: every rank calls this) */
    struct xsum acc[7];
    double s[7];
    for (int k = 0; k < 7; k++)
        xsum_init(&acc[k]);
    for (size_t i = 0; i < p->n_owned; i++) {
        for (int k = 0; k < 6; k++)
            xsum_add(&acc[k], m->sig[6 * i + k]);
        xsum_add(&acc[6], p->mass[i] * (p->v[0][i] * p->v[0][i] + p->v[1][i] * p->v[1][i] +
                                        p->v[2][i] * p->v[2][i]));
    }
    par_xsum_finish(sim, acc, 7, s);
    const double ke = s[6];
    double len, spread;
    gauge_read(m, sim, p->x, &len, &spread);
    uint64_t npl = 0;
    if (m->nl)
        for (size_t q = 0; q < m->nl->offset[p->n_owned]; q++)
            npl += m->kappa[q] > 0.0;
    if (sim->par)
        npl = par_sum_u64(npl);
    const double pairs = (double)npl;
    const size_t n_all = par_n_global(sim);
    size_t k = 0;
    names[k] = "strain";
    values[k++] = m->gauge0 > 0.0 ? len / m->gauge0 - 1.0 : 0.0;
    names[k] = "lateral_strain";
    values[k++] = m->spread0 > 0.0 ? spread / m->spread0 - 1.0 : 0.0;
    names[k] = "stress_axial";
    values[k++] = s[a] / m->volume;
    names[k] = "stress_nominal";
    values[k++] = s[a] / (m->volume * (len / m->gauge0));
    names[k] = "stress_xx";
    values[k++] = s[0] / m->volume;
    names[k] = "stress_yy";
    values[k++] = s[1] / m->volume;
    names[k] = "stress_zz";
    values[k++] = s[2] / m->volume;
    names[k] = "kinetic_temperature";
    values[k++] = n_all ? ke / (3.0 * (double)n_all * MACRO_KB) : 0.0;
    names[k] = "plastic_pairs";
    values[k++] = 0.5 * pairs;
    names[k] = "neighbor_builds";
    values[k++] = (double)m->n_builds;
    return k;
}

static void macro_describe(const struct model *m, const struct sim *sim, char *buf, size_t len)
{
    const struct macro_calib *c = &m->cal;
    (void)sim;
    snprintf(buf, len,
             "macro-particle model ([Saitoh]): fcc r0 = %g m, p = %g, q = %g; N_atom = %.6g "
             "(Eq. 11), P_atom = %.6g J (Eq. 10), D = %.6g J, phi''(r0) = %.6g N/m, "
             "particle mass %.6g kg, E (Eq. 15) = %.6g Pa; calibration %s: D = %.6g x P_atom/6, "
             "lattice E_[100] = %.6g Pa, nu_[100] = %.4g, residual pressure %.3g Pa; cut-off %g r0 "
             "(taper from %g r0), skin %g r0; damping %s (gamma %.4g kg/s, mu %.4g kg/s), T = %g "
             "K, eta_cg %g; plasticity %s\n",
             c->r0, c->p, c->q, c->n_atom, c->p_atom, c->D, c->k, c->mass, c->E,
             c->mode == MACRO_CAL_LATTICE ? "lattice" : "eq15", c->d_scale, c->E_fcc100,
             c->nu_fcc100, c->pressure,
             m->cutoff_ratio, m->taper_ratio, m->skin_ratio,
             m->damping == MACRO_DAMP_NONE ? "none"
             : m->damping == MACRO_DAMP_ABSOLUTE ? "absolute" : "pairwise",
             m->gamma_used, m->mu_used, m->temperature, m->eta_cg,
             isfinite(m->pp.e_y) ? "on" : "off");
}

static size_t macro_interactions(const struct model *m, const struct sim *sim)
{
    (void)sim;
    return m->nl ? m->nl->offset[m->nl->n] / 2 : 0;
}

extern const struct model_fixture macro_fixtures[]; /* macro_fixture.c */
const struct model_ops macroparticle_model_ops = {
    .name = "macroparticle",
    .summary = "macro-particle model ([Saitoh]): FCC particles, Mie pairs from cohesive energy, "
               "Langevin forces, pair plasticity",
    .create = macro_create,
    .parse_material = macro_parse_material,
    .init = macro_init,
    .register_fields = macro_register_fields,
    .register_state = macro_register_state,
    .compute_forces = macro_forces,
    .stable_dt = macro_stable_dt,
    .end_step = macro_end_step,
    .energy = macro_energy_fn,
    .history = macro_history,
    .describe = macro_describe,
    .destroy = macro_destroy,
    .interactions = macro_interactions,
    .fixtures = macro_fixtures,
    .localize = macro_localize,
    .spatial_ghosts = macro_spatial_ghosts,
    .spatial_rebuilt = macro_spatial_rebuilt,
    .migrate_arrays = macro_migrate_arrays,
};
