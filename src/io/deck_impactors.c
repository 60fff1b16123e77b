/**
 * @file deck_impactors.c
 * @brief `impactors:` — a list of rigid bodies (core/rigid.h):
 *
 *   impactors:
 *     - {name: tup, shape: round_nose, position: [x, y], radius: 6.35e-3,
 *        length: 0.05, axis: [0, -1], mass: 3.318, velocity: [0, -1.87],
 *        contact: no_slip}
 *
 * Every key is checked; errors name file:line:column.
 */
#include "io/deck_impactors.h"

#include "core/rigid.h"
#include "core/sim.h"
#include "io/deck.h"
#include "io/deck_time_function.h"
#include "spall/error.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

static int unit_vector(const struct deck_node *n, const char *key, int dim, double v[3],
                       struct spall_error *err)
{
    int rc = deck_vector(n, key, false, (size_t)dim, (size_t)dim, v, err);
    if (rc)
        return rc;
    double l = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    if (!(l > 0))
        return deck_error_key(err, n, key, "'%s' must be a non-zero vector", key);
    for (int d = 0; d < 3; d++)
        v[d] /= l;
    return SPALL_OK;
}

static int parse_one(struct sim *s, const struct deck_node *n, struct spall_error *err)
{
    static const char *const keys[] = {"name", "shape", "position", "radius", "length",
                                       "edge_radius", "nose_radius", "axis", "normal", "mass",
                                       "velocity", "motion", "function", "gravity", "contact",
                                       "stiffness_factor", "stiffness", "friction",
                                       "stiffness_dt", "contact_offset", NULL};
    static const char *const kdts[] = {"step", "first_contact", NULL};
    static const char *const shapes[] = {"sphere", "cylinder", "round_nose", "wall", "flat_punch",
                                         NULL};
    static const char *const motions[] = {"free", "prescribed", NULL};
    static const char *const contacts[] = {"no_slip", "penalty", NULL};
    const int dim = s->dim;
    struct impactor im;
    memset(&im, 0, sizeof im);
    const char *name = NULL;
    int shape = 0, motion = 0, contact = 1, kdt = 0;
    int rc;
    if ((rc = deck_expect_map(n, "an impactor mapping (name, shape, position, ...)", err)) ||
        (rc = deck_string(n, "name", true, &name, err)) ||
        (rc = deck_enum(n, "shape", true, shapes, &shape, err)))
        return rc;
    if (strlen(name) >= sizeof im.name)
        return deck_error_key(err, n, "name", "impactor name longer than %zu characters",
                              sizeof im.name - 1);
    snprintf(im.name, sizeof im.name, "%s", name);
    im.shape = shape == 4 ? RIGID_CYLINDER : (enum rigid_shape)shape;
    /* a wall is a fixed support unless told otherwise */
    motion = im.shape == RIGID_WALL ? 1 : 0;
    im.axis[dim - 1] = -1.0;
    im.gravity = true;
    im.stiffness_factor = 0.25;
    if ((rc = deck_vector(n, "position", true, (size_t)dim, (size_t)dim, im.x, err)) ||
        (rc = deck_enum(n, "motion", false, motions, &motion, err)) ||
        (rc = deck_enum(n, "contact", false, contacts, &contact, err)) ||
        (rc = deck_velocity(n, "velocity", false, (size_t)dim, im.v, err)) ||
        (rc = deck_bool(n, "gravity", false, &im.gravity, err)) ||
        (rc = deck_double(n, "stiffness_factor", false, 1e-6, 1.0, &im.stiffness_factor, err)) ||
        (rc = deck_double_pos(n, "stiffness", false, &im.stiffness, err)) ||
        (rc = deck_double(n, "friction", false, 0.0, INFINITY, &im.friction, err)) ||
        (rc = deck_enum(n, "stiffness_dt", false, kdts, &kdt, err)) ||
        (rc = deck_double(n, "contact_offset", false, 0.0, INFINITY, &im.contact_offset, err)))
        return rc;
    im.stiffness_frozen = kdt == 1;
    im.motion = (enum rigid_motion)motion;
    im.contact = (enum rigid_contact)contact;
    if (im.contact == RIGID_NO_SLIP && deck_peek(n, "friction"))
        return deck_error_key(err, n, "friction",
                              "friction applies to contact: penalty; no_slip has no tangential "
                              "motion at all ([Wang2010] sec. 3.2)");
    if (im.shape == RIGID_WALL) {
        if (deck_peek(n, "axis"))
            return deck_error_key(err, n, "axis", "a wall takes 'normal', not 'axis'");
        if (!deck_peek(n, "normal"))
            return deck_error(err, n, "missing required key 'normal' (outward, towards the "
                                      "body) for a wall");
        if ((rc = unit_vector(n, "normal", dim, im.axis, err)))
            return rc;
    } else {
        if (deck_peek(n, "normal"))
            return deck_error_key(err, n, "normal", "only a wall takes 'normal'; use 'axis'");
        if ((rc = deck_double_pos(n, "radius", true, &im.radius, err)))
            return rc;
        if (im.shape != RIGID_SPHERE) {
            im.length = 4.0 * im.radius;
            im.nose_radius = im.radius;
            if ((rc = unit_vector(n, "axis", dim, im.axis, err)) ||
                (rc = deck_double_pos(n, "length", false, &im.length, err)) ||
                (rc = deck_double(n, "edge_radius", false, 0.0, im.radius, &im.edge_radius, err)) ||
                (rc = deck_double(n, "nose_radius", false, im.radius, INFINITY, &im.nose_radius,
                                  err)))
                return rc;
            if (im.shape == RIGID_CYLINDER && deck_peek(n, "nose_radius"))
                return deck_error_key(err, n, "nose_radius", "nose_radius is for round_nose");
            if (im.shape == RIGID_ROUND_NOSE && deck_peek(n, "edge_radius"))
                return deck_error_key(err, n, "edge_radius", "edge_radius is for cylinder");
            if (2.0 * im.edge_radius > im.length)
                return deck_error_key(err, n, "edge_radius",
                                      "edge_radius %g exceeds half the length %g", im.edge_radius,
                                      im.length);
        }
    }
    if (im.motion == RIGID_FREE) {
        if ((rc = deck_double_pos(n, "mass", true, &im.mass, err)))
            return rc;
        if (deck_peek(n, "function"))
            return deck_error_key(err, n, "function", "'function' needs motion: prescribed");
    } else {
        if (deck_peek(n, "mass"))
            return deck_error_key(err, n, "mass",
                                  "a prescribed impactor has no mass (its motion is given)");
        memcpy(im.v0, im.v, sizeof im.v0);
        if ((rc = deck_build_time_function(n, &im.tf, err)))
            return rc;
    }
    if ((rc = deck_check_unused(n, "impactor", keys, err))) {
        time_function_free(&im.tf);
        return rc;
    }
    if ((rc = rigid_add(s, &im, err))) {
        time_function_free(&im.tf);
        if (rc == SPALL_ERR_INPUT) {
            char msg[sizeof err->msg];
            snprintf(msg, sizeof msg, "%s", err->msg);
            return deck_error_key(err, n, "name", "%s", msg);
        }
        return rc;
    }
    return SPALL_OK;
}

int deck_parse_impactors(struct sim *s, const struct deck_node *root, struct spall_error *err)
{
    const struct deck_node *list = NULL;
    int rc = deck_list(root, "impactors", "a list of impactors", &list, err);
    if (rc || !list)
        return rc;
    for (size_t k = 0; k < list->n; k++)
        if ((rc = parse_one(s, list->items[k], err)))
            return rc;
    return SPALL_OK;
}
