/*
 * Compact families of the peridynamics kernels (pd_compact.c): the same
 * problems run with bond_storage compact and full give the same positions,
 * velocities, bond states and energies bit for bit (3D PMB with breaking in
 * both break orders, 2D with the surface correction, whose coefficients
 * differ bond by bond near the edges; LPS and EPS in 3D and 2D, their table
 * holding omega beta, built by pd_lps_init), and the layouts the table does not
 * take keep the arrays (LPS with its surface correction).
 */
#include <setjmp.h>
#include <stdbool.h>
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

#include <stdio.h>
#include <string.h>

static struct sim *build_ok(const char *yaml)
{
    struct spall_error err = {0};
    struct deck *d = NULL;
    struct sim *s = NULL;
    struct run_output ro;
    int rc = deck_load_string(&d, "test", yaml, &err);
    if (!rc)
        rc = deck_build_sim(d, &s, &ro, &err);
    deck_destroy(&d);
    if (rc)
        fprintf(stderr, "%s\n", err.msg);
    assert_int_equal(rc, 0);
    return s;
}

/* A 3D SC block pulled apart at its ends (the deck of bench/pd_vs_lammps.sh,
 * smaller and faster so that bonds break), or a 2D square plate. */
static void deck(char *buf, size_t len, int dim, const char *model_extra, const char *storage)
{
    /* lps / eps take E and nu (eps a yield stress low enough to yield here) */
    const bool st = strstr(model_extra, "lps") || strstr(model_extra, "eps");
    const char *st_mat = !st ? ""
                         : strstr(model_extra, "eps") ? "poisson_ratio: 0.25, yield_stress: 5.0e7, "
                                                      : "poisson_ratio: 0.25, ";
    if (dim == 3)
        snprintf(buf, len,
                 "model: {type: peridynamics, horizon_factor: 3.015, partial_volume_rule: "
                 "lammps, bond_storage: %s%s}\n"
                 "materials:\n  glass: {density: 2440, %s: 48.0e9, %s"
                 "critical_stretch: 0.002}\n"
                 "lattice: {type: sc, spacing: 1.0e-3}\n"
                 "geometry:\n  block: {box: {min: [-0.0005, -0.0005, -0.0005], max: [0.0095, "
                 "0.0075, 0.0075]}}\n"
                 "body: {geometry: block, material: glass}\n"
                 "groups:\n  left: {box: {min: [-1, -1, -1], max: [0.0015, 1, 1]}}\n"
                 "  right: {box: {min: [0.0075, -1, -1], max: [1, 1, 1]}}\n"
                 "boundary_conditions:\n"
                 "  - {group: left, type: velocity, components: [x], value: -50.0}\n"
                 "  - {group: right, type: velocity, components: [x], value: 50.0}\n"
                 "run: {dt: 5.0e-8, dt_override: true, steps: 60}\n",
                 storage, model_extra, st ? "youngs_modulus" : "bulk_modulus", st_mat);
    else
        snprintf(buf, len,
                 "model: {type: peridynamics, bond_storage: %s%s}\n"
                 "materials:\n  glass: {density: 2440, youngs_modulus: 72.0e9, "
                 "%sfracture_energy: 3.8}\n"
                 "lattice: {type: square, spacing: 1.0e-3, thickness: 1.0e-3}\n"
                 "geometry:\n  plate: {box: {min: [0, 0], max: [0.02, 0.01]}}\n"
                 "body: {geometry: plate, material: glass}\n"
                 "groups:\n  left: {box: {min: [-1, -1], max: [0.0015, 1]}}\n"
                 "  right: {box: {min: [0.0185, -1], max: [1, 1]}}\n"
                 "boundary_conditions:\n"
                 "  - {group: left, type: velocity, components: [x], value: -40.0}\n"
                 "  - {group: right, type: velocity, components: [x], value: 40.0}\n"
                 "run: {dt: 5.0e-8, dt_override: true, steps: 80}\n",
                 storage, model_extra, st_mat);
}

