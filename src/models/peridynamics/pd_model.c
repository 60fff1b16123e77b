/**
 * @file pd_model.c
 * @brief Bond-based peridynamics (PMB, Silling & Askari 2005) and the
 *        peridynamic lattice model PDLM of [PDLM2019], with orthotropic
 *        laminae (fiber and matrix bonds): life cycle, deck, fields.
 *
 * Deck keys (copied to docs/decks.md, peridynamics section):
 *
 *   model:
 *     type: peridynamics
 *     variant: pmb | pdlm       pmb (default): family = every site within the
 *                               horizon delta = horizon_factor * spacing;
 *                               pdlm: triangular lattice, the 6 nearest
 *                               neighbours only ([PDLM2019])
 *     horizon_factor: m > 0     pmb only, default 3.015
 *     plane: plane_stress | plane_strain   2D only (default plane_stress)
 *     partial_volume: bool      pmb: beta_ij for sites cut by the horizon
 *                               (default true)
 *     partial_volume_rule: linear | lammps | cell   linear (default): family
 *                               to delta + dx/2, beta = (delta + dx/2 - xi)/dx
 *                               in the cut shell; lammps: same beta but the
 *                               family ends at delta (Parks et al. PDLAMMPS,
 *                               pair peri/pmb), for like-for-like races;
 *                               cell (lps/eps): beta = the fraction of the
 *                               neighbour's lattice cell inside the horizon
 *                               (pd_cellvol.c)
 *     break_order: immediate | next_step   immediate (default): a bond past
 *                               s0 carries no force from that step on;
 *                               next_step: it acts in the step it breaks
 *                               (PDLAMMPS order)
 *     bond_storage: compact | full   compact (default): lengths, coefficients
 *                               (lps/eps: omega beta) and types in a table
 *                               of the distinct ones, a 16-bit row per
 *                               half-bond (pd_compact.c); full: one of each
 *                               per half-bond.  Same results bit for bit.
 *     surface_correction: bool  pmb: energy method of Madenci & Oterkus 2014
 *                               sec. 4.2 (default false); lps also position_aware
 *     quasi_static: off | adr   adr: adaptive dynamic relaxation damping
 *                               (Kilic & Madenci 2010) on the real masses
 *     fiber_model: lattice | angular   orthotropic laminae: fiber bonds are
 *                               the bonds parallel to fiber_angle (lattice,
 *                               rotate the lattice: [PDLM2019]), or every bond
 *                               with c = c_m + c_f cos^2n(phi) (angular)
 *     fiber_power: n >= 1       angular model exponent (default 32)
 *     mixed_mode: bk | off      laminae: matrix bonds break at s0_m sqrt(G_c /
 *                               G_Ic), G_c from the local mode mix by the
 *                               Benzeggagh-Kenane law (pd_mixed.c; default bk)
 *     bk_exponent: eta          BK exponent (default 2)
 *     matrix_crack: bond | fiber_plane   fiber_plane (PDLM laminae): a
 *                               stretch-broken matrix bond also breaks its two
 *                               zigzag neighbours on the same fiber-parallel
 *                               interface (pd_plane.c; default bond)
 *     formulation: bond | lps | eps   lps: linear peridynamic solid
 *                               ([Silling2007], pd_lps.c), any nu; materials
 *                               need poisson_ratio; eps: lps with deviatoric
 *                               plasticity (pd_eps.c), materials need
 *                               yield_stress
 *     influence: one | inverse  lps: omega = 1 or delta / |xi|
 *     influence_correction: none | cubic   lps/eps on square, sc, fcc: omega
 *                               (1 + gamma P(n)), isotropic fourth moment
 *     interfaces: [{materials: [a, b], critical_stretch | fracture_energy,
 *                  stiffness_factor}]   bonds between two materials
 *                               (pd_interface.c); default: the smaller s0
 *
 *   materials:
 *     <name>:   isotropic
 *       density, youngs_modulus (or bulk_modulus in 3D), poisson_ratio
 *       (optional; must be the model's fixed value: 1/4 in 3D and plane
 *       strain, 1/3 in plane stress and PDLM; required and free with lps), fracture_energy G0 [J/m^2]
 *       or critical_stretch (neither: unbreakable), yield_stress [Pa] (eps only)
 *     <name>:   orthotropic lamina (2D plane stress)
 *       density, fiber_modulus E1, transverse_modulus E2, shear_modulus G12,
 *       major_poisson_ratio nu12, fiber_angle [deg] (default: lattice
 *       angle), matrix_fracture_energy G_Ic, fiber_fracture_energy G_f,
 *       mode2_fracture_energy G_IIc (mixed-mode matrix failure, pd_mixed.c)
 *
 * Fields: damage (phi = 1 - intact/initial bonds, pre-cut count as
 * broken), damage_fiber, damage_matrix (orthotropic), strain_energy [J],
 * stress [Pa] (virial), plastic_strain (eps).  History: bonds_broken, damage_fraction, adr_damping,
 * damage_sum.
 */
#include "models/peridynamics/pd_internal.h"
#include "models/peridynamics/pd_cellvol.h"

