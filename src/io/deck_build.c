/**
 * @file deck_build.c
 * @brief Deck -> simulation.  Reads the sections in dependency order
 *        (lattice, model, materials, geometry, body, regions, groups,
 *        pre-cracks, loads, probes, run, output); every mapping is checked
 *        for unknown keys; every error names file:line:column.
 */
#include "core/mathconst.h"
#include "io/deck_build.h"
#include "io/setup_check_sim.h"
#include "io/deck_shapes.h"

#include "core/geometry.h"
#include "core/lattice_gen.h"
#include "core/lattice_polar.h"
#include "core/particles.h"
#include "core/sim.h"
#include "io/deck.h"
#include "io/deck_contact.h"
#include "io/deck_impactors.h"
#include "io/deck_inclusions.h"
#include "io/deck_setup_dist.h"
#include "core/parallel/setup_dist.h"
#include "io/deck_time_function.h"
#include "io/output.h"
#include "io/run_balance.h"
#include "core/model.h"
#include "models/registry.h"
#include "spall/error.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define DEG_TO_RAD (SPALL_PI / 180.0)

static const char *const top_keys[] = {"title", "description", "model", "materials", "geometry",
                                       "lattice", "body", "bodies", "regions", "precracks", "groups",
                                       "boundary_conditions", "initial_velocity", "gravity",
                                       "damping", "probes", "run", "output", "parallel",
                                       /* impact (issue 3) keys */
                                       "impactors", "contact",

                                       /* other section keys */
                                       "inclusions",
                                       NULL};

struct build_ctx {
    const struct deck *deck;
    const struct deck_node *geometry; /* the `geometry:` mapping, may be NULL */
    struct sim *sim;
    int dim;
};

/* Shapes are parsed by io/deck_shapes.c against the deck's `geometry:` map. */
static int parse_shape(struct build_ctx *c, const struct deck_node *node, int depth,
                       struct geom **out, struct spall_error *err)
{
    (void)depth;
    const struct deck_shape_ctx sc = {c->geometry, c->dim};
    return deck_parse_shape(&sc, node, out, err);
}

static int shape_at_key(struct build_ctx *c, const struct deck_node *map, const char *key,
                        struct geom **out, struct spall_error *err)
{
    const struct deck_shape_ctx sc = {c->geometry, c->dim};
    return deck_shape_at_key(&sc, map, key, out, err);
}

/* Indices of particles whose reference position lies in @p g. */
static int select_particles(const struct sim *s, const struct geom *g, size_t **idx, size_t *n,
                            struct spall_error *err)
{
    const struct particles *p = s->p;
    *idx = malloc((p->n ? p->n : 1) * sizeof **idx);
    if (!*idx)
        return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory selecting particles");
    *n = 0;
    for (size_t i = 0; i < p->n_owned; i++) {
        double x[3] = {0, 0, 0};
        for (int d = 0; d < s->dim; d++)
            x[d] = p->x0[d][i];
        if (geom_contains(g, x, s->dim))
            (*idx)[(*n)++] = i;
    }
    return SPALL_OK;
}

/* ---- sections ------------------------------------------------------------ */

static int parse_lattice(struct build_ctx *c, const struct deck_node *root, struct spall_error *err)
{
    static const char *const keys[] = {"type", "spacing", "origin", "angle", "thickness", NULL};
    const struct deck_node *lat = deck_get(root, "lattice");
    if (!lat)
        return deck_error(err, root, "missing required key 'lattice' (the particle lattice)");
    int rc = deck_expect_map(lat, "the lattice mapping (type, spacing, ...)", err);
    if (rc)
        return rc;
    int kind = 0;
    double spacing = 0, origin[3] = {0, 0, 0}, angle_deg = 0, thickness = 0;
    if ((rc = deck_enum(lat, "type", true, lattice_kind_names(), &kind, err)) ||
        (rc = deck_double_pos(lat, "spacing", true, &spacing, err)) ||
        (rc = deck_vector(lat, "origin", false, 1, 3, origin, err)) ||
        (rc = deck_double(lat, "angle", false, -360.0, 360.0, &angle_deg, err)) ||
        (rc = deck_double_pos(lat, "thickness", false, &thickness, err)) ||
        (rc = deck_check_unused(lat, "lattice", keys, err)))
        return rc;
    enum lattice_kind lk = (enum lattice_kind)kind; /* deck_enum index = enum order */
    c->dim = lattice_kind_dim(lk);
    rc = sim_create(&c->sim, c->dim, err);
    if (rc)
        return rc;
    struct sim *s = c->sim;
    s->lattice.kind = lk;
    s->lattice.spacing = spacing;
    memcpy(s->lattice.origin, origin, sizeof origin);
    s->lattice.angle = angle_deg * DEG_TO_RAD;
    s->thickness_given = thickness > 0.0;
    if (s->thickness_given) {
        s->thickness = thickness;
    } else if (lk == LATTICE_TRIANGULAR || lk == LATTICE_TRIPLE_HONEYCOMB) {
        /* [Wang2010]: the constants of Eqs. 16/18 correspond to a volume r0^3 per
         * particle, i.e. a plate 2 r0 / sqrt(3) thick */
        s->thickness = 2.0 * spacing / sqrt(3.0);
    } else if (lk == LATTICE_CHAIN) {
        s->thickness = spacing * spacing; /* cross-section r0^2: volume r0^3 */
    } else {
        s->thickness = spacing;
    }
    return SPALL_OK;
}

