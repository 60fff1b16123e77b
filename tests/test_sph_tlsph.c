/**
 * @file test_sph_tlsph.c
 * @brief Total-Lagrangian SPH after the pair-constant rewrite (sph_tlsph.c):
 *        a free 3D elastic block set spinning and stretching keeps its
 *        momentum to round-off and kinetic + internal energy to 1 % (the
 *        stress power is now V0 P : dF/dt per particle instead of a pair
 *        sum: a wrong pairing shows up as an energy drift), and a 3D
 *        Taylor bar gives bitwise the same positions on 1 and 2 threads,
 *        and with the pipelined sweep as with the stages run one after the
 *        other (sph_set_split_loops).
 */
#include "core/particles.h"
#include "core/sim.h"
#include "models/sph/sph.h"
#include "spall/error.h"

#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "tests/test_support.h"
#include "tests/test_tlsph_bar.h"

#include <math.h>
#include <omp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static void test_free_block_conservation(void **state)
{
    (void)state;
    static const char *yaml =
        "model: {type: tlsph, kernel: wendland, h_factor: 1.005,\n"
        "        viscosity: [0.5, 0.5]}\n"
        "materials: {m: {density: 1000, youngs_modulus: 1.0e7, poisson_ratio: 0.3}}\n"
        "lattice: {type: sc, spacing: 1.0e-3, origin: [0.0005, 0.0005, 0.0005]}\n"
        "body: {geometry: {box: {min: [0, 0, 0], max: [0.006, 0.005, 0.004]}}, material: m}\n"
        "groups: {left: {box: {min: [0, 0, 0], max: [0.002, 1, 1]}},\n"
        "         top: {box: {min: [0.004, 0, 0.002], max: [1, 1, 1]}}}\n"
        "initial_velocity: [{group: left, value: [-1.0, 0.3, 0.2]},\n"
        "                   {group: top, value: [0.8, -0.4, 0.5]}]\n"
        "run: {steps: 300}\n";
    struct sim *s = test_build(yaml);
    assert_non_null(s);
    struct spall_error err = {0};
    double p0[3], p1[3];
    test_momentum_3d(s, p0);
    const double e0 = test_mech_energy(s);
    while (!sim_done(s))
        assert_int_equal(sim_step(s, &err), 0);
    const double e1 = test_mech_energy(s);
    const double pscale = test_momentum_3d(s, p1);
    for (int d = 0; d < 3; d++)
        assert_true(fabs(p1[d] - p0[d]) < 1e-12 * pscale);
    print_message("energy %.9g -> %.9g\n", e0, e1);
    assert_true(fabs(e1 - e0) < 1e-2 * e0);
    sim_destroy(&s);
}

/* The copper bar (about 280 particles, the list's band b ~ 60) run for 150
 * steps on @p threads with @p extra model keys; x and v of every particle
 * into @p xs (2 * 3 * n values, zero-padded to @p nx). */
static void run_bar_keys(int threads, const char *extra, bool split, double *xs, size_t nx)
{
    omp_set_num_threads(threads);
    struct sim *s = test_tlsph_bar(extra, 150);
    if (split)
        sph_set_split_loops(s->model);
    struct spall_error err = {0};
    while (!sim_done(s))
        assert_int_equal(sim_step(s, &err), 0);
    test_pack_xv(s, xs, nx);
    sim_destroy(&s);
}

static void run_bar(int threads, double *xs, size_t nx)
{
    run_bar_keys(threads, "", false, xs, nx);
}

static void test_bar_threads(void **state)
{
    (void)state;
    double a[300], b[300];
    run_bar(1, a, 300);
    run_bar(2, b, 300);
    assert_memory_equal(a, b, sizeof a);
}

/* The pipelined sweep (stage 2 b particles behind stage 1, sph_tlsph.c)
 * against the stages run one after the other (sph_set_split_loops): the same
 * arithmetic per particle, so every position and velocity must agree
 * bitwise -- on 1 thread, 2 threads (shares > 2b: pipelined inside, edges
 * after the barrier) and 5 threads (shares < 2b: everything after it), for
 * both time integrators (the leapfrog advances the state inside stage 1)
 * and with viscosity_switch: balsara. */
