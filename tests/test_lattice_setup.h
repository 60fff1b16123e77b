/**
 * @file test_lattice_setup.h
 * @brief The lattice model set up by hand for unit tests of one material:
 *        an empty simulation on a given lattice, the model created from the
 *        YAML's `model:` mapping and material `mat` parsed from its `mat:`
 *        mapping (density 1000 kg/m^3 in the core; the YAML's density key is
 *        read so that it is not reported unused).  One copy for every test
 *        that checks a lattice material law or a refused material.
 */
#ifndef SPALL_TEST_LATTICE_SETUP_H
#define SPALL_TEST_LATTICE_SETUP_H

#include "core/lattice_gen.h"
#include "core/model.h"
#include "core/sim.h"
#include "io/deck.h"
#include "models/lattice/lattice.h"
#include "spall/error.h"

extern const struct model_ops lattice_model_ops;

/** Set up *s (always created: destroy it) and *dk (destroy it) with the
 *  model of @p yaml on lattice @p kind of spacing @p spacing (2D thickness
 *  and 1D cross-section the same number); returns the status of the model's
 *  create or parse_material (the refusal a test may expect). */
static inline int test_lattice_material(enum lattice_kind kind, double spacing, const char *yaml,
                                        struct sim **s, struct deck **dk, struct spall_error *err)
{
    *s = NULL;
    *dk = NULL;
    int rc = deck_load_string(dk, "t.yaml", yaml, err);
    if (!rc)
        rc = sim_create(s, lattice_kind_dim(kind), err);
    if (rc)
        return rc;
    (*s)->lattice.kind = kind;
    (*s)->lattice.spacing = spacing;
    (*s)->thickness = spacing;
    if ((rc = sim_add_material(*s, "mat", 1000.0, NULL, err)))
        return rc;
    const struct deck_node *mn = deck_get((*dk)->root, "model");
    (void)deck_get(mn, "type");
    struct model *m = NULL;
    if ((rc = lattice_model_ops.create(&m, *s, mn, err)))
        return rc;
    (*s)->ops = &lattice_model_ops;
    (*s)->model = m;
    const struct deck_node *mat = deck_get((*dk)->root, "mat");
    (void)deck_get(mat, "density");
    return lattice_model_ops.parse_material(m, *s, 0, mat, err);
}

/** Status of setting up @p yaml on lattice @p kind (spacing 1 mm), nothing kept. */
static inline int test_lattice_material_status(enum lattice_kind kind, const char *yaml,
                                               struct spall_error *err)
{
    struct sim *s = NULL;
    struct deck *dk = NULL;
    int rc = test_lattice_material(kind, 1e-3, yaml, &s, &dk, err);
    sim_destroy(&s);
    deck_destroy(&dk);
    return rc;
}

#endif