static int parse_model(struct build_ctx *c, const struct deck_node *root, struct spall_error *err)
{
    const struct deck_node *m = deck_get(root, "model");
    if (!m)
        return deck_error(err, root, "missing required key 'model'");
    int rc = deck_expect_map(m, "the model mapping (type and parameters)", err);
    if (rc)
        return rc;
    int idx = 0;
    if ((rc = deck_enum(m, "type", true, model_names(), &idx, err)))
        return rc;
    const struct model_ops *ops = model_find(model_names()[idx]);
    if (lattice_kind_is_polar(c->sim->lattice.kind) && ops && !ops->particle_volumes)
        return deck_error_key(err, deck_peek(root, "lattice"), "type",
                              "lattice type '%s' needs a model that takes each particle's own "
                              "volume (sph); the %s model needs a regular lattice",
                              lattice_kind_name(c->sim->lattice.kind), ops->name);
    return sim_set_model(c->sim, ops, m, err);
}

static int parse_materials(struct build_ctx *c, const struct deck_node *root,
                           struct spall_error *err)
{
    const struct deck_node *mats = deck_get(root, "materials");
    if (!mats)
        return deck_error(err, root, "missing required key 'materials'");
    int rc = deck_expect_map(mats, "a mapping of material names to properties", err);
    if (rc)
        return rc;
    if (mats->n == 0)
        return deck_error(err, mats, "no material defined");
    for (size_t k = 0; k < mats->n; k++) {
        const struct deck_node *mn = mats->items[k];
        mats->used[k] = true;
        if ((rc = deck_expect_map(mn, "a mapping of material properties", err)))
            return rc;
        double rho = 0;
        if ((rc = deck_double_pos(mn, "density", true, &rho, err)))
            return rc;
        int index = 0;
        if ((rc = sim_add_material(c->sim, mats->keys[k], rho, &index, err)))
            return deck_error_key(err, mats, mats->keys[k], "%s", err->msg);
        if ((rc = c->sim->ops->parse_material(c->sim->model, c->sim, index, mn, err)))
            return rc;
    }
    return SPALL_OK;
}

static int material_at_key(struct build_ctx *c, const struct deck_node *map, const char *key,
                           int *index, struct spall_error *err)
{
    const char *name = NULL;
    int rc = deck_string(map, key, true, &name, err);
    if (rc)
        return rc;
    *index = sim_find_material(c->sim, name);
    if (*index < 0)
        return deck_error(err, deck_peek(map, key), "unknown material '%.64s'; define it under 'materials:'",
                          name);
    return SPALL_OK;
}

/* Fill one body: every site of @p spec inside its shape becomes a particle
 * with the body's material and the site volume of @p spec. */
