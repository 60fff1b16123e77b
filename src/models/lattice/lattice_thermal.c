/**
 * @file lattice_thermal.c
 * @brief Thermal lattice: conduction, heating, expansion, melting (see
 *        lattice_thermal.h for the equations and the bond conductance).
 */
#include "models/lattice/lattice_thermal.h"

#include "core/bond_list.h"
#include "core/field_state.h"
#include "core/fields.h"
#include "core/particles.h"
#include "core/sim.h"
#include "core/options.h"
#include "core/parallel/comm.h"
#include "core/parallel/decomp.h"
#include "core/parallel/migrate.h"
#include "models/lattice/lattice_internal.h"
#include "spall/error.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define TH_MAX_BC 16
#define TH_DEFAULT_T 293.15 /* K */
#define TH_MAX_ETAB 64

struct th_material {
    bool given;
    double C;      /**< specific heat J/(kg K) */
    double k;      /**< conductivity W/(m K) */
    double alpha;  /**< 1/K */
    double P;      /**< power density W/m^3 */
    double T_melt; /**< K (INFINITY: none) */
    double T_init, T_ref;
    size_t n_e;                 /**< youngs_modulus_table points (0: none) */
    double eT[TH_MAX_ETAB], eE[TH_MAX_ETAB];
};

struct th_bc {
    char group[SPALL_NAME_LEN];
    double T;
    int g; /**< resolved at init */
};

struct lattice_thermal {
    size_t n_mat;
    struct th_material *mat;
    struct th_bc bc[TH_MAX_BC];
    size_t n_bc;
    bool any;         /**< some material has thermal keys */
    /* state (after init) */
    size_t n;
    double *T, *T_new;
    double *rest0;    /**< reference rest lengths (half-bond) */
    double *kappa;    /**< conductance per half-bond W/K */
    double *heat;     /**< P_d V per particle, W */
    double *inv_mC;   /**< 1 / (m C) */
    double dt_limit;  /**< explicit stability limit of conduction */
    size_t melted;    /**< bonds removed by melting (counted once; the whole run's) */
    bool any_table;   /**< some material has youngs_modulus_table */
    double *kscale;   /**< per half-bond E(T)/E_ref (only with a table) */
};

bool lattice_thermal_enabled(const struct model *m)
{
    return m->th && m->th->any;
}

static int th_get(struct model *m, size_t n_mat, struct spall_error *err)
{
    if (!m->th) {
        m->th = calloc(1, sizeof *m->th);
        if (!m->th)
            return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory (thermal lattice)");
    }
    struct lattice_thermal *th = m->th;
    if (th->n_mat < n_mat) {
        struct th_material *t = realloc(th->mat, n_mat * sizeof *t);
        if (!t)
            return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory (thermal lattice)");
        memset(t + th->n_mat, 0, (n_mat - th->n_mat) * sizeof *t);
        th->mat = t;
        th->n_mat = n_mat;
    }
    return SPALL_OK;
}

/* `youngs_modulus_table: [[T, E], ...]`: strictly increasing T > 0, E > 0
 * and E <= youngs_modulus (the stable time step is sized with youngs_modulus,
 * so a stiffer bond at temperature would make the run unstable). */
