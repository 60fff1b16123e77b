/**
 * @file registry.c
 * @brief The table of particle models known to the engine.  Adding a model:
 *        one line in SPALL_MODELS, nothing else.
 */
#include "core/model.h"
#include "models/registry.h"

#include <string.h>

/* Every model, by the name of its model_ops (<name>_model_ops, whose .name
 * is "<name>").  The extern declarations, the table and the name list below
 * are all derived from this one list, so they cannot disagree. */
#define SPALL_MODELS(X) X(lattice) X(peridynamics) X(macroparticle) X(sph) X(tlsph)

#define SPALL_MODEL_EXTERN(n) extern const struct model_ops n##_model_ops;
SPALL_MODELS(SPALL_MODEL_EXTERN)
#undef SPALL_MODEL_EXTERN

#define SPALL_MODEL_ENTRY(n) &n##_model_ops,
static const struct model_ops *const model_table[] = {SPALL_MODELS(SPALL_MODEL_ENTRY)};
#undef SPALL_MODEL_ENTRY

#define N_MODELS (sizeof model_table / sizeof model_table[0])

const struct model_ops *model_find(const char *name)
{
    for (size_t k = 0; k < N_MODELS; k++)
        if (strcmp(model_table[k]->name, name) == 0)
            return model_table[k];
    return NULL;
}

/* Names in table order (constant data, no state); a test checks that each
 * is its model_ops' name. */
#define SPALL_MODEL_NAME(n) #n,
static const char *const model_name_list[] = {SPALL_MODELS(SPALL_MODEL_NAME) NULL};
#undef SPALL_MODEL_NAME

const char *const *model_names(void)
{
    return model_name_list;
}
