/**
 * @file test_lattice_interface.c
 * @brief Bonds between two materials in the lattice model (model.interfaces,
 *        src/models/lattice/lattice_interface.c):
 *  - the default pair law: the two springs in series and the smaller failure
 *    strain; an entry's stiffness_factor, failure_strain, tensile_strength
 *    (over the pair's series modulus) and compressive_failure_strain, the
 *    same for [a, b] and [b, a];
 *  - a plate of two materials pulled apart breaks only interface bonds when
 *    the interface is the weakest, none when it is the strongest;
 *  - the deck refuses an unknown material, a pair given twice, a material
 *    paired with itself, both failure_strain and tensile_strength, and a law
 *    other than linear.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include "core/bond_list.h"
#include "models/lattice/lattice.h"
#include "models/lattice/lattice_laws.h"
#include "tests/test_support.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* A 20 x 10 mm triangular-lattice plate: material a for x < 10 mm, b beyond
 * (a region: lattice bonds do not cross bodies), ends pulled apart. */
static void deck(char *buf, size_t len, const char *model, const char *ifc, const char *run)
{
    snprintf(buf, len,
             "model: {type: lattice%s%s}\n"
             "materials:\n"
             "  a: {density: 1000, youngs_modulus: 1.0e9, poisson_ratio: 0.3333333333333333, "
             "failure_strain: 0.02}\n"
             "  b: {density: 1000, youngs_modulus: 3.0e9, poisson_ratio: 0.3333333333333333, "
             "failure_strain: 0.005}\n"
             "lattice: {type: triangular, spacing: 1.0e-3, thickness: 1.0e-3}\n"
             "body: {geometry: {box: {min: [0, 0], max: [0.0201, 0.0101]}}, material: a}\n"
             "regions: [{geometry: {box: {min: [0.0099, -1], max: [1, 1]}}, material: b}]\n"
             "groups:\n  l: {box: {min: [-1, -1], max: [0.0015, 1]}}\n"
             "  r: {box: {min: [0.0185, -1], max: [1, 1]}}\n"
             "boundary_conditions:\n"
             "  - {group: l, type: velocity, components: [x], value: -2.0}\n"
             "  - {group: r, type: velocity, components: [x], value: 2.0}\n"
             "%s",
             model, ifc, run);
}

static void test_pair_laws(void **state)
{
    (void)state;
    char buf[2048];
    deck(buf, sizeof buf, "", "", "run: {end_time: 1.0e-6}\n");
    struct sim *s = test_build_ok(buf);
    const struct lattice_bond_law *aa = lattice_pair_law(s->model, 0, 0, 0);
    const struct lattice_bond_law *bb = lattice_pair_law(s->model, 1, 1, 0);
    const struct lattice_bond_law *ab = lattice_pair_law(s->model, 0, 1, 0);
    const double k_ser = 2.0 * aa->k * bb->k / (aa->k + bb->k);
    assert_true(fabs(ab->k / k_ser - 1.0) < 1e-12);
    assert_true(fabs(ab->t_lim - 1.005) < 1e-12); /* the weaker: b's 0.005 */
    const double k_aa = aa->k, k_bb = bb->k;
    sim_destroy(&s);

    deck(buf, sizeof buf, "",
         ", interfaces: [{materials: [b, a], failure_strain: 0.002, stiffness_factor: 0.5, "
         "compressive_failure_strain: 0.05}]",
         "run: {end_time: 1.0e-6}\n");
    s = test_build_ok(buf);
    for (int o = 0; o < 2; o++) {
        const struct lattice_bond_law *w = lattice_pair_law(s->model, o, 1 - o, 0);
        assert_true(fabs(w->k / (0.5 * k_ser) - 1.0) < 1e-12);
        assert_true(fabs(w->dfdr_max / (0.5 * k_ser) - 1.0) < 1e-12);
        assert_true(fabs(w->t_lim - 1.002) < 1e-12);
        assert_true(fabs(w->c_lim - 0.95) < 1e-12);
    }
    /* the bulk pairs keep their own laws */
    assert_true(lattice_pair_law(s->model, 0, 0, 0)->k == k_aa);
    assert_true(lattice_pair_law(s->model, 1, 1, 0)->k == k_bb);
    assert_true(fabs(lattice_pair_law(s->model, 1, 1, 0)->t_lim - 1.005) < 1e-12);
    sim_destroy(&s);

    /* tensile_strength over the pair's series modulus f 2 E_a E_b / (E_a + E_b) */
    deck(buf, sizeof buf, "",
         ", interfaces: [{materials: [a, b], tensile_strength: 3.0e6, stiffness_factor: 2.0}]",
         "run: {end_time: 1.0e-6}\n");
    s = test_build_ok(buf);
    const double Eab = 2.0 * 2.0 * 1e9 * 3e9 / 4e9;
    assert_true(fabs(lattice_pair_law(s->model, 0, 1, 0)->t_lim - (1.0 + 3e6 / Eab)) < 1e-12);
    sim_destroy(&s);
}

/* Pull until bonds break; count broken half-bonds by kind. */
static void pull(const char *ifc, size_t *n_ifc, size_t *n_bulk)
{
    char buf[2048];
    deck(buf, sizeof buf, "", ifc, "run: {end_time: 8.0e-5}\n");
    struct sim *s = test_build_ok(buf);
    struct spall_error err = {0};
    while (!sim_done(s))
        assert_int_equal(sim_step(s, &err), SPALL_OK);
    const struct bond_list *bl = lattice_bond_list(s->model);
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
    print_message("lattice %s: broken half-bonds: %zu interface, %zu bulk\n", ifc, *n_ifc,
                  *n_bulk);
    sim_destroy(&s);
}

static void test_weak_and_strong_interface(void **state)
{
    (void)state;
    size_t ni, nb;
    pull(", interfaces: [{materials: [a, b], failure_strain: 0.002}]", &ni, &nb);
    assert_true(ni > 0);
    assert_int_equal(nb, 0);
    /* a strong interface: the weaker bulk goes first (b: 0.005 of 3 GPa, 15
     * MPa, against a's 20 MPa) */
    pull(", interfaces: [{materials: [b, a], failure_strain: 0.5}]", &ni, &nb);
    assert_int_equal(ni, 0);
    assert_true(nb > 0);
}

static void test_refusals(void **state)
{
    (void)state;
    char buf[2048];
    const char *run = "run: {end_time: 1.0e-6}\n";
    deck(buf, sizeof buf, "", ", interfaces: [{materials: [a, c], failure_strain: 0.01}]", run);
    test_deck_refused(buf, "no material 'c'");
    deck(buf, sizeof buf, "",
         ", interfaces: [{materials: [a, b]}, {materials: [b, a], failure_strain: 0.01}]", run);
    test_deck_refused(buf, "given twice");
    deck(buf, sizeof buf, "", ", interfaces: [{materials: [a, a]}]", run);
    test_deck_refused(buf, "twice");
    deck(buf, sizeof buf, "",
         ", interfaces: [{materials: [a, b], failure_strain: 0.01, tensile_strength: 1.0e6}]",
         run);
    test_deck_refused(buf, "not both");
    deck(buf, sizeof buf, ", law: lennard_jones",
         ", interfaces: [{materials: [a, b], failure_strain: 0.01}]", run);
    test_deck_refused(buf, "law: linear");
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_pair_laws),
        cmocka_unit_test(test_weak_and_strong_interface),
        cmocka_unit_test(test_refusals),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
