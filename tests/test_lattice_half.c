/**
 * @file test_lattice_half.c
 * @brief The once-per-bond linear loop (src/models/lattice/lattice_half.c)
 *        gives the row loop's results bit for bit (lattice_forces.c: every
 *        bond from both rows) on 1, 2 and 3 threads: positions, velocities,
 *        forces, bond states and the released energy of fracture runs of a
 *        1D chain, a 2D alpha plate of one and of two neighbour shells (bond
 *        types), a 2D alpha-beta plate (angular springs) and a 3D FCC block.
 *        The alpha plate takes the stencil blocks for most rows
 *        (lattice_stencil_rows) and the general blocks around its broken
 *        bonds: both paths and their hand-over in one run.  The chain
 *        breaks in its first step (a stencil block that falls back before
 *        its pushes; on 2 and 3 threads the intact part takes them); the
 *        FCC block's order of particles has no runs.  Every run also
 *        checks that the model's force call writes the forces without
 *        reading them (model_ops.sets_forces).
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include "tests/test_support.h"

#include "core/bond_list.h"
#include "core/model.h"
#include "core/particles.h"
#include "core/sim.h"
#include "models/lattice/lattice.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#ifdef _OPENMP
#include <omp.h>
#endif

/* what a run leaves: positions, velocities, forces (dim each), bond states */
struct snap {
    size_t n, nh;
    int dim;
    double *xvf;
    uint8_t *state;
    double dissipated;
    size_t broken;
    bool half;
    size_t stencil_rows; /* the largest count of one step */
};

static void set_threads(int t)
{
#ifdef _OPENMP
    omp_set_num_threads(t);
#else
    (void)t;
#endif
}

/* The model writes the owned forces without reading them
 * (model_ops.sets_forces: the integrator does not clear them): two force
 * calls at the end state, one on cleared forces, one on NaNs, give the
 * same bits (the state does not change: the step's own call at these
 * positions broke what breaks). */
static void check_sets_forces(struct sim *s)
{
    struct particles *p = s->p;
    const size_t n = p->n_owned;
    struct spall_error err = {0};
    assert_true(s->ops->sets_forces);
    double *fa = malloc((size_t)s->dim * (n ? n : 1) * sizeof *fa);
    assert_non_null(fa);
    particles_zero_forces(p);
    assert_int_equal(s->ops->compute_forces(s->model, s, &err), SPALL_OK);
    for (int d = 0; d < s->dim; d++) {
        memcpy(fa + (size_t)d * n, p->f[d], n * sizeof *fa);
        for (size_t i = 0; i < n; i++)
            p->f[d][i] = NAN;
    }
    assert_int_equal(s->ops->compute_forces(s->model, s, &err), SPALL_OK);
    for (int d = 0; d < s->dim; d++)
        assert_memory_equal(p->f[d], fa + (size_t)d * n, n * sizeof *fa);
    free(fa);
}

/* Run @p deck for @p steps on @p threads threads, the row loop only when
 * @p rows. */
static struct snap run(const char *deck, long steps, int threads, bool rows)
{
    set_threads(threads);
    struct sim *s = test_build_ok(deck);
    lattice_set_row_loop(s->model, rows);
    struct spall_error err = {0};
    struct snap r = {0};
    for (long k = 0; k < steps && !sim_done(s); k++) {
        assert_int_equal(sim_step(s, &err), SPALL_OK);
        if (lattice_stencil_rows(s->model) > r.stencil_rows)
            r.stencil_rows = lattice_stencil_rows(s->model);
    }
    const struct particles *p = s->p;
    r.n = p->n_owned;
    r.dim = s->dim;
    r.xvf = malloc(3 * (size_t)r.dim * r.n * sizeof *r.xvf);
    assert_non_null(r.xvf);
    for (int d = 0; d < r.dim; d++) {
        memcpy(r.xvf + (size_t)(3 * d) * r.n, p->x[d], r.n * sizeof(double));
        memcpy(r.xvf + (size_t)(3 * d + 1) * r.n, p->v[d], r.n * sizeof(double));
        memcpy(r.xvf + (size_t)(3 * d + 2) * r.n, p->f[d], r.n * sizeof(double));
    }
    const struct bond_list *bl = lattice_bond_list(s->model);
    r.nh = bl->offset[bl->n];
    r.state = malloc(r.nh ? r.nh : 1);
    assert_non_null(r.state);
    memcpy(r.state, bl->state, r.nh);
    r.broken = bond_list_count_broken(bl);
    sim_update_energy(s);
    r.dissipated = s->energy.model_dissipated;
    r.half = lattice_used_half_loop(s->model);
    check_sets_forces(s);
    sim_destroy(&s);
    set_threads(1);
    return r;
}

static void snap_free(struct snap *r)
{
    free(r->xvf);
    free(r->state);
}

/* what the stencil blocks must take: more than half of the rows in some
 * step, no row, or any count */
enum stencil_use { STENCIL_MOST, STENCIL_NONE, STENCIL_ANY };

/* The row loop on one thread against the once-per-bond loop on 1, 2 and 3
 * threads; @p min_broken bonds must have broken. */
