/**
 * @file sim.c
 * @brief Simulation context: tables of materials, groups, BCs, probes, and
 *        preparation of a run (model init, fields, stable time step).
 * The time step itself lives in integrator.c.
 */
#include "core/sim.h"
#include "core/rigid.h"
#include "core/contact_particles.h"

#include "core/fields.h"
#include "core/fragments.h"
#include "core/geometry.h"
#include "core/particles.h"
#include "core/model.h"
#include "core/parallel/comm.h"
#include "core/parallel/decomp.h"
#include "core/parallel/setup_dist.h"
#include "spall/error.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

int sim_create(struct sim **out, int dim, struct spall_error *err)
{
    *out = NULL;
    struct sim *s = calloc(1, sizeof *s);
    if (!s)
        return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory creating simulation");
    s->dim = dim;
    s->dt_factor = 0.5;
    s->energy_blowup = 100.0;
    s->seed = 12345;
    int rc = particles_create(&s->p, dim, 1024, err);
    if (!rc)
        rc = field_registry_create(&s->fields, err);
    if (rc) {
        sim_destroy(&s);
        return rc;
    }
    *out = s;
    return SPALL_OK;
}

void sim_destroy(struct sim **sp)
{
    if (!sp || !*sp)
        return;
    struct sim *s = *sp;
    if (s->ops && s->model)
        s->ops->destroy(&s->model);
    particles_destroy(&s->p);
    field_registry_destroy(&s->fields);
    for (size_t g = 0; g < s->n_groups; g++)
        free(s->groups[g].idx);
    free(s->groups);
    for (size_t b = 0; b < s->n_bcs; b++)
        time_function_free(&s->bcs[b].tf);
    free(s->bcs);
    free(s->probes);
    free(s->precracks);
    for (int d = 0; d < 3; d++)
        free(s->v_half[d]);
    free(s->drift_save);
    free(s->kinetic_part);
    free(s->no_drift_velocity);
    free(s->materials);
    rigid_set_destroy(&s->rigid);
    particle_contact_destroy(&s->pcontact);
    par_decomp_destroy(&s->par);
    par_setup_destroy(&s->setup);
    free(s);
    *sp = NULL;
}

int sim_find_material(const struct sim *s, const char *name)
{
    for (size_t k = 0; k < s->n_materials; k++)
        if (strcmp(s->materials[k].name, name) == 0)
            return (int)k;
    return -1;
}

int sim_add_material(struct sim *s, const char *name, double density, int *index,
                     struct spall_error *err)
{
    if (sim_find_material(s, name) >= 0)
        return spall_error_set(err, SPALL_ERR_INPUT, "material '%s' defined twice", name);
    if (strlen(name) >= SPALL_NAME_LEN)
        return spall_error_set(err, SPALL_ERR_INPUT, "material name '%s' longer than %d characters",
                               name, SPALL_NAME_LEN - 1);
    if (!(density > 0.0) || !isfinite(density))
        return spall_error_set(err, SPALL_ERR_PHYSICS,
                               "material '%s': density must be positive and finite (got %g kg/m^3)",
                               name, density);
    struct material *m = realloc(s->materials, (s->n_materials + 1) * sizeof *m);
    if (!m)
        return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory adding material");
    s->materials = m;
    memset(&m[s->n_materials], 0, sizeof *m);
    strcpy(m[s->n_materials].name, name);
    m[s->n_materials].density = density;
    if (index)
        *index = (int)s->n_materials;
    s->n_materials++;
    return SPALL_OK;
}

int sim_find_group(const struct sim *s, const char *name)
{
    for (size_t k = 0; k < s->n_groups; k++)
        if (strcmp(s->groups[k].name, name) == 0)
            return (int)k;
    return -1;
}