#include "core/bond_list.h"
#include "core/exact_sum.h"
#include "core/fields.h"
#include "core/particles.h"
#include "core/sim.h"
#include "core/options.h"
#include "core/model.h"
#include "core/parallel/comm.h"
#include "core/parallel/decomp.h"
#include "core/parallel/psum.h"
#include "spall/error.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static void pd_destroy(struct model **pm)
{
    if (!pm || !*pm)
        return;
    struct model *m = *pm;
    free(m->mat);
    free(m->ifc);
    bond_list_destroy(&m->bl);
    free(m->coef);
    free(m->kind);
    free(m->k_rest);
    free(m->k_coef);
    free(m->k_type);
    free(m->n_init);
    free(m->n_init_f);
    free(m->diss);
    free(m->mm_g);
    free(m->mm_beta);
    free(m->twin);
    free(m->fresh);
    free(m->tw_gid);
    free(m->half_buf);
    free(m->half_flags);
    pd_lps_free(&m->lps);
    for (int d = 0; d < 3; d++)
        free(m->f_prev[d]);
    free(m);
    *pm = NULL;
}

static int pd_create(struct model **out, struct sim *sim, const struct deck_node *params,
                     struct spall_error *err)
{
    static const char *const variants[] = {"pmb", "pdlm", NULL};
    static const char *const planes[] = {"plane_stress", "plane_strain", NULL};
    static const char *const qs[] = {"off", "adr", NULL};
    static const char *const fm[] = {"lattice", "angular", NULL};
    static const char *const pvr[] = {"linear", "lammps", "cell", NULL};
    static const char *const bo[] = {"immediate", "next_step", NULL};
    static const char *const bst[] = {"compact", "full", NULL};
    static const char *const mmo[] = {"bk", "off", NULL};
    static const char *const mco[] = {"bond", "fiber_plane", NULL};
    static const char *const fmo[] = {"bond", "lps", "eps", NULL};
    static const char *const inf[] = {"one", "inverse", NULL};
    static const char *const icor[] = {"none", "cubic", NULL};
    static const char *const keys[] = {"type", "variant", "horizon_factor", "plane",
                                       "partial_volume", "partial_volume_rule", "break_order", "bond_storage", "surface_correction", "quasi_static",
                                       "fiber_model", "fiber_power", "mixed_mode", "bk_exponent", "matrix_crack",
                                       "formulation", "influence", "interfaces",
                                       "influence_correction", NULL};
    *out = NULL;
    struct model *m = calloc(1, sizeof *m);
    if (!m)
        return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory creating the PD model");
    m->sim = sim;
    m->opt.horizon_factor = 3.015;
    m->opt.partial_volume = true;
    m->opt.fiber_power = 32;
    m->opt.mixed_mode = true;
    m->opt.bk_exponent = 2.0;
    if (params) {
        int v = 0, pl = 0, q = 0, f = 0, pr = 0, b = 0, mmode = 0, mc = 0, fo = 0, in = 0, ic = 0;
        int bs = 0;
        int rc;
        long pw = 32;
        if ((rc = deck_enum(params, "variant", false, variants, &v, err)) ||
            (rc = deck_double_pos(params, "horizon_factor", false, &m->opt.horizon_factor, err)) ||
            (rc = deck_enum(params, "plane", false, planes, &pl, err)) ||
            (rc = deck_bool(params, "partial_volume", false, &m->opt.partial_volume, err)) ||
            (rc = deck_enum(params, "partial_volume_rule", false, pvr, &pr, err)) ||
            (rc = deck_enum(params, "break_order", false, bo, &b, err)) ||
            (rc = deck_enum(params, "bond_storage", false, bst, &bs, err)) ||
            (rc = deck_enum(params, "quasi_static", false, qs, &q, err)) ||
            (rc = deck_enum(params, "fiber_model", false, fm, &f, err)) ||
            (rc = deck_long(params, "fiber_power", false, 1, 64, &pw, err)) ||
            (rc = deck_enum(params, "mixed_mode", false, mmo, &mmode, err)) ||
            (rc = deck_enum(params, "matrix_crack", false, mco, &mc, err)) ||
            (rc = deck_double(params, "bk_exponent", false, 0.1, 20.0, &m->opt.bk_exponent,
                              err)) ||
            (rc = deck_enum(params, "formulation", false, fmo, &fo, err)) ||
            (rc = deck_enum(params, "influence", false, inf, &in, err)) ||
            (rc = deck_enum(params, "influence_correction", false, icor, &ic, err))) {
            free(m);
            return rc;
        }
        m->opt.variant = (enum pd_variant)v;
        m->opt.plane = (enum pd_plane)pl;
        m->opt.quasi = (enum pd_quasi)q;
        m->opt.fiber_model = (enum pd_fiber_model)f;
        m->opt.fiber_power = (int)pw;
        m->opt.mixed_mode = mmode == 0;
        m->opt.fiber_plane = mc == 1;
        m->opt.family_at_delta = pr == 1;
        m->opt.cell_volumes = pr == 2;
        m->opt.break_late = b == 1;
        m->opt.full_bonds = bs == 1;
        m->opt.lps = fo >= 1; /* eps is lps with a plastic deviatoric state */
        m->opt.eps = fo == 2;
        m->lps.influence = (enum pd_influence)in;
        m->lps.cubic = ic == 1;
        if (m->opt.cell_volumes && (!m->opt.lps || !m->opt.partial_volume)) {
            free(m);
            return deck_error_key(err, params, "partial_volume_rule", "partial_volume_rule "
                                  "cell is for formulation lps or eps with partial_volume "
                                  "true");
        }
        if (m->lps.cubic && !m->opt.lps) {
            free(m);
            return deck_error_key(err, params, "influence_correction", "influence_correction "
                                  "is for formulation lps or eps");
        }
        if (m->opt.lps && (sim->dim == 1 || m->opt.variant == PD_PDLM)) {
            free(m);
            return deck_error_key(err, params, "formulation", "lps and eps need a 2D or 3D pmb "
                                  "run");
        }
        if ((rc = pd_surface_opts(m, params, err))) { /* pmb, or lps's own (pd_lps_pals.c) */
            free(m);
            return rc;
        }
        if (m->opt.variant == PD_PDLM && sim->dim != 2) {
            free(m);
            return deck_error_key(err, params, "variant",
                                  "pdlm is the 2D triangular-lattice variant (this run is %dD)",
                                  sim->dim);
        }
        if (m->opt.fiber_plane &&
            (m->opt.variant != PD_PDLM || m->opt.fiber_model != PD_FIBER_LATTICE)) {
            free(m);
            return deck_error_key(err, params, "matrix_crack", "fiber_plane needs variant pdlm "
                                  "with fiber_model lattice (zigzag matrix bonds between "
                                  "fiber rows)");
        }
        if (pl == 1 && (sim->dim != 2 || m->opt.variant == PD_PDLM)) {
            free(m);
            return deck_error_key(err, params, "plane", "plane_strain needs a 2D pmb run");
        }
        if ((rc = pd_interfaces_parse(m, params, err)) ||
            (rc = deck_check_unused(params, "model", keys, err))) {
            free(m->ifc);
            free(m);
            return rc;
        }
    }
    *out = m;
    return SPALL_OK;
}