static void check_deck(const char *what, const char *deck, long steps, size_t min_broken,
                       enum stencil_use stencil)
{
    struct snap ref = run(deck, steps, 1, true);
    assert_false(ref.half);
    assert_int_equal(ref.stencil_rows, 0);
    print_message("%s: %zu particles, %zu broken bonds after %ld steps\n", what, ref.n,
                  ref.broken, steps);
    assert_true(ref.broken >= min_broken);
    for (int t = 1; t <= 3; t++) {
        struct snap h = run(deck, steps, t, false);
        assert_true(h.half); /* the loop under test ran */
        print_message("  %d thread(s): stencil blocks took up to %zu rows a step\n", t,
                      h.stencil_rows);
        if (stencil == STENCIL_MOST)
            assert_true(2 * h.stencil_rows > h.n);
        else if (stencil == STENCIL_NONE)
            assert_int_equal(h.stencil_rows, 0);
        assert_int_equal(h.n, ref.n);
        assert_int_equal(h.nh, ref.nh);
        assert_memory_equal(h.xvf, ref.xvf, 3 * (size_t)ref.dim * ref.n * sizeof(double));
        assert_memory_equal(h.state, ref.state, ref.nh);
        assert_memory_equal(&h.dissipated, &ref.dissipated, sizeof(double));
        snap_free(&h);
    }
    snap_free(&ref);
}

static void test_chain(void **state)
{
    (void)state;
    check_deck("chain",
               "model: {type: lattice, law: linear}\n"
               "materials: {m: {density: 1000, youngs_modulus: 1.0e9, "
               "poisson_ratio: 0.3333333333333333, failure_strain: 0.005}}\n"
               "lattice: {type: chain, spacing: 1.0e-3}\n"
               "body: {geometry: {box: {min: [-0.0005], max: [0.0405]}}, material: m}\n"
               "groups:\n"
               "  l: {box: {min: [-0.001], max: [0.0005]}}\n"
               "  r: {box: {min: [0.0395], max: [0.041]}}\n"
               "boundary_conditions:\n"
               "  - {group: l, type: fixed}\n"
               "  - {group: r, type: velocity, value: 20.0}\n"
               "run: {end_time: 2.0e-5}\n",
               400, 1, STENCIL_ANY);
}

/* a pre-cracked plate pulled apart at its grips (validation case
 * lattice-threads at a coarser spacing), Poisson ratio @p nu: 1/3 axial
 * springs only, 0.2 with angular springs; @p layers neighbour shells */
static void plate(const char *what, const char *nu, int layers, enum stencil_use stencil)
{
    char deck[2048];
    snprintf(deck, sizeof deck,
             "model: {type: lattice, law: linear, layers: %d}\n"
             "materials:\n"
             "  p: {density: 1140, youngs_modulus: 3.0e9, poisson_ratio: %s, "
             "tensile_strength: 60.0e6}\n"
             "lattice: {type: triangular, spacing: 1.0e-3}\n"
             "body: {geometry: {box: {min: [-0.0001, -0.0001], max: [0.0301, 0.0150]}}, "
             "material: p}\n"
             "groups:\n"
             "  bottom: {box: {min: [-1, -1], max: [1, 0.0010]}}\n"
             "  top: {box: {min: [-1, 0.0140], max: [1, 1]}}\n"
             "precracks:\n"
             "  - {from: [-0.001, 0.00736], to: [0.012, 0.00736]}\n"
             "boundary_conditions:\n"
             "  - {group: bottom, type: velocity, components: [x, y], value: [0, -8.0],\n"
             "     function: {type: linear_ramp, duration: 1.0e-5}}\n"
             "  - {group: top, type: velocity, components: [x, y], value: [0, 8.0],\n"
             "     function: {type: linear_ramp, duration: 1.0e-5}}\n"
             "run: {end_time: 1.0e-3}\n",
             layers, nu);
    check_deck(what, deck, 1500, 10, stencil);
}

static void test_plate_alpha(void **state)
{
    (void)state;
    plate("alpha plate", "0.3333333333333333", 1, STENCIL_MOST);
}

static void test_plate_angles(void **state)
{
    (void)state;
    plate("alpha-beta plate", "0.2", 1, STENCIL_NONE); /* angles: general blocks */
}

/* an FCC block pulled apart in z */
static void test_fcc(void **state)
{
    (void)state;
    char deck[2048];
    snprintf(deck, sizeof deck, "%s",
             "model: {type: lattice, law: linear}\n"
             "materials: {m: {density: 2000, youngs_modulus: 1.0e9, poisson_ratio: 0.25, "
             "failure_strain: 0.01}}\n"
             "lattice: {type: fcc, spacing: 1.0e-3}\n"
             "body: {geometry: {box: {min: [0, 0, 0], max: [0.0045, 0.0045, 0.0085]}}, "
             "material: m}\n"
             "groups:\n"
             "  lo: {box: {min: [-1, -1, -1], max: [1, 1, 0.0005]}}\n"
             "  hi: {box: {min: [-1, -1, 0.008], max: [1, 1, 1]}}\n"
             "boundary_conditions:\n"
             "  - {group: lo, type: velocity, components: [z], value: -10.0}\n"
             "  - {group: hi, type: velocity, components: [z], value: 10.0}\n"
             "run: {end_time: 1.0e-3}\n");
    check_deck("fcc block", deck, 600, 1, STENCIL_NONE);
}

/* two neighbour shells (bond types): the alpha plate with layers: 2 */
static void test_plate_two_shells(void **state)
{
    (void)state;
    plate("alpha plate, two shells", "0.3333333333333333", 2, STENCIL_NONE); /* types */
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_chain),
        cmocka_unit_test(test_plate_alpha),
        cmocka_unit_test(test_plate_angles),
        cmocka_unit_test(test_fcc),
        cmocka_unit_test(test_plate_two_shells),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
