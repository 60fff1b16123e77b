/**
 * @file sph_forms.c
 * @brief Formulation per body (issue 6 item 6: Total-Lagrangian SPH
 *        "selectable per body"): `model.body_formulation: {name: total |
 *        updated}` overrides the run's `formulation:` for the bodies[]
 *        entries of that `name:`.
 *
 * Why the bodies must not share kernel sums: a TLSPH particle's sums run
 * over its reference neighbours (fixed list, reference kernel, B0^-1 of
 * the reference configuration), an updated-form particle's over its
 * current neighbours with the current density.  A pair across the two
 * would enter one sum and not the other (no antisymmetric force, no
 * momentum conservation), and the TLSPH body's reference neighbours would
 * include target particles it later leaves.  So a run mixing the two
 * formulations needs `interface: bodies` (sph_interface.c): kernel sums
 * inside each body, a penalty between bodies; it is refused otherwise.
 * `interface: materials` is accepted too (a graded target of several
 * lattices of one material stays one continuum): the updated bodies then
 * share sums per material, a TLSPH body still only with itself.
 *
 * How the split works (m->form, one byte per particle, NULL when every
 * particle has one formulation and no interface is asked for):
 *  - sph_tlsph_init keeps in the reference list only the pairs of one
 *    TLSPH body (same body, both total);
 *  - the current-configuration list (sph_rates.c) is built over all
 *    particles, and sph_interface_split keeps the pairs inside an
 *    updated-form body (material), drops the pairs inside a TLSPH body
 *    (they live in the reference list) and moves every other pair to the
 *    penalty list;
 *  - the updated-form loops (fused, two-pass, leapfrog, pressure) skip the
 *    TLSPH particles and the TLSPH loops skip the others: one predictable
 *    test per particle (not per pair), none at all when m->form is NULL.
 * The time step is the minimum over all particles (sph_stable_dt already
 * takes each particle's B^-1 norm: TLSPH B0^-1, identity or CSPM for the
 * others), and the energy sums run over all particles.
 *
 * A run where every body ends up with one formulation is the plain run of
 * that formulation (no m->form, bitwise the same as `formulation:` alone)
 * unless an interface is also given; TLSPH bodies with an interface touch
 * through the penalty like updated-form ones.
 */
#include "models/sph/sph_internal.h"

#include "core/particles.h"
#include "core/sim.h"
#include "core/options.h"
#include "spall/error.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Name of body k of the deck (NULL: none given). */
static const char *body_name(const struct deck_node *root, size_t k)
{
    const struct deck_node *bodies = deck_peek(root, "bodies");
    const struct deck_node *b =
        bodies && bodies->kind == DECK_SEQUENCE ? (k < bodies->n ? bodies->items[k] : NULL)
                                                : (k == 0 ? deck_peek(root, "body") : NULL);
    const struct deck_node *nm = b && b->kind == DECK_MAPPING ? deck_peek(b, "name") : NULL;
    return nm && nm->kind == DECK_SCALAR ? nm->scalar : NULL;
}

int sph_forms_parse(const struct deck_node *params, int run_form, uint8_t **body_total,
                    size_t *n_bodies, struct spall_error *err)
{
    static const char *const forms[] = {"updated", "total", NULL};
    *body_total = NULL;
    *n_bodies = 0;
    const struct deck_node *root = params && params->deck ? params->deck->root : NULL;
    const struct deck_node *bodies = root ? deck_peek(root, "bodies") : NULL;
    size_t nb = bodies && bodies->kind == DECK_SEQUENCE ? bodies->n : 1;
    uint8_t *bt = malloc(nb ? nb : 1);
    if (!bt)
        return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory (body formulations)");
    for (size_t k = 0; k < nb; k++)
        bt[k] = (uint8_t)run_form;
    const struct deck_node *bf = params ? deck_get(params, "body_formulation") : NULL;
    int rc = SPALL_OK;
    if (bf) {
        rc = deck_expect_map(bf, "a mapping {body name: updated | total}", err);
        for (size_t q = 0; !rc && q < bf->n; q++) {
            const char *want = bf->keys[q];
            int f = 0;
            if ((rc = deck_enum(bf, want, true, forms, &f, err)))
                break;
            size_t hits = 0;
            for (size_t k = 0; k < nb; k++) {
                const char *nm = root ? body_name(root, k) : NULL;
                if (nm && strcmp(nm, want) == 0) {
                    bt[k] = (uint8_t)f;
                    hits++;
                }
            }
            if (hits == 0) {
                char names[256] = "";
                size_t len = 0;
                for (size_t k = 0; k < nb && len + 2 < sizeof names; k++) {
                    const char *nm = root ? body_name(root, k) : NULL;
                    if (nm)
                        len += (size_t)snprintf(names + len, sizeof names - len, "%s%s",
                                                len ? ", " : "", nm);
                }
                rc = deck_error_key(err, bf, want,
                                    "body_formulation names body '%s', but no body has "
                                    "name: %s (named bodies: %s)",
                                    want, want, len ? names : "none; give bodies[] a name:");
            } else if (hits > 1) {
                rc = deck_error_key(err, bf, want,
                                    "body_formulation: %zu bodies are named '%s'; names must "
                                    "be unique",
                                    hits, want);
            }
        }
    }
    if (rc) {
        free(bt);
        return rc;
    }
    *body_total = bt;
    *n_bodies = nb;
    return SPALL_OK;
}

int sph_forms_init(struct model *m, struct sim *s, struct spall_error *err)
{
    const struct particles *p = s->p;
    const size_t n = p->n_owned;
    m->form = malloc(n ? n : 1);
    if (!m->form)
        return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory (particle formulations)");
    m->n_total = 0;
    for (size_t i = 0; i < n; i++) {
        const int32_t b = p->body[i];
        if (b < 0 || (size_t)b >= m->n_bodies)
            return spall_error_set(err, SPALL_ERR_INTERNAL,
                                   "particle %zu of body %d: only %zu bodies were declared", i,
                                   (int)b, m->n_bodies);
        m->form[i] = m->body_total[b];
        m->n_total += m->form[i];
    }
    return SPALL_OK;
}

void sph_forms_describe(const struct model *m, const struct sim *s, char *buf, size_t len)
{
    size_t off = (size_t)snprintf(buf, len, "  formulation per body (TLSPH %zu of %zu particles):",
                                  m->n_total, s->p->n_owned);
    for (size_t k = 0; k < m->n_bodies && off < len; k++)
        off += (size_t)snprintf(buf + off, len - off, "%s body %zu %s", k ? "," : "", k,
                                m->body_total[k] ? "total" : "updated");
    if (off < len)
        snprintf(buf + off, len - off, "\n");
}