/** The fixed Poisson ratio of bond-based PD in this setting. */
static double pd_fixed_nu(const struct model *m, int dim)
{
    if (dim == 3 || (dim == 2 && m->opt.plane == PD_PLANE_STRAIN && m->opt.variant == PD_PMB))
        return 0.25;
    return 1.0 / 3.0;
}

static int pd_parse_material(struct model *m, struct sim *sim, int index,
                             const struct deck_node *node, struct spall_error *err)
{
    static const char *const k_iso[] = {"density", "youngs_modulus", "bulk_modulus",
                                        "poisson_ratio", "fracture_energy", "critical_stretch",
                                        "yield_stress", NULL};
    static const char *const k_ort[] = {"density", "fiber_modulus", "transverse_modulus",
                                        "shear_modulus", "major_poisson_ratio", "fiber_angle",
                                        "matrix_fracture_energy", "fiber_fracture_energy",
                                        "mode2_fracture_energy", NULL};
    if (index < 0 || index >= PD_MAX_MAT)
        return deck_error(err, node, "peridynamics: at most %d materials", PD_MAX_MAT);
    if ((size_t)index >= m->n_mat) {
        struct pd_material *q = realloc(m->mat, ((size_t)index + 1) * sizeof *q);
        if (!q)
            return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory for materials");
        memset(q + m->n_mat, 0, ((size_t)index + 1 - m->n_mat) * sizeof *q);
        m->mat = q;
        m->n_mat = (size_t)index + 1;
    }
    struct pd_material mt;
    memset(&mt, 0, sizeof mt);
    int rc;
    const int dim = sim->dim;
    if (deck_peek(node, "fiber_modulus")) {
        double ang = NAN;
        mt.ortho = true;
        if ((rc = deck_double_pos(node, "fiber_modulus", true, &mt.E1, err)) ||
            (rc = deck_double_pos(node, "transverse_modulus", true, &mt.E2, err)) ||
            (rc = deck_double_pos(node, "shear_modulus", true, &mt.G12, err)) ||
            (rc = deck_double(node, "major_poisson_ratio", true, 0.0, 0.5, &mt.nu12, err)) ||
            (rc = deck_double(node, "fiber_angle", false, -360.0, 360.0, &ang, err)) ||
            (rc = deck_double(node, "matrix_fracture_energy", false, 0.0, INFINITY, &mt.GIc,
                              err)) ||
            (rc = deck_double(node, "fiber_fracture_energy", false, 0.0, INFINITY, &mt.Gf,
                              err)) ||
            (rc = deck_double(node, "mode2_fracture_energy", false, 0.0, INFINITY, &mt.GIIc,
                              err)) ||
            (rc = deck_check_unused(node, "an orthotropic peridynamic material", k_ort, err)))
            return rc;
        if (dim != 2)
            return deck_error(err, node, "orthotropic laminae are 2D (plane stress); this run "
                              "is %dD", dim);
        if (m->opt.plane == PD_PLANE_STRAIN)
            return deck_error(err, node, "orthotropic laminae are plane stress");
        mt.fiber_angle = isnan(ang) ? sim->lattice.angle : ang * SPALL_PI / 180.0;
        mt.E = mt.E2;
        mt.Q22 = mt.E2 / (1.0 - mt.nu12 * mt.nu12 * mt.E2 / mt.E1);
    } else {
        double nu = NAN;
        if ((rc = deck_double(node, "youngs_modulus", false, 0.0, INFINITY, &mt.E, err)) ||
            (rc = deck_double(node, "bulk_modulus", false, 0.0, INFINITY, &mt.K, err)) ||
            (rc = deck_double(node, "poisson_ratio", false, -1.0, 0.5, &nu, err)) ||
            (rc = deck_double(node, "fracture_energy", false, 0.0, INFINITY, &mt.G0, err)) ||
            (rc = deck_double(node, "critical_stretch", false, 0.0, INFINITY, &mt.s0_given,
                              err)) ||
            (rc = deck_double(node, "yield_stress", m->opt.eps, 0.0, INFINITY, &mt.yield_stress,
                              err)) ||
            (rc = deck_check_unused(node, "a peridynamic material", k_iso, err)))
            return rc;
        double fixed = pd_fixed_nu(m, dim);
        if (!m->opt.eps && mt.yield_stress > 0.0)
            return deck_error_key(err, node, "yield_stress", "yield_stress needs "
                                  "model.formulation eps (elastic-plastic state-based PD)");
        if (m->opt.eps && !(mt.yield_stress > 0.0))
            return deck_error_key(err, node, "yield_stress", "formulation eps needs "
                                  "yield_stress > 0");
        if (m->opt.lps) {
            if (isnan(nu))
                return deck_error(err, node, "formulation %s needs poisson_ratio",
                                  m->opt.eps ? "eps" : "lps");
            if (!(nu < 0.5) || (dim == 2 && m->opt.plane == PD_PLANE_STRESS && !(nu < 1.0)))
                return deck_error_key(err, node, "poisson_ratio", "poisson_ratio must be "
                                      "below 1/2");
            fixed = nu;
        }
        if (!isnan(nu) && dim > 1 && fabs(nu - fixed) > 1e-3) {
            deck_error_key(err, node, "poisson_ratio",
                           "bond-based peridynamics fixes nu = %.4g in %s (pair forces: Cauchy "
                           "relation); got %g. Use the fixed value or a state-based model",
                           fixed, dim == 3 ? "3D" : m->opt.plane == PD_PLANE_STRAIN
                                                        ? "plane strain" : "plane stress",
                           nu);
            err->code = SPALL_ERR_PHYSICS;
            return SPALL_ERR_PHYSICS;
        }
        mt.nu = dim == 1 ? 0.0 : fixed;
        if ((mt.E > 0.0) == (mt.K > 0.0))
            return deck_error(err, node, "give exactly one of youngs_modulus and bulk_modulus "
                              "(> 0)");
        if (mt.K > 0.0 && dim != 3)
            return deck_error_key(err, node, "bulk_modulus", "bulk_modulus is for 3D runs; "
                                  "give youngs_modulus");
        if (dim == 3) {
            if (mt.K > 0.0)
                mt.E = 3.0 * mt.K * (1.0 - 2.0 * mt.nu);
            else
                mt.K = mt.E / (3.0 * (1.0 - 2.0 * mt.nu));
        }
        if (dim > 1) {
            /* LPS: shear modulus and the bulk modulus of the dimension */
            mt.mu = mt.E / (2.0 * (1.0 + mt.nu));
            mt.kd = dim == 3 ? mt.K
                    : m->opt.plane == PD_PLANE_STRESS ? mt.E / (2.0 * (1.0 - mt.nu))
                                                      : mt.E / (3.0 * (1.0 - 2.0 * mt.nu)) + mt.mu / 3.0;
        }
        if (mt.G0 > 0.0 && mt.s0_given > 0.0)
            return deck_error(err, node, "give fracture_energy or critical_stretch, not both");
    }
    mt.parsed = true;
    m->mat[index] = mt;
    return SPALL_OK;
}

