/**
 * @file lattice_material.c
 * @brief Material section of a lattice deck: the keys of each axial law
 *        (linear, Lennard-Jones, piecewise-linear curve, softening), thermal
 *        keys, calibration of the spring constants (moved out of
 *        lattice_model.c to keep files short; keys listed there and in
 *        docs/decks.md).
 */
#include "models/lattice/lattice_calib.h"
#include "models/lattice/lattice_honeycomb.h"
#include "models/lattice/lattice_internal.h"
#include "models/lattice/lattice_softening.h"
#include "models/lattice/lattice_thermal.h"

#include "core/particles.h"
#include "core/sim.h"
#include "core/options.h"
#include "core/model.h"
#include "spall/error.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

void lattice_curve_free(struct lattice_curve *c)
{
    free(c->e);
    free(c->g);
    free(c->slope);
    free(c->G);
    memset(c, 0, sizeof *c);
}

/** Read `curve` into a normalised lattice_curve; *E0 = first slope. */
static int parse_curve(const struct deck_node *node, struct lattice_curve *cv, double *E0,
                       struct spall_error *err)
{
    const struct deck_node *c = deck_get(node, "curve");
    int rc = deck_expect_seq(c, "a list of [strain, stress] points", err);
    if (rc)
        return rc;
    if (c->n < 2)
        return deck_error(err, c, "curve needs at least 2 points; expected [[0, 0], [e1, s1], ...]");
    size_t n = c->n;
    cv->n = n;
    cv->e = calloc(n, sizeof *cv->e);
    cv->g = calloc(n, sizeof *cv->g);
    cv->slope = calloc(n, sizeof *cv->slope);
    cv->G = calloc(n, sizeof *cv->G);
    if (!cv->e || !cv->g || !cv->slope || !cv->G)
        return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory for a curve");
    for (size_t k = 0; k < n; k++) {
        const struct deck_node *pt = c->items[k];
        if ((rc = deck_expect_seq(pt, "a [strain, stress] pair", err)))
            return rc;
        if (pt->n != 2)
            return deck_error(err, pt, "curve point has %zu numbers; expected [strain, stress]",
                              pt->n);
        if ((rc = deck_node_double(pt->items[0], &cv->e[k], err)) ||
            (rc = deck_node_double(pt->items[1], &cv->g[k], err)))
            return rc;
        if (k == 0 && (cv->e[0] != 0.0 || cv->g[0] != 0.0))
            return deck_error(err, pt, "curve must start at [0, 0]");
        if (k > 0 && !(cv->e[k] > cv->e[k - 1]))
            return deck_error(err, pt, "curve strain %g is not above the previous %g; expected "
                              "strictly increasing strain", cv->e[k], cv->e[k - 1]);
    }
    *E0 = cv->g[1] / cv->e[1];
    if (!(*E0 > 0.0))
        return deck_error(err, c->items[1], "curve's first slope must be positive (got %g Pa)",
                          *E0);
    for (size_t k = 0; k < n; k++)
        cv->g[k] /= *E0;
    for (size_t k = 0; k + 1 < n; k++)
        cv->slope[k] = (cv->g[k + 1] - cv->g[k]) / (cv->e[k + 1] - cv->e[k]);
    cv->slope[n - 1] = cv->slope[n - 2];
    cv->G[0] = 0.0;
    for (size_t k = 1; k < n; k++) {
        double d = cv->e[k] - cv->e[k - 1];
        cv->G[k] = cv->G[k - 1] + 0.5 * (cv->g[k] + cv->g[k - 1]) * d;
    }
    return SPALL_OK;
}

