/**
 * @file setup_typed.c
 * @brief The typed helpers of include/spall/setup.h: each sets the deck
 *        keys its comment names through the key-path setters
 *        (src/api/setup_api.c), so they are checked as a deck's keys are.
 */
#include "spall/setup.h"

#include <stdio.h>

/** Key path "PREFIX.NAME.SUFFIX" into @p buf; SPALL_ERR_INPUT if too long. */
static int key_of(char *buf, size_t cap, const char *prefix, const char *name,
                  const char *suffix, struct spall_error *err)
{
    if (!name || !name[0])
        return spall_error_set(err, SPALL_ERR_INPUT, "spall_setup: empty %s name", prefix);
    int m = snprintf(buf, cap, "%s.%s%s%s", prefix, name, suffix[0] ? "." : "", suffix);
    if (m < 0 || (size_t)m >= cap)
        return spall_error_set(err, SPALL_ERR_INPUT, "spall_setup: %s name '%.64s' too long",
                               prefix, name);
    return SPALL_OK;
}

static int check_dim(int dim, const char *who, struct spall_error *err)
{
    if (dim != 2 && dim != 3)
        return spall_error_set(err, SPALL_ERR_INPUT, "%s: dimension %d; expected 2 or 3", who,
                               dim);
    return SPALL_OK;
}

int spall_setup_model(struct spall_setup *s, const char *type, struct spall_error *err)
{
    return spall_setup_text(s, "model.type", type, err);
}

int spall_setup_material(struct spall_setup *s, const char *name,
                         const struct spall_material *m, struct spall_error *err)
{
    if (!m)
        return spall_error_set(err, SPALL_ERR_INPUT, "spall_setup_material: material is NULL");
    const struct {
        const char *key;
        double v;
    } keys[] = {{"density", m->density},
                {"youngs_modulus", m->youngs_modulus},
                {"poisson_ratio", m->poisson_ratio},
                {"tensile_strength", m->tensile_strength},
                {"fracture_energy", m->fracture_energy}};
    for (size_t k = 0; k < sizeof keys / sizeof keys[0]; k++) {
        char path[SPALL_ERROR_KEY_LEN];
        int rc = key_of(path, sizeof path, "materials", name, keys[k].key, err);
        if (!rc && keys[k].v != 0.0)
            rc = spall_setup_number(s, path, keys[k].v, err);
        if (rc)
            return rc;
    }
    return SPALL_OK;
}

int spall_setup_lattice(struct spall_setup *s, const char *type, double spacing,
                        struct spall_error *err)
{
    int rc = spall_setup_text(s, "lattice.type", type, err);
    return rc ? rc : spall_setup_number(s, "lattice.spacing", spacing, err);
}

int spall_setup_box(struct spall_setup *s, const char *name, int dim, const double *min,
                    const double *max, struct spall_error *err)
{
    char path[SPALL_ERROR_KEY_LEN];
    int rc = check_dim(dim, "spall_setup_box", err);
    if (!rc)
        rc = key_of(path, sizeof path, "geometry", name, "box.min", err);
    if (!rc)
        rc = spall_setup_numbers(s, path, min, (size_t)dim, err);
    if (!rc)
        rc = key_of(path, sizeof path, "geometry", name, "box.max", err);
    return rc ? rc : spall_setup_numbers(s, path, max, (size_t)dim, err);
}

int spall_setup_circle(struct spall_setup *s, const char *name, int dim, const double *center,
                       double radius, struct spall_error *err)
{
    char path[SPALL_ERROR_KEY_LEN];
    const char *shape = dim == 3 ? "sphere" : "circle";
    char sub[32];
    int rc = check_dim(dim, "spall_setup_circle", err);
    snprintf(sub, sizeof sub, "%s.center", shape);
    if (!rc)
        rc = key_of(path, sizeof path, "geometry", name, sub, err);
    if (!rc)
        rc = spall_setup_numbers(s, path, center, (size_t)dim, err);
    snprintf(sub, sizeof sub, "%s.radius", shape);
    if (!rc)
        rc = key_of(path, sizeof path, "geometry", name, sub, err);
    return rc ? rc : spall_setup_number(s, path, radius, err);
}

int spall_setup_difference(struct spall_setup *s, const char *name, const char *a,
                           const char *b, struct spall_error *err)
{
    char path[SPALL_ERROR_KEY_LEN];
    const char *const list[2] = {a, b};
    int rc = key_of(path, sizeof path, "geometry", name, "difference", err);
    return rc ? rc : spall_setup_texts(s, path, list, 2, err);
}

int spall_setup_body(struct spall_setup *s, const char *geometry, const char *material,
                     struct spall_error *err)
{
    int rc = spall_setup_text(s, "body.geometry", geometry, err);
    return rc ? rc : spall_setup_text(s, "body.material", material, err);
}

int spall_setup_group_box(struct spall_setup *s, const char *name, int dim, const double *min,
                          const double *max, struct spall_error *err)
{
    char path[SPALL_ERROR_KEY_LEN];
    int rc = check_dim(dim, "spall_setup_group_box", err);
    if (!rc)
        rc = key_of(path, sizeof path, "groups", name, "box.min", err);
    if (!rc)
        rc = spall_setup_numbers(s, path, min, (size_t)dim, err);
    if (!rc)
        rc = key_of(path, sizeof path, "groups", name, "box.max", err);
    return rc ? rc : spall_setup_numbers(s, path, max, (size_t)dim, err);
}

int spall_setup_velocity_bc(struct spall_setup *s, const char *group, int dim,
                            const double *value, double ramp, struct spall_error *err)
{
    static const char *const axes[3] = {"x", "y", "z"};
    int rc = check_dim(dim, "spall_setup_velocity_bc", err);
    if (rc)
        return rc;
    size_t k = spall_setup_length(s, "boundary_conditions");
    char path[SPALL_ERROR_KEY_LEN];
#define BC_KEY(sub) snprintf(path, sizeof path, "boundary_conditions[%zu].%s", k, sub)
    BC_KEY("group");
    rc = spall_setup_text(s, path, group, err);
    BC_KEY("type");
    if (!rc)
        rc = spall_setup_text(s, path, "velocity", err);
    BC_KEY("components");
    if (!rc)
        rc = spall_setup_texts(s, path, axes, (size_t)dim, err);
    BC_KEY("value");
    if (!rc)
        rc = spall_setup_numbers(s, path, value, (size_t)dim, err);
    if (!rc && ramp > 0.0) {
        BC_KEY("function.type");
        rc = spall_setup_text(s, path, "linear_ramp", err);
        BC_KEY("function.duration");
        if (!rc)
            rc = spall_setup_number(s, path, ramp, err);
    }
#undef BC_KEY
    return rc;
}

int spall_setup_end_time(struct spall_setup *s, double end_time, struct spall_error *err)
{
    return spall_setup_number(s, "run.end_time", end_time, err);
}