/* ---- init -------------------------------------------------------------------------- */

static int is_fiber(const struct model *m, const struct sim *sim, size_t i, size_t s)
{
    const struct particles *p = sim->p;
    size_t j = (size_t)m->bl->partner[s];
    const struct pd_material *a = &m->mat[p->material[i]], *b = &m->mat[p->material[j]];
    if (!a->ortho && !b->ortho)
        return 0;
    const struct pd_material *o = a->ortho ? a : b;
    double ex = p->x0[0][j] - p->x0[0][i], ey = p->x0[1][j] - p->x0[1][i];
    double cphi = fabs(ex * cos(o->fiber_angle) + ey * sin(o->fiber_angle)) / m->bl->rest[s];
    if (m->opt.fiber_model == PD_FIBER_ANGULAR)
        return pow(cphi * cphi, (double)m->opt.fiber_power) > 0.5;
    return cphi > 0.9999;
}

static int pd_init(struct model *m, struct sim *sim, struct spall_error *err)
{
    struct particles *p = sim->p;
    const size_t nm = sim->n_materials, n = p->n;
    m->dim = sim->dim;
    m->dx = sim->lattice.spacing;
    if (nm == 0 || m->n_mat < nm)
        return spall_error_set(err, SPALL_ERR_INPUT, "peridynamics: a material has no "
                               "parameters");
    m->n_mat = nm;
    if (m->opt.variant == PD_PDLM && sim->lattice.kind != LATTICE_TRIANGULAR)
        return spall_error_set_key(err, SPALL_ERR_INPUT, "model.variant",
                                   "peridynamics variant pdlm needs the "
                                   "triangular lattice (got %s)",
                                   lattice_kind_name(sim->lattice.kind));
    double radius;
    if (m->opt.variant == PD_PDLM) {
        m->delta = m->dx;
        radius = 1.05 * m->dx;
    } else {
        m->delta = m->opt.horizon_factor * m->dx;
        radius = m->opt.partial_volume && !m->opt.family_at_delta ? m->delta + 0.5 * m->dx
                                                                   : m->delta * (1.0 + 1e-12);
        if (m->opt.cell_volumes) { /* every site whose cell the sphere cuts */
            const double reach = pd_cellvol_reach(sim->lattice.kind);
            if (!(reach > 0.0) || (sim->dim == 3) != (sim->lattice.kind == LATTICE_SC ||
                                                      sim->lattice.kind == LATTICE_FCC))
                return spall_error_set_key(err, SPALL_ERR_INPUT, "model.partial_volume_rule",
                                           "partial_volume_rule cell is for the triangular, "
                                           "square, sc and fcc lattices (got %s)",
                                           lattice_kind_name(sim->lattice.kind));
            radius = m->delta + reach * m->dx * (1.0 + 1e-12);
        }
    }
    /* isotropic constants */
    int rc;
    const double t = sim->thickness;
    for (size_t k = 0; k < nm; k++) {
        struct pd_material *mt = &m->mat[k];
        if (!mt->parsed)
            return spall_error_set(err, SPALL_ERR_INPUT, "peridynamics: material '%s' has no "
                                   "parameters", sim->materials[k].name);
        m->ortho |= mt->ortho;
        if (mt->ortho && m->opt.lps)
            return spall_error_set_key(err, SPALL_ERR_INPUT, "model.formulation",
                                       "formulation lps is isotropic; material '%s' is an "
                                       "orthotropic lamina", sim->materials[k].name);
        if (mt->ortho) {
            mt->c = 1.0; /* unused */
            continue;
        }
        if (m->opt.variant == PD_PDLM) {
            mt->c = pd_pdlm_micromodulus(mt->E, m->dx, t);
            mt->s0 = pd_pdlm_critical_stretch(mt->E, mt->G0, m->dx);
        } else {
            mt->c = pd_micromodulus(sim->dim, m->opt.plane, mt->E, mt->K, m->delta, t);
            mt->s0 = pd_critical_stretch(sim->dim, mt->c, mt->G0, m->delta, t);
            if (m->opt.lps)
                mt->s0 = pd_lps_critical_stretch(sim->dim, mt->kd, mt->mu, mt->G0, m->delta);
        }
        if (mt->s0_given > 0.0)
            mt->s0 = mt->s0_given;
    }
    /* where the deck allows compact families the set-up builds them
     * directly and never holds the per-half-bond lengths, coefficients and
     * types (pd_compact.c; docs/performance.md "Set-up peak memory") */
    const bool direct = pd_compact_predicted(m);
    rc = direct ? bond_list_build_compact(&m->bl, p, radius, err)
                : bond_list_build(&m->bl, p, radius, err);
    if (rc)
        return rc;
    struct bond_list *bl = m->bl;
    m->n_half = bl->offset[n];
    m->n_init = calloc(n ? n : 1, sizeof *m->n_init);
    m->n_init_f = calloc(n ? n : 1, sizeof *m->n_init_f);
    m->diss = calloc(n ? n : 1, sizeof *m->diss);
    if (!m->n_init || !m->n_init_f || !m->diss)
        return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory in the PD model");
    if (m->opt.quasi == PD_QS_ADR)
        for (int d = 0; d < sim->dim; d++)
            if (!(m->f_prev[d] = calloc(2 * (n ? n : 1), sizeof(double))))
                return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory for ADR");
    /* lps / eps: pd_lps_init builds their table (omega beta in it) */
    const bool lps_direct = direct && m->opt.lps;
    if (direct && !lps_direct && (rc = pd_compact_build(m, sim, err)))
        return rc;
    if (!m->kind && !lps_direct) {
        /* bond types: (ma * nm + mb) * 2 + fiber */
        for (size_t i = 0; i < n; i++)
            for (size_t s = bl->offset[i]; s < bl->offset[i + 1]; s++) {
                size_t j = (size_t)bl->partner[s];
                bl->type[s] = (uint8_t)(((size_t)p->material[i] * nm +
                                         (size_t)p->material[j]) * 2 +
                                        (size_t)is_fiber(m, sim, i, s));
            }
        for (size_t k = 0; k < nm; k++)
            if (m->mat[k].ortho) {
                double ach[4];
                if ((rc = pd_calibrate_ortho(m, sim, (int)k, ach, err))) {
                    spall_error_prefix(err, "material '%s': ", sim->materials[k].name);
                    spall_error_default_key(err, "materials.%s", sim->materials[k].name);
                    return rc;
                }
            }
        /* lps / eps never read the pair coefficients (their force state is
         * omega beta and the moduli, pd_lps.c) */
        if (!m->opt.lps && (rc = pd_build_coefficients(m, sim, err)))
            return rc;
    }
    if ((rc = pd_mixed_init(m, sim, err)) ||
        (rc = pd_plane_init(m, sim, err)) || (m->opt.lps && (rc = pd_lps_init(m, sim, err))) ||
        (m->opt.eps && (rc = pd_eps_init(m, sim, err))))
        return rc;
    for (size_t a = 0; a < nm; a++)
        for (size_t b = 0; b < nm; b++)
            for (int f = 0; f < 2; f++) {
                const struct pd_material *A = &m->mat[a], *B = &m->mat[b];
                double sa = A->ortho ? (f ? A->s0_f : A->s0_m) : A->s0;
                double sb = B->ortho ? (f ? B->s0_f : B->s0_m) : B->s0;
                m->s0_tab[(a * nm + b) * 2 + (size_t)f] = fmin(sa, sb);
            }
    if ((rc = pd_interfaces_apply(m, sim, err))) /* model.interfaces (pd_interface.c) */
        return rc;
    for (size_t i = 0; i < n; i++) {
        m->n_init[i] = bl->offset[i + 1] - bl->offset[i];
        for (size_t s = bl->offset[i]; s < bl->offset[i + 1]; s++)
            m->n_init_f[i] += pd_type(m, s) & 1u;
    }
    m->initialised = true;
    return SPALL_OK;
}

