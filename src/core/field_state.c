/**
 * @file field_state.c
 * @brief Restart state registry (see field_state.h) and the engine's own
 *        restart state.
 */
#include "core/field_state.h"

#include "core/bond_list.h"
#include "core/contact_particles.h"
#include "core/model.h"
#include "core/particles.h"
#include "core/rigid.h"
#include "core/sim.h"
#include "spall/error.h"

#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

int field_state_create(struct field_state **out, struct spall_error *err)
{
    *out = calloc(1, sizeof **out);
    return *out ? SPALL_OK : spall_error_set(err, SPALL_ERR_NOMEM, "out of memory (restart state)");
}

void field_state_destroy(struct field_state **fs)
{
    if (!fs || !*fs)
        return;
    free((*fs)->slots);
    free(*fs);
    *fs = NULL;
}

size_t field_state_type_size(enum field_type type)
{
    switch (type) {
    case FIELD_F64:
    case FIELD_I64:
        return 8;
    case FIELD_I32:
        return 4;
    case FIELD_U8:
        return 1;
    }
    return 0;
}

static int add_slot(struct field_state *fs, const struct field_state_slot *s,
                    struct spall_error *err)
{
    if (!s->name[0] || strlen(s->name) >= FIELD_STATE_NAME_LEN || s->width == 0)
        return spall_error_set(err, SPALL_ERR_INTERNAL, "restart state slot '%s' is malformed",
                               s->name);
    if (field_state_find(fs, s->name))
        return spall_error_set(err, SPALL_ERR_INTERNAL, "restart state slot '%s' registered twice",
                               s->name);
    if (fs->n == fs->cap) {
        size_t cap = fs->cap ? 2 * fs->cap : 32;
        struct field_state_slot *g = realloc(fs->slots, cap * sizeof *g);
        if (!g)
            return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory (restart state)");
        fs->slots = g;
        fs->cap = cap;
    }
    fs->slots[fs->n++] = *s;
    return SPALL_OK;
}

int field_state_add_array(struct field_state *fs, const char *name, enum field_type type,
                          void **data, size_t rows, size_t width, struct spall_error *err)
{
    struct field_state_slot s = {.type = type, .width = width, .data = data, .rows_fixed = rows,
                                 .layout = FIELD_STATE_LOCAL};
    snprintf(s.name, sizeof s.name, "%s", name);
    return add_slot(fs, &s, err);
}

int field_state_add_particle_array(struct field_state *fs, const char *name,
                                   enum field_type type, void **data, size_t n_owned,
                                   size_t width, struct spall_error *err)
{
    struct field_state_slot s = {.type = type, .width = width, .data = data,
                                 .rows_fixed = n_owned, .layout = FIELD_STATE_PARTICLE};
    snprintf(s.name, sizeof s.name, "%s", name);
    return add_slot(fs, &s, err);
}

int field_state_add_bond_array(struct field_state *fs, const char *name, enum field_type type,
                               void **data, const struct bond_list *bonds, size_t width,
                               struct spall_error *err)
{
    struct field_state_slot s = {.type = type, .width = width, .data = data,
                                 .rows_fixed = bonds->offset[bonds->n],
                                 .layout = FIELD_STATE_HALF_BOND, .bonds = bonds};
    snprintf(s.name, sizeof s.name, "%s", name);
    return add_slot(fs, &s, err);
}

int field_state_add_bond_list(struct field_state *fs, const char *name, enum field_type type,
                              void **data, const struct bond_list *bonds, size_t width,
                              field_state_set_rows_fn set_rows, void *ctx,
                              struct spall_error *err)
{
    struct field_state_slot s = {.type = type, .width = width, .data = data,
                                 .rows_fixed = bonds->offset[bonds->n], .set_rows = set_rows,
                                 .ctx = ctx, .layout = FIELD_STATE_HALF_BOND, .bonds = bonds};
    snprintf(s.name, sizeof s.name, "%s", name);
    return add_slot(fs, &s, err);
}

int field_state_add_offsets(struct field_state *fs, const char *name, void **data,
                            const struct bond_list *bonds, struct spall_error *err)
{
    _Static_assert(sizeof(size_t) == sizeof(int64_t), "offsets are saved as int64");
    struct field_state_slot s = {.type = FIELD_I64, .width = 1, .data = data,
                                 .rows_fixed = bonds->n + 1, .layout = FIELD_STATE_OFFSETS,
                                 .bonds = bonds};
    snprintf(s.name, sizeof s.name, "%s", name);
    return add_slot(fs, &s, err);
}

int field_state_add_list(struct field_state *fs, const char *name, enum field_type type,
                         void **data, size_t width, field_state_rows_fn rows,
                         field_state_set_rows_fn set_rows, void *ctx, struct spall_error *err)
{
    struct field_state_slot s = {.type = type, .width = width, .data = data, .rows = rows,
                                 .set_rows = set_rows, .ctx = ctx, .layout = FIELD_STATE_LOCAL};
    snprintf(s.name, sizeof s.name, "%s", name);
    return add_slot(fs, &s, err);
}

int field_state_add_values(struct field_state *fs, const char *name, enum field_type type,
                           void *values, size_t count, struct spall_error *err)
{
    struct field_state_slot s = {.type = type, .width = 1, .direct = values, .rows_fixed = count};
    snprintf(s.name, sizeof s.name, "%s", name);
    return add_slot(fs, &s, err);
}

int field_state_add_values_hook(struct field_state *fs, const char *name, enum field_type type,
                                void *values, size_t count, field_state_set_rows_fn loaded,
                                void *ctx, struct spall_error *err)
{
    /* the hook stands in for the row-count check of fixed values: it
     * checks the count itself (field_state_slot_resize) */
    struct field_state_slot s = {.type = type, .width = 1, .direct = values, .rows_fixed = count,
                                 .set_rows = loaded, .ctx = ctx};
    snprintf(s.name, sizeof s.name, "%s", name);
    return add_slot(fs, &s, err);
}

