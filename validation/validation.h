/**
 * @file validation.h
 * @brief Built-in validation cases (`spall validate`): each case runs the
 *        engine on a benchmark and records checks of the form
 *        reference / measured / error / tolerance / source -> PASS or FAIL.
 *
 * A case that does not reach its reference stays in the suite: its check is
 * recorded with `known_gap` set and the gap explained in `note`; it still
 * counts as FAIL (exit status non-zero) so it can never silently pass.
 */
#ifndef SPALL_VALIDATION_H
#define SPALL_VALIDATION_H

#include <stdbool.h>
#include <stddef.h>
#include <stdio.h>

struct spall_error;

struct vcheck {
    char case_name[48];
    char quantity[96];
    char unit[16];
    double reference;
    double measured;
    double tolerance;  /**< relative (fraction) if relative, else absolute in unit */
    bool relative;
    char source[160];  /**< where the reference comes from */
    char note[320];    /**< why this tolerance; explanation of a gap */
    bool known_gap;
    bool pass;
};

struct vreport {
    struct vcheck *checks;
    size_t n, cap;
    FILE *log;         /**< extra lines printed by cases (may be NULL) */
    int quick;         /**< reduced sizes for the test suite */
    const char *current_case;
};

/** Record a check; error = |measured - reference| (/|reference| if relative);
 *  pass = error <= tolerance. */
int vreport_check(struct vreport *r, const char *quantity, const char *unit, double reference,
                  double measured, double tolerance, bool relative, const char *source,
                  const char *note, struct spall_error *err);
/** Record a yes/no check (reference 1, measured 1 or 0). */
int vreport_check_true(struct vreport *r, const char *quantity, bool ok, const char *source,
                       const char *note, struct spall_error *err);
/** Mark the last recorded check as a known, documented gap. */
void vreport_mark_gap(struct vreport *r, const char *note);
/** Informational line (printed under the table). */
void vreport_info(struct vreport *r, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 2, 3)))
#endif
    ;
void vreport_free(struct vreport *r);

struct vcase {
    const char *name;   /**< e.g. "lattice-patch" */
    const char *title;  /**< one line */
    bool in_quick;      /**< part of `--quick` */
    int (*run)(struct vreport *r, struct spall_error *err);
};

/** All built-in cases (registry in validation/cases.c). */
const struct vcase *validation_cases(size_t *n);

#endif