static int pd_precrack(struct model *m, struct sim *sim, const struct precrack *c, size_t *n_cut,
                       struct spall_error *err)
{
    if (!m->bl)
        return spall_error_set(err, SPALL_ERR_INTERNAL, "PD pre-crack before init");
    *n_cut = bond_list_apply_precrack(m->bl, sim->p, c);
    if (m->opt.lps)
        pd_lps_weights(m, sim); /* a pre-cut bond leaves the family */
    return m->lps.pals ? pd_lps_pals_init(m, sim, err) : SPALL_OK; /* pd_lps_pals.c */
}

/* ---- fields ------------------------------------------------------------------------ */

/* which: 0 total, 1 fiber, 2 matrix */
static void damage_of(const struct model *m, size_t n, double *out, int which)
{
    const struct bond_list *bl = m->bl;
#pragma omp parallel for schedule(static)
    for (size_t i = 0; i < n; i++) {
        size_t intact = 0, init;
        for (size_t s = bl->offset[i]; s < bl->offset[i + 1]; s++) {
            int fib = pd_type(m, s) & 1u;
            if ((which == 1 && !fib) || (which == 2 && fib))
                continue;
            intact += !(bl->state[s] & BOND_BROKEN);
        }
        init = which == 0 ? m->n_init[i] : which == 1 ? m->n_init_f[i]
                                                       : m->n_init[i] - m->n_init_f[i];
        out[i] = init ? 1.0 - (double)intact / (double)init : 0.0;
    }
}