static void run(struct sim *s)
{
    struct spall_error err = {0};
    int rc = 0;
    while (!sim_done(s) && !rc)
        rc = sim_step(s, &err);
    if (rc)
        fprintf(stderr, "%s\n", err.msg);
    assert_int_equal(rc, 0);
}

/* Runs the deck in both storages; returns the bonds broken (counted once). */
static size_t same_both_ways(int dim, const char *model_extra)
{
    char buf[2048];
    deck(buf, sizeof buf, dim, model_extra, "compact");
    struct sim *a = build_ok(buf);
    deck(buf, sizeof buf, dim, model_extra, "full");
    struct sim *b = build_ok(buf);
    assert_true(pd_compact_kinds(a->model) > 0);
    assert_int_equal(pd_compact_kinds(b->model), 0);
    run(a);
    run(b);
    const struct particles *pa = a->p, *pb = b->p;
    assert_int_equal(pa->n, pb->n);
    for (int d = 0; d < dim; d++) {
        assert_memory_equal(pa->x[d], pb->x[d], pa->n * sizeof(double));
        assert_memory_equal(pa->v[d], pb->v[d], pa->n * sizeof(double));
    }
    const struct bond_list *ba = pd_bonds(a->model), *bb = pd_bonds(b->model);
    const size_t nh = ba->offset[ba->n];
    assert_int_equal(nh, bb->offset[bb->n]);
    assert_memory_equal(ba->state, bb->state, nh);
    struct model_energy ea, eb;
    a->ops->energy(a->model, a, &ea);
    b->ops->energy(b->model, b, &eb);
    assert_memory_equal(&ea.strain, &eb.strain, sizeof(double));
    assert_memory_equal(&ea.dissipated, &eb.dissipated, sizeof(double));
    assert_true(ea.strain > 0.0);
    size_t broken = bond_list_count_broken(ba);
    printf("  %dD%s: %zu table rows, %zu of %zu bonds broken\n", dim, model_extra,
           pd_compact_kinds(a->model), broken, bond_list_count(ba));
    sim_destroy(&a);
    sim_destroy(&b);
    return broken;
}

static void test_same_3d(void **state)
{
    (void)state;
    assert_true(same_both_ways(3, ", break_order: next_step") > 0);
    assert_true(same_both_ways(3, "") > 0);
}

static void test_same_2d_surface(void **state)
{
    (void)state;
    assert_true(same_both_ways(2, ", surface_correction: true") > 0);
}

/* LPS and EPS (pd_lps_init): the rows hold the lengths, omega beta and
 * types; with influence inverse and partial volumes the family has several
 * values of omega beta, and cubic makes them differ by direction. */
static void test_same_lps_eps(void **state)
{
    (void)state;
    assert_true(same_both_ways(3, ", formulation: lps, influence: inverse, break_order: "
                                  "next_step") > 0);
    assert_true(same_both_ways(3, ", formulation: eps") > 0);
    assert_true(same_both_ways(2, ", formulation: lps, influence_correction: cubic") > 0);
    assert_true(same_both_ways(2, ", formulation: eps, influence: inverse") > 0);
}

/* lps with its surface correction keeps its per-bond arrays: omega beta is
 * scaled bond by bond near the edges (pd_lps_surface.c). */
static void test_lps_surface_keeps_arrays(void **state)
{
    (void)state;
    char buf[2048];
    deck(buf, sizeof buf, 2, ", formulation: lps, surface_correction: true", "compact");
    struct sim *s = build_ok(buf);
    assert_int_equal(pd_compact_kinds(s->model), 0);
    sim_destroy(&s);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_same_3d),
        cmocka_unit_test(test_same_2d_surface),
        cmocka_unit_test(test_same_lps_eps),
        cmocka_unit_test(test_lps_surface_keeps_arrays),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