int sim_add_group(struct sim *s, const char *name, const size_t *idx, size_t n, int *index,
                  struct spall_error *err)
{
    if (sim_find_group(s, name) >= 0)
        return spall_error_set(err, SPALL_ERR_INPUT, "group '%s' defined twice", name);
    if (strlen(name) >= SPALL_NAME_LEN)
        return spall_error_set(err, SPALL_ERR_INPUT, "group name '%s' longer than %d characters",
                               name, SPALL_NAME_LEN - 1);
    struct group *g = realloc(s->groups, (s->n_groups + 1) * sizeof *g);
    if (!g)
        return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory adding group");
    s->groups = g;
    struct group *ng = &g[s->n_groups];
    memset(ng, 0, sizeof *ng);
    strcpy(ng->name, name);
    ng->idx = malloc((n ? n : 1) * sizeof *ng->idx);
    if (!ng->idx)
        return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory adding group");
    if (n)
        memcpy(ng->idx, idx, n * sizeof *idx);
    ng->n = n;
    if (index)
        *index = (int)s->n_groups;
    s->n_groups++;
    return SPALL_OK;
}

int sim_add_bc(struct sim *s, const struct bc *bc, struct spall_error *err)
{
    struct bc *b = realloc(s->bcs, (s->n_bcs + 1) * sizeof *b);
    if (!b)
        return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory adding boundary condition");
    s->bcs = b;
    b[s->n_bcs++] = *bc;
    return SPALL_OK;
}

int sim_add_precrack(struct sim *s, const struct precrack *c, struct spall_error *err)
{
    struct precrack *q = realloc(s->precracks, (s->n_precracks + 1) * sizeof *q);
    if (!q)
        return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory adding pre-crack");
    s->precracks = q;
    q[s->n_precracks++] = *c;
    return SPALL_OK;
}

int sim_add_probe(struct sim *s, const char *name, const double pos[3], struct spall_error *err)
{
    if (s->p->n == 0)
        return spall_error_set(err, SPALL_ERR_INPUT, "probe '%s': no particles", name);
    struct probe *pr = realloc(s->probes, (s->n_probes + 1) * sizeof *pr);
    if (!pr)
        return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory adding probe");
    s->probes = pr;
    struct probe *q = &pr[s->n_probes];
    memset(q, 0, sizeof *q);
    snprintf(q->name, sizeof q->name, "%s", name);
    memcpy(q->pos, pos, sizeof q->pos);
    /* nearest particle in the reference configuration; ties -> lowest index */
    double best = INFINITY;
    for (size_t i = 0; i < s->p->n_owned; i++) {
        double d2 = 0.0;
        for (int d = 0; d < s->dim; d++) {
            double dx = s->p->x0[d][i] - pos[d];
            d2 += dx * dx;
        }
        if (d2 < best) {
            best = d2;
            q->particle = i;
        }
    }
    s->n_probes++;
    return SPALL_OK;
}

int sim_set_model(struct sim *s, const struct model_ops *ops, const struct deck_node *params,
                  struct spall_error *err)
{
    if (!ops)
        return spall_error_set(err, SPALL_ERR_INTERNAL, "sim_set_model: no model given");
    s->ops = ops;
    int rc = ops->create(&s->model, s, params, err);
    if (rc || !ops->time_scheme)
        return rc;
    struct time_scheme ts = {s->integrator, s->adaptive_dt, s->dt_factor};
    ops->time_scheme(s->model, &ts);
    s->integrator = ts.integrator;
    s->adaptive_dt = ts.adaptive_dt;
    s->dt_factor = ts.dt_factor;
    return SPALL_OK;
}

/* ---- computed core fields ------------------------------------------------ */

static void field_displacement(const void *ctx, size_t n, double *out)
{
    const struct sim *s = ctx;
    int dim = s->dim;
    for (size_t i = 0; i < n; i++)
        for (int d = 0; d < dim; d++)
            out[i * (size_t)dim + (size_t)d] = s->p->x[d][i] - s->p->x0[d][i];
}

static void field_speed(const void *ctx, size_t n, double *out)
{
    const struct sim *s = ctx;
    for (size_t i = 0; i < n; i++) {
        double v2 = 0.0;
        for (int d = 0; d < s->dim; d++)
            v2 += s->p->v[d][i] * s->p->v[d][i];
        out[i] = sqrt(v2);
    }
}