static int fill_body(struct build_ctx *c, const struct deck_node *body,
                     const struct lattice_spec *spec, const char *what, int32_t body_id,
                     struct spall_error *err)
{
    static const char *const keys[] = {"geometry", "material", "lattice", "name", NULL};
    int rc = deck_expect_map(body, "a mapping with geometry and material", err);
    if (rc)
        return rc;
    int mat = 0;
    struct geom *g = NULL;
    const char *name = NULL; /* a label other sections use (model.body_formulation) */
    if ((rc = deck_string(body, "name", false, &name, err)) ||
        (rc = material_at_key(c, body, "material", &mat, err)) ||
        (rc = shape_at_key(c, body, "geometry", &g, err)) ||
        (rc = deck_check_unused(body, what, keys, err))) {
        geom_destroy(&g);
        return rc;
    }
    const struct model_ops *ops = c->sim->ops;
    /* (a polar deck lattice in such a model was refused with the model) */
    if (spec->kind != c->sim->lattice.kind && !(ops && ops->particle_volumes)) {
        geom_destroy(&g);
        return deck_error(err, deck_peek(body, "lattice") ? deck_peek(body, "lattice") : body,
                          "%s: lattice type '%s' needs a model that takes each particle's own "
                          "volume (sph); the %s model uses the deck's lattice '%s' everywhere",
                          what, lattice_kind_name(spec->kind), ops ? ops->name : "?",
                          lattice_kind_name(c->sim->lattice.kind));
    }
    size_t first = c->sim->p->n, added = 0;
    rc = c->sim->setup ? deck_setup_dist_fill(c->sim, spec, g, mat, &added, err)
                       : lattice_fill(c->sim->p, spec, g, mat, &added, err);
    geom_destroy(&g);
    if (rc) {
        const struct deck_node *gn = deck_peek(body, "geometry");
        char msg[SPALL_ERROR_MSG_LEN];
        snprintf(msg, sizeof msg, "%s", err->msg);
        if (gn && gn->kind == DECK_SCALAR)
            return deck_error_key(err, body, "geometry", "%s: geometry '%s' %s", what, gn->scalar,
                                  msg);
        return deck_error_key(err, body, "geometry", "%s: the geometry %s", what, msg);
    }
    struct particles *p = c->sim->p;
    for (size_t i = first; i < first + added; i++) {
        double pos[3] = {p->x[0][i], p->dim > 1 ? p->x[1][i] : 0.0, p->dim > 2 ? p->x[2][i] : 0.0};
        p->volume[i] = lattice_site_volume_at(spec, pos, c->sim->thickness);
        p->mass[i] = c->sim->materials[mat].density * p->volume[i];
        p->body[i] = body_id;
    }
    return SPALL_OK;
}

/* `body: {geometry, material}` or `bodies: [{geometry, material, lattice:
 * {spacing, origin, angle}}, ...]` — several bodies, each optionally on its
 * own spacing (graded resolution, projectile and target).  Bodies must not
 * overlap. */
static int parse_body(struct build_ctx *c, const struct deck_node *root, struct spall_error *err)
{
    const struct deck_node *body = deck_get(root, "body");
    const struct deck_node *bodies = deck_get(root, "bodies");
    if (body && bodies)
        return deck_error_key(err, root, "bodies", "give either 'body' or 'bodies', not both");
    if (body)
        return fill_body(c, body, &c->sim->lattice, "body", 0, err);
    if (!bodies)
        return deck_error(err, root, "missing required key 'body' (geometry and material to fill)");
    int rc = deck_expect_seq(bodies, "a list of bodies {geometry, material, lattice}", err);
    if (rc)
        return rc;
    if (bodies->n == 0)
        return deck_error(err, bodies, "'bodies' is empty; expected at least one body");
    for (size_t k = 0; k < bodies->n; k++) {
        const struct deck_node *b = bodies->items[k];
        struct lattice_spec spec = c->sim->lattice;
        const struct deck_node *ln = deck_peek(b, "lattice");
        if (ln) {
            static const char *const keys[] = {"type", "spacing", "origin", "angle", NULL};
            double angle_deg = spec.angle / DEG_TO_RAD;
            int kind = (int)spec.kind;
            (void)deck_get(b, "lattice");
            if ((rc = deck_expect_map(ln, "a mapping with type, spacing, origin, angle", err)) ||
                (rc = deck_enum(ln, "type", false, lattice_kind_names(), &kind, err)) ||
                (rc = deck_double_pos(ln, "spacing", false, &spec.spacing, err)) ||
                (rc = deck_vector(ln, "origin", false, 1, 3, spec.origin, err)) ||
                (rc = deck_double(ln, "angle", false, -360.0, 360.0, &angle_deg, err)) ||
                (rc = deck_check_unused(ln, "bodies[].lattice", keys, err)))
                return rc;
            spec.angle = angle_deg * DEG_TO_RAD;
            spec.kind = (enum lattice_kind)kind;
            if (lattice_kind_dim(spec.kind) != c->dim)
                return deck_error_key(err, ln, "type",
                                      "lattice type '%s' is %dD; expected a %dD type like the "
                                      "deck's lattice '%s'",
                                      lattice_kind_name(spec.kind), lattice_kind_dim(spec.kind),
                                      c->dim, lattice_kind_name(c->sim->lattice.kind));
        }
        char what[32];
        snprintf(what, sizeof what, "bodies[%zu]", k);
        if ((rc = fill_body(c, b, &spec, what, (int32_t)k, err)))
            return rc;
    }
    return SPALL_OK;
}

