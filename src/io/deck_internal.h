/**
 * @file deck_internal.h
 * @brief Helpers shared by the deck parser (deck.c) and the typed getters
 *        (deck_get.c).  Not part of any interface.
 */
#ifndef SPALL_DECK_INTERNAL_H
#define SPALL_DECK_INTERNAL_H

#include "io/deck.h"

#include <stdbool.h>

/* Messages are one line (the CLI prints exactly one): a key or value holding
 * a newline or tab must not break that. */
static inline void deck_one_line(char *msg)
{
    for (; *msg; ++msg)
        if ((unsigned char)*msg < 0x20)
            *msg = ' ';
}

/* An unquoted empty value ("key:" with nothing after it). */
static inline bool deck_is_empty_value(const struct deck_node *n)
{
    return n->kind == DECK_SCALAR && !n->quoted && n->scalar[0] == '\0';
}

#endif
