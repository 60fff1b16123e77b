/* The macro-particle pair loop that evaluates each pair once
 * (model.pair_loop: half, src/models/macroparticle/macro_half.c) against the
 * reference loop that evaluates every pair from both ends (pair_loop: full):
 * positions, velocities, forces, every history value and the energy account
 * (pass 2's groups leave the energies to macro_half_epot) bit for bit equal,
 * on one and two threads, with pair plasticity, pairwise and absolute
 * Langevin forces at a temperature, the second FCC shell inside the
 * cut-off, an undamped elastic run (the vector finish of four rows,
 * half_finish4), the virial left out on the steps whose stress nothing
 * reads (sim.stress_skip), and neighbour-list rebuilds during the run; and the bounds
 * test that lets pass 2 leave the pair vectors of non-counting pairs
 * unmasked (macro_half_bounded). */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include "core/model.h"
#include "models/macroparticle/macro_half.h"
#include "tests/test_support.h"

#include <omp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* An aluminium block (above the loop's threading threshold of 2048
 * particles), its top pulled, its bottom fixed; %s: extra model keys. */
static const char *const BLOCK =
    "model: {type: macroparticle, %s}\n"
    "materials:\n"
    "  al: {density: 2700, atomic_mass_u: 26.98, cohesive_energy_ev: 3.39, exponents: [4, 9],\n"
    "       debye_temperature: 428%s}\n"
    "lattice: {type: fcc, spacing: 1.0e-3}\n"
    "geometry:\n"
    "  block: {box: {min: [0, 0, 0], max: [11.3e-3, 11.3e-3, 14.1e-3]}}\n"
    "body: {geometry: block, material: al}\n"
    "groups:\n"
    "  top: {box: {min: [-1, -1, 13.2e-3], max: [1, 1, 1]}}\n"
    "  bottom: {box: {min: [-1, -1, -1], max: [1, 1, 0.3e-3]}}\n"
    "boundary_conditions:\n"
    "  - {group: top, type: velocity, components: [z], value: 40.0}\n"
    "  - {group: bottom, type: fixed}\n"
    "run: {steps: 120, seed: 7}\n";

struct result {
    size_t n;
    double *xvf;  /* x, v, f: 9 n values */
    double hist[MODEL_HISTORY_MAX];
    const char *names[MODEL_HISTORY_MAX]; /* the model's string constants */
    size_t nh;
    double energy[2]; /* the account's strain (sum of the particles' energies), dissipated */
};

/* @p skip: sim.stress_skip on every step but each 7th and the last (as the
 * run loop sets it between history rows), or on every step (-1), or never
 * (0). */
static void run_skip(const char *model_keys, const char *material_keys, const char *loop,
                     int threads, int skip, struct result *out)
{
    char keys[256], text[2048];
    snprintf(keys, sizeof keys, "%s, pair_loop: %s", model_keys, loop);
    snprintf(text, sizeof text, BLOCK, keys, material_keys);
    omp_set_num_threads(threads);
    struct sim *s = test_build_ok(text);
    struct spall_error err = {0};
    while (!sim_done(s)) {
        const long k = s->step + 1;
        s->stress_skip = skip < 0 || (skip > 0 && k % 7 != 0 && k < s->n_steps);
        int rc = sim_step(s, &err);
        if (rc)
            print_error("%s\n", err.msg);
        assert_int_equal(rc, 0);
    }
    s->stress_skip = false;
    sim_update_energy(s); /* 3D half loop: the energies from the pair values */
    out->energy[0] = s->energy.strain;
    out->energy[1] = s->energy.model_dissipated;
    const size_t n = s->p->n_owned;
    out->n = n;
    out->xvf = malloc(9 * n * sizeof(double));
    assert_non_null(out->xvf);
    for (int c = 0; c < 3; c++) {
        memcpy(out->xvf + c * n, s->p->x[c], n * sizeof(double));
        memcpy(out->xvf + (3 + c) * n, s->p->v[c], n * sizeof(double));
        memcpy(out->xvf + (6 + c) * n, s->p->f[c], n * sizeof(double));
    }
    out->nh = s->ops->history(s->model, s, out->names, out->hist);
    for (size_t k = 0; k < out->nh; k++) {
        if (strcmp(out->names[k], "neighbor_builds") == 0)
            assert_true(out->hist[k] > 1.0); /* the list was rebuilt during the run */
    }
    sim_destroy(&s);
}

static void run(const char *model_keys, const char *material_keys, const char *loop,
                int threads, struct result *out)
{
    run_skip(model_keys, material_keys, loop, threads, 0, out);
}

static void assert_same(const struct result *a, const struct result *b)
{
    assert_int_equal(a->n, b->n);
    assert_memory_equal(a->xvf, b->xvf, 9 * a->n * sizeof(double));
    assert_int_equal(a->nh, b->nh);
    assert_memory_equal(a->hist, b->hist, a->nh * sizeof(double));
    assert_memory_equal(a->energy, b->energy, sizeof a->energy);
}

