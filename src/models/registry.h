/**
 * @file registry.h
 * @brief The table of particle models (models/registry.c): the layer above
 *        the core picks a model by name here and hands its model_ops to
 *        sim_set_model; the core itself never looks a model up.
 */
#ifndef SPALL_MODELS_REGISTRY_H
#define SPALL_MODELS_REGISTRY_H

#include "core/model.h"

/** Find a model by name; NULL if unknown. */
const struct model_ops *model_find(const char *name);
/** NULL-terminated list of registered model names (for messages). */
const char *const *model_names(void);

#endif
