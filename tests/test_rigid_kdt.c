/**
 * @file test_rigid_kdt.c
 * @brief Impactor penalty stiffness with an adaptive step (`stiffness_dt`,
 *        core/rigid.c): with `first_contact` k = eta m / dt^2 is frozen at
 *        the first contact step and the penalty conserves energy; with
 *        `step` (the default) k follows the adaptive dt (SPH) and the
 *        springs that stiffen while compressed create energy (measured,
 *        printed, not asserted).
 */
#include "core/rigid.h"
#include "core/sim.h"
#include "io/deck.h"
#include "io/deck_build.h"
#include "spall/error.h"

#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "tests/test_support.h"

#include <math.h>
#include <stdio.h>

/* A rigid disc at 200 m/s onto a soft plane-strain SPH block (adaptive dt:
 * the step drops as the hit particles speed up); returns the largest
 * |energy balance| over the run relative to the disc's kinetic energy. */
static double run(const char *mode, double *k_dt)
{
    char yaml[1024];
    snprintf(yaml, sizeof yaml,
             "model: {type: sph, kernel: wendland, h_factor: 1.3, viscosity: [0.5, 0.2],\n"
             "        plane: strain}\n"
             "materials: {a: {density: 1000, youngs_modulus: 1.0e7, poisson_ratio: 0.3}}\n"
             "lattice: {type: square, spacing: 1.0e-3, origin: [0.0005, 0.0005]}\n"
             "body: {geometry: {box: {min: [0, 0], max: [0.012, 0.008]}}, material: a}\n"
             "impactors:\n"
             "  - {name: ball, shape: sphere, position: [0.006, 0.0105], radius: 0.002,\n"
             "     mass: 2.0e-2, velocity: [0, -200], gravity: false, contact: penalty,\n"
             "     stiffness_dt: %s}\n"
             "run: {end_time: 6.0e-5}\n",
             mode);
    struct deck *d = NULL;
    struct sim *s = NULL;
    struct run_output ro;
    struct spall_error err = {0};
    if (deck_load_string(&d, "t", yaml, &err) || deck_build_sim(d, &s, &ro, &err))
        print_error("%s\n", err.msg);
    deck_destroy(&d);
    assert_non_null(s);
    const double ke0 = 0.5 * 2.0e-2 * 200.0 * 200.0;
    double worst = 0.0;
    while (!sim_done(s)) {
        assert_int_equal(sim_step(s, &err), 0);
        sim_update_energy(s);
        worst = fmax(worst, fabs(s->energy.balance) / ke0);
    }
    *k_dt = s->rigid->im[0].k_dt;
    sim_destroy(&s);
    return worst;
}

static void test_frozen_stiffness_conserves(void **state)
{
    (void)state;
    double kdt_step, kdt_frozen;
    double e_step = run("step", &kdt_step);
    double e_frozen = run("first_contact", &kdt_frozen);
    print_message("max |energy balance| / KE0: step %.3g, first_contact %.3g (k dt %.4g s)\n",
                  e_step, e_frozen, kdt_frozen);
    assert_true(kdt_step == 0.0);  /* not frozen by default */
    assert_true(kdt_frozen > 0.0); /* frozen at the first contact */
    assert_true(e_frozen < 2e-5);  /* measured 5.3e-6 (step: 1.5e-3) */
}

static void test_bad_value(void **state)
{
    (void)state;
    const char *yaml =
        "model: {type: sph}\n"
        "materials: {a: {density: 1000, youngs_modulus: 1.0e7, poisson_ratio: 0.3}}\n"
        "lattice: {type: square, spacing: 1.0e-3, origin: [0.0005, 0.0005]}\n"
        "body: {geometry: {box: {min: [0, 0], max: [0.004, 0.004]}}, material: a}\n"
        "impactors: [{name: b, shape: sphere, position: [0.002, 0.006], radius: 0.001,\n"
        "             mass: 1.0e-3, stiffness_dt: initial}]\n"
        "run: {steps: 1}\n";
    test_deck_refused(yaml, "stiffness_dt");
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_frozen_stiffness_conserves),
        cmocka_unit_test(test_bad_value),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
