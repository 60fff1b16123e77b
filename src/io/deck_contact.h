/**
 * @file deck_contact.h
 * @brief The deck's `contact:` section (particle-particle contact,
 *        core/contact_particles.h); keys documented in docs/decks.md.
 */
#ifndef SPALL_DECK_CONTACT_H
#define SPALL_DECK_CONTACT_H

struct deck_node;
struct sim;
struct spall_error;

/** Read `contact: {distance, stiffness, exponent}` of the deck root
 *  (absent: no particle-particle contact). */
int deck_parse_contact(struct sim *s, const struct deck_node *root, struct spall_error *err);

#endif