static void field_damage(const void *ctx, size_t n, double *out) { damage_of(ctx, n, out, 0); }
static void field_damage_f(const void *ctx, size_t n, double *out) { damage_of(ctx, n, out, 1); }
static void field_damage_m(const void *ctx, size_t n, double *out) { damage_of(ctx, n, out, 2); }

static void field_mixity(const void *ctx, size_t n, double *out)
{
    const struct model *m = ctx;
    for (size_t i = 0; i < n; i++)
        out[i] = m->mm_beta ? m->mm_beta[i] : 0.0;
}

static void field_energy(const void *ctx, size_t n, double *out)
{
    const struct model *m = ctx;
#pragma omp parallel for schedule(static)
    for (size_t i = 0; i < n; i++)
        pd_particle_eval(m, m->sim, i, &out[i], NULL);
}

static void field_stress(const void *ctx, size_t n, double *out)
{
    const struct model *m = ctx;
    const size_t nc = (size_t)field_symtensor_ncomp(m->dim);
#pragma omp parallel for schedule(static)
    for (size_t i = 0; i < n; i++)
        pd_particle_eval(m, m->sim, i, NULL, &out[i * nc]);
}

static void field_plastic(const void *ctx, size_t n, double *out)
{
    const struct model *m = ctx;
#pragma omp parallel for schedule(static)
    for (size_t i = 0; i < n; i++)
        out[i] = pd_eps_plastic_strain(m, m->sim, i);
}

