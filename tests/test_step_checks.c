/**
 * @file test_step_checks.c
 * @brief The time step's ownership rules seen from the library API:
 *        sim_step itself stops an energy blow-up (not only the CLI), and
 *        the model's drift velocity (XSPH) never moves a particle whose
 *        velocity a BC prescribes.  The second kick's kinetic-energy
 *        block sums and the passes with one uniform mass give the bits
 *        of the separate passes.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include "tests/test_support.h"

#include "core/step_passes.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* A lattice plate pulled at 1 m/s with dt 14x above its stability limit
 * (the deck of tests/cli/unstable_run.sh): the energy grows without
 * bound.  sim_step must stop it with SPALL_ERR_UNSTABLE on the energy
 * criterion while the state is still finite (the NaN check would fire only
 * later, after overflow), naming step, time and particle. */
static void test_energy_blowup_in_sim_step(void **state)
{
    (void)state;
    struct sim *s = test_build_ok(
        "model: {type: lattice}\n"
        "materials: {m: {density: 1000, youngs_modulus: 1.0e9, "
        "poisson_ratio: 0.3333333333333333, failure_strain: 10}}\n"
        "lattice: {type: triangular, spacing: 0.001}\n"
        "body: {geometry: {box: {min: [0, 0], max: [0.02, 0.02]}}, material: m}\n"
        "groups: {left: {box: {min: [-1, -1], max: [0.0006, 1]}}}\n"
        "boundary_conditions: [{group: left, type: velocity, components: [x], value: 1.0}]\n"
        "run: {steps: 400, dt: 2.0e-6, dt_override: true}\n");
    struct spall_error err = {0};
    int rc = SPALL_OK;
    while (!sim_done(s) && !(rc = sim_step(s, &err)))
        ;
    print_message("%s\n", err.msg);
    assert_int_equal(rc, SPALL_ERR_UNSTABLE);
    assert_non_null(strstr(err.msg, "times the energy put in"));
    assert_non_null(strstr(err.msg, "fastest particle"));
    for (size_t i = 0; i < s->p->n_owned; i++)
        for (int d = 0; d < s->dim; d++)
            assert_true(isfinite(s->p->x[d][i]) && isfinite(s->p->v[d][i]));
    sim_destroy(&s);
}

/* SPH plate with XSPH, clamped at x < 0, its free part moving: the clamp
 * particles' XSPH velocity is not zero (their neighbours move), yet a
 * prescribed velocity is the particle's whole motion, so they stay at x0
 * bit for bit; the free particles do move by it (the drift differs from
 * dt v). */
static void test_drift_velocity_skips_prescribed(void **state)
{
    (void)state;
    struct sim *s = test_build_ok(
        "model: {type: sph, kernel: cubic_spline, h_factor: 1.5, plane: strain, "
        "viscosity: [0, 0], xsph: 0.5, time_integration: leapfrog}\n"
        "materials: {rubber: {density: 1000, youngs_modulus: 2.0e6, poisson_ratio: 0.3975}}\n"
        "lattice: {type: square, spacing: 0.002, origin: [0.001, 0.001], thickness: 1.0}\n"
        "body: {geometry: {box: {min: [-0.01, -0.01], max: [0.04, 0.01]}}, material: rubber}\n"
        "groups: {clamp: {box: {min: [-1, -1], max: [0, 1]}}, "
        "free: {box: {min: [0, -1], max: [1, 1]}}}\n"
        "boundary_conditions: [{group: clamp, type: fixed}]\n"
        "initial_velocity: [{group: free, value: [0, 0.5]}]\n"
        "run: {steps: 20}\n");
    const struct particles *p = s->p;
    const struct group *clamp = &s->groups[sim_find_group(s, "clamp")];
    assert_true(clamp->n > 0);
    struct spall_error err = {0};
    double xsph_move = 0.0; /* largest |x_n+1 - x_n - dt v_n+1/2| of a free particle */
    for (int k = 0; k < 5; k++) {
        const size_t n = p->n_owned;
        double *x1 = malloc(n * sizeof *x1), *vh = malloc(n * sizeof *vh);
        assert_non_null(x1);
        assert_non_null(vh);
        for (size_t i = 0; i < n; i++) { /* y of the drift by v_n+1/2 alone */
            vh[i] = p->v[1][i] + 0.5 * s->dt * p->f[1][i] / p->mass[i];
            x1[i] = p->x[1][i];
        }
        const double dt = s->dt;
        assert_int_equal(sim_step(s, &err), SPALL_OK);
        for (size_t i = 0; i < n; i++)
            if (p->x0[0][i] > 0.0)
                xsph_move = fmax(xsph_move, fabs(p->x[1][i] - x1[i] - dt * vh[i]));
        free(x1);
        free(vh);
    }
    for (size_t q = 0; q < clamp->n; q++) {
        size_t i = clamp->idx[q];
        for (int d = 0; d < s->dim; d++)
            assert_true(p->x[d][i] == p->x0[d][i]);
    }
    /* XSPH moves the free particles: well above round-off of x (~1e-18 m) */
    print_message("largest XSPH displacement of a free particle %g m\n", xsph_move);
    assert_true(xsph_move > 1e-12);
    sim_destroy(&s);
}