static int parse_regions(struct build_ctx *c, const struct deck_node *root, struct spall_error *err)
{
    static const char *const keys[] = {"geometry", "material", NULL};
    const struct deck_node *regs = NULL;
    int rc = deck_list(root, "regions", "a list of {geometry, material}", &regs, err);
    if (rc || !regs)
        return rc;
    for (size_t k = 0; k < regs->n; k++) {
        const struct deck_node *r = regs->items[k];
        int mat = 0;
        struct geom *g = NULL;
        size_t *idx = NULL, n = 0;
        if ((rc = deck_expect_map(r, "a mapping with geometry and material", err)) ||
            (rc = material_at_key(c, r, "material", &mat, err)) ||
            (rc = shape_at_key(c, r, "geometry", &g, err)) ||
            (rc = deck_check_unused(r, "region", keys, err)) ||
            (rc = select_particles(c->sim, g, &idx, &n, err))) {
            geom_destroy(&g);
            free(idx);
            return rc;
        }
        geom_destroy(&g);
        size_t in_body = 0;
        if ((rc = deck_setup_dist_count(c->sim, idx, n, &in_body, err)) || in_body == 0) {
            free(idx);
            return rc ? rc : deck_error(err, r, "region contains no particle of the body");
        }
        for (size_t q = 0; q < n; q++)
            c->sim->p->material[idx[q]] = mat;
        free(idx);
    }
    return SPALL_OK;
}

/* Mass = density of the (possibly re-assigned) material x site volume. */
static void assign_masses(struct sim *s)
{
    for (size_t i = 0; i < s->p->n; i++)
        s->p->mass[i] = s->materials[s->p->material[i]].density * s->p->volume[i];
}

/* The predefined group 'all' is created only when a deck refers to it: its
 * index array would otherwise cost 8 bytes per particle for nothing. */
static int ensure_group_all(struct sim *s, struct spall_error *err)
{
    if (sim_find_group(s, "all") >= 0)
        return SPALL_OK;
    size_t *all = malloc((s->p->n ? s->p->n : 1) * sizeof *all);
    if (!all)
        return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory creating group 'all'");
    for (size_t i = 0; i < s->p->n; i++)
        all[i] = i;
    int rc = sim_add_group(s, "all", all, s->p->n, NULL, err);
    free(all);
    return rc;
}

static int parse_groups(struct build_ctx *c, const struct deck_node *root, struct spall_error *err)
{
    int rc;
    const struct deck_node *gs = deck_get(root, "groups");
    if (!gs)
        return SPALL_OK;
    if ((rc = deck_expect_map(gs, "a mapping of group names to shapes", err)))
        return rc;
    for (size_t k = 0; k < gs->n; k++) {
        gs->used[k] = true;
        if (strcmp(gs->keys[k], "all") == 0)
            return deck_error_key(err, gs, "all", "group name 'all' is reserved (every particle)");
        struct geom *g = NULL;
        size_t *idx = NULL, n = 0;
        if ((rc = parse_shape(c, gs->items[k], 0, &g, err)) ||
            (rc = select_particles(c->sim, g, &idx, &n, err))) {
            geom_destroy(&g);
            free(idx);
            return rc;
        }
        char why[300] = ""; /* the likely cause: a region thinner than the spacing */
        size_t in_body = 0; /* the whole body's */
        if ((rc = deck_setup_dist_count(c->sim, idx, n, &in_body, err))) {
            geom_destroy(&g);
            free(idx);
            return rc;
        }
        const bool empty = in_body == 0;
        if (empty)
            setup_empty_group_hint(c->sim, g, why, sizeof why);
        geom_destroy(&g);
        if (empty) {
            free(idx);
            return deck_error_key(err, gs, gs->keys[k],
                                  "group '%s' contains no particle; %s", gs->keys[k],
                                  why[0] ? why : "check its geometry against the body");
        }
        rc = sim_add_group(c->sim, gs->keys[k], idx, n, NULL, err);
        free(idx);
        if (rc)
            return deck_error_key(err, gs, gs->keys[k], "%s", err->msg);
    }
    return SPALL_OK;
}

