/**
 * @file deck_setup_dist.h
 * @brief The deck side of the distributed set-up (core/parallel/setup_dist.h):
 *        whether a deck can build each rank's region only, and the fill of
 *        that region.  What it cannot support yet keeps the replicated
 *        set-up, with a one-line reason for run.log.
 */
#ifndef SPALL_DECK_SETUP_DIST_H
#define SPALL_DECK_SETUP_DIST_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

struct deck_node;
struct geom;
struct lattice_spec;
struct sim;
struct spall_error;

/** Called by the deck builder once the model and materials exist and
 *  before any body is filled.  On several MPI ranks with @p wanted, a deck
 *  that the distributed set-up supports gets s->setup; otherwise @p note
 *  says why the set-up stays replicated (empty on one rank).  Decided from
 *  the deck alone, so the same on every rank. */
int deck_setup_dist_decide(struct sim *s, const struct deck_node *root, bool wanted, char *note,
                           size_t len, struct spall_error *err);

/** Called before the bodies are filled, with the deck's `geometry:`
 *  mapping (may be NULL): where a model may bond particles of different
 *  bodies (ops->bonds_within_bodies false) and two of the bodies' shapes
 *  come within one interaction range of each other (or a shape is
 *  unbounded or does not parse: its error comes with the fill), one
 *  body's window would miss the other body's partners, so the set-up
 *  turns replicated (s->setup freed) and @p note says why.  Decided from
 *  the deck alone, the same on every rank. */
void deck_setup_dist_bodies(struct sim *s, const struct deck_node *root,
                            const struct deck_node *geometry, int dim, char *note, size_t len);

/** Fill this rank's window of the body (lattice_fill_window) and set the
 *  global ids (collective). */
int deck_setup_dist_fill(struct sim *s, const struct lattice_spec *spec, const struct geom *g,
                         int32_t material, size_t *added, struct spall_error *err);

/** Members of a set of local indices over the whole body into *count:
 *  idx's count on the replicated set-up, the sum of the ranks' blocks on the
 *  distributed one (collective there, and agreed first: a rank that failed
 *  since the last agreement stops all here; docs/parallel.md). */
int deck_setup_dist_count(const struct sim *s, const size_t *idx, size_t n, size_t *count,
                          struct spall_error *err);

#endif
