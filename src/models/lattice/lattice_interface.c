/**
 * @file lattice_interface.c
 * @brief Bonds between two materials in the lattice model (deck
 *        `model.interfaces`, issue 26 item 3), the lattice counterpart of
 *        src/models/peridynamics/pd_interface.c.
 *
 * Default, without an entry (lattice_model.c, build_pair_table): a bond
 * joining materials a and b is the two half-springs in series, k = 2 k_a k_b
 * / (k_a + k_b) per bond type, and fails at the smaller of the two failure
 * strains (the weaker of the two), in tension and in compression.  An entry
 *   {materials: [a, b], failure_strain: e_t | tensile_strength: S,
 *    compressive_failure_strain: e_c, stiffness_factor: f}
 * (each key optional, at most one of the first two, the pair in either order,
 * once) multiplies the pair's stiffness by f (every bond type; the stable
 * time step follows) and sets its failure strains: e_t given, or S / E_ab
 * with E_ab = f 2 E_a E_b / (E_a + E_b), the Young's modulus of the pair's
 * series spring ([Wang2010] Eq. 26, eps_max = sigma_TS / E, with the pair's
 * modulus).  Linear law only: the other laws tie the failure strain to
 * their force curve (Lennard-Jones peak, piecewise-linear end, softening
 * branch), which an interface entry would have to rebuild.  Angular springs
 * keep the per-particle constants of their vertex.
 */
#include "models/lattice/lattice_internal.h"

#include "core/options.h"
#include "core/sim.h"
#include "spall/error.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

int lattice_interfaces_parse(struct model *m, const struct deck_node *params,
                             struct spall_error *err)
{
    static const char *const keys[] = {"materials", "failure_strain", "tensile_strength",
                                       "compressive_failure_strain", "stiffness_factor", NULL};
    const struct deck_node *list = NULL;
    int rc = deck_list(params, "interfaces", "a list of {materials: [a, b], ...}", &list, err);
    if (rc || !list)
        return rc;
    if (m->opt.law != LATTICE_LAW_LINEAR)
        return deck_error_key(err, params, "interfaces", "interfaces need law: linear (the "
                              "other laws tie the failure strain to their force curve)");
    m->ifc = calloc(list->n ? list->n : 1, sizeof *m->ifc);
    if (!m->ifc)
        return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory for interfaces");
    for (size_t k = 0; k < list->n; k++) {
        const struct deck_node *e = list->items[k];
        struct lattice_interface *q = &m->ifc[k];
        q->stiffness = 1.0;
        q->ia = q->ib = -1;
        if ((rc = deck_expect_map(e, "an interface {materials: [a, b], ...}", err)))
            return rc;
        if ((rc = deck_material_pair(e, q->a, q->b, sizeof q->a, err)))
            return rc;
        if ((rc = deck_double_pos(e, "failure_strain", false, &q->eps_t, err)) ||
            (rc = deck_double_pos(e, "tensile_strength", false, &q->strength, err)) ||
            (rc = deck_double_pos(e, "compressive_failure_strain", false, &q->eps_c, err)) ||
            (rc = deck_double_pos(e, "stiffness_factor", false, &q->stiffness, err)) ||
            (rc = deck_check_unused(e, "model.interfaces entry", keys, err)))
            return rc;
        if (q->eps_t > 0.0 && q->strength > 0.0)
            return deck_error(err, e, "interface: give failure_strain or tensile_strength, "
                              "not both");
        for (size_t j = 0; j < k; j++)
            if ((!strcmp(m->ifc[j].a, q->a) && !strcmp(m->ifc[j].b, q->b)) ||
                (!strcmp(m->ifc[j].a, q->b) && !strcmp(m->ifc[j].b, q->a)))
                return deck_error(err, deck_get(e, "materials"), "interface %s-%s given twice",
                                  q->a, q->b);
        m->n_ifc++;
    }
    return SPALL_OK;
}

int lattice_interfaces_resolve(struct model *m, const struct sim *sim, struct spall_error *err)
{
    for (size_t k = 0; k < m->n_ifc; k++) {
        struct lattice_interface *q = &m->ifc[k];
        q->ia = sim_find_material(sim, q->a);
        q->ib = sim_find_material(sim, q->b);
        if (q->ia < 0 || q->ib < 0) {
            char key[64];
            snprintf(key, sizeof key, "model.interfaces[%zu].materials", k);
            return spall_error_set_key(err, SPALL_ERR_INPUT, key,
                                       "interface: no material '%s' in this run",
                                       q->ia < 0 ? q->a : q->b);
        }
    }
    return SPALL_OK;
}

void lattice_interfaces_apply(struct model *m)
{
    const size_t nm = m->n_mat;
    for (size_t k = 0; k < m->n_ifc; k++) {
        const struct lattice_interface *q = &m->ifc[k];
        if (q->ia < 0 || q->ib < 0)
            continue; /* not resolved yet: init resolves before the pair table */
        const struct lattice_material *A = &m->mat[q->ia], *B = &m->mat[q->ib];
        const double Eab = q->stiffness * 2.0 * A->E * B->E / (A->E + B->E);
        const double et = q->eps_t > 0.0 ? q->eps_t : q->strength > 0.0 ? q->strength / Eab : 0.0;
        for (int t = 0; t < LATTICE_MAX_TYPES; t++) {
            struct lattice_bond_law *w = &m->pair[((size_t)q->ia * nm + (size_t)q->ib) *
                                                      LATTICE_MAX_TYPES + (size_t)t];
            w->k *= q->stiffness;
            w->dfdr_max *= q->stiffness;
            if (et > 0.0)
                w->t_lim = 1.0 + et;
            if (q->eps_c > 0.0)
                w->c_lim = 1.0 - q->eps_c;
            m->pair[((size_t)q->ib * nm + (size_t)q->ia) * LATTICE_MAX_TYPES + (size_t)t] = *w;
        }
    }
}
