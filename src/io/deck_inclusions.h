/**
 * @file deck_inclusions.h
 * @brief `inclusions:` deck section: seeded random non-overlapping discs
 *        (2D) / spheres (3D) / segments (1D) of a material inside a shape.
 */
#ifndef SPALL_DECK_INCLUSIONS_H
#define SPALL_DECK_INCLUSIONS_H

struct deck_node;
struct sim;
struct spall_error;

/**
 * Parse `inclusions: [{material, count, radius, within, seed, min_gap}]`
 * and assign each entry's material to the particles whose reference
 * position lies inside one of its placed inclusions (after `regions:`;
 * masses are recomputed by the caller).  Centres and radii come from a
 * counter-based generator (splitmix64 of seed and draw index), so the
 * result depends only on the deck, never on the run or the thread count.
 * Inclusions of all entries are mutually non-overlapping (gap >= min_gap).
 * @param geometry the deck's `geometry:` mapping (named shapes), may be NULL
 */
int deck_parse_inclusions(struct sim *s, const struct deck_node *root,
                          const struct deck_node *geometry, int dim, struct spall_error *err);

#endif