static int th_parse_table(struct th_material *t, const struct deck_node *node,
                          struct spall_error *err)
{
    const struct deck_node *tab = NULL;
    int rc = deck_list(node, "youngs_modulus_table", "a list of [temperature K, youngs_modulus Pa] pairs", &tab, err);
    if (rc || !tab)
        return rc;
    if (tab->n < 1 || tab->n > TH_MAX_ETAB)
        return deck_error(err, tab, "youngs_modulus_table has %zu points; expected 1 to %d",
                          tab->n, TH_MAX_ETAB);
    double E_ref = INFINITY;
    const struct deck_node *en = deck_peek(node, "youngs_modulus");
    if (en && (rc = deck_node_double(en, &E_ref, err)))
        return rc;
    for (size_t k = 0; k < tab->n; k++) {
        const struct deck_node *row = tab->items[k];
        if (row->kind != DECK_SEQUENCE || row->n != 2)
            return deck_error(err, row, "youngs_modulus_table[%zu]: expected [T, E]", k);
        if ((rc = deck_node_double(row->items[0], &t->eT[k], err)) ||
            (rc = deck_node_double(row->items[1], &t->eE[k], err)))
            return rc;
        if (!(t->eT[k] >= 0.0) || !isfinite(t->eT[k]))
            return deck_error(err, row->items[0], "youngs_modulus_table[%zu]: temperature %g K; "
                              "expected >= 0", k, t->eT[k]);
        if (k > 0 && !(t->eT[k] > t->eT[k - 1]))
            return deck_error(err, row->items[0], "youngs_modulus_table[%zu]: temperature %g K "
                              "not above the previous %g K (strictly increasing T)", k, t->eT[k],
                              t->eT[k - 1]);
        if (!(t->eE[k] > 0.0) || !isfinite(t->eE[k]))
            return deck_error(err, row->items[1], "youngs_modulus_table[%zu]: E %g Pa; expected "
                              "> 0", k, t->eE[k]);
        if (t->eE[k] > E_ref * (1.0 + 1e-12))
            return deck_error(err, row->items[1], "youngs_modulus_table[%zu]: E %g Pa above "
                              "youngs_modulus %g Pa (the time step is sized with youngs_modulus)",
                              k, t->eE[k], E_ref);
    }
    t->n_e = tab->n;
    return SPALL_OK;
}

/* E(T) / E_ref, piecewise linear in T, held constant outside the table */
static double th_efactor(const struct th_material *t, double E_ref, double T)
{
    if (!t->n_e)
        return 1.0;
    const size_t n = t->n_e;
    if (T <= t->eT[0])
        return t->eE[0] / E_ref;
    if (T >= t->eT[n - 1])
        return t->eE[n - 1] / E_ref;
    size_t k = 1;
    while (t->eT[k] < T)
        k++;
    const double w = (T - t->eT[k - 1]) / (t->eT[k] - t->eT[k - 1]);
    return ((1.0 - w) * t->eE[k - 1] + w * t->eE[k]) / E_ref;
}

int lattice_thermal_parse_material(struct model *m, struct sim *sim, int index,
                                   const struct deck_node *node, struct spall_error *err)
{
    (void)sim;
    int rc = th_get(m, (size_t)index + 1, err);
    if (rc)
        return rc;
    struct th_material *t = &m->th->mat[index];
    memset(t, 0, sizeof *t);
    t->T_melt = INFINITY;
    t->T_init = t->T_ref = TH_DEFAULT_T;
    if (!deck_peek(node, "specific_heat")) {
        static const char *const others[] = {LATTICE_THERMAL_KEYS, NULL};
        for (size_t k = 1; others[k]; k++)
            if (deck_peek(node, others[k]))
                return deck_error_key(err, node, others[k],
                                      "thermal key '%s' needs specific_heat [J/(kg K)] too",
                                      others[k]);
        return SPALL_OK;
    }
    if ((rc = deck_double_pos(node, "specific_heat", true, &t->C, err)) ||
        (rc = deck_double(node, "conductivity", false, 0.0, INFINITY, &t->k, err)) ||
        (rc = deck_double(node, "thermal_expansion", false, -1e-2, 1e-2, &t->alpha, err)) ||
        (rc = deck_double(node, "power_density", false, -INFINITY, INFINITY, &t->P, err)) ||
        (rc = deck_double_pos(node, "melting_temperature", false, &t->T_melt, err)) ||
        (rc = deck_double(node, "reference_temperature", false, 0.0, INFINITY, &t->T_ref, err)))
        return rc;
    t->T_init = t->T_ref;
    if ((rc = deck_double(node, "initial_temperature", false, 0.0, INFINITY, &t->T_init, err)) ||
        (rc = th_parse_table(t, node, err)))
        return rc;
    if (t->n_e)
        m->th->any_table = true;
    t->given = true;
    m->th->any = true;
    return SPALL_OK;
}

