/**
 * @file error.h
 * @brief Status codes and the error record every libspall call fills.
 *
 * The library never calls exit(): a failing call returns a non-zero status
 * and writes one human-readable line naming the cause into struct spall_error.
 * The CLI prints that line and exits with the status (2 for bad input).
 *
 * When the refusal is about one input key, the record also names that key as
 * data (err->key), set where the error is raised: the deck reader turns it
 * into file:line:column, and a library user reads it without parsing text.
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
#define SPALL_ERROR_KEY_LEN 128

/** Error record: code, one line of text, and the input key it is about.
 *
 *  Key path syntax: deck keys from the top of the deck joined by '.', a
 *  sequence item as "[k]" (0-based) after its key, e.g. "run.dt",
 *  "model.clamp", "materials.steel", "bodies[2].lattice.type".  Empty when
 *  the error is about no single key (or the path did not fit). */
struct spall_error {
    int code;
    char msg[SPALL_ERROR_MSG_LEN];
    char key[SPALL_ERROR_KEY_LEN];
    /** Non-zero once the MPI error agreement handed this error to every rank
     *  (core/parallel/comm.h, par_agree): all ranks are then on their way
     *  out with it, and further agreements pass it on without a message.
     *  Reset by spall_error_clear() and by an agreement that all ranks pass. */
    int agreed;
};

/** Record an error; returns @p code so callers can `return spall_error_set(...)`.
 *  A NULL @p err is allowed (the message is dropped).  Clears err->key. */
int spall_error_set(struct spall_error *err, int code, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;

/** spall_error_set() for a refusal of the input key path @p key (syntax
 *  above; NULL or "" for none), kept in err->key. */
int spall_error_set_key(struct spall_error *err, int code, const char *key, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 4, 5)))
#endif
    ;

/** Give an error already recorded the key path formatted from @p fmt unless
 *  it names one already: the innermost (most precise) key wins. */
void spall_error_default_key(struct spall_error *err, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 2, 3)))
#endif
    ;

/** Prefix the existing message with context ("while reading X: ...");
 *  code and key are kept. */
void spall_error_prefix(struct spall_error *err, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 2, 3)))
#endif
    ;

/** Reset to SPALL_OK with an empty message and no key. */
void spall_error_clear(struct spall_error *err);

#endif
