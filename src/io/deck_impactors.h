/**
 * @file deck_impactors.h
 * @brief The deck's `impactors:` section (rigid impactors and supports,
 *        core/rigid.h); keys documented in docs/decks.md.
 */
#ifndef SPALL_DECK_IMPACTORS_H
#define SPALL_DECK_IMPACTORS_H

struct deck_node;
struct sim;
struct spall_error;

/** Read `impactors:` of the deck root (absent: nothing to do). */
int deck_parse_impactors(struct sim *s, const struct deck_node *root, struct spall_error *err);

#endif