int lattice_thermal_parse_options(struct model *m, const struct deck_node *node,
                                  struct spall_error *err)
{
    static const char *const keys[] = {"boundary", NULL};
    static const char *const bkeys[] = {"group", "temperature", NULL};
    int rc = deck_expect_map(node, "model.thermal", err);
    if (rc || (rc = th_get(m, 0, err)))
        return rc;
    const struct deck_node *b = NULL;
    if ((rc = deck_list(node, "boundary", "a list of {group, temperature}", &b, err)))
        return rc;
    if (b) {
        if (b->n > TH_MAX_BC)
            return deck_error(err, b, "%zu thermal boundary conditions; at most %d", b->n,
                              TH_MAX_BC);
        for (size_t k = 0; k < b->n; k++) {
            const struct deck_node *e = b->items[k];
            const char *g = NULL;
            struct th_bc *bc = &m->th->bc[k];
            if ((rc = deck_expect_map(e, "{group, temperature}", err)) ||
                (rc = deck_string(e, "group", true, &g, err)) ||
                (rc = deck_double_pos(e, "temperature", true, &bc->T, err)) ||
                (rc = deck_check_unused(e, "model.thermal.boundary", bkeys, err)))
                return rc;
            snprintf(bc->group, sizeof bc->group, "%s", g);
        }
        m->th->n_bc = b->n;
    }
    return deck_check_unused(node, "model.thermal", keys, err);
}

int lattice_thermal_init(struct model *m, struct sim *sim, struct spall_error *err)
{
    struct lattice_thermal *th = m->th;
    if (!th)
        return SPALL_OK;
    if (!th->any) {
        if (th->n_bc)
            return spall_error_set_key(err, SPALL_ERR_INPUT, "model.thermal",
                                       "model.thermal: boundary temperatures "
                                       "given but no material has specific_heat");
        return SPALL_OK;
    }
    for (size_t k = 0; k < sim->n_materials; k++)
        if (k >= th->n_mat || !th->mat[k].given) {
            spall_error_set(err, SPALL_ERR_INPUT,
                            "thermal lattice: material '%s' has no specific_heat (every "
                            "material needs the thermal keys once one has them)",
                            sim->materials[k].name);
            spall_error_default_key(err, "materials.%s", sim->materials[k].name);
            return SPALL_ERR_INPUT;
        }
    const struct particles *p = sim->p;
    const struct bond_list *bl = m->bl;
    const size_t n = p->n, nh = bl->offset[bl->n];
    th->n = n;
    free(th->T); /* init may run again (rebuilt bonds) */
    free(th->T_new);
    free(th->heat);
    free(th->inv_mC);
    free(th->rest0);
    free(th->kappa);
    th->T = malloc((n ? n : 1) * sizeof *th->T);
    th->T_new = malloc((n ? n : 1) * sizeof *th->T_new);
    th->heat = malloc((n ? n : 1) * sizeof *th->heat);
    th->inv_mC = malloc((n ? n : 1) * sizeof *th->inv_mC);
    th->rest0 = malloc((nh ? nh : 1) * sizeof *th->rest0);
    th->kappa = malloc((nh ? nh : 1) * sizeof *th->kappa);
    free(th->kscale);
    th->kscale = NULL;
    m->kscale = NULL;
    if (th->any_table) {
        for (size_t k = 0; k < sim->n_materials; k++)
            if (th->mat[k].n_e && th->mat[k].eE[0] > 0.0)
                for (size_t q = 0; q < th->mat[k].n_e; q++)
                    if (th->mat[k].eE[q] > m->mat[k].E * (1.0 + 1e-12))
                        return spall_error_set(err, SPALL_ERR_INPUT,
                                               "material '%s': youngs_modulus_table E %g Pa "
                                               "above youngs_modulus %g Pa",
                                               sim->materials[k].name, th->mat[k].eE[q],
                                               m->mat[k].E);
        th->kscale = malloc((nh ? nh : 1) * sizeof *th->kscale);
        if (!th->kscale)
            return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory (thermal lattice)");
        for (size_t s = 0; s < nh; s++)
            th->kscale[s] = 1.0;
        m->kscale = th->kscale;
    }
    if (!th->T || !th->T_new || !th->heat || !th->inv_mC || !th->rest0 || !th->kappa)
        return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory (thermal lattice)");
    /* bulk second moment S and volume V: the particle with the largest S */
    double S = 0.0, V = 0.0;
    for (size_t i = 0; i < bl->n; i++) {
        double si = 0.0;
        for (size_t s = bl->offset[i]; s < bl->offset[i + 1]; s++)
            si += bl->rest[s] * bl->rest[s];
        if (si > S) {
            S = si;
            V = p->volume[i];
        }
    }
    const double geo = S > 0.0 ? 2.0 * (double)sim->dim * V / S : 0.0;
    for (size_t i = 0; i < n; i++) {
        const struct th_material *t = &th->mat[p->material[i]];
        th->T[i] = t->T_init;
        th->heat[i] = t->P * p->volume[i];
        th->inv_mC[i] = 1.0 / (p->mass[i] * t->C);
    }
    th->dt_limit = INFINITY;
    for (size_t i = 0; i < bl->n; i++) {
        const double ki = th->mat[p->material[i]].k;
        double sum = 0.0;
        for (size_t s = bl->offset[i]; s < bl->offset[i + 1]; s++) {
            const double kj = th->mat[p->material[bl->partner[s]]].k;
            const double kk = ki + kj > 0.0 ? 2.0 * ki * kj / (ki + kj) : 0.0;
            th->kappa[s] = geo * kk;
            th->rest0[s] = bl->rest[s];
            sum += th->kappa[s];
        }
        if (sum > 0.0)
            th->dt_limit = fmin(th->dt_limit, 1.0 / (sum * th->inv_mC[i]));
    }
    for (size_t k = 0; k < th->n_bc; k++) {
        th->bc[k].g = sim_find_group(sim, th->bc[k].group);
        if (th->bc[k].g < 0) { /* bc[k] is item k of the deck's list */
            spall_error_set(err, SPALL_ERR_INPUT, "model.thermal.boundary: no group named '%s'",
                            th->bc[k].group);
            spall_error_default_key(err, "model.thermal.boundary[%zu].group", k);
            return SPALL_ERR_INPUT;
        }
        const struct group *g = &sim->groups[th->bc[k].g];
        for (size_t q = 0; q < g->n; q++)
            th->T[g->idx[q]] = th->bc[k].T;
    }
    /* rest lengths at the initial temperatures */
    return lattice_thermal_step(m, sim, 0.0, err);
}