static int group_at_key(struct build_ctx *c, const struct deck_node *map, const char *key,
                        int *g, struct spall_error *err)
{
    const char *name = NULL;
    int rc = deck_string(map, key, true, &name, err);
    if (rc)
        return rc;
    if (strcmp(name, "all") == 0 && (rc = ensure_group_all(c->sim, err)))
        return rc;
    *g = sim_find_group(c->sim, name);
    if (*g < 0)
        return deck_error(err, deck_peek(map, key),
                          "unknown group '%.64s'; define it under 'groups:' (or use 'all')", name);
    return SPALL_OK;
}

static int parse_precracks(struct build_ctx *c, const struct deck_node *root,
                           struct spall_error *err)
{
    const struct deck_node *pcs = NULL;
    int rc = deck_list(root, "precracks", "a list of pre-cracks", &pcs, err);
    if (rc || !pcs)
        return rc;
    for (size_t k = 0; k < pcs->n; k++) {
        const struct deck_node *n = pcs->items[k];
        struct precrack pc;
        memset(&pc, 0, sizeof pc);
        pc.dim = c->dim;
        if ((rc = deck_expect_map(n, "a pre-crack mapping", err)))
            return rc;
        if (c->dim == 2) {
            static const char *const keys[] = {"from", "to", NULL};
            if ((rc = deck_vector(n, "from", true, 2, 2, pc.a, err)) ||
                (rc = deck_vector(n, "to", true, 2, 2, pc.b, err)) ||
                (rc = deck_check_unused(n, "precrack (2D: from, to)", keys, err)))
                return rc;
        } else if (c->dim == 3) {
            static const char *const keys[] = {"origin", "edge1", "edge2", NULL};
            if ((rc = deck_vector(n, "origin", true, 3, 3, pc.origin, err)) ||
                (rc = deck_vector(n, "edge1", true, 3, 3, pc.e1, err)) ||
                (rc = deck_vector(n, "edge2", true, 3, 3, pc.e2, err)) ||
                (rc = deck_check_unused(n, "precrack (3D: origin, edge1, edge2)", keys, err)))
                return rc;
        } else {
            return deck_error(err, n, "pre-cracks need a 2D or 3D lattice");
        }
        if ((rc = sim_add_precrack(c->sim, &pc, err)))
            return rc;
    }
    return SPALL_OK;
}

static int parse_components(const struct deck_node *map, int dim, unsigned *mask,
                            struct spall_error *err)
{
    const struct deck_node *cn = deck_get(map, "components");
    *mask = (1u << dim) - 1u;
    if (!cn)
        return SPALL_OK;
    const struct deck_node *single[1] = {cn};
    const struct deck_node *const *items = single;
    size_t n = 1;
    if (cn->kind == DECK_SEQUENCE) {
        items = (const struct deck_node *const *)cn->items;
        n = cn->n;
    }
    if (n == 0)
        return deck_error(err, cn, "components must not be empty; expected x, y, z or all");
    *mask = 0;
    for (size_t k = 0; k < n; k++) {
        const struct deck_node *it = items[k];
        if (it->kind != DECK_SCALAR)
            return deck_error(err, it, "expected a component name: x, y, z or all");
        const char *s = it->scalar;
        int d = -1;
        if (strcmp(s, "all") == 0) {
            *mask = (1u << dim) - 1u;
            continue;
        }
        if (strcmp(s, "x") == 0)
            d = 0;
        else if (strcmp(s, "y") == 0)
            d = 1;
        else if (strcmp(s, "z") == 0)
            d = 2;
        if (d < 0 || d >= dim)
            return deck_error(err, it, "component '%s' is not valid in %dD; expected %s", s, dim,
                              dim == 1 ? "x" : dim == 2 ? "x, y or all" : "x, y, z or all");
        *mask |= 1u << d;
    }
    return SPALL_OK;
}

/* value: a number (applied to every listed component) or a vector of dim */
static int parse_bc_value(const struct deck_node *map, int dim, unsigned mask, double v[3],
                          struct spall_error *err)
{
    const struct deck_node *vn = deck_peek(map, "value");
    if (!vn)
        return deck_error(err, map, "missing required key 'value'");
    if (vn->kind == DECK_SCALAR) {
        double x = 0;
        int rc = deck_double(map, "value", true, -INFINITY, INFINITY, &x, err);
        if (rc)
            return rc;
        for (int d = 0; d < dim; d++)
            v[d] = (mask & (1u << d)) ? x : 0.0;
        return SPALL_OK;
    }
    return deck_vector(map, "value", true, (size_t)dim, (size_t)dim, v, err);
}

