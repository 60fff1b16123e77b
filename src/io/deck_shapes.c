/**
 * @file deck_shapes.c
 * @brief Deck shapes: a name from the `geometry:` map or a mapping with one
 *        of box / rectangle, circle / sphere, cylinder, halfspace, polygon,
 *        union, intersection, difference (docs/decks.md, "Shapes").
 */
#include "io/deck_shapes.h"

#include "core/geometry.h"
#include "io/deck.h"
#include "spall/error.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define SHAPE_DEPTH_MAX 32

/* ---- shapes -------------------------------------------------------------- */

static int parse_shape(const struct deck_shape_ctx *c, const struct deck_node *node, int depth,
                       struct geom **out, struct spall_error *err);

static int parse_shape_list(const struct deck_shape_ctx *c, const struct deck_node *seq, int depth,
                            enum geom_kind kind, struct geom **out, struct spall_error *err)
{
    int rc = deck_expect_seq(seq, "a list of shapes (names or shape mappings)", err);
    if (rc)
        return rc;
    if (seq->n == 0 || (kind == GEOM_DIFFERENCE && seq->n < 2))
        return deck_error(err, seq, "a %s needs at least %d shapes",
                          kind == GEOM_DIFFERENCE ? "difference" : "combination",
                          kind == GEOM_DIFFERENCE ? 2 : 1);
    struct geom **kids = calloc(seq->n, sizeof *kids);
    if (!kids)
        return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory parsing shapes");
    for (size_t k = 0; k < seq->n; k++) {
        rc = parse_shape(c, seq->items[k], depth + 1, &kids[k], err);
        if (rc) {
            for (size_t q = 0; q < k; q++)
                geom_destroy(&kids[q]);
            free(kids);
            return rc;
        }
    }
    *out = geom_combine(kind, kids, seq->n);
    free(kids);
    if (!*out)
        return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory combining shapes");
    return SPALL_OK;
}

static int parse_primitive(const struct deck_shape_ctx *c, const char *kind, const struct deck_node *body,
                           struct geom **out, struct spall_error *err)
{
    int dim = c->dim;
    int rc;
    if (strcmp(kind, "box") == 0 || strcmp(kind, "rectangle") == 0) {
        static const char *const keys[] = {"min", "max", NULL};
        double lo[3] = {0}, hi[3] = {0};
        if ((rc = deck_expect_map(body, "a mapping with min and max", err)) ||
            (rc = deck_vector(body, "min", true, (size_t)dim, 3, lo, err)) ||
            (rc = deck_vector(body, "max", true, (size_t)dim, 3, hi, err)) ||
            (rc = deck_check_unused(body, kind, keys, err)))
            return rc;
        for (int d = 0; d < dim; d++)
            if (!(hi[d] > lo[d]))
                return deck_error_key(err, body, "max",
                                      "box max must exceed min in every direction; "
                                      "component %d has min %g, max %g",
                                      d, lo[d], hi[d]);
        if (dim < 3) {
            lo[2] = hi[2] = 0.0;
            if (dim < 2)
                lo[1] = hi[1] = 0.0;
        }
        *out = geom_box(lo, hi);
    } else if (strcmp(kind, "sphere") == 0 || strcmp(kind, "circle") == 0) {
        static const char *const keys[] = {"center", "radius", NULL};
        double ctr[3] = {0}, r = 0;
        if ((rc = deck_expect_map(body, "a mapping with center and radius", err)) ||
            (rc = deck_vector(body, "center", true, (size_t)dim, 3, ctr, err)) ||
            (rc = deck_double_pos(body, "radius", true, &r, err)) ||
            (rc = deck_check_unused(body, kind, keys, err)))
            return rc;
        *out = geom_sphere(ctr, r);
    } else if (strcmp(kind, "cylinder") == 0) {
        static const char *const keys[] = {"base", "top", "center", "radius", NULL};
        double p0[3] = {0}, p1[3] = {0}, r = 0;
        if ((rc = deck_expect_map(body, "a mapping with base, top and radius", err)) ||
            (rc = deck_double_pos(body, "radius", true, &r, err)))
            return rc;
        if (dim == 3) {
            if ((rc = deck_vector(body, "base", true, 3, 3, p0, err)) ||
                (rc = deck_vector(body, "top", true, 3, 3, p1, err)))
                return rc;
            double l2 = 0;
            for (int d = 0; d < 3; d++)
                l2 += (p1[d] - p0[d]) * (p1[d] - p0[d]);
            if (!(l2 > 0))
                return deck_error_key(err, body, "top", "cylinder top equals its base");
        } else {
            if ((rc = deck_vector(body, "center", true, (size_t)dim, 3, p0, err)))
                return rc;
            memcpy(p1, p0, sizeof p1);
            p1[2] = 1.0;
        }
        if ((rc = deck_check_unused(body, kind, keys, err)))
            return rc;
        *out = geom_cylinder(p0, p1, r);
    } else if (strcmp(kind, "halfspace") == 0) {
        static const char *const keys[] = {"point", "normal", NULL};
        double pt[3] = {0}, nrm[3] = {0};
        if ((rc = deck_expect_map(body, "a mapping with point and normal", err)) ||
            (rc = deck_vector(body, "point", true, (size_t)dim, 3, pt, err)) ||
            (rc = deck_vector(body, "normal", true, (size_t)dim, 3, nrm, err)) ||
            (rc = deck_check_unused(body, kind, keys, err)))
            return rc;
        if (nrm[0] == 0 && nrm[1] == 0 && nrm[2] == 0)
            return deck_error_key(err, body, "normal", "half-space normal must not be zero");
        *out = geom_halfspace(pt, nrm);
    } else if (strcmp(kind, "polygon") == 0) {
        static const char *const keys[] = {"points", NULL};
        if ((rc = deck_expect_map(body, "a mapping with points", err)))
            return rc;
        if (dim != 2)
            return deck_error(err, body, "polygon is a 2D shape; this deck is %dD", dim);
        const struct deck_node *pts = deck_get(body, "points");
        if (!pts)
            return deck_error(err, body, "missing required key 'points' in polygon");
        if ((rc = deck_expect_seq(pts, "a list of [x, y] points", err)))
            return rc;
        if (pts->n < 3)
            return deck_error(err, pts, "a polygon needs at least 3 points (got %zu)", pts->n);
        double *xy = malloc(2 * pts->n * sizeof *xy);
        if (!xy)
            return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory reading polygon");
        for (size_t k = 0; k < pts->n; k++) {
            const struct deck_node *pt = pts->items[k];
            if (pt->kind != DECK_SEQUENCE || pt->n != 2) {
                free(xy);
                return deck_error(err, pt, "polygon point must be [x, y]");
            }
            if ((rc = deck_node_double(pt->items[0], &xy[2 * k], err)) ||
                (rc = deck_node_double(pt->items[1], &xy[2 * k + 1], err))) {
                free(xy);
                return rc;
            }
        }
        if ((rc = deck_check_unused(body, kind, keys, err))) {
            free(xy);
            return rc;
        }
        *out = geom_polygon(xy, pts->n);
        free(xy);
    } else {
        return SPALL_ERR_INTERNAL;
    }
    if (!*out)
        return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory creating shape");
    return SPALL_OK;
}

