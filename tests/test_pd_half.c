/**
 * @file test_pd_half.c
 * @brief The once-per-bond PMB loop (src/models/peridynamics/pd_half.c)
 *        gives the split kernel's results bit for bit (pd_forces.c: every
 *        half-bond from its own row) on 1, 2 and 3 threads: positions,
 *        velocities, forces, bond states and the released energy of
 *        fracture runs of a 3D block (both break orders, compact and full
 *        bond storage), a pre-cracked 2D plate with the surface correction
 *        (coefficients that differ bond by bond) and a 1D bar.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include "tests/test_support.h"

#include "core/bond_list.h"
#include "core/particles.h"
#include "core/sim.h"
#include "models/peridynamics/pd.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#ifdef _OPENMP
#include <omp.h>
#endif

/* what a run leaves: positions, velocities, forces (dim each), bond states */
struct pd_snap {
    size_t n, nh, broken;
    int dim;
    double *xvf;
    uint8_t *state;
    double dissipated;
    bool half;
};

/* Run @p deck to its end on @p threads threads, the split kernel only when
 * @p split. */
static struct pd_snap pd_run(const char *deck, int threads, bool split)
{
#ifdef _OPENMP
    omp_set_num_threads(threads);
#else
    (void)threads;
#endif
    struct sim *s = test_build_ok(deck);
    pd_set_row_loop(s->model, split);
    test_run_to_end(s);
    struct pd_snap r = {.n = s->p->n_owned, .dim = s->dim};
    double *const *what[3] = {s->p->x, s->p->v, s->p->f};
    r.xvf = malloc(3 * (size_t)r.dim * r.n * sizeof *r.xvf);
    assert_non_null(r.xvf);
    for (size_t q = 0; q < 3 * (size_t)r.dim; q++)
        memcpy(r.xvf + q * r.n, what[q / (size_t)r.dim][q % (size_t)r.dim], r.n * sizeof(double));
    r.state = test_copy_states(pd_bonds(s->model), &r.nh);
    r.broken = bond_list_count_broken(pd_bonds(s->model));
    sim_update_energy(s);
    r.dissipated = s->energy.model_dissipated;
    r.half = pd_used_half_loop(s->model);
    sim_destroy(&s);
#ifdef _OPENMP
    omp_set_num_threads(1);
#endif
    return r;
}

/* @p a and @p b bit for bit: sizes, positions, velocities, forces, bond
 * states and released energy. */
static void pd_same(const struct pd_snap *a, const struct pd_snap *b)
{
    assert_true(a->n == b->n && a->nh == b->nh && a->dim == b->dim);
    assert_memory_equal(a->xvf, b->xvf, 3 * (size_t)a->dim * a->n * sizeof(double));
    assert_memory_equal(a->state, b->state, a->nh);
    assert_memory_equal(&a->dissipated, &b->dissipated, sizeof(double));
}

static void pd_snap_free(struct pd_snap *r)
{
    free(r->xvf);
    free(r->state);
}

/* The split kernel on one thread against the once-per-bond loop on 1, 2
 * and 3 threads; @p min_broken bonds must have broken. */
static void pd_check(const char *what, const char *deck, size_t min_broken)
{
    struct pd_snap ref = pd_run(deck, 1, true);
    assert_false(ref.half);
    print_message("%s: %zu particles, %zu broken bonds, %.6g J released\n", what, ref.n,
                  ref.broken, ref.dissipated);
    assert_true(ref.broken >= min_broken);
    assert_true(ref.dissipated > 0.0);
    for (int t = 1; t <= 3; t++) {
        struct pd_snap h = pd_run(deck, t, false);
        assert_true(h.half); /* the loop under test ran */
        pd_same(&h, &ref);
        pd_snap_free(&h);
    }
    pd_snap_free(&ref);
}

/* the race deck of bench/pd_vs_lammps.sh, smaller and pulled faster; long
 * in z, the slowest index, so that each of 3 threads has rows further than
 * a bond's index span from its range's ends */