/* Owned particles with velocities, forces and masses from a fixed
 * sequence (3 blocks and 5 more, so a block is partial and a tail is not
 * a multiple of four lanes); with @p uniform all masses are one double. */
static struct particles *pass_particles(bool uniform)
{
    struct particles *p = NULL;
    assert_int_equal(particles_create(&p, 2, 16, NULL), SPALL_OK);
    const size_t n = 3 * STEP_SUM_BLOCK + 5;
    uint64_t r = 88172645463325252u;
    for (size_t i = 0; i < n; i++) {
        const double pos[3] = {(double)i, 0.0, 0.0};
        assert_int_equal(particles_append(p, pos, 0, NULL, NULL), SPALL_OK);
        double u[5];
        for (int k = 0; k < 5; k++) { /* xorshift64: deterministic */
            r ^= r << 13;
            r ^= r >> 7;
            r ^= r << 17;
            u[k] = (double)(r >> 11) * 0x1p-53 - 0.5;
        }
        p->v[0][i] = u[0];
        p->v[1][i] = u[1];
        p->f[0][i] = 1e3 * u[2];
        p->f[1][i] = 1e3 * u[3];
        p->mass[i] = uniform ? 1.7e-6 : 1.7e-6 * (1.5 + u[4]);
    }
    return p;
}

static void assert_same_doubles(const double *a, const double *b, size_t n)
{
    assert_memory_equal(a, b, n * sizeof *a);
}

/* step_kick_sum against step_kick then step_block_mv2 per block: the
 * velocities and the block sums bit for bit, with masses read from the
 * array or the one uniform mass, on the test's threads (ctest: 2); and the
 * fused kick and drift with the uniform mass as with the array. */
static void test_kick_sum_matches_passes(void **state)
{
    (void)state;
    for (int uniform = 0; uniform < 2; uniform++) {
        struct particles *a = pass_particles(uniform), *b = pass_particles(uniform);
        const size_t n = a->n_owned, nb = (n + STEP_SUM_BLOCK - 1) / STEP_SUM_BLOCK;
        a->mass_uniform = uniform ? a->mass[0] : 0.0;
        double part[3 * 4] = {0};
        assert_true(nb <= 4);
        step_kick_sum(a, 3.5e-8, part);
        step_kick(b, 3.5e-8); /* b reads the masses */
        for (int d = 0; d < 2; d++) {
            assert_same_doubles(a->v[d], b->v[d], n);
            for (size_t k = 0; k < nb; k++) {
                const size_t lo = k * STEP_SUM_BLOCK;
                const size_t hi = lo + STEP_SUM_BLOCK < n ? lo + STEP_SUM_BLOCK : n;
                const double ref = step_block_mv2(b->mass, b->v[d], lo, hi);
                assert_memory_equal(&part[3 * k + (size_t)d], &ref, sizeof ref);
            }
        }
        step_kick_drift(a, 3.5e-8, 7e-8, true);
        step_kick_drift(b, 3.5e-8, 7e-8, true);
        for (int d = 0; d < 2; d++) {
            assert_same_doubles(a->v[d], b->v[d], n);
            assert_same_doubles(a->x[d], b->x[d], n);
            assert_same_doubles(a->f[d], b->f[d], n);
        }
        particles_destroy(&a);
        particles_destroy(&b);
    }
}

/* The run's first step finds the lattice's masses all equal; a mass
 * changed afterwards (particles_masses_changed) turns the uniform passes
 * off at the next step. */
