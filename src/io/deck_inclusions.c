/**
 * @file deck_inclusions.c
 * @brief Random inclusions (issue 3): rejection sampling of non-overlapping
 *        balls inside a shape with a deterministic counter-based generator.
 */
#include "io/deck_inclusions.h"
#include "io/deck_setup_dist.h"
#include "io/deck_shapes.h"

#include "core/geometry.h"
#include "core/particles.h"
#include "core/sim.h"
#include "io/deck.h"
#include "spall/error.h"

#include <math.h>
#include <limits.h>
#include <stdint.h>
#include <stdlib.h>

/* Tries per requested inclusion before the entry is refused: enough for
 * packings up to roughly half the random close packing, bounded so that an
 * impossible request fails in well under a second. */
#define INCL_TRIES_PER_ITEM 2000L
#define INCL_MAX_COUNT 1000000L

struct incl_ball {
    double c[3];
    double r;
};

/* splitmix64 finaliser (Steele, Lea & Flood 2014): a bijective mix, so
 * (seed, k) -> mix(seed * golden + k) is a counter-based stream. */
static uint64_t incl_mix(uint64_t z)
{
    z += 0x9E3779B97F4A7C15ull;
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
}

/* uniform in [0, 1): the top 53 bits of draw k of stream seed */
static double incl_uniform(uint64_t seed, uint64_t k)
{
    const uint64_t z = incl_mix(incl_mix(seed) ^ incl_mix(k + 0x632BE59BD9B4E019ull));
    return (double)(z >> 11) * 0x1.0p-53;
}