static int register_core_fields(struct sim *s, struct spall_error *err)
{
    struct particles *p = s->p;
    double **xs[3] = {&p->x[0], &p->x[1], &p->x[2]};
    double **vs[3] = {&p->v[0], &p->v[1], &p->v[2]};
    double **fs[3] = {&p->f[0], &p->f[1], &p->f[2]};
    double **x0s[3] = {&p->x0[0], &p->x0[1], &p->x0[2]};
    double **ms[1] = {&p->mass};
    double **vol[1] = {&p->volume};
    unsigned all = FIELD_OUTPUT | FIELD_RESTART | FIELD_MIGRATE | FIELD_GHOST;
    /* position, velocity and force are vectors under sim_reflect_particle;
     * the reference position is the particle's label in the reference
     * configuration, which a reflection of the current one leaves alone */
    int rc = field_registry_add_f64_parity(s->fields, "position", "m", s->dim, xs,
                                           all | FIELD_DEFAULT, FIELD_VECTOR, err);
    if (!rc)
        rc = field_registry_add_f64_parity(s->fields, "velocity", "m/s", s->dim, vs,
                                           all | FIELD_DEFAULT, FIELD_VECTOR, err);
    if (!rc)
        rc = field_registry_add_f64_parity(s->fields, "force", "N", s->dim, fs, FIELD_OUTPUT,
                                           FIELD_VECTOR, err);
    if (!rc)
        rc = field_registry_add_f64(s->fields, "reference_position", "m", s->dim, x0s,
                                    FIELD_OUTPUT | FIELD_RESTART | FIELD_MIGRATE, err);
    if (!rc)
        rc = field_registry_add_f64(s->fields, "mass", "kg", 1, ms,
                                    FIELD_OUTPUT | FIELD_RESTART | FIELD_MIGRATE | FIELD_GHOST, err);
    if (!rc)
        rc = field_registry_add_f64(s->fields, "volume", "m^3", 1, vol,
                                    FIELD_OUTPUT | FIELD_RESTART | FIELD_MIGRATE, err);
    if (rc)
        return rc;
    struct field_desc d;
    memset(&d, 0, sizeof d);
    strcpy(d.name, "id");
    strcpy(d.unit, "1");
    d.ncomp = 1;
    d.type = FIELD_I64;
    d.flags = all | FIELD_DEFAULT;
    d.comp[0] = (void **)&p->gid;
    rc = field_registry_add(s->fields, &d, err);
    if (rc)
        return rc;
    memset(&d, 0, sizeof d);
    strcpy(d.name, "material");
    strcpy(d.unit, "1");
    d.ncomp = 1;
    d.type = FIELD_I32;
    d.flags = all;
    d.comp[0] = (void **)&p->material;
    rc = field_registry_add(s->fields, &d, err);
    if (rc)
        return rc;
    memset(&d, 0, sizeof d);
    strcpy(d.name, "displacement");
    strcpy(d.unit, "m");
    d.ncomp = s->dim;
    d.type = FIELD_F64;
    d.flags = FIELD_OUTPUT | FIELD_DEFAULT;
    d.compute = field_displacement;
    d.ctx = s;
    rc = field_registry_add(s->fields, &d, err);
    if (rc)
        return rc;
    strcpy(d.name, "speed");
    strcpy(d.unit, "m/s");
    d.ncomp = 1;
    d.flags = FIELD_OUTPUT;
    d.compute = field_speed;
    return field_registry_add(s->fields, &d, err);
}