static void test_uniform_mass_flag(void **state)
{
    (void)state;
    struct sim *s = test_build_ok(
        "model: {type: lattice}\n"
        "materials: {m: {density: 1000, youngs_modulus: 1.0e9, "
        "poisson_ratio: 0.3333333333333333, failure_strain: 10}}\n"
        "lattice: {type: triangular, spacing: 0.001}\n"
        "body: {geometry: {box: {min: [0, 0], max: [0.02, 0.02]}}, material: m}\n"
        "run: {steps: 4}\n");
    struct spall_error err = {0};
    assert_int_equal(sim_step(s, &err), SPALL_OK);
    assert_true(s->p->mass_checked);
    assert_true(s->p->mass_uniform > 0.0);
    assert_memory_equal(&s->p->mass_uniform, &s->p->mass[s->p->n_owned / 2], sizeof(double));
    s->p->mass[3] *= 1.25;
    particles_masses_changed(s->p);
    assert_int_equal(sim_step(s, &err), SPALL_OK);
    assert_true(s->p->mass_checked);
    assert_true(s->p->mass_uniform == 0.0);
    sim_destroy(&s);
}

/* The velocity conditions applied before the second kick (its kinetic
 * sums then see the final velocities) against after it: the same plate
 * with a no-slip impactor far from it, which keeps the separate passes.
 * Corner particles belong to two velocity BCs (x of both, y of one).
 * Positions, velocities, forces, reactions, work and the energy account
 * bit for bit. */
static void test_velocity_bcs_before_kick(void **state)
{
    (void)state;
    const char *deck =
        "model: {type: lattice}\n"
        "materials: {m: {density: 1000, youngs_modulus: 1.0e9, "
        "poisson_ratio: 0.3333333333333333, failure_strain: 0.01}}\n"
        "lattice: {type: triangular, spacing: 0.001}\n"
        "body: {geometry: {box: {min: [0, 0], max: [0.03, 0.012]}}, material: m}\n"
        "groups:\n"
        "  left: {box: {min: [-1, -1], max: [0.0006, 1]}}\n"
        "  corner: {box: {min: [-1, -1], max: [0.004, 0.0015]}}\n"
        "  right: {box: {min: [0.0294, -1], max: [1, 1]}}\n"
        "boundary_conditions:\n"
        "  - {group: left, type: velocity, components: [x], value: -2.0}\n"
        "  - {group: corner, type: velocity, components: [x, y], value: [-1.0, 0.5]}\n"
        "  - {group: right, type: fixed}\n"
        "run: {steps: 120}\n";
    char with[2048];
    snprintf(with, sizeof with, "%s%s", deck,
             "impactors:\n"
             "  - {name: far, shape: round_nose, position: [5.0, 5.0], radius: 0.003,\n"
             "     axis: [0, -1], motion: prescribed, velocity: [0, 0], contact: no_slip}\n");
    struct sim *a = test_build_ok(deck), *b = test_build_ok(with);
    struct spall_error err = {0};
    while (!sim_done(a)) {
        assert_int_equal(sim_step(a, &err), SPALL_OK);
        assert_int_equal(sim_step(b, &err), SPALL_OK);
    }
    assert_int_equal(a->p->n_owned, b->p->n_owned);
    const size_t n = a->p->n_owned;
    for (int d = 0; d < 2; d++) {
        assert_same_doubles(a->p->x[d], b->p->x[d], n);
        assert_same_doubles(a->p->v[d], b->p->v[d], n);
        assert_same_doubles(a->p->f[d], b->p->f[d], n);
    }
    for (size_t k = 0; k < a->n_bcs; k++) {
        assert_same_doubles(a->bcs[k].reaction, b->bcs[k].reaction, 3);
        assert_memory_equal(&a->bcs[k].work, &b->bcs[k].work, sizeof(double));
    }
    assert_memory_equal(&a->energy.external, &b->energy.external, sizeof(double));
    sim_destroy(&a);
    sim_destroy(&b);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_energy_blowup_in_sim_step),
        cmocka_unit_test(test_drift_velocity_skips_prescribed),
        cmocka_unit_test(test_kick_sum_matches_passes),
        cmocka_unit_test(test_uniform_mass_flag),
        cmocka_unit_test(test_velocity_bcs_before_kick),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