static int parse_bcs(struct build_ctx *c, const struct deck_node *root, struct spall_error *err)
{
    static const char *const kinds[] = {"fixed", "velocity", "force", "traction", NULL};
    static const char *const keys[] = {"group", "type", "components", "value", "area", "function",
                                       NULL};
    const struct deck_node *bcs = NULL;
    int rc = deck_list(root, "boundary_conditions", "a list of boundary conditions", &bcs, err);
    if (rc || !bcs)
        return rc;
    for (size_t k = 0; k < bcs->n; k++) {
        const struct deck_node *n = bcs->items[k];
        struct bc b;
        memset(&b, 0, sizeof b);
        int kind = 0;
        if ((rc = deck_expect_map(n, "a boundary-condition mapping", err)) ||
            (rc = group_at_key(c, n, "group", &b.group, err)) ||
            (rc = deck_enum(n, "type", true, kinds, &kind, err)) ||
            (rc = parse_components(n, c->dim, &b.comp_mask, err)))
            return rc;
        b.kind = (enum bc_kind)kind;
        if (b.kind != BC_FIXED && (rc = parse_bc_value(n, c->dim, b.comp_mask, b.value, err)))
            return rc;
        if (b.kind == BC_TRACTION) {
            const struct group *g = &c->sim->groups[b.group];
            /* default loaded area: each boundary particle carries the
             * cross-section of its lattice cell, volume / spacing */
            size_t in_body = 0;
            if ((rc = deck_setup_dist_count(c->sim, g->idx, g->n, &in_body, err)))
                return rc;
            b.area = (double)in_body * lattice_site_volume(&c->sim->lattice, c->sim->thickness) /
                     c->sim->lattice.spacing;
            if ((rc = deck_double_pos(n, "area", false, &b.area, err)))
                return rc;
        }
        if ((rc = deck_build_time_function(n, &b.tf, err)))
            return rc;
        if ((rc = deck_check_unused(n, "boundary condition", keys, err)) ||
            (rc = sim_add_bc(c->sim, &b, err))) {
            time_function_free(&b.tf);
            return rc;
        }
    }
    return SPALL_OK;
}

static int parse_initial_velocity(struct build_ctx *c, const struct deck_node *root,
                                  struct spall_error *err)
{
    static const char *const keys[] = {"group", "value", NULL};
    const struct deck_node *ivs = NULL;
    int rc = deck_list(root, "initial_velocity", "a list of {group, value}", &ivs, err);
    if (rc || !ivs)
        return rc;
    for (size_t k = 0; k < ivs->n; k++) {
        const struct deck_node *n = ivs->items[k];
        int g = 0;
        double v[3] = {0, 0, 0};
        if ((rc = deck_expect_map(n, "a mapping with group and value", err)) ||
            (rc = group_at_key(c, n, "group", &g, err)) ||
            (rc = deck_velocity(n, "value", true, (size_t)c->dim, v, err)) ||
            (rc = deck_check_unused(n, "initial_velocity", keys, err)))
            return rc;
        const struct group *gr = &c->sim->groups[g];
        for (size_t q = 0; q < gr->n; q++)
            for (int d = 0; d < c->dim; d++)
                c->sim->p->v[d][gr->idx[q]] = v[d];
    }
    return SPALL_OK;
}

static int parse_probes(struct build_ctx *c, const struct deck_node *root, struct spall_error *err)
{
    static const char *const keys[] = {"name", "position", NULL};
    const struct deck_node *ps = NULL;
    int rc = deck_list(root, "probes", "a list of {name, position}", &ps, err);
    if (rc || !ps)
        return rc;
    for (size_t k = 0; k < ps->n; k++) {
        const struct deck_node *n = ps->items[k];
        const char *name = NULL;
        double pos[3] = {0, 0, 0};
        if ((rc = deck_expect_map(n, "a probe mapping", err)) ||
            (rc = deck_string(n, "name", true, &name, err)) ||
            (rc = deck_vector(n, "position", true, (size_t)c->dim, 3, pos, err)) ||
            (rc = deck_check_unused(n, "probe", keys, err)))
            return rc;
        for (size_t q = 0; q < c->sim->n_probes; q++)
            if (strcmp(c->sim->probes[q].name, name) == 0)
                return deck_error_key(err, n, "name", "probe '%s' defined twice", name);
        if (strlen(name) >= SPALL_NAME_LEN)
            return deck_error_key(err, n, "name", "probe name longer than %d characters",
                                  SPALL_NAME_LEN - 1);
        if ((rc = sim_add_probe(c->sim, name, pos, err)))
            return rc;
        if (c->sim->setup && (rc = par_setup_probe(c->sim, c->sim->n_probes - 1, err)))
            return rc;
    }
    return SPALL_OK;
}