static void test_pipeline_split(void **state)
{
    (void)state;
    enum { NX = 6 * 400 };
    static double ref[NX], got[NX], lf[NX];
    /* the third: Balsara's switch, whose f_j the rows read from the
     * partners' blocks written in their stage 1 */
    static const char *const tint[3] = {"", " time_integration: leapfrog, hourglass: 1.0,",
                                        " time_integration: leapfrog, hourglass: 1.0, "
                                        "viscosity_switch: balsara,"};
    for (int k = 0; k < 3; k++) {
        run_bar_keys(1, tint[k], true, ref, NX);
        assert_true(ref[6 * 250] != 0.0); /* about 280 particles filled in */
        const int threads[3] = {1, 2, 5};
        for (int t = 0; t < 3; t++) {
            run_bar_keys(threads[t], tint[k], false, got, NX);
            assert_memory_equal(ref, got, sizeof ref);
        }
        if (k == 1)
            memcpy(lf, ref, sizeof lf);
    }
    assert_true(memcmp(lf, ref, sizeof lf) != 0); /* the switch acts on the bar */
}

/* det F guard: a TLSPH block whose positions are mapped by @p map (then
 * one step) stops with a message naming particle @p who and @p what. */
static void guard_case(const char *extra, int map, const char *who, const char *what)
{
    char yaml[1024];
    snprintf(yaml, sizeof yaml,
             "model: {type: tlsph, plane: strain%s}\n"
             "materials: {m: {density: 1000, youngs_modulus: 1.0e7, poisson_ratio: 0.3}}\n"
             "lattice: {type: square, spacing: 1.0e-3, origin: [0.0005, 0.0005]}\n"
             "body: {geometry: {box: {min: [0, 0], max: [0.006, 0.006]}}, material: m}\n"
             "run: {steps: 5}\n",
             extra);
    struct sim *s = test_build_ok(yaml);
    struct spall_error err = {0};
    for (size_t i = 0; i < s->p->n; i++) {
        double *x = &s->p->x[0][i], *y = &s->p->x[1][i];
        if (map == 0) /* uniform compression to 30 % in x: det F = 0.3 */
            *x *= 0.3;
        else if (map == 1) /* simple shear gamma = 10: distortion (2 + 100)/2 = 51 */
            *x += 10.0 * *y;
        else if (map == 2) /* mirrored: det F = -1 */
            *x = -*x;
    }
    int rc = 0;
    while (!rc && !sim_done(s))
        rc = sim_step(s, &err);
    print_message("guard: %s\n", err.msg);
    assert_int_equal(rc, SPALL_ERR_UNSTABLE);
    assert_non_null(strstr(err.msg, who));
    assert_non_null(strstr(err.msg, what));
    sim_destroy(&s);
}

static void test_det_f_guard(void **state)
{
    (void)state;
    guard_case(", det_f_range: [0.5, 2]", 0, "particle 0 ", "outside det_f_range [0.5, 2]");
    guard_case(", max_distortion: 20", 1, "particle 0 ", "distortion 51");
    guard_case("", 2, "particle 0 ", "inverted or singular (det F = -1");
    /* defaults: det F 0.3 and distortion 51 run on */
    for (int map = 0; map < 2; map++) {
        char yaml[1024];
        snprintf(yaml, sizeof yaml,
                 "model: {type: tlsph, plane: strain}\n"
                 "materials: {m: {density: 1000, youngs_modulus: 1.0e7, poisson_ratio: 0.3}}\n"
                 "lattice: {type: square, spacing: 1.0e-3, origin: [0.0005, 0.0005]}\n"
                 "body: {geometry: {box: {min: [0, 0], max: [0.006, 0.006]}}, material: m}\n"
                 "run: {steps: 1}\n");
        struct sim *s = test_build_ok(yaml);
        for (size_t i = 0; i < s->p->n; i++) {
            if (map == 0)
                s->p->x[0][i] *= 0.3;
            else
                s->p->x[0][i] += 10.0 * s->p->x[1][i];
        }
        struct spall_error err = {0};
        assert_int_equal(sim_step(s, &err), 0);
        sim_destroy(&s);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_free_block_conservation),
        cmocka_unit_test(test_bar_threads),
        cmocka_unit_test(test_pipeline_split),
        cmocka_unit_test(test_det_f_guard),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
