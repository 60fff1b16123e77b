/**
 * @file deck.h
 * @brief YAML deck reader: libyaml events -> the option tree of
 *        core/options.h (every node remembers its file, line and column).
 *        The typed getters and positioned errors are in core/options.h.
 */
#ifndef SPALL_DECK_H
#define SPALL_DECK_H

#include "core/options.h"

struct spall_error;

/** Parse a YAML file.  Syntax errors come back as "FILE:L:C: <libyaml problem>". */
int deck_load_file(struct deck **out, const char *path, struct spall_error *err);
/** Parse YAML text held in memory; @p name is used in messages. */
int deck_load_string(struct deck **out, const char *name, const char *text,
                     struct spall_error *err);
void deck_destroy(struct deck **d);
/** Free a node and its children (nodes made as the reader makes them: every
 *  string and array malloc'd; src/api/setup_api.c builds trees too). */
void deck_node_free(struct deck_node *n);

#endif
