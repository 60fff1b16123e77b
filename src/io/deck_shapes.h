/**
 * @file deck_shapes.h
 * @brief Parse deck shapes into core/geometry objects.
 */
#ifndef SPALL_DECK_SHAPES_H
#define SPALL_DECK_SHAPES_H

struct deck_node;
struct geom;
struct spall_error;

/** Where named shapes live and the deck's dimension. */
struct deck_shape_ctx {
    const struct deck_node *geometry; /**< the `geometry:` mapping, may be NULL */
    int dim;
};

/** Shape from a node: a geometry name (scalar) or a shape mapping.  Errors
 *  name file:line:column. Name cycles are refused. */
int deck_parse_shape(const struct deck_shape_ctx *c, const struct deck_node *node,
                     struct geom **out, struct spall_error *err);
/** Shape held by key @p key of @p map (required). */
int deck_shape_at_key(const struct deck_shape_ctx *c, const struct deck_node *map, const char *key,
                      struct geom **out, struct spall_error *err);

#endif
