/**
 * @file setup_internal.h
 * @brief Between src/api's files: the option tree a struct spall_setup
 *        holds (include/spall/setup.h), copied for the deck builder.
 */
#ifndef SPALL_API_SETUP_INTERNAL_H
#define SPALL_API_SETUP_INTERNAL_H

struct deck;
struct spall_error;
struct spall_setup;

/** A deck holding a copy of the settings of @p s (the builder marks keys
 *  as read, so each simulation gets its own); free with deck_destroy. */
int setup_deck_copy(const struct spall_setup *s, struct deck **out, struct spall_error *err);

#endif