/* run.max_particles, read before the bodies are filled (lattice_fill refuses more). */
static int parse_max_particles(struct build_ctx *c, const struct deck_node *root,
                               struct spall_error *err)
{
    const struct deck_node *r = deck_peek(root, "run");
    long max = (long)SPALL_MAX_PARTICLES_DEFAULT;
    int rc = r && r->kind == DECK_MAPPING ? deck_long(r, "max_particles", false, 1,
                                                      (long)SPALL_MAX_PARTICLES_LIMIT, &max, err)
                                          : SPALL_OK;
    c->sim->p->max_n = (size_t)max;
    return rc;
}

static int parse_run(struct build_ctx *c, const struct deck_node *root, struct run_output *ro,
                     struct spall_error *err)
{
    static const char *const keys[] = {"end_time", "steps", "dt", "dt_factor", "dt_override",
                                       "threads", "energy_blowup", "seed", "max_particles", "allow",
                                       NULL};
    const struct deck_node *r = deck_get(root, "run");
    if (!r)
        return deck_error(err, root, "missing required key 'run' (end_time or steps)");
    struct sim *s = c->sim;
    long threads = 0, seed = 12345;
    int rc;
    if ((rc = deck_expect_map(r, "the run mapping", err)) ||
        (rc = deck_double_pos(r, "end_time", false, &s->end_time, err)) ||
        (rc = deck_long(r, "steps", false, 1, 2000000000L, &s->n_steps, err)) ||
        (rc = deck_double_pos(r, "dt", false, &s->dt, err)) ||
        (rc = deck_double(r, "dt_factor", false, 1e-6, 1.0, &s->dt_factor, err)) ||
        (rc = deck_bool(r, "dt_override", false, &s->dt_override, err)) ||
        (rc = deck_long(r, "threads", false, 0, 4096, &threads, err)) ||
        (rc = deck_double(r, "energy_blowup", false, 1.0, INFINITY, &s->energy_blowup, err)) ||
        (rc = deck_long(r, "seed", false, 0, 2147483647L, &seed, err)) ||
        (rc = deck_check_unused(r, "run", keys, err)))
        return rc;
    if (!deck_peek(r, "end_time") && !deck_peek(r, "steps"))
        return deck_error(err, r, "run needs 'end_time' (s) or 'steps'");
    if (deck_peek(r, "end_time") && deck_peek(r, "steps"))
        return deck_error(err, r, "give either 'end_time' or 'steps' in run, not both");
    s->seed = (uint64_t)seed;
    ro->threads = (int)threads;
    return SPALL_OK;
}

static int parse_output(struct build_ctx *c, const struct deck_node *root, struct run_output *ro,
                        struct spall_error *err)
{
    static const char *const keys[] = {"fields", "field_interval", "field_every",
                                       "history_every", "checkpoint", NULL};
    (void)c;
    ro->history_every = 0;
    const struct deck_node *o = deck_get(root, "output");
    if (!o)
        return SPALL_OK;
    int rc;
    if ((rc = deck_expect_map(o, "the output mapping", err)) ||
        (rc = deck_double_pos(o, "field_interval", false, &ro->field_interval, err)) ||
        (rc = deck_long(o, "field_every", false, 0, 2000000000L, &ro->field_every, err)) ||
        (rc = deck_long(o, "history_every", false, 1, 2000000000L, &ro->history_every, err)) ||
        (rc = checkpoint_parse_options(o, &ro->checkpoint, err)))
        return rc;
    const struct deck_node *f = NULL;
    if ((rc = deck_list(o, "fields", "a list of field names", &f, err)))
        return rc;
    if (f) {
        if (f->n > RUN_MAX_FIELDS)
            return deck_error(err, f, "at most %d output fields", RUN_MAX_FIELDS);
        for (size_t k = 0; k < f->n; k++) {
            if (f->items[k]->kind != DECK_SCALAR)
                return deck_error(err, f->items[k], "expected a field name");
            ro->fields[ro->n_fields++] = f->items[k]->scalar;
        }
    }
    return deck_check_unused(o, "output", keys, err);
}

int deck_build_sim(const struct deck *d, struct sim **out, struct run_output *ro,
                   struct spall_error *err)
{
    return deck_build_sim_setup(d, out, ro, false, NULL, 0, err);
}

