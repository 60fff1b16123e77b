/**
 * @file error.h
 * @brief Status codes and the error record every libspall call fills.
 *
 * The library never calls exit(): a failing call returns a non-zero status
 * and writes one human-readable line naming the cause into struct spall_error.
 * The CLI prints that line and exits with the status (2 for bad input).
 */
#ifndef SPALL_ERROR_H
#define SPALL_ERROR_H

#include <stddef.h>

/** Status codes returned by libspall functions. */
enum spall_status {
    SPALL_OK = 0,
    SPALL_ERR_INPUT = 2,    /**< bad deck / bad user input (CLI exit 2) */
    SPALL_ERR_PHYSICS = 3,  /**< impossible physics refused before running */
    SPALL_ERR_IO = 4,       /**< file system / HDF5 failure */
    SPALL_ERR_NOMEM = 5,    /**< allocation failed */
    SPALL_ERR_UNSTABLE = 6, /**< run went unstable (NaN, energy blow-up) */
    SPALL_ERR_INTERNAL = 7  /**< broken invariant (a bug) */
};

#define SPALL_ERROR_MSG_LEN 1024

/** Error record: code plus one line of text. */
struct spall_error {
    int code;
    char msg[SPALL_ERROR_MSG_LEN];
};

/** Record an error; returns @p code so callers can `return spall_error_set(...)`.
 *  A NULL @p err is allowed (the message is dropped). */
int spall_error_set(struct spall_error *err, int code, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;

/** Prefix the existing message with context ("while reading X: ..."). */
void spall_error_prefix(struct spall_error *err, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 2, 3)))
#endif
    ;

/** Reset to SPALL_OK with an empty message. */
void spall_error_clear(struct spall_error *err);

#endif