static int pd_register_fields(struct model *m, struct sim *sim, struct field_registry *reg,
                              struct spall_error *err)
{
    int nc = field_symtensor_ncomp(sim->dim);
    int rc;
    const unsigned od = FIELD_OUTPUT | FIELD_DEFAULT;
    if ((rc = field_registry_add_computed(reg, "damage", "1", 1, od, field_damage, m, err)) ||
        (m->ortho && (rc = field_registry_add_computed(reg, "damage_fiber", "1", 1, od, field_damage_f, m, err))) ||
        (m->ortho && (rc = field_registry_add_computed(reg, "damage_matrix", "1", 1, od, field_damage_m, m, err))) ||
        (m->ortho && (rc = field_registry_add_computed(reg, "mode2_share", "1", 1, FIELD_OUTPUT, field_mixity, m, err))) ||
        (rc = field_registry_add_computed(reg, "strain_energy", "J", 1, FIELD_OUTPUT, field_energy, m, err)) ||
        (rc = field_registry_add_computed(reg, "stress", "Pa", nc, od, field_stress, m, err)) ||
        (m->opt.eps && (rc = field_registry_add_computed(reg, "plastic_strain", "1", 1, od,
                                                          field_plastic, m, err))))
        return rc;
    return SPALL_OK;
}

/* ---- step hooks -------------------------------------------------------------------- */

static double pd_dt(const struct model *m, const struct sim *sim)
{
    return m->opt.lps ? pd_lps_stable_dt(m, sim) : pd_stable_dt(m, sim);
}

static int pd_end_step(struct model *m, struct sim *sim, struct spall_error *err)
{
    /* breaking is fused into the force loop; fiber-plane twins here */
    return m->fresh ? pd_plane_end_step(m, sim, err) : SPALL_OK;
}

static void pd_energy(const struct model *m, const struct sim *sim, struct model_energy *out)
{
    /* exact sums: one value for any thread and rank count */
    par_bond_energy(m, sim, pd_particle_eval, m->diss, &out->strain, &out->dissipated);
}

static size_t pd_history(const struct model *m, const struct sim *sim, const char **names,
                         double *values)
{
    const struct bond_list *bl = m->bl;
    size_t run = 0, all = 0, nh = bl->offset[sim->p->n_owned];
    for (size_t s = 0; s < nh; s++) {
        all += (bl->state[s] & BOND_BROKEN) != 0;
        run += bl->state[s] == BOND_BROKEN;
    }
    if (sim->par) { /* distributed: the counts over all ranks */
        uint64_t c[3] = {run, all, nh};
        par_sum_u64_array(c, 3);
        run = (size_t)c[0];
        all = (size_t)c[1];
        nh = (size_t)c[2];
    }
    /* sum over particles of phi_i (exact, any rank count): compared with
     * LAMMPS's compute damage/atom in bench/pd_vs_lammps.sh */
    struct xsum acc;
    xsum_init(&acc);
    for (size_t i = 0; i < sim->p->n_owned; i++) {
        size_t intact = 0;
        for (size_t s = bl->offset[i]; s < bl->offset[i + 1]; s++)
            intact += !(bl->state[s] & BOND_BROKEN);
        xsum_add(&acc, m->n_init[i] ? 1.0 - (double)intact / (double)m->n_init[i] : 0.0);
    }
    double dsum;
    par_xsum_finish(sim, &acc, 1, &dsum);
    names[0] = "bonds_broken";
    values[0] = 0.5 * (double)run;
    names[1] = "damage_fraction";
    values[1] = nh ? (double)all / (double)nh : 0.0;
    names[2] = "adr_damping";
    values[2] = m->opt.quasi == PD_QS_ADR ? sim->damping : 0.0;
    names[3] = "damage_sum";
    values[3] = dsum;
    return 4;
}