const struct field_state_slot *field_state_find(const struct field_state *fs, const char *name)
{
    for (size_t k = 0; k < fs->n; k++)
        if (strcmp(fs->slots[k].name, name) == 0)
            return &fs->slots[k];
    return NULL;
}

size_t field_state_slot_rows(const struct field_state_slot *s)
{
    return s->rows ? s->rows(s->ctx) : s->rows_fixed;
}

void *field_state_slot_data(const struct field_state_slot *s)
{
    return s->direct ? s->direct : *s->data;
}

int field_state_slot_resize(const struct field_state_slot *s, size_t rows, struct spall_error *err)
{
    if (s->set_rows)
        return s->set_rows(s->ctx, rows, err);
    size_t have = field_state_slot_rows(s);
    if (have != rows)
        return spall_error_set(err, SPALL_ERR_INPUT,
                               "state '%s' holds %zu rows in the checkpoint, %zu in this run",
                               s->name, rows, have);
    return SPALL_OK;
}

/* ---- the engine's state ------------------------------------------------- */

static int register_rigid(struct sim *s, struct field_state *fs, struct spall_error *err)
{
    int rc = SPALL_OK;
    for (size_t k = 0; s->rigid && k < s->rigid->n && !rc; k++) {
        struct impactor *im = &s->rigid->im[k];
        /* the geometry and drive come from the deck; these evolve */
        double *vals[] = {im->x, im->v, im->f_pen, im->f_noslip};
        const char *names[] = {"x", "v", "f_pen", "f_noslip"};
        char nm[FIELD_STATE_NAME_LEN];
        for (size_t q = 0; q < 4 && !rc; q++) {
            snprintf(nm, sizeof nm, "rigid.%zu.%s", k, names[q]);
            rc = field_state_add_values(fs, nm, FIELD_F64, vals[q], 3, err);
        }
        double *acc[] = {&im->k_dt, &im->pen_energy, &im->friction_loss, &im->noslip_loss,
                         &im->push_work, &im->drive_work, &im->gravity_work};
        const char *an[] = {"k_dt", "pen_energy", "friction_loss", "noslip_loss",
                            "push_work", "drive_work", "gravity_work"};
        for (size_t q = 0; q < 7 && !rc; q++) {
            snprintf(nm, sizeof nm, "rigid.%zu.%s", k, an[q]);
            rc = field_state_add_values(fs, nm, FIELD_F64, acc[q], 1, err);
        }
        if (!rc) {
            snprintf(nm, sizeof nm, "rigid.%zu.n_contact", k);
            rc = field_state_add_values(fs, nm, FIELD_I64, &im->n_contact, 1, err);
        }
    }
    return rc;
}

int sim_register_state(struct sim *s, struct field_state *fs, struct spall_error *err)
{
    if (!s->ops->register_state)
        return spall_error_set(err, SPALL_ERR_INPUT, "model '%s' cannot be checkpointed",
                               s->ops->name);
    _Static_assert(sizeof(long) == 8 && sizeof(size_t) == 8, "checkpoint counters are 64-bit");
    struct particles *p = s->p;
    int rc = SPALL_OK;
    /* the integrator: t, step, dt, the coefficient ADR may have changed */
    if ((rc = field_state_add_values(fs, "sim.t", FIELD_F64, &s->t, 1, err)) ||
        (rc = field_state_add_values(fs, "sim.dt", FIELD_F64, &s->dt, 1, err)) ||
        (rc = field_state_add_values(fs, "sim.step", FIELD_I64, &s->step, 1, err)) ||
        (rc = field_state_add_values(fs, "sim.dt_rest", FIELD_F64, &s->dt_rest, 1, err)) ||
        (rc = field_state_add_values(fs, "sim.n_split", FIELD_I64, &s->n_split, 1, err)) ||
        (rc = field_state_add_values(fs, "sim.damping", FIELD_F64, &s->damping, 1, err)) ||
        (rc = field_state_add_values(fs, "sim.energy", FIELD_F64, &s->energy,
                                     sizeof s->energy / sizeof(double), err)))
        return rc;
    char nm[FIELD_STATE_NAME_LEN];
    for (size_t k = 0; k < s->n_bcs && !rc; k++) {
        snprintf(nm, sizeof nm, "bc.%zu.reaction", k);
        rc = field_state_add_values(fs, nm, FIELD_F64, s->bcs[k].reaction, 3, err);
        snprintf(nm, sizeof nm, "bc.%zu.work", k);
        if (!rc)
            rc = field_state_add_values(fs, nm, FIELD_F64, &s->bcs[k].work, 1, err);
    }
    /* the forces of the last step feed the first kick of the next one */
    for (int d = 0; d < s->dim && !rc; d++) {
        snprintf(nm, sizeof nm, "particles.force.%d", d);
        rc = field_state_add_particle_array(fs, nm, FIELD_F64, (void **)&p->f[d], p->n_owned, 1,
                                            err);
        if (!rc && s->v_half[d]) {
            snprintf(nm, sizeof nm, "sim.v_half.%d", d);
            rc = field_state_add_particle_array(fs, nm, FIELD_F64, (void **)&s->v_half[d],
                                                p->n_owned, 1, err);
        }
    }
    if (!rc)
        rc = register_rigid(s, fs, err);
    if (!rc)
        rc = particle_contact_register_state(s, fs, err);
    if (!rc)
        rc = s->ops->register_state(s->model, s, fs, err);
    return rc;
}
