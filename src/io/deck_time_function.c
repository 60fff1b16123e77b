/**
 * @file deck_time_function.c
 * @brief The `function:` key of loads and impactors: a time function
 *        (constant, linear or quadratic ramp, table) that scales a value.
 */
#include "io/deck_time_function.h"

#include "core/time_function.h"
#include "io/deck.h"
#include "spall/error.h"

#include <stdlib.h>
#include <string.h>

int deck_build_time_function(const struct deck_node *bcn, struct time_function *tf,
                             struct spall_error *err)
{
    static const char *const kinds[] = {"constant", "linear_ramp", "quadratic_ramp", "table",
                                        NULL};
    static const char *const keys[] = {"type", "duration", "points", NULL};
    memset(tf, 0, sizeof *tf);
    const struct deck_node *fn = deck_get(bcn, "function");
    if (!fn)
        return SPALL_OK;
    int rc = deck_expect_map(fn, "a time function mapping (type, duration or points)", err);
    if (rc)
        return rc;
    int kind = 0;
    if ((rc = deck_enum(fn, "type", true, kinds, &kind, err)))
        return rc;
    tf->kind = (enum time_function_kind)kind;
    if (tf->kind == TF_LINEAR_RAMP || tf->kind == TF_QUADRATIC_RAMP) {
        if ((rc = deck_double_pos(fn, "duration", true, &tf->t_ramp, err)))
            return rc;
    } else if (tf->kind == TF_TABLE) {
        const struct deck_node *pts = deck_get(fn, "points");
        if (!pts)
            return deck_error(err, fn, "missing required key 'points' ([[t, f], ...]) in table");
        if ((rc = deck_expect_seq(pts, "a list of [time, factor] pairs", err)))
            return rc;
        if (pts->n < 1)
            return deck_error(err, pts, "a table needs at least one [time, factor] point");
        tf->t = malloc(pts->n * sizeof *tf->t);
        tf->f = malloc(pts->n * sizeof *tf->f);
        if (!tf->t || !tf->f) {
            time_function_free(tf);
            return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory reading table");
        }
        tf->n = pts->n;
        for (size_t k = 0; k < pts->n; k++) {
            const struct deck_node *pt = pts->items[k];
            if (pt->kind != DECK_SEQUENCE || pt->n != 2) {
                time_function_free(tf);
                return deck_error(err, pt, "table point must be [time, factor]");
            }
            if ((rc = deck_node_double(pt->items[0], &tf->t[k], err)) ||
                (rc = deck_node_double(pt->items[1], &tf->f[k], err))) {
                time_function_free(tf);
                return rc;
            }
            if (k > 0 && !(tf->t[k] > tf->t[k - 1])) {
                time_function_free(tf);
                return deck_error(err, pt, "table times must increase strictly");
            }
        }
    }
    rc = deck_check_unused(fn, "function", keys, err);
    if (rc)
        time_function_free(tf);
    return rc;
}