/* sim_prepare's checks and the model's set-up, before the time step. */
static int prepare_model(struct sim *s, struct spall_error *err)
{
    if (!s->ops || !s->model)
        return spall_error_set(err, SPALL_ERR_INPUT, "no model selected");
    if (s->p->n == 0)
        return spall_error_set(err, SPALL_ERR_INPUT, "the body contains no particles");
    for (size_t i = 0; i < s->p->n; i++)
        if (!(s->p->mass[i] > 0.0))
            return spall_error_set(err, SPALL_ERR_INTERNAL, "particle %zu has no mass", i);
    int rc = s->ops->init(s->model, s, err);
    if (!rc)
        rc = par_fault("model_init", err);
    if (rc)
        return rc;
    s->n_precut = 0;
    for (size_t k = 0; k < s->n_precracks; k++) {
        if (!s->ops->precrack)
            return spall_error_set(err, SPALL_ERR_INPUT, "model '%s' does not support pre-cracks",
                                   s->ops->name);
        size_t cut = 0;
        rc = s->ops->precrack(s->model, s, &s->precracks[k], &cut, err);
        if (rc)
            return rc;
        s->n_precut += cut;
    }
    rc = register_core_fields(s, err);
    if (!rc)
        rc = s->ops->register_fields(s->model, s, s->fields, err);
    if (!rc)
        rc = fragments_register_field(s, err); /* needs the model's bonds */
    return rc;
}

int sim_prepare(struct sim *s, struct spall_error *err)
{
    int rc = prepare_model(s, err);
    /* each rank built its window (s->setup): the whole body's limit below is
     * a reduction, so a failure of one rank above is agreed first, here where
     * every rank stands (the deck layer then words it alike on all ranks) */
    if (s->setup)
        rc = par_agree(rc, err);
    if (rc)
        return rc;
    s->dt_limit = fmin(s->ops->stable_dt(s->model, s), particle_contact_stable_dt(s));
    if (s->setup)
        s->dt_limit = par_setup_dt_limit(s->dt_limit);
    if (!(s->dt_limit > 0.0) || !isfinite(s->dt_limit))
        return spall_error_set(err, SPALL_ERR_PHYSICS,
                               "model '%s' reports no finite stable time step (got %g s)",
                               s->ops->name, s->dt_limit);
    if (s->dt > 0.0) {
        if (s->dt > s->dt_limit && !s->dt_override)
            return spall_error_set_key(err, SPALL_ERR_PHYSICS, "run.dt",
                                       "time step %g s is above the stability limit %g s "
                                       "of the %s model (run.log's model_constants say how "
                                       "it is derived); lower run.dt or set "
                                       "run.dt_override: true",
                                       s->dt, s->dt_limit, s->ops->name);
    } else {
        s->dt = s->dt_factor * s->dt_limit;
    }
    if (s->n_steps <= 0) {
        if (!(s->end_time > 0.0))
            return spall_error_set(err, SPALL_ERR_INPUT, "run needs end_time or steps");
        s->n_steps = (long)ceil(s->end_time / s->dt - 1e-9);
    } else if (!(s->end_time > 0.0)) {
        s->end_time = (double)s->n_steps * s->dt;
    }
    if (s->integrator == INTEGRATOR_PREDICTOR_CORRECTOR)
        for (int d = 0; d < s->dim; d++) {
            s->v_half[d] = malloc(s->p->cap * sizeof(double));
            if (!s->v_half[d])
                return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory (integrator)");
        }
    if (s->integrator == INTEGRATOR_LEAPFROG && !s->ops->compute_forces_kick)
        return spall_error_set(err, SPALL_ERR_INPUT,
                               "model '%s' has no state to integrate by the leapfrog",
                               s->ops->name);
    if (s->ops->drift_velocity) {
        /* a prescribed velocity is the particle's whole motion: the model's
         * drift velocity (XSPH) does not move it */
        s->no_drift_velocity = calloc(s->p->cap ? s->p->cap : 1, 1);
        if (!s->no_drift_velocity)
            return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory (integrator)");
        for (size_t k = 0; k < s->n_bcs; k++) {
            const struct bc *b = &s->bcs[k];
            if (b->kind != BC_FIXED && b->kind != BC_VELOCITY)
                continue;
            const struct group *g = &s->groups[b->group];
            for (size_t q = 0; q < g->n; q++)
                s->no_drift_velocity[g->idx[q]] = 1;
        }
    }
    s->t = 0.0;
    s->step = 0;
    s->dt_rest = 0.0;
    s->n_split = 0;
    /* a window of the body (distributed set-up): the initial forces, BC
     * reactions and energy need the whole body's groups and sums, so
     * par_setup_distribute computes them once the window is partitioned */
    return s->setup ? SPALL_OK : sim_initial_forces(s, err);
}