static void pd_describe(const struct model *m, const struct sim *sim, char *buf, size_t len)
{
    size_t w = 0;
#define PUT(...)                                                                                \
    do {                                                                                        \
        if (w < len)                                                                            \
            w += (size_t)snprintf(buf + w, len - w, __VA_ARGS__);                               \
    } while (0)
    PUT("peridynamics (%s): %s lattice, dx = %g m, horizon %g m (m = %g), %s, partial volume "
        "%s, surface correction %s, quasi-static %s, %zu bonds\n",
        m->opt.variant == PD_PDLM ? "PDLM" : "PMB", lattice_kind_name(sim->lattice.kind), m->dx,
        m->delta, m->delta / m->dx,
        sim->dim == 2 ? (m->opt.plane == PD_PLANE_STRAIN ? "plane strain" : "plane stress")
                      : sim->dim == 3 ? "3D" : "1D",
        m->opt.partial_volume ? (m->opt.cell_volumes ? "on (cell rule)" : "on") : "off",
        m->lps.pals ? "position_aware" : (m->opt.surface_correction || m->lps.surface) ? "on" : "off",
        m->opt.quasi == PD_QS_ADR ? "adr" : "off", m->bl ? bond_list_count(m->bl) : 0);
    if (m->bl) { /* the allocations themselves: the memory target of issue 25 */
        const size_t n = sim->p->n_owned, nb = pd_model_bytes(m, n);
        PUT("  model arrays: %zu B, %.0f B/particle (%s families%s)\n", nb,
            n ? (double)nb / (double)n : 0.0, m->kind ? "compact" : "full",
            m->kind ? "" : pd_compact_eligible(m) ? ": over 65535 distinct bonds" : "");
        if (m->kind)
            PUT("  compact families: %zu distinct (length, %s, type)\n", m->n_kind,
                m->opt.lps ? "omega beta" : "coefficient");
    }
    for (size_t k = 0; k < m->n_mat; k++) {
        const struct pd_material *mt = &m->mat[k];
        if (mt->ortho)
            PUT("  material '%s': lamina E1 = %g, E2 = %g, G12 = %g Pa, nu12 = %g, fiber %g deg: "
                "c_f = %g, c_m = %g, s0_f = %g, s0_m = %g\n", sim->materials[k].name, mt->E1,
                mt->E2, mt->G12, mt->nu12, mt->fiber_angle * 180.0 / SPALL_PI, mt->c_f, mt->c_m,
                mt->s0_f, mt->s0_m);
        else if (m->opt.eps)
            PUT("  material '%s': EPS, E = %g Pa, nu = %g, mu = %g Pa, k = %g Pa, s0 = %g, "
                "yield stress %g Pa\n", sim->materials[k].name, mt->E, mt->nu, mt->mu, mt->kd,
                mt->s0, mt->yield_stress);
        else if (m->opt.lps)
            PUT("  material '%s': LPS, E = %g Pa, nu = %g, mu = %g Pa, k = %g Pa, s0 = %g\n",
                sim->materials[k].name, mt->E, mt->nu, mt->mu, mt->kd, mt->s0);
        else
            PUT("  material '%s': E = %g Pa, nu = %g (fixed), c = %g, s0 = %g\n",
                sim->materials[k].name, mt->E, mt->nu, mt->c, mt->s0);
    }
    if (m->mixed)
        PUT("  mixed-mode matrix failure: s0_m x sqrt(G_c(beta) / G_Ic), Benzeggagh-Kenane "
            "eta = %g\n", m->opt.bk_exponent);
    if (m->bl)
        PUT("  stable dt = %g s (%s)\n", sim->par ? sim->dt_limit : pd_dt(m, sim),
            m->opt.lps ? "LPS: Gershgorin bound of the stiffness, pd_lps.c"
                       : "Silling & Askari 2005 Eq. 15");
#undef PUT
}

/* Distributed set-up: the family radius of pd_init (its largest choice) */
static double pd_setup_range(const struct model *m, const struct sim *sim)
{
    const double dx = sim->lattice.spacing;
    if (m->opt.variant == PD_PDLM)
        return 1.05 * dx;
    if (m->opt.cell_volumes) /* as pd_init: to the farthest cell the sphere cuts */
        return (m->opt.horizon_factor + pd_cellvol_reach(sim->lattice.kind) * (1.0 + 1e-12)) * dx;
    return (m->opt.horizon_factor + 0.5) * dx;
}

static size_t pd_interactions(const struct model *m, const struct sim *sim)
{
    (void)sim;
    return m->bl ? bond_list_count(m->bl) : 0;
}

/* ADR: the coefficient of the last force call; none before the first
 * estimate (the engine keeps the deck's damping) or without ADR. */
static bool pd_damping(const struct model *m, const struct sim *sim, double *c)
{
    (void)sim;
    if (m->opt.quasi != PD_QS_ADR || !m->adr_estimated)
        return false;
    *c = m->adr_damping;
    return true;
}

extern const struct model_fixture pd_fixtures[]; /* pd_fixture.c */
const struct model_ops peridynamics_model_ops = {
    .name = "peridynamics",
    .summary = "bond-based peridynamics (PMB, PDLM lattice, orthotropic laminae)",
    .create = pd_create,
    .parse_material = pd_parse_material,
    .init = pd_init,
    .precrack = pd_precrack,
    .register_fields = pd_register_fields,
    .register_state = pd_register_state,
    .compute_forces = pd_compute_forces,
    .stable_dt = pd_dt,
    .end_step = pd_end_step,
    .energy = pd_energy,
    .history = pd_history,
    .describe = pd_describe,
    .destroy = pd_destroy,
    .interactions = pd_interactions,
    .setup_range = pd_setup_range,
    .setup_tables = pd_setup_tables,
    .damping = pd_damping,
    .localize = pd_localize,
    .migrate_arrays = pd_migrate_arrays,
    .halo_bonds = pd_bonds,
    .fixtures = pd_fixtures,
};

const struct bond_list *pd_bonds(const struct model *m)
{
    return m->bl;
}

size_t pd_compact_kinds(const struct model *m)
{
    return m->kind ? m->n_kind : 0;
}

const struct pd_material *pd_material_get(const struct model *m, int k)
{
    return &m->mat[k];
}

bool pd_mixed_state(const struct model *m, size_t i, double *beta, double *g)
{
    const bool on = m->mixed && m->mm_g && m->mm_beta;
    *beta = on ? m->mm_beta[i] : 0.0;
    *g = on ? m->mm_g[i] : 1.0;
    return on;
}