/* one explicit conduction + heating sub-step (gather: thread independent) */
static void th_substep(struct lattice_thermal *th, const struct bond_list *bl, size_t n_owned,
                       double h)
{
    const double *T = th->T;
    double *Tn = th->T_new;
#pragma omp parallel for schedule(static) if (n_owned > 4096)
    for (size_t i = 0; i < n_owned; i++) {
        double q = th->heat[i];
        for (size_t s = bl->offset[i]; s < bl->offset[i + 1]; s++)
            if (!(bl->state[s] & BOND_BROKEN))
                q += th->kappa[s] * (T[bl->partner[s]] - T[i]);
        Tn[i] = T[i] + h * q * th->inv_mC[i];
    }
    for (size_t i = n_owned; i < th->n; i++)
        Tn[i] = T[i];
    double *t = th->T;
    th->T = th->T_new;
    th->T_new = t;
}

int lattice_thermal_step(struct model *m, struct sim *sim, double dt, struct spall_error *err)
{
    (void)err;
    struct lattice_thermal *th = m->th;
    if (!th || !th->any)
        return SPALL_OK;
    const struct particles *p = sim->p;
    struct bond_list *bl = m->bl;
    if (dt > 0.0) {
        /* sub-cycle below 0.9 of the explicit limit */
        long nsub = isfinite(th->dt_limit) ? (long)ceil(dt / (0.9 * th->dt_limit)) : 1;
        if (nsub < 1)
            nsub = 1;
        for (long k = 0; k < nsub; k++) {
            th_substep(th, bl, p->n_owned, dt / (double)nsub);
            for (size_t b = 0; b < th->n_bc; b++) { /* fixed temperatures */
                const struct group *g = &sim->groups[th->bc[b].g];
                for (size_t q = 0; q < g->n; q++)
                    th->T[g->idx[q]] = th->bc[b].T;
            }
            if (sim->par) /* ghosts: their owners' temperatures, for the next sub-step */
                par_halo_values(sim, th->T, 1);
        }
    }
    /* expansion of rest lengths (Eq. 21) and melting; symmetric in i, j so
     * both halves of a bond get the same value and the same decision */
    size_t melted = 0;
#pragma omp parallel for schedule(static) reduction(+ : melted) if (p->n_owned > 4096)
    for (size_t i = 0; i < p->n_owned; i++) {
        const struct th_material *a = &th->mat[p->material[i]];
        for (size_t s = bl->offset[i]; s < bl->offset[i + 1]; s++) {
            const size_t j = (size_t)bl->partner[s];
            const struct th_material *b = &th->mat[p->material[j]];
            const double alpha = 0.5 * (a->alpha + b->alpha);
            const double dT = 0.5 * (th->T[i] + th->T[j]) - 0.5 * (a->T_ref + b->T_ref);
            bl->rest[s] = th->rest0[s] * (1.0 + alpha * dT);
            if (th->kscale) {
                /* series pair stiffness 2 ka kb / (ka + kb) with each side
                 * scaled by its E(Tbar)/E_ref: ratio fa fb (ka+kb)/(fa ka + fb kb) */
                const double Tb = 0.5 * (th->T[i] + th->T[j]);
                const int32_t ma = p->material[i], mb = p->material[j];
                const double fa = th_efactor(a, m->mat[ma].E, Tb);
                double f = fa;
                if (mb != ma) {
                    const double fb = th_efactor(b, m->mat[mb].E, Tb);
                    const double ka = m->mat[ma].k[bl->type[s]], kb = m->mat[mb].k[bl->type[s]];
                    const double den = fa * ka + fb * kb;
                    f = den > 0.0 ? fa * fb * (ka + kb) / den : fa;
                }
                th->kscale[s] = f;
            }
            if (!(bl->state[s] & BOND_BROKEN) && (th->T[i] > a->T_melt || th->T[j] > b->T_melt)) {
                bl->state[s] |= BOND_BROKEN;
                melted += p->gid[j] > p->gid[i]; /* once per bond, on every rank count */
            }
        }
    }
    /* distributed: each rank counted the bonds it owns the lower end of;
     * the total (one integer sum) keeps th->melted the whole run's on every
     * rank, which the checkpoint stores once */
    th->melted += sim->par ? (size_t)par_sum_u64(melted) : melted;
    return SPALL_OK;
}

