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
#include "io/deck.h"
#include "spall/error.h"

#include <stdio.h>
#include <string.h>

/* The deck features the distributed set-up does not build per region yet:
 * (key, why).  Each keeps the replicated set-up. */
static const char *unsupported(const struct deck_node *root)
{
    const struct deck_node *model = deck_peek(root, "model");
    if (deck_peek(root, "bodies"))
        return "several bodies (bodies:)";
    if (deck_peek(root, "inclusions"))
        return "inclusions";
    if (deck_peek(root, "contact"))
        return "particle contact (contact:)";
    /* the state-based stable time step reads the weighted volumes of the
     * partners' partners, which the edge of a window leaves too small */
    const struct deck_node *f = model && model->kind == DECK_MAPPING
                                    ? deck_peek(model, "formulation") : NULL;
    if (f && f->kind == DECK_SCALAR && strcmp(f->scalar, "bond") != 0)
        return "state-based peridynamics (model.formulation)";
    /* the corrected coefficients of a window's edge are not monotone in
     * its missing bonds, so the minimum of the windows' stable steps is
     * not proven to be the serial one */
    const struct deck_node *sc = model && model->kind == DECK_MAPPING
                                     ? deck_peek(model, "surface_correction") : NULL;
    if (sc && sc->kind == DECK_SCALAR && strcmp(sc->scalar, "false") != 0)
        return "surface correction (model.surface_correction)";
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

int deck_setup_dist_fill(struct sim *s, const struct lattice_spec *spec, const struct geom *g,
                         int32_t material, size_t *added, struct spall_error *err)
{
    struct lattice_window w;
    memset(&w, 0, sizeof w);
    w.rank = s->setup->rank;
    w.size = s->setup->size;
    w.halo = s->setup->halo;
    size_t first = s->p->n;
    int rc = lattice_fill_window(s->p, spec, g, material, &w, err);
    *added = s->p->n - first;
    if (rc)
        return rc;
    return par_setup_filled(s, &w, err);
}

size_t deck_setup_dist_count(const struct sim *s, const size_t *idx, size_t n)
{
    return s->setup ? par_setup_count(s, idx, n) : n;
}
