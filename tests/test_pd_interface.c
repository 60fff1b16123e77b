/*
 * Tests of the bonds between materials (model.interfaces,
 * src/models/peridynamics/pd_interface.c):
 *  - a plate of two materials pulled apart breaks only interface bonds when
 *    the interface's critical stretch is the lowest (formulations bond and
 *    lps), and none of them when its critical stretch is above the bulk ones
 *    (the bulk, weaker material then breaks);
 *  - stiffness_factor f scales the interface bonds only: the strain energy of
 *    a uniform strain is linear in f, W(f) = W_bulk + f W_ifc;
 *  - the deck refuses an unknown material, a pair given twice, a material
 *    paired with itself, stiffness_factor with lps and both s0 and G.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include "core/bond_list.h"
#include "core/model.h"
#include "core/particles.h"
#include "core/sim.h"
#include "io/deck.h"
#include "io/deck_build.h"
#include "models/peridynamics/pd.h"
#include "spall/error.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static int build(const char *yaml, struct sim **s, struct spall_error *err)
{
    struct deck *d = NULL;
    *s = NULL;
    int rc = deck_load_string(&d, "test", yaml, err);
    if (rc)
        return rc;
    struct run_output ro;
    rc = deck_build_sim(d, s, &ro, err);
    deck_destroy(&d);
    return rc;
}

/* Two halves (a: x < 10 mm, b: x > 10 mm) of a 20 x 10 mm plate. */
static void deck(char *buf, size_t len, const char *model, const char *ifc, const char *run)
{
    snprintf(buf, len,
             "model: {type: peridynamics, %s%s}\n"
             "materials:\n"
             "  a: {density: 1000, youngs_modulus: 1.0e9, poisson_ratio: %s, "
             "critical_stretch: 0.02}\n"
             "  b: {density: 1000, youngs_modulus: 3.0e9, poisson_ratio: %s, "
             "critical_stretch: 0.01}\n"
             "lattice: {type: square, spacing: 1.0e-3, thickness: 1.0e-3}\n"
             "geometry:\n  left: {box: {min: [0, 0], max: [0.0099, 0.0101]}}\n"
             "  right: {box: {min: [0.0099, 0], max: [0.0201, 0.0101]}}\n"
             "bodies:\n  - {geometry: left, material: a}\n  - {geometry: right, material: b}\n"
             "groups:\n  l: {box: {min: [-1, -1], max: [0.0015, 1]}}\n"
             "  r: {box: {min: [0.0185, -1], max: [1, 1]}}\n"
             "boundary_conditions:\n"
             "  - {group: l, type: velocity, components: [x], value: -2.0}\n"
             "  - {group: r, type: velocity, components: [x], value: 2.0}\n"
             "%s",
             model, ifc, strstr(model, "lps") ? "0.3" : "0.3333333333333333",
             strstr(model, "lps") ? "0.3" : "0.3333333333333333", run);
}

/* Pull until bonds break; count broken bonds by kind (interface or not). */
static void pull(const char *model, const char *ifc, size_t *n_ifc, size_t *n_bulk)
{
    char buf[2048];
    deck(buf, sizeof buf, model, ifc, "run: {end_time: 4.0e-5}\n");
    struct spall_error err = {0};
    struct sim *s = NULL;
    int rc = build(buf, &s, &err);
    if (rc)
        fprintf(stderr, "%s\n", err.msg);
    assert_int_equal(rc, 0);
    while (s->t < 4.0e-5 && !rc)
        rc = sim_step(s, &err);
    assert_int_equal(rc, 0);
    const struct bond_list *bl = pd_bonds(s->model);
    const struct particles *p = s->p;
    *n_ifc = *n_bulk = 0;
    for (size_t i = 0; i < p->n; i++)
        for (size_t k = bl->offset[i]; k < bl->offset[i + 1]; k++)
            if (bl->state[k] & BOND_BROKEN) {
                if (p->material[i] != p->material[bl->partner[k]])
                    (*n_ifc)++;
                else
                    (*n_bulk)++;
            }
    printf("  %s %s: broken half-bonds: %zu interface, %zu bulk\n", model, ifc, *n_ifc,
           *n_bulk);
    sim_destroy(&s);
}

static void test_weak_interface(void **state)
{
    (void)state;
    static const char *const models[] = {"formulation: bond", "formulation: lps"};
    for (int k = 0; k < 2; k++) {
        size_t ni, nb;
        pull(models[k], ", interfaces: [{materials: [a, b], critical_stretch: 0.002}]", &ni,
             &nb);
        assert_true(ni > 0);
        assert_int_equal(nb, 0);
        /* a strong interface: the weaker bulk (b, s0 = 0.01) goes first */
        pull(models[k], ", interfaces: [{materials: [b, a], critical_stretch: 0.5}]", &ni, &nb);
        assert_int_equal(ni, 0);
        assert_true(nb > 0);
    }
}

static double strain_energy(const char *ifc)
{
    char buf[2048];
    deck(buf, sizeof buf, "formulation: bond", ifc, "run: {end_time: 1.0}\n");
    struct spall_error err = {0};
    struct sim *s = NULL;
    int rc = build(buf, &s, &err);
    if (rc)
        fprintf(stderr, "%s\n", err.msg);
    assert_int_equal(rc, 0);
    struct particles *p = s->p;
    for (size_t i = 0; i < p->n; i++) {
        p->x[0][i] = p->x0[0][i] * (1 + 1e-4);
        p->x[1][i] = p->x0[1][i];
    }
    struct model_energy e;
    memset(&e, 0, sizeof e);
    s->ops->energy(s->model, s, &e);
    sim_destroy(&s);
    return e.strain;
}

static void test_stiffness_factor(void **state)
{
    (void)state;
    const double w1 = strain_energy("");
    const double w2 = strain_energy(", interfaces: [{materials: [a, b], stiffness_factor: 2}]");
    const double w3 = strain_energy(", interfaces: [{materials: [a, b], stiffness_factor: 3}]");
    printf("  strain energy at f = 1, 2, 3: %.9g %.9g %.9g J\n", w1, w2, w3);
    assert_true(w2 > w1 * (1 + 1e-3));
    assert_true(fabs((w3 - w2) - (w2 - w1)) < 1e-9 * w1);
}

static void refused(const char *model, const char *ifc, const char *want)
{
    char buf[2048];
    deck(buf, sizeof buf, model, ifc, "run: {end_time: 1.0}\n");
    struct spall_error err = {0};
    struct sim *s = NULL;
    assert_int_not_equal(build(buf, &s, &err), 0);
    printf("  refused: %s\n", err.msg);
    assert_non_null(strstr(err.msg, want));
    assert_null(s);
}

static void test_deck(void **state)
{
    (void)state;
    refused("formulation: bond", ", interfaces: [{materials: [a, c], critical_stretch: 0.01}]",
            "no material 'c'");
    refused("formulation: bond", ", interfaces: [{materials: [a, a]}]", "twice");
    refused("formulation: bond", ", interfaces: [{materials: [a, b]}, {materials: [b, a]}]",
            "given twice");
    refused("formulation: lps", ", interfaces: [{materials: [a, b], stiffness_factor: 2}]",
            "formulation bond");
    refused("formulation: bond",
            ", interfaces: [{materials: [a, b], critical_stretch: 0.01, fracture_energy: 1}]",
            "not both");
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_weak_interface),
        cmocka_unit_test(test_stiffness_factor),
        cmocka_unit_test(test_deck),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
