/**
 * @file test_sph_as_smooth.c
 * @brief The kernel-averaged artificial stress (sph_as_smooth.c): a uniform
 *        R is kept exactly (surfaces included), a checkerboard R is damped,
 *        the deck key is refused with symmetry planes, and the instability
 *        it removes: a small quintic-spline cantilever with AS 0.5 and no
 *        artificial viscosity gains kinetic energy far beyond the load's work
 *        with the pointwise R and stays physical with the averaged one.
 */
#include "core/neighbor.h"
#include "core/particles.h"
#include "core/sim.h"
#include "io/deck.h"
#include "io/deck_build.h"
#include "models/sph/sph.h"
#include "spall/error.h"

#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include <math.h>
#include <stdio.h>
#include <string.h>

static struct sim *build(const char *yaml, struct spall_error *err)
{
    struct deck *d = NULL;
    struct sim *s = NULL;
    struct run_output ro;
    if (deck_load_string(&d, "t", yaml, err) || deck_build_sim(d, &s, &ro, err)) {
        deck_destroy(&d);
        return NULL;
    }
    deck_destroy(&d);
    return s;
}

static const char *BLOCK =
    "model: {type: sph, kernel: quintic_spline, h_factor: 1.2, plane: stress, cspm: true,\n"
    "        artificial_stress: 0.5, artificial_stress_smoothing: true}\n"
    "materials: {m: {density: 7800, youngs_modulus: 210.0e9, poisson_ratio: 0.3}}\n"
    "lattice: {type: square, spacing: 1.0e-3, origin: [0.0005, 0.0005], thickness: 1.0e-3}\n"
    "body: {geometry: {box: {min: [0, 0], max: [0.012, 0.008]}}, material: m}\n"
    "run: {steps: 1}\n";

static void uniform_and_checkerboard(void **state)
{
    (void)state;
    struct spall_error err = {0};
    struct sim *s = build(BLOCK, &err);
    if (!s)
        print_error("%s\n", err.msg);
    assert_non_null(s);
    assert_int_equal(sim_initial_forces(s, &err), 0);
    struct model *m = s->model;
    const struct particles *p = s->p;
    struct sph_stats st;
    sph_stats_get(m, &st);
    assert_true(st.as_smooth);
    double *R[6];
    for (int c = 0; c < 6; c++)
        R[c] = sph_artificial_stress_data(m, c);
    for (size_t i = 0; i < p->n; i++)
        for (int c = 0; c < 6; c++)
            R[c][i] = 1.0 + 0.5 * c;
    sph_artificial_stress_smooth(m, s);
    for (size_t i = 0; i < p->n; i++)
        for (int c = 0; c < 6; c++)
            assert_true(fabs(R[c][i] - (1.0 + 0.5 * c)) < 1e-12);
    /* checkerboard: the particle-scale part the smoothing is for */
    double worst = 0.0;
    for (size_t i = 0; i < p->n; i++) {
        int a = (int)floor(p->x0[0][i] * 1e3), b = (int)floor(p->x0[1][i] * 1e3);
        for (int c = 0; c < 6; c++)
            R[c][i] = ((a + b) % 2) ? 1.0 : -1.0;
    }
    sph_artificial_stress_smooth(m, s);
    for (size_t i = 0; i < p->n; i++) {
        double x = p->x0[0][i], y = p->x0[1][i];
        if (x > 0.004 && x < 0.008 && y > 0.004 && y < 0.005) /* interior */
            worst = fmax(worst, fabs(R[SXX][i]));
    }
    assert_true(worst < 0.2);
    sim_destroy(&s);
}

static void refused_with_symmetry(void **state)
{
    (void)state;
    struct spall_error err = {0};
    struct sim *s = build(
        "model: {type: sph, symmetry: x, artificial_stress: 0.5,"
        " artificial_stress_smoothing: true}\n"
        "materials: {m: {density: 7800, youngs_modulus: 210.0e9, poisson_ratio: 0.3}}\n"
        "lattice: {type: square, spacing: 1.0e-3, origin: [0.0005, 0.0005]}\n"
        "body: {geometry: {box: {min: [0, 0], max: [0.005, 0.005]}}, material: m}\n"
        "run: {steps: 1}\n",
        &err);
    assert_null(s);
    assert_int_equal(err.code, SPALL_ERR_INPUT);
    assert_non_null(strstr(err.msg, "artificial_stress_smoothing"));
}

/* Kinetic energy / load work after 1000 steps of a 40 x 8 mm quintic beam. */
static double beam_ke_ratio(bool smooth)
{
    char deck[2048];
    snprintf(deck, sizeof deck,
             "model: {type: sph, kernel: quintic_spline, h_factor: 1.2, plane: stress,\n"
             "        cspm: true, time_integration: leapfrog, viscosity: [0, 0],\n"
             "        artificial_stress: 0.5, artificial_stress_smoothing: %s}\n"
             "materials: {m: {density: 7800, youngs_modulus: 210.0e9, poisson_ratio: 0.3}}\n"
             "lattice: {type: square, spacing: 1.0e-3, origin: [0.0005, 0.0005], "
             "thickness: 1.0e-3}\n"
             "body: {geometry: {box: {min: [-0.003, -0.004], max: [0.04, 0.004]}}, "
             "material: m}\n"
             "groups:\n"
             "  clamp: {box: {min: [-0.004, -1], max: [0.0, 1]}}\n"
             "  tip: {box: {min: [0.039, -1], max: [0.041, 1]}}\n"
             "boundary_conditions:\n"
             "  - {group: clamp, type: fixed}\n"
             "  - {group: tip, type: force, components: [y], value: -100.0,\n"
             "     function: {type: quadratic_ramp, duration: 1.0e-3}}\n"
             "run: {steps: 1000, dt_factor: 0.5, energy_blowup: 1e30}\n",
             smooth ? "true" : "false");
    struct spall_error err = {0};
    struct sim *s = build(deck, &err);
    if (!s)
        print_error("%s\n", err.msg);
    assert_non_null(s);
    int rc = 0;
    while (!sim_done(s) && !rc)
        rc = sim_step(s, &err);
    double ratio = INFINITY;
    if (!rc) {
        sim_update_energy(s);
        ratio = s->energy.kinetic / s->energy.external;
    }
    sim_destroy(&s);
    return ratio;
}

static void beam_instability(void **state)
{
    (void)state;
    double pointwise = beam_ke_ratio(false), smoothed = beam_ke_ratio(true);
    print_message("KE / load work after 1000 steps: pointwise R %.3g, averaged R %.3g\n",
                  pointwise, smoothed);
    assert_true(smoothed < 1.0);  /* a loaded elastic beam: KE below the work */
    assert_true(pointwise > 10.0); /* the pointwise R's instability */
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(uniform_and_checkerboard),
        cmocka_unit_test(refused_with_symmetry),
        cmocka_unit_test(beam_instability),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