int deck_build_sim_setup(const struct deck *d, struct sim **out, struct run_output *ro,
                         bool distribute, char *note, size_t note_len, struct spall_error *err)
{
    char none[1];
    if (!note || !note_len) {
        note = none;
        note_len = sizeof none;
    }
    *out = NULL;
    memset(ro, 0, sizeof *ro);
    const struct deck_node *root = d->root;
    if (!root)
        return spall_error_set(err, SPALL_ERR_INPUT, "%s:1:1: the deck is empty; expected a mapping "
                               "with model, materials, lattice, body and run",
                               d->path);
    int rc = deck_expect_map(root, "a mapping of sections (model, materials, lattice, ...)", err);
    if (rc)
        return rc;
    struct build_ctx c = {.deck = d};
    const char *title = NULL;
    if ((rc = deck_string(root, "title", false, &title, err)))
        return rc;
    snprintf(ro->title, sizeof ro->title, "%s", title ? title : "");
    const char *desc = NULL;
    if ((rc = deck_string(root, "description", false, &desc, err)))
        return rc;
    c.geometry = deck_get(root, "geometry");
    if (c.geometry && (rc = deck_expect_map(c.geometry, "a mapping of shape names to shapes", err)))
        return rc;
    if (c.geometry)
        for (size_t k = 0; k < c.geometry->n; k++)
            c.geometry->used[k] = true;

    if ((rc = parse_lattice(&c, root, err)))
        goto fail;
    if ((rc = parse_model(&c, root, err)) || (rc = parse_materials(&c, root, err)) ||
        (rc = parse_max_particles(&c, root, err)) ||
        (rc = deck_setup_dist_decide(c.sim, root, distribute, note, note_len, err)))
        goto fail;
    deck_setup_dist_bodies(c.sim, root, c.geometry, c.dim, note, note_len);
    if ((rc = parse_body(&c, root, err)) ||
        (rc = parse_regions(&c, root, err)) ||
        (rc = deck_parse_inclusions(c.sim, root, c.geometry, c.dim, err)))
        goto fail;
    assign_masses(c.sim);
    double gravity[3] = {0, 0, 0};
    if ((rc = parse_groups(&c, root, err)) || (rc = parse_precracks(&c, root, err)) ||
        (rc = parse_bcs(&c, root, err)) || (rc = parse_initial_velocity(&c, root, err)) ||
        (rc = parse_probes(&c, root, err)) || (rc = deck_parse_impactors(c.sim, root, err)) ||
        (rc = deck_parse_contact(c.sim, root, err)) ||
        (rc = deck_vector(root, "gravity", false, (size_t)c.dim, 3, gravity, err)) ||
        (rc = deck_double(root, "damping", false, 0.0, INFINITY, &c.sim->damping, err)) ||
        (rc = parse_run(&c, root, ro, err)) || (rc = parse_output(&c, root, ro, err)) ||
        (rc = run_balance_parse(root, &ro->parallel, err)) ||
        (rc = deck_check_unused(root, "the deck", top_keys, err)))
        goto fail;
    memcpy(c.sim->gravity, gravity, sizeof gravity);
    if ((rc = sim_prepare(c.sim, err))) {
        /* point at the key the refusal names (err->key), else at 'model':
         * the model's set-up refused it */
        if (!deck_locate_error(root, err)) {
            char msg[SPALL_ERROR_MSG_LEN], key[SPALL_ERROR_KEY_LEN];
            snprintf(msg, sizeof msg, "%s", err->msg);
            memcpy(key, err->key, sizeof key);
            if (deck_peek(root, "model"))
                deck_error_key(err, root, "model", "%s", msg);
            else
                spall_error_set(err, rc, "%s: %s", d->path, msg);
            memcpy(err->key, key, sizeof key); /* kept for the caller */
        }
        err->code = rc;
        goto fail;
    }
    size_t bad = 0; /* output.fields, refused before any output exists */
    if ((rc = field_writer_check_names(c.sim, ro->fields, ro->n_fields, &bad, err))) {
        char msg[SPALL_ERROR_MSG_LEN];
        snprintf(msg, sizeof msg, "%s", err->msg);
        deck_error(err, deck_peek(deck_peek(root, "output"), "fields")->items[bad], "%s", msg);
        goto fail;
    }
    *out = c.sim;
    return SPALL_OK;
fail:
    sim_destroy(&c.sim);
    return rc;
}