int lattice_thermal_register_fields(struct model *m, struct field_registry *reg,
                                    struct spall_error *err)
{
    if (!lattice_thermal_enabled(m))
        return SPALL_OK;
    double **T[1] = {&m->th->T};
    return field_registry_add_f64(reg, "temperature", "K", 1, T, FIELD_OUTPUT | FIELD_DEFAULT,
                                  err);
}

int lattice_thermal_register_state(struct model *m, size_t n_owned, struct field_state *fs,
                                   struct spall_error *err)
{
    if (!lattice_thermal_enabled(m))
        return SPALL_OK;
    struct lattice_thermal *th = m->th;
    /* temperatures, and what melting and E(T) change per half-bond (the
     * rest lengths follow T by thermal expansion), per owned particle and
     * per half-bond, so that a distributed run writes them by global ids;
     * the melted count is the whole run's on every rank (lattice_thermal_step) */
    int rc = field_state_add_particle_array(fs, "lattice.T", FIELD_F64, (void **)&th->T, n_owned,
                                            1, err);
    if (!rc)
        rc = field_state_add_bond_array(fs, "lattice.conductance", FIELD_F64,
                                        (void **)&th->kappa, m->bl, 1, err);
    if (!rc)
        rc = field_state_add_particle_array(fs, "lattice.heat", FIELD_F64, (void **)&th->heat,
                                            n_owned, 1, err);
    if (!rc && th->kscale)
        rc = field_state_add_bond_array(fs, "lattice.kscale", FIELD_F64, (void **)&th->kscale,
                                        m->bl, 1, err);
    if (!rc)
        rc = field_state_add_values(fs, "lattice.melted", FIELD_I64, &th->melted, 1, err);
    return rc;
}

/* rows (m T, m, T) -> the serial loop's sum m T, sum m, max T */
static void th_reduce(const double *rows, size_t n, int ncol, double *out, const void *ctx)
{
    (void)ctx;
    double sum = 0.0, mass = 0.0, tmax = -INFINITY;
    for (size_t q = 0; q < n; q++) {
        const double *r = rows + q * (size_t)ncol;
        sum += r[0];
        mass += r[1];
        tmax = fmax(tmax, r[2]);
    }
    out[0] = sum;
    out[1] = mass;
    out[2] = tmax;
}

