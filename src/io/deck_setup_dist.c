/**
 * @file deck_setup_dist.c
 * @brief Deck side of the distributed set-up (deck_setup_dist.h).
 */
#include "io/deck_setup_dist.h"

#include "core/lattice_gen.h"
#include "core/lattice_polar.h"
#include "core/model.h"
#include "core/parallel/comm.h"
#include "core/parallel/setup_dist.h"
#include "core/particles.h"
#include "core/sim.h"
#include "core/geometry.h"
#include "io/deck.h"
#include "io/deck_shapes.h"
#include "spall/error.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* The deck features the distributed set-up does not build per region yet:
 * (key, why).  Each keeps the replicated set-up. */
static const char *unsupported(const struct deck_node *root)
{
    /* a lamina's calibration fits its constants on the built body */
    const struct deck_node *mats = deck_peek(root, "materials");
    for (size_t k = 0; mats && mats->kind == DECK_MAPPING && k < mats->n; k++)
        if (mats->items[k]->kind == DECK_MAPPING && deck_peek(mats->items[k], "fiber_modulus"))
            return "orthotropic laminae (fiber_modulus)";
    return NULL;
}

int deck_setup_dist_decide(struct sim *s, const struct deck_node *root, bool wanted, char *note,
                           size_t len, struct spall_error *err)
{
    if (len)
        note[0] = '\0';
    if (par_size() < 2)
        return SPALL_OK;
    const struct deck_node *par = deck_peek(root, "parallel");
    const struct deck_node *mode = par && par->kind == DECK_MAPPING ? deck_peek(par, "setup")
                                                                      : NULL;
    const char *why = NULL;
    if (mode && mode->kind == DECK_SCALAR && strcmp(mode->scalar, "replicated") == 0)
        why = "parallel.setup: replicated";
    else if (!wanted)
        why = "a restart (the checkpoint holds the particles)";
    else if (!s->ops || !s->ops->setup_range || !s->ops->localize || !s->ops->migrate_arrays)
        why = "the model builds its set-up whole";
    else if (lattice_kind_is_polar(s->lattice.kind))
        why = "rings and shells";
    else
        why = unsupported(root);
    if (why) {
        snprintf(note, len, "setup: replicated on every rank (%s)", why);
        return SPALL_OK;
    }
    /* two interaction ranges: the partners of the block's partners (their
     * families set per-bond constants, surface corrections, angles) */
    const double halo = 2.0 * s->ops->setup_range(s->model, s);
    int rc = par_setup_create(&s->setup, halo, err);
    if (!rc)
        snprintf(note, len, "setup: distributed (each rank built its block of %s layers and a "
                 "halo of %.6g m)", lattice_kind_dim(s->lattice.kind) == 3 ? "z" : "row", halo);
    return rc;
}

/* Whether the bounding boxes of the bodies' shapes keep every pair more
 * than @p range apart (false where a shape is unbounded or fails to parse). */
static bool bodies_apart(const struct deck_node *bodies, const struct deck_shape_ctx *sc,
                         double range)
{
    const size_t n = bodies->n;
    double(*box)[2][3] = calloc(n, sizeof *box);
    bool ok = box != NULL;
    for (size_t k = 0; ok && k < n; k++) {
        const struct deck_node *b = bodies->items[k];
        struct geom *g = NULL;
        struct spall_error ignored;
        memset(&ignored, 0, sizeof ignored);
        ok = b->kind == DECK_MAPPING && deck_shape_at_key(sc, b, "geometry", &g, &ignored) == 0 &&
             g && geom_bounds(g, sc->dim, box[k][0], box[k][1]);
        geom_destroy(&g);
    }
    for (size_t i = 0; ok && i < n; i++)
        for (size_t j = i + 1; ok && j < n; j++) {
            double gap = -INFINITY; /* the boxes' distance is at least the widest gap */
            for (int d = 0; d < sc->dim; d++)
                gap = fmax(gap, fmax(box[j][0][d] - box[i][1][d], box[i][0][d] - box[j][1][d]));
            ok = gap > range;
        }
    free(box);
    return ok;
}

void deck_setup_dist_bodies(struct sim *s, const struct deck_node *root,
                            const struct deck_node *geometry, int dim, char *note, size_t len)
{
    const struct deck_node *bodies = deck_peek(root, "bodies");
    if (!s->setup || s->ops->bonds_within_bodies || !bodies || bodies->kind != DECK_SEQUENCE ||
        bodies->n < 2)
        return;
    const struct deck_shape_ctx sc = {geometry, dim};
    if (bodies_apart(bodies, &sc, 0.5 * s->setup->halo)) /* the halo is two ranges */
        return;
    par_setup_destroy(&s->setup);
    snprintf(note, len, "setup: replicated on every rank (bodies within one interaction range of "
             "each other: the model's bonds may join them)");
}

int deck_setup_dist_fill(struct sim *s, const struct lattice_spec *spec, const struct geom *g,
                         int32_t material, size_t *added, struct spall_error *err)
{
    struct lattice_window w;
    memset(&w, 0, sizeof w);
    w.rank = s->setup->rank;
    w.size = s->setup->size;
    w.halo = s->setup->halo;
    w.n_prior = (size_t)s->setup->n_global;
    size_t first = s->p->n;
    int rc = lattice_fill_window(s->p, spec, g, material, &w, err);
    *added = s->p->n - first;
    if (!rc)
        rc = par_fault("setup_fill", err);
    if (rc) /* met by the others' first agreement in par_setup_filled */
        return par_agree(rc, err);
    return par_setup_filled(s, &w, first, err);
}

int deck_setup_dist_count(const struct sim *s, const size_t *idx, size_t n, size_t *count,
                          struct spall_error *err)
{
    *count = n;
    if (!s->setup)
        return SPALL_OK;
    int rc = par_agree(SPALL_OK, err);
    if (!rc)
        *count = par_setup_count(s, idx, n);
    return rc;
}