static int parse_shape(const struct deck_shape_ctx *c, const struct deck_node *node, int depth,
                       struct geom **out, struct spall_error *err)
{
    *out = NULL;
    if (depth > SHAPE_DEPTH_MAX)
        return deck_error(err, node, "shape references nest deeper than %d (a cycle?)",
                          SHAPE_DEPTH_MAX);
    if (node->kind == DECK_SCALAR) {
        const struct deck_node *named = c->geometry ? deck_peek(c->geometry, node->scalar) : NULL;
        if (!named)
            return deck_error(err, node, "unknown geometry '%.64s'; define it under 'geometry:'",
                              node->scalar);
        return parse_shape(c, named, depth + 1, out, err);
    }
    if (node->kind != DECK_MAPPING || node->n != 1)
        return deck_error(err, node,
                          "a shape must be a geometry name or a mapping with exactly one of: "
                          "box, circle, sphere, cylinder, halfspace, polygon, union, "
                          "intersection, difference");
    const char *kind = node->keys[0];
    const struct deck_node *body = deck_get(node, kind);
    if (strcmp(kind, "union") == 0)
        return parse_shape_list(c, body, depth, GEOM_UNION, out, err);
    if (strcmp(kind, "intersection") == 0)
        return parse_shape_list(c, body, depth, GEOM_INTERSECTION, out, err);
    if (strcmp(kind, "difference") == 0)
        return parse_shape_list(c, body, depth, GEOM_DIFFERENCE, out, err);
    static const char *const prims[] = {"box", "rectangle", "circle", "sphere", "cylinder",
                                        "halfspace", "polygon", NULL};
    for (const char *const *k = prims; *k; k++)
        if (strcmp(kind, *k) == 0)
            return parse_primitive(c, kind, body, out, err);
    return deck_error_key(err, node, kind,
                          "unknown shape '%.64s'; expected one of: box, rectangle, circle, sphere, "
                          "cylinder, halfspace, polygon, union, intersection, difference",
                          kind);
}

int deck_shape_at_key(const struct deck_shape_ctx *c, const struct deck_node *map, const char *key,
                      struct geom **out, struct spall_error *err)
{
    const struct deck_node *n = deck_get(map, key);
    if (!n)
        return deck_error(err, map, "missing required key '%s'", key);
    return parse_shape(c, n, 0, out, err);
}

int deck_parse_shape(const struct deck_shape_ctx *c, const struct deck_node *node,
                     struct geom **out, struct spall_error *err)
{
    return parse_shape(c, node, 0, out, err);
}