int lattice_thermal_localize(struct model *m, const size_t *keep, size_t n_keep,
                             const struct bond_rows *rows, struct spall_error *err)
{
    struct lattice_thermal *th = m->th;
    if (!lattice_thermal_enabled(m))
        return SPALL_OK;
    /* T itself is the registered field `temperature`: the engine compacts
     * it with the particles (core/parallel/decomp.c) */
    double **pp[6] = {&th->T_new, &th->heat, &th->inv_mC, &th->rest0, &th->kappa, &th->kscale};
    double *np[6] = {NULL, NULL, NULL, NULL, NULL, NULL};
    int bad = 0;
    for (int k = 0; k < 6; k++) {
        if (!*pp[k])
            continue; /* kscale: only with a youngs_modulus_table */
        np[k] = k < 3 ? array_gather(*pp[k], sizeof(double), keep, n_keep)
                      : bond_rows_gather(rows, *pp[k], sizeof(double));
        bad |= !np[k];
    }
    if (bad) {
        for (int k = 0; k < 6; k++)
            free(np[k]);
        return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory localising the thermal lattice");
    }
    for (int k = 0; k < 6; k++)
        if (*pp[k]) {
            free(*pp[k]);
            *pp[k] = np[k];
        }
    th->n = n_keep;
    m->kscale = th->kscale;
    return SPALL_OK;
}

size_t lattice_thermal_history(const struct model *m, const struct sim *sim, const char **names,
                               double *values)
{
    if (!lattice_thermal_enabled(m))
        return 0;
    const struct lattice_thermal *th = m->th;
    double sum = 0.0, mass = 0.0, tmax = -INFINITY;
    size_t melted = th->melted;
    if (sim->par) { /* distributed: the serial sums, in gid order */
        const size_t n = sim->p->n_owned;
        double *rows = malloc((n ? n : 1) * 3 * sizeof *rows), out[3] = {0.0, 0.0, -INFINITY};
        for (size_t i = 0; rows && i < n; i++) {
            rows[3 * i] = sim->p->mass[i] * th->T[i];
            rows[3 * i + 1] = sim->p->mass[i];
            rows[3 * i + 2] = th->T[i];
        }
        /* collective even without memory: this rank then sends no rows and
         * the means are of the others (a NOMEM at a history row only) */
        par_ordered_reduce(sim->p->gid, rows ? rows : out, rows ? n : 0, 3, th_reduce, NULL, out,
                           3);
        free(rows);
        sum = out[0];
        mass = out[1];
        tmax = out[2];
    } else {
        for (size_t i = 0; i < sim->p->n_owned; i++) {
            sum += sim->p->mass[i] * th->T[i];
            mass += sim->p->mass[i];
            tmax = fmax(tmax, th->T[i]);
        }
    }
    names[0] = "temperature_mean [K]";
    values[0] = mass > 0.0 ? sum / mass : 0.0;
    names[1] = "temperature_max [K]";
    values[1] = tmax;
    names[2] = "bonds_melted";
    values[2] = (double)melted;
    return 3;
}

void lattice_thermal_destroy(struct lattice_thermal **pth)
{
    if (!pth || !*pth)
        return;
    struct lattice_thermal *th = *pth;
    free(th->mat);
    free(th->T);
    free(th->T_new);
    free(th->rest0);
    free(th->kappa);
    free(th->heat);
    free(th->inv_mC);
    free(th->kscale);
    free(th);
    *pth = NULL;
}

/* Distributed runs, migration (lattice_localize.c): the per-particle and
 * per-half-bond state travels with its particle.  T is the registered field
 * `temperature` (the engine moves it); T_new is scratch, lent only so that
 * it keeps the particle count. */
void lattice_thermal_migrate_arrays(struct model *m, struct par_model_arrays *a)
{
    struct lattice_thermal *th = m->th;
    if (!lattice_thermal_enabled(m))
        return;
    double **part[3] = {&th->T_new, &th->heat, &th->inv_mC};
    for (int k = 0; k < 3; k++) {
        a->particle[a->n_particle] = (void **)part[k];
        a->particle_size[a->n_particle++] = sizeof(double);
    }
    double **bond[3] = {&th->rest0, &th->kappa, &th->kscale};
    for (int k = 0; k < 3; k++)
        if (*bond[k]) { /* kscale: only with a youngs_modulus_table */
            a->bond[a->n_bond] = (void **)bond[k];
            a->bond_size[a->n_bond++] = sizeof(double);
        }
}

void lattice_thermal_migrated(struct model *m, size_t n)
{
    if (!lattice_thermal_enabled(m))
        return;
    m->th->n = n;
    m->kscale = m->th->kscale; /* the force loop's view of the moved array */
}
