/**
 * @file deck_time_function.h
 * @brief Read a deck's `function:` key into a time function.
 */
#ifndef SPALL_DECK_TIME_FUNCTION_H
#define SPALL_DECK_TIME_FUNCTION_H

struct deck_node;
struct spall_error;
struct time_function;

/** The `function:` key of @p map (a time function; absent: constant 1).
 *  Keys: type (constant | linear_ramp | quadratic_ramp | table), duration,
 *  points; docs/decks.md. */
int deck_build_time_function(const struct deck_node *map, struct time_function *tf,
                             struct spall_error *err);

#endif
