/**
 * @file registry.c
 * @brief The table of particle models known to the engine.  Adding a model:
 *        one extern declaration and one table entry here, nothing else.
 */
#include "models/model.h"

#include <string.h>

extern const struct model_ops lattice_model_ops;
/* peridynamics extern */
extern const struct model_ops peridynamics_model_ops;

/* macro-particle extern */
extern const struct model_ops macroparticle_model_ops;

/* sph extern */
extern const struct model_ops sph_model_ops;

static const struct model_ops *const model_table[] = {
    &lattice_model_ops,
    /* peridynamics entry */
    &peridynamics_model_ops,

    /* macro-particle entry */
    &macroparticle_model_ops,

    /* sph entry */
    &sph_model_ops,

};

#define N_MODELS (sizeof model_table / sizeof model_table[0])

const struct model_ops *model_find(const char *name)
{
    for (size_t k = 0; k < N_MODELS; k++)
        if (strcmp(model_table[k]->name, name) == 0)
            return model_table[k];
    return NULL;
}

/* Names in table order (kept beside the table: constant data, no state). */
static const char *const model_name_list[] = {
    "lattice",
    /* peridynamics name */
    "peridynamics",

    /* macro-particle name */
    "macroparticle",

    /* sph name */
    "sph",

    NULL};

const char *const *model_names(void)
{
    return model_name_list;
}