static void block(const char *what, const char *model_extra)
{
    char deck[2048];
    snprintf(deck, sizeof deck,
             "model: {type: peridynamics, horizon_factor: 3.015, partial_volume_rule: lammps%s}\n"
             "materials:\n  glass: {density: 2440, bulk_modulus: 48.0e9, "
             "critical_stretch: 0.002}\n"
             "lattice: {type: sc, spacing: 1.0e-3}\n"
             "geometry:\n  block: {box: {min: [-0.0005, -0.0005, -0.0005], max: [0.0115, "
             "0.0075, 0.0235]}}\n"
             "body: {geometry: block, material: glass}\n"
             "groups:\n  left: {box: {min: [-1, -1, -1], max: [0.0015, 1, 1]}}\n"
             "  right: {box: {min: [0.0095, -1, -1], max: [1, 1, 1]}}\n"
             "boundary_conditions:\n"
             "  - {group: left, type: velocity, components: [x], value: -50.0}\n"
             "  - {group: right, type: velocity, components: [x], value: 50.0}\n"
             "run: {dt: 5.0e-8, dt_override: true, steps: 80}\n",
             model_extra);
    pd_check(what, deck, 100);
}

static void test_block_next_step(void **state)
{
    (void)state;
    block("3D block, next_step", ", break_order: next_step");
}

static void test_block_immediate(void **state)
{
    (void)state;
    block("3D block, immediate", "");
}

static void test_block_full(void **state)
{
    (void)state;
    block("3D block, full storage", ", break_order: next_step, bond_storage: full");
}

/* a pre-cracked square plate pulled apart, with the surface correction */
static void test_plate(void **state)
{
    (void)state;
    pd_check("2D plate",
             "model: {type: peridynamics, surface_correction: true}\n"
             "materials:\n  glass: {density: 2440, youngs_modulus: 72.0e9, "
             "fracture_energy: 3.8}\n"
             "lattice: {type: square, spacing: 1.0e-3, thickness: 1.0e-3}\n"
             "geometry:\n  plate: {box: {min: [0, 0], max: [0.03, 0.02]}}\n"
             "body: {geometry: plate, material: glass}\n"
             "precracks:\n  - {from: [-0.001, 0.0105], to: [0.008, 0.0105]}\n"
             "groups:\n  bottom: {box: {min: [-1, -1], max: [1, 0.0015]}}\n"
             "  top: {box: {min: [-1, 0.0185], max: [1, 1]}}\n"
             "boundary_conditions:\n"
             "  - {group: bottom, type: velocity, components: [y], value: -20.0}\n"
             "  - {group: top, type: velocity, components: [y], value: 20.0}\n"
             "run: {dt: 5.0e-8, dt_override: true, steps: 150}\n",
             10);
}

/* a bar pulled apart at its ends */
static void test_bar(void **state)
{
    (void)state;
    pd_check("1D bar",
             "model: {type: peridynamics}\n"
             "materials:\n  m: {density: 1000, youngs_modulus: 1.0e9, "
             "critical_stretch: 0.01}\n"
             "lattice: {type: chain, spacing: 1.0e-3, thickness: 1.0e-6}\n"
             "geometry:\n  b: {box: {min: [0], max: [0.0405]}}\n"
             "body: {geometry: b, material: m}\n"
             "groups:\n  l: {box: {min: [-1], max: [0.0015]}}\n"
             "  r: {box: {min: [0.039], max: [1]}}\n"
             "boundary_conditions:\n"
             "  - {group: l, type: velocity, components: [x], value: -20.0}\n"
             "  - {group: r, type: velocity, components: [x], value: 20.0}\n"
             "run: {dt: 1.0e-7, dt_override: true, steps: 300}\n",
             1);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_block_next_step), cmocka_unit_test(test_block_immediate),
        cmocka_unit_test(test_block_full),      cmocka_unit_test(test_plate),
        cmocka_unit_test(test_bar),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
