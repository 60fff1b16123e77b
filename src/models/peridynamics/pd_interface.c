/**
 * @file pd_interface.c
 * @brief Bonds between two materials (deck `model.interfaces`, issue 26
 *        item 3): a law per material pair for the bonds that join them.
 *
 * Without an entry a bond between materials a and b breaks at the smaller
 * of their critical stretches (the weaker of the two) and, with pair forces
 * (formulation bond), has the micromodulus of the two halves in series,
 * 2 c_a c_b / (c_a + c_b) (pd_forces.c); a state-based bond (lps, eps) takes
 * each end's own moduli in its half of the force state (pd_lps.c).  An entry
 *   {materials: [a, b], critical_stretch: s0 | fracture_energy: G,
 *    stiffness_factor: f}
 * sets the pair's critical stretch, given or from G (formulation bond: the
 * G -> s0 relation of the bulk, pd_critical_stretch, with the pair's
 * micromodulus f 2 c_a c_b / (c_a + c_b); lps/eps: pd_lps_critical_stretch
 * with the smaller bulk and shear moduli of a and b, the weaker side), and
 * multiplies the pair's micromodulus by f (formulation bond only: the force
 * state of lps/eps has no per-bond stiffness of its own).  Isotropic
 * materials only (a lamina's fiber and matrix bonds keep their own laws).
 */
#include "models/peridynamics/pd_internal.h"

#include "core/bond_list.h"
#include "core/options.h"
#include "core/particles.h"
#include "core/sim.h"
#include "spall/error.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

int pd_interfaces_parse(struct model *m, const struct deck_node *params,
                        struct spall_error *err)
{
    static const char *const keys[] = {"materials", "critical_stretch", "fracture_energy",
                                       "stiffness_factor", NULL};
    const struct deck_node *list = NULL;
    int rc = deck_list(params, "interfaces", "a list of {materials: [a, b], ...}", &list, err);
    if (rc || !list)
        return rc;
    if (list->n > PD_MAX_MAT * PD_MAX_MAT)
        return deck_error(err, list, "%zu interfaces; at most %d", list->n,
                          PD_MAX_MAT * PD_MAX_MAT);
    m->ifc = calloc(list->n ? list->n : 1, sizeof *m->ifc);
    if (!m->ifc)
        return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory for interfaces");
    for (size_t k = 0; k < list->n; k++) {
        const struct deck_node *e = list->items[k];
        struct pd_interface *q = &m->ifc[k];
        q->stiffness = 1.0;
        if ((rc = deck_expect_map(e, "an interface {materials: [a, b], ...}", err)))
            return rc;
        if ((rc = deck_material_pair(e, q->a, q->b, sizeof q->a, err)))
            return rc;
        if ((rc = deck_double_pos(e, "critical_stretch", false, &q->s0, err)) ||
            (rc = deck_double_pos(e, "fracture_energy", false, &q->G, err)) ||
            (rc = deck_double_pos(e, "stiffness_factor", false, &q->stiffness, err)) ||
            (rc = deck_check_unused(e, "model.interfaces entry", keys, err)))
            return rc;
        if (q->s0 > 0.0 && q->G > 0.0)
            return deck_error(err, e, "interface: give critical_stretch or fracture_energy, "
                              "not both");
        if (m->opt.lps && deck_peek(e, "stiffness_factor"))
            return deck_error_key(err, e, "stiffness_factor", "stiffness_factor is for "
                                  "formulation bond: a state-based bond takes each end's own "
                                  "moduli");
        for (size_t j = 0; j < k; j++)
            if ((!strcmp(m->ifc[j].a, q->a) && !strcmp(m->ifc[j].b, q->b)) ||
                (!strcmp(m->ifc[j].a, q->b) && !strcmp(m->ifc[j].b, q->a)))
                return deck_error(err, deck_get(e, "materials"), "interface %s-%s given twice",
                                  q->a, q->b);
        m->n_ifc++;
    }
    return SPALL_OK;
}

int pd_interfaces_apply(struct model *m, struct sim *sim, struct spall_error *err)
{
    const size_t nm = m->n_mat;
    const struct bond_list *bl = m->bl;
    for (size_t k = 0; k < m->n_ifc; k++) {
        const struct pd_interface *q = &m->ifc[k];
        const int ia = sim_find_material(sim, q->a), ib = sim_find_material(sim, q->b);
        char key[64];
        snprintf(key, sizeof key, "model.interfaces[%zu].materials", k);
        if (ia < 0 || ib < 0)
            return spall_error_set_key(err, SPALL_ERR_INPUT, key,
                                       "interface: no material '%s' in this run",
                                       ia < 0 ? q->a : q->b);
        const struct pd_material *A = &m->mat[ia], *B = &m->mat[ib];
        if (A->ortho || B->ortho)
            return spall_error_set_key(err, SPALL_ERR_INPUT, key,
                                       "interface %s-%s: interfaces join isotropic materials "
                                       "(a lamina keeps its fiber and matrix laws)", q->a, q->b);
        double s0 = q->s0;
        if (q->G > 0.0) {
            if (m->opt.lps)
                s0 = pd_lps_critical_stretch(sim->dim, fmin(A->kd, B->kd), fmin(A->mu, B->mu),
                                             q->G, m->delta);
            else if (m->opt.variant == PD_PDLM)
                s0 = pd_pdlm_critical_stretch(q->stiffness * 2.0 * A->E * B->E / (A->E + B->E),
                                              q->G, m->dx);
            else
                s0 = pd_critical_stretch(sim->dim, q->stiffness * 2.0 * A->c * B->c /
                                                       (A->c + B->c),
                                         q->G, m->delta, sim->thickness);
        }
        for (int f = 0; f < 2; f++)
            if (s0 > 0.0) {
                m->s0_tab[((size_t)ia * nm + (size_t)ib) * 2 + (size_t)f] = s0;
                m->s0_tab[((size_t)ib * nm + (size_t)ia) * 2 + (size_t)f] = s0;
            }
        if (q->stiffness != 1.0 && !m->opt.lps) {
            const uint8_t t1 = (uint8_t)(((size_t)ia * nm + (size_t)ib) * 2);
            const uint8_t t2 = (uint8_t)(((size_t)ib * nm + (size_t)ia) * 2);
            for (size_t s = 0; m->coef && s < bl->offset[bl->n]; s++)
                if ((bl->type[s] & ~1u) == t1 || (bl->type[s] & ~1u) == t2)
                    m->coef[s] *= q->stiffness;
        }
    }
    return SPALL_OK;
}

double pd_interface_scale(const struct model *m, const struct sim *sim, uint8_t type,
                          double coef)
{
    const size_t nm = m->n_mat;
    for (size_t k = 0; k < m->n_ifc; k++) {
        const struct pd_interface *q = &m->ifc[k];
        const int ia = sim_find_material(sim, q->a), ib = sim_find_material(sim, q->b);
        if (ia < 0 || ib < 0 || q->stiffness == 1.0 || m->opt.lps)
            continue; /* pd_interfaces_apply reports the unknown name */
        const uint8_t t1 = (uint8_t)(((size_t)ia * nm + (size_t)ib) * 2);
        const uint8_t t2 = (uint8_t)(((size_t)ib * nm + (size_t)ia) * 2);
        if ((type & ~1u) == t1 || (type & ~1u) == t2)
            coef *= q->stiffness;
    }
    return coef;
}
