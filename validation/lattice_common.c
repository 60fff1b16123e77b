/**
 * @file lattice_common.c
 * @brief Helpers shared by the lattice validation cases: build a simulation
 *        from an in-memory deck and read the model's history columns.
 */
#include "validation/lattice_cases.h"

#include "core/sim.h"
#include "io/deck.h"
#include "io/deck_build.h"
#include "core/model.h"
#include "spall/error.h"

#include <math.h>
#include <string.h>

int vlat_build(const char *name, const char *yaml, struct sim **out, struct spall_error *err)
{
    struct deck *d = NULL;
    *out = NULL;
    int rc = deck_load_string(&d, name, yaml, err);
    if (rc)
        return rc;
    struct run_output ro;
    rc = deck_build_sim(d, out, &ro, err);
    /* the simulation keeps no pointer into the deck (only ro.fields do) */
    deck_destroy(&d);
    if (rc)
        spall_error_prefix(err, "validation deck '%s': ", name);
    return rc;
}

double vlat_history(const struct sim *s, const char *column)
{
    if (!s->ops->history)
        return NAN;
    const char *names[MODEL_HISTORY_MAX];
    double values[MODEL_HISTORY_MAX];
    size_t n = s->ops->history(s->model, s, names, values);
    for (size_t k = 0; k < n && k < MODEL_HISTORY_MAX; k++)
        if (strcmp(names[k], column) == 0)
            return values[k];
    return NAN;
}

int vlat_group(const struct sim *s, const char *name, int *index, struct spall_error *err)
{
    *index = sim_find_group(s, name);
    if (*index < 0)
        return spall_error_set(err, SPALL_ERR_INTERNAL, "validation: deck has no group '%s'",
                               name);
    return SPALL_OK;
}