int lattice_parse_material(struct model *m, struct sim *sim, int index,
                                  const struct deck_node *node, struct spall_error *err)
{
    static const char *const k_lin[] = {"density", "youngs_modulus", "poisson_ratio",
                                        "tensile_strength", "failure_strain",
                                        "compressive_failure_strain", "angular_failure",
                                        LATTICE_THERMAL_KEYS, NULL};
    static const char *const k_lj[] = {"density", "youngs_modulus", "poisson_ratio",
                                       "failure_strain", "compressive_failure_strain",
                                       "angular_failure", "exponents", LATTICE_THERMAL_KEYS,
                                       NULL};
    static const char *const k_soft[] = {"density", "youngs_modulus", "poisson_ratio",
                                         "tensile_strength", "onset_strain", "fracture_energy",
                                         "failure_strain", "compressive_failure_strain",
                                         "angular_failure", LATTICE_THERMAL_KEYS, NULL};
    static const char *const k_pwl[] = {"density", "youngs_modulus", "poisson_ratio", "curve",
                                        "compressive_failure_strain", "angular_failure",
                                        LATTICE_THERMAL_KEYS, NULL};
    const char *name = sim->materials[index].name;
    char what[SPALL_NAME_LEN + 16];
    snprintf(what, sizeof what, "materials.%s", name);
    const enum lattice_law law = m->opt.law;
    const enum lattice_kind kind = sim->lattice.kind;
    struct lattice_material mt;
    memset(&mt, 0, sizeof mt);
    mt.eps_t = mt.eps_c = INFINITY;
    mt.dphi_c = mt.dphi_t = INFINITY;
    int rc;
    if ((rc = deck_double_pos(node, "youngs_modulus", law != LATTICE_LAW_PWL, &mt.E, err)))
        goto fail;
    mt.nu_given = deck_peek(node, "poisson_ratio") != NULL;
    mt.nu = (kind == LATTICE_SC || kind == LATTICE_FCC) ? 0.25 : 1.0 / 3.0;
    if ((rc = deck_double(node, "poisson_ratio", kind != LATTICE_CHAIN, -1.0, 1.0, &mt.nu, err)))
        goto fail;
    double sts = 0.0, eps = 0.0, epc = 0.0;
    if (law != LATTICE_LAW_PWL &&
        (rc = deck_double_pos(node, "failure_strain", false, &eps, err)))
        goto fail;
    if (law == LATTICE_LAW_SOFT) {
        if ((rc = lattice_soft_parse(node, what, eps, &mt, err)))
            goto fail;
    } else if (law == LATTICE_LAW_LINEAR) {
        if ((rc = deck_double_pos(node, "tensile_strength", false, &sts, err)))
            goto fail;
        if ((sts > 0.0) == (eps > 0.0)) {
            rc = deck_error(err, node, "%s: give exactly one of tensile_strength [Pa] and "
                            "failure_strain ([Wang2010] Eq. 26)", what);
            goto fail;
        }
        mt.eps_t = eps > 0.0 ? eps : sts / mt.E;
        mt.eps_t_given = true;
    } else if (law == LATTICE_LAW_LJ) {
        if (eps > 0.0) {
            mt.eps_t = eps;
            mt.eps_t_given = true;
        }
        double pq[2] = {0, 0};
        if ((rc = deck_vector(node, "exponents", true, 2, 2, pq, err)))
            goto fail;
        if (!(pq[0] >= 1.0) || !(pq[1] > pq[0])) {
            rc = deck_error_key(err, node, "exponents", "exponents [%g, %g]; expected [p, q] "
                                "with q > p >= 1 ([Wang2010] Eq. 1)", pq[0], pq[1]);
            goto fail;
        }
        mt.lj_p = pq[0];
        mt.lj_q = pq[1];
    } else {
        double E0 = 0.0;
        if ((rc = parse_curve(node, &mt.curve, &E0, err)))
            goto fail;
        if (mt.E > 0.0 && fabs(mt.E - E0) > 0.01 * E0) {
            rc = deck_error_key(err, node, "youngs_modulus", "youngs_modulus %g Pa differs from "
                                "the curve's first slope %g Pa by more than 1%%", mt.E, E0);
            goto fail;
        }
        mt.E = E0;
        mt.eps_t = mt.curve.e[mt.curve.n - 1];
        mt.eps_t_given = true;
    }
    if ((rc = deck_double_pos(node, "compressive_failure_strain", false, &epc, err)))
        goto fail;
    if (epc > 0.0)
        mt.eps_c = epc;
    if (deck_peek(node, "angular_failure")) {
        double lim[2] = {0, 0};
        if ((rc = deck_vector(node, "angular_failure", true, 2, 2, lim, err)))
            goto fail;
        if (!(lim[0] > 0.0) || !(lim[1] > 0.0)) {
            rc = deck_error_key(err, node, "angular_failure", "angular_failure [%g, %g]; "
                                "expected [dphi_c, dphi_t] both > 0 rad", lim[0], lim[1]);
            goto fail;
        }
        mt.ang_fail = true;
        mt.dphi_c = lim[0];
        mt.dphi_t = lim[1];
    }
    if ((rc = lattice_thermal_parse_material(m, sim, index, node, err)))
        goto fail;
    const char *const *allowed = law == LATTICE_LAW_LINEAR ? k_lin
                                 : law == LATTICE_LAW_LJ   ? k_lj
                                 : law == LATTICE_LAW_SOFT ? k_soft
                                                           : k_pwl;
    if ((rc = deck_check_unused(node, what, allowed, err)))
        goto fail;
    /* the lattice decides which nu are possible: refuse here, with a position */
    struct lattice_calib c;
    memset(&c, 0, sizeof c);
    c.kind = kind;
    c.layers = m->opt.layers;
    c.angular = m->opt.angular;
    c.second_layer_ratio = m->opt.second_layer_ratio;
    c.E = mt.E;
    c.nu = mt.nu;
    c.r0 = sim->lattice.spacing > 0.0 ? sim->lattice.spacing : 1.0;
    c.thickness = sim->thickness > 0.0 ? sim->thickness : 1.0;
    if (lattice_calibrate(&c, err)) {
        char msg[SPALL_ERROR_MSG_LEN];
        snprintf(msg, sizeof msg, "%s", err->msg);
        deck_error_key(err, node, "poisson_ratio", "%s: %s", what, msg);
        err->code = SPALL_ERR_PHYSICS;
        rc = SPALL_ERR_PHYSICS;
        goto fail;
    }
    return lattice_model_set_material(m, index, &mt, err);
fail:
    lattice_curve_free(&mt.curve);
    return rc;
}