static void compare(const char *model_keys, const char *material_keys)
{
    struct result full, half1, half2;
    run(model_keys, material_keys, "full", 1, &full);
    assert_true(full.n >= 2048);
    run(model_keys, material_keys, "half", 1, &half1);
    run(model_keys, material_keys, "half", 2, &half2);
    assert_same(&full, &half1);
    assert_same(&full, &half2);
    free(full.xvf);
    free(half1.xvf);
    free(half2.xvf);
}

/* Pair plasticity and pairwise Langevin forces (random, keyed by the
 * pair): the plastic state and the negated partner term. */
static void test_plastic_pairwise(void **state)
{
    (void)state;
    compare("damping: pairwise, mu: 2.0e-3, temperature: 1.0e12",
            ", yield_strain: 0.002, hardening: 0.1");
}

/* The second shell inside the cut-off (the race deck's cutoff 1.5 and
 * taper 1.45), a thin skin, absolute Langevin forces. */
static void test_second_shell_absolute(void **state)
{
    (void)state;
    compare("cutoff: 1.5, taper: 1.45, skin: 0.05, damping: absolute, gamma: 1.0e-3, "
            "temperature: 1.0e12",
            "");
}

/* No damping, no plasticity (the race deck of bench/macro_vs_lammps.sh):
 * pass 2 finishes four rows at once with vector loads and stores. */
static void test_second_shell_elastic(void **state)
{
    (void)state;
    compare("cutoff: 1.5, taper: 1.45, skin: 0.05", "");
}

/* sim.stress_skip (the virial left out of pass 2's groups on the steps
 * whose stress nothing reads): positions, velocities, forces and, with the
 * last step's virial formed, every history value the full loop's on 1 and
 * 2 threads; skipped on every step, the stress of the history is an older
 * one (the flag acts) while the rest stays the same. */
static void test_stress_skip(void **state)
{
    (void)state;
    const char *keys = "cutoff: 1.5, taper: 1.45, skin: 0.05";
    struct result full, half1, half2, stale;
    run(keys, "", "full", 1, &full);
    run_skip(keys, "", "half", 1, 1, &half1);
    run_skip(keys, "", "half", 2, 1, &half2);
    assert_same(&full, &half1);
    assert_same(&full, &half2);
    run_skip(keys, "", "half", 1, -1, &stale);
    assert_memory_equal(full.xvf, stale.xvf, 9 * full.n * sizeof(double));
    assert_memory_equal(full.energy, stale.energy, sizeof full.energy);
    assert_int_equal(full.nh, stale.nh);
    size_t differ = 0;
    for (size_t k = 0; k < full.nh; k++) {
        const bool stress = strncmp(full.names[k], "stress_", 7) == 0;
        if (!stress)
            assert_memory_equal(&full.hist[k], &stale.hist[k], sizeof(double));
        else
            differ += memcmp(&full.hist[k], &stale.hist[k], sizeof(double)) != 0;
    }
    assert_true(differ > 0);
    free(full.xvf);
    free(half1.xvf);
    free(half2.xvf);
    free(stale.xvf);
}

/* macro_half_bounded: true only when every coordinate of the range lies
 * within +-1e300; a huge, infinite or NaN value in any component and at any
 * position (the four-lane part and the tail) makes it false. */
static void test_bounded(void **state)
{
    (void)state;
    enum { N = 11 };
    double c[3][N];
    for (int d = 0; d < 3; d++)
        for (int i = 0; i < N; i++)
            c[d][i] = (d + 1) * 1.0e-3 * i - 2.0e-3;
    double *const x[3] = {c[0], c[1], c[2]};
    assert_true(macro_half_bounded(x, 0, N));
    assert_true(macro_half_bounded(x, 3, 3)); /* an empty range */
    const double bad[] = {1.0e301, -1.0e301, INFINITY, -INFINITY, NAN};
    for (size_t b = 0; b < sizeof bad / sizeof bad[0]; b++)
        for (int d = 0; d < 3; d++)
            for (int i = 0; i < N; i++) {
                const double keep = c[d][i];
                c[d][i] = bad[b];
                assert_false(macro_half_bounded(x, 0, N));
                /* a range that leaves the value out */
                if (i > 0)
                    assert_true(macro_half_bounded(x, 0, (size_t)i));
                c[d][i] = keep;
            }
    c[1][5] = 1.0e300; /* the bound itself is inside */
    assert_true(macro_half_bounded(x, 0, N));
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_plastic_pairwise),
        cmocka_unit_test(test_second_shell_absolute),
        cmocka_unit_test(test_second_shell_elastic),
        cmocka_unit_test(test_stress_skip),
        cmocka_unit_test(test_bounded),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