static int incl_entry(struct sim *s, const struct deck_node *e, size_t entry,
                      const struct deck_shape_ctx *sc, struct incl_ball **balls, size_t *nb,
                      size_t *cap, struct spall_error *err)
{
    static const char *const keys[] = {"material", "count", "radius", "within",
                                       "seed", "min_gap", NULL};
    int rc = deck_expect_map(e, "a mapping {material, count, radius, within, seed, min_gap}", err);
    if (rc)
        return rc;
    const char *name = NULL;
    long count = 0, seed = 1;
    double rmin = 0.0, rmax = 0.0, gap = 0.0;
    if ((rc = deck_string(e, "material", true, &name, err)))
        return rc;
    const int mat = sim_find_material(s, name);
    if (mat < 0)
        return deck_error(err, deck_peek(e, "material"),
                          "unknown material '%.64s'; define it under 'materials:'", name);
    if ((rc = deck_long(e, "count", true, 1, INCL_MAX_COUNT, &count, err)) ||
        (rc = deck_long(e, "seed", false, 0, LONG_MAX, &seed, err)) ||
        (rc = deck_double(e, "min_gap", false, 0.0, INFINITY, &gap, err)))
        return rc;
    const struct deck_node *rn = deck_peek(e, "radius");
    if (rn && rn->kind == DECK_SEQUENCE) {
        double rr[2] = {0, 0};
        if ((rc = deck_vector(e, "radius", true, 2, 2, rr, err)))
            return rc;
        rmin = rr[0];
        rmax = rr[1];
        if (!(rmin > 0.0) || !(rmax >= rmin) || !isfinite(rmax))
            return deck_error_key(err, e, "radius",
                                  "radius [%g, %g]: expected [Rmin, Rmax] with 0 < Rmin <= Rmax",
                                  rmin, rmax);
    } else {
        if ((rc = deck_double_pos(e, "radius", true, &rmin, err)))
            return rc;
        rmax = rmin;
    }
    struct geom *g = NULL;
    if ((rc = deck_shape_at_key(sc, e, "within", &g, err)))
        return rc;
    if ((rc = deck_check_unused(e, "inclusions[]", keys, err))) {
        geom_destroy(&g);
        return rc;
    }
    double lo[3] = {0, 0, 0}, hi[3] = {0, 0, 0};
    if (!geom_bounds(g, sc->dim, lo, hi)) {
        geom_destroy(&g);
        return deck_error_key(err, e, "within", "inclusions[%zu]: the shape is unbounded", entry);
    }
    if (*nb + (size_t)count > *cap) {
        size_t nc = *nb + (size_t)count;
        struct incl_ball *t = realloc(*balls, nc * sizeof *t);
        if (!t) {
            geom_destroy(&g);
            return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory placing inclusions");
        }
        *balls = t;
        *cap = nc;
    }
    const size_t first = *nb;
    const long max_tries = INCL_TRIES_PER_ITEM * count;
    uint64_t k = 0; /* draw counter of this entry's stream */
    const uint64_t stream = (uint64_t)seed;
    long placed = 0, tries = 0;
    while (placed < count && tries < max_tries) {
        tries++;
        struct incl_ball b = {{0, 0, 0}, rmin};
        for (int d = 0; d < sc->dim; d++)
            b.c[d] = lo[d] + (hi[d] - lo[d]) * incl_uniform(stream, k++);
        b.r = rmin + (rmax - rmin) * incl_uniform(stream, k++);
        if (!geom_contains(g, b.c, sc->dim))
            continue;
        int ok = 1;
        for (size_t q = 0; q < *nb && ok; q++) {
            const struct incl_ball *o = &(*balls)[q];
            double d2 = 0.0;
            for (int d = 0; d < sc->dim; d++)
                d2 += (b.c[d] - o->c[d]) * (b.c[d] - o->c[d]);
            const double lim = b.r + o->r + gap;
            ok = d2 >= lim * lim;
        }
        if (!ok)
            continue;
        (*balls)[(*nb)++] = b;
        placed++;
    }
    geom_destroy(&g);
    if (placed < count)
        return deck_error(err, e,
                          "inclusions[%zu] (material '%s'): placed only %ld of %ld non-overlapping "
                          "inclusions in %ld tries; lower count, radius or min_gap",
                          entry, name, placed, count, tries);
    /* assign the material: particles whose reference position is inside */
    const struct particles *p = s->p;
    size_t *hit_idx = malloc((p->n_owned ? p->n_owned : 1) * sizeof *hit_idx);
    if (!hit_idx) /* distributed: the others meet it at their next agreement */
        return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory placing inclusions");
    size_t hit = 0;
    for (size_t i = 0; i < p->n_owned; i++) {
        for (size_t q = first; q < *nb; q++) {
            const struct incl_ball *o = &(*balls)[q];
            double d2 = 0.0;
            for (int d = 0; d < sc->dim; d++)
                d2 += (p->x0[d][i] - o->c[d]) * (p->x0[d][i] - o->c[d]);
            if (d2 <= o->r * o->r) {
                p->material[i] = mat;
                hit_idx[hit++] = i;
                break;
            }
        }
    }
    /* the whole body's count: a distributed set-up's window holds part of it */
    size_t in_body = 0;
    rc = deck_setup_dist_count(s, hit_idx, hit, &in_body, err);
    free(hit_idx);
    if (rc)
        return rc;
    if (in_body == 0)
        return deck_error(err, e, "inclusions[%zu]: no particle lies inside the %ld inclusions "
                          "(radius below the lattice spacing?)", entry, count);
    return SPALL_OK;
}

int deck_parse_inclusions(struct sim *s, const struct deck_node *root,
                          const struct deck_node *geometry, int dim, struct spall_error *err)
{
    const struct deck_node *list = NULL;
    int rc = deck_list(root, "inclusions", "a list of {material, count, radius, within, seed}", &list, err);
    if (rc || !list)
        return rc;
    const struct deck_shape_ctx sc = {geometry, dim};
    struct incl_ball *balls = NULL;
    size_t nb = 0, cap = 0;
    for (size_t k = 0; k < list->n && !rc; k++)
        rc = incl_entry(s, list->items[k], k, &sc, &balls, &nb, &cap, err);
    free(balls);
    return rc;
}
