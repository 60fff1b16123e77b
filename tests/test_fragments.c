/* Tests for core/fragments.h: a plate cut in two by a pre-crack gives two
 * fragments with the right masses and ids; labels of a fracturing run are the
 * same with 1 and 2 threads; the fragment_id field exists for bonded models. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include "tests/test_support.h"

#include "core/bond_list.h"
#include "core/fields.h"
#include "core/fragments.h"
#include "core/particles.h"
#include "core/sim.h"
#include "core/model.h"
#include "spall/error.h"

#include <math.h>
#include <omp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* 20 x 10 mm plate (alpha-beta: axial + angular springs); pre-crack at x = 10.25 mm across
 * the whole height (plus a stub that ends inside, which must not split) */
static const char *plate_deck =
    "model: {type: lattice, law: linear}\n"
    "materials:\n"
    "  m: {density: 1000, youngs_modulus: 1.0e9, poisson_ratio: 0.25, failure_strain: 0.01}\n"
    "lattice: {type: triangular, spacing: 1.0e-3}\n"
    "geometry:\n"
    "  plate: {box: {min: [0, 0], max: [0.0201, 0.0101]}}\n"
    "body: {geometry: plate, material: m}\n"
    "precracks:\n"
    "  - {from: [0.01025, -0.001], to: [0.01025, 0.011]}\n"
    "  - {from: [0.00525, -0.001], to: [0.00525, 0.0045]}\n"
    "run: {end_time: 1.0e-6}\n";

static void test_plate_cut_in_two(void **state)
{
    (void)state;
    struct sim *s = test_build_ok(plate_deck);
    const struct particles *p = s->p;
    struct fragments *f = NULL;
    struct spall_error err = {0};
    assert_int_equal(fragments_create(&f, p->n_owned, &err), SPALL_OK);
    assert_int_equal(fragments_of_sim(f, s, &err), SPALL_OK);
    assert_int_equal(fragments_count(f), 2);
    /* expected: masses and smallest gids of the two sides */
    double m_left = 0.0, m_right = 0.0;
    int64_t id_left = INT64_MAX, id_right = INT64_MAX;
    size_t n_left = 0;
    for (size_t i = 0; i < p->n_owned; i++) {
        if (p->x0[0][i] < 0.01025) {
            m_left += p->mass[i];
            n_left++;
            id_left = p->gid[i] < id_left ? p->gid[i] : id_left;
        } else {
            m_right += p->mass[i];
            id_right = p->gid[i] < id_right ? p->gid[i] : id_right;
        }
    }
    const struct fragment_info *fi = fragments_list(f);
    const struct fragment_info *a = fi[0].id == id_left ? &fi[0] : &fi[1];
    const struct fragment_info *b = fi[0].id == id_left ? &fi[1] : &fi[0];
    assert_true(a->id == id_left && b->id == id_right);
    assert_int_equal(a->count, n_left);
    assert_true(fabs(a->mass - m_left) <= 1e-12 * m_left);
    assert_true(fabs(b->mass - m_right) <= 1e-12 * m_right);
    const int64_t *lab = fragments_labels(f);
    for (size_t i = 0; i < p->n_owned; i++)
        assert_true(lab[i] == (p->x0[0][i] < 0.01025 ? id_left : id_right));
    struct fragment_summary sum;
    fragments_summarise(f, &sum);
    assert_int_equal(sum.count, 2);
    assert_int_equal(sum.singles, 0);
    assert_true(fabs(sum.total_mass - (m_left + m_right)) <= 1e-12 * sum.total_mass);
    assert_true(sum.largest_mass >= sum.second_mass && sum.second_mass > 0.0);
    /* centre-of-mass velocity and kinetic energy of a moving fragment */
    for (size_t i = 0; i < p->n_owned; i++) {
        p->v[0][i] = p->x0[0][i] < 0.01025 ? -2.0 : 3.0;
        p->v[1][i] = 0.0;
    }
    assert_int_equal(fragments_of_sim(f, s, &err), SPALL_OK);
    fi = fragments_list(f);
    a = fi[0].id == id_left ? &fi[0] : &fi[1];
    b = fi[0].id == id_left ? &fi[1] : &fi[0];
    assert_true(fabs(a->vcm[0] + 2.0) < 1e-12 && fabs(b->vcm[0] - 3.0) < 1e-12);
    assert_true(fabs(a->kinetic - 0.5 * m_left * 4.0) <= 1e-12 * a->kinetic);
    assert_true(fabs(b->kinetic_cm - 0.5 * m_right * 9.0) <= 1e-12 * b->kinetic);
    /* the output field */
    const struct field_desc *fd = field_registry_find(s->fields, "fragment_id");
    assert_non_null(fd);
    double *out = malloc(p->n_owned * sizeof *out);
    field_gather_f64(fd, p->n_owned, out);
    for (size_t i = 0; i < p->n_owned; i++)
        assert_true(out[i] == (double)lab[i]);
    free(out);
    fragments_destroy(&f);
    assert_null(f);
    sim_destroy(&s);
}

/* a small plate pulled apart fast enough to shatter near the grips */
static const char *burst_deck =
    "model: {type: lattice, law: linear}\n"
    "materials:\n"
    "  m: {density: 1000, youngs_modulus: 1.0e9, poisson_ratio: 0.3333333333333333, "
    "failure_strain: 0.002}\n"
    "lattice: {type: triangular, spacing: 1.0e-3}\n"
    "geometry:\n"
    "  plate: {box: {min: [0, 0], max: [0.0301, 0.0151]}}\n"
    "body: {geometry: plate, material: m}\n"
    "groups:\n"
    "  l: {box: {min: [-1, -1], max: [0.0015, 1]}}\n"
    "  r: {box: {min: [0.0285, -1], max: [1, 1]}}\n"
    "boundary_conditions:\n"
    "  - {group: l, type: velocity, components: [x, y], value: [-20, 5]}\n"
    "  - {group: r, type: velocity, components: [x, y], value: [20, -5]}\n"
    "run: {end_time: 1.0e-4}\n";

static void test_thread_independence(void **state)
{
    (void)state;
    int saved = omp_get_max_threads();
    int64_t *labels[2] = {NULL, NULL};
    size_t nf[2] = {0, 0}, n = 0;
    struct spall_error err = {0};
    for (int pass = 0; pass < 2; pass++) {
        omp_set_num_threads(pass == 0 ? 1 : 2);
        struct sim *s = test_build_ok(burst_deck);
        for (int k = 0; k < 300; k++)
            assert_int_equal(sim_step(s, &err), SPALL_OK);
        struct fragments *f = NULL;
        n = s->p->n_owned;
        assert_int_equal(fragments_create(&f, n, &err), SPALL_OK);
        assert_int_equal(fragments_of_sim(f, s, &err), SPALL_OK);
        nf[pass] = fragments_count(f);
        labels[pass] = malloc(n * sizeof *labels[pass]);
        memcpy(labels[pass], fragments_labels(f), n * sizeof *labels[pass]);
        fragments_destroy(&f);
        sim_destroy(&s);
    }
    omp_set_num_threads(saved);
    assert_true(nf[0] >= 2);
    assert_int_equal(nf[0], nf[1]);
    assert_memory_equal(labels[0], labels[1], n * sizeof *labels[0]);
    free(labels[0]);
    free(labels[1]);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_plate_cut_in_two),
        cmocka_unit_test(test_thread_independence),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
