/*
 * Tests of the triple honeycomb (alpha-beta-gamma) lattice: sublattice
 * colouring, bond families, the calibration formulas, the relaxed patch test
 * for nu = 0.4, 0.443 and 0.7 (E and nu within 1e-3), refusal of nu outside
 * [1/3, 1), a small plate that fractures under tension, the stable step
 * (omega_max dt < 2, bounded energy) and the example deck.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include "core/bond_list.h"
#include "core/lattice_gen.h"
#include "core/particles.h"
#include "core/sim.h"
#include "io/deck.h"
#include "io/deck_build.h"
#include "models/lattice/lattice_calib.h"
#include "models/lattice/lattice_honeycomb.h"
#include "core/model.h"
#include "spall/error.h"
#include "validation/lattice_cases.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static void near(double a, double b, double tol)
{
    assert_true(fabs(a - b) <= tol);
}

static struct lattice_calib hc_calib(double nu)
{
    struct lattice_calib c;
    memset(&c, 0, sizeof c);
    c.kind = LATTICE_TRIPLE_HONEYCOMB;
    c.angular = -1;
    c.E = 3.0e9;
    c.nu = nu;
    c.rho = 1140.0;
    c.r0 = 1e-3;
    c.thickness = 2e-3 / sqrt(3.0);
    return c;
}

static void test_sublattice_colouring(void **state)
{
    (void)state;
    const double angles[] = {0.0, 0.3, -1.1};
    for (int a = 0; a < 3; a++) {
        struct lattice_spec s = {.kind = LATTICE_TRIPLE_HONEYCOMB, .spacing = 1e-3,
                                 .origin = {0.2e-3, -0.1e-3, 0}, .angle = angles[a]};
        int count[3] = {0, 0, 0};
        for (int j = -4; j <= 4; j++)
            for (int i = -4; i <= 4; i++) {
                /* site i a1 + j a2 in the lattice frame, rotated */
                double u = (i + 0.5 * j) * 1e-3, v = j * 1e-3 * sqrt(3.0) / 2.0;
                double ca = cos(s.angle), sa = sin(s.angle);
                double x[2] = {s.origin[0] + ca * u - sa * v, s.origin[1] + sa * u + ca * v};
                int c = lattice_sublattice(&s, x);
                assert_true(c >= 0 && c <= 2);
                count[c]++;
                for (int k = 0; k < 6; k++) { /* every neighbour has another colour */
                    double th = s.angle + k * 1.0471975511965976;
                    double y[2] = {x[0] + 1e-3 * cos(th), x[1] + 1e-3 * sin(th)};
                    int cn = lattice_sublattice(&s, y);
                    assert_int_not_equal(cn, c);
                    /* +r0 along the lattice's x axis: next colour (k even), else previous */
                    assert_int_equal(cn, (c + (k % 2 == 0 ? 1 : 2)) % 3);
                }
            }
        assert_true(count[0] > 20 && count[1] > 20 && count[2] > 20);
    }
    struct lattice_spec sq = {.kind = LATTICE_SQUARE, .spacing = 1e-3};
    const double z[2] = {0, 0};
    assert_int_equal(lattice_sublattice(&sq, z), -1);
}

static void test_constants_and_moduli(void **state)
{
    (void)state;
    struct spall_error err = {0};
    const double E = 3e9, t = 1e-3;
    const double nus[] = {1.0 / 3.0, 0.35, 0.4, 0.443, 0.6, 0.9, 0.99};
    for (size_t q = 0; q < sizeof nus / sizeof nus[0]; q++) {
        double k[3], kap, mu;
        assert_int_equal(lattice_honeycomb_constants(E, nus[q], t, k, &err), 0);
        assert_true(k[0] > 0.0 && k[0] <= k[1] * (1.0 + 1e-12) && k[1] == k[2]);
        lattice_honeycomb_moduli(k, &kap, &mu);
        double Em = 4.0 * kap * mu / (kap + mu) / t, num = (kap - mu) / (kap + mu);
        near(Em, E, 1e-9 * E);
        near(num, nus[q], 1e-9);
    }
    double k[3];
    assert_int_equal(lattice_honeycomb_constants(E, 1.0 / 3.0, t, k, &err), 0);
    near(k[0], k[1], 1e-9 * k[1]); /* plain triangular lattice */
    near(k[0], E * t / (sqrt(3.0) * (2.0 / 3.0)), 1e-9 * k[0]);
    assert_int_equal(lattice_honeycomb_constants(E, 0.3, t, k, &err), SPALL_ERR_PHYSICS);
    assert_non_null(strstr(err.msg, "[1/3, 1)"));
    assert_int_equal(lattice_honeycomb_constants(E, 1.0, t, k, &err), SPALL_ERR_PHYSICS);
    assert_int_equal(lattice_honeycomb_constants(E, -0.2, t, k, &err), SPALL_ERR_PHYSICS);
}

static void test_patch_relaxed(void **state)
{
    (void)state;
    struct spall_error err = {0};
    const double nus[] = {0.4, 0.443, 0.7};
    for (size_t q = 0; q < 3; q++) {
        struct lattice_calib c = hc_calib(nus[q]);
        struct lattice_patch_result r;
        assert_int_equal(lattice_patch_test_full(&c, 1e-6, 0, &r, &err), 0);
        assert_true(fabs(r.E / c.E - 1.0) < 1e-3);
        assert_true(fabs(r.nu - nus[q]) < 1e-3);
        assert_true(r.f_interior_max < 1e-6); /* relaxed: interior in equilibrium */
        /* without the sublattice shifts the block is the affine lattice:
         * nu = 1/3 whatever the families */
        assert_true(fabs(r.nu_affine - 1.0 / 3.0) < 1e-4);
        assert_true(r.E_affine > r.E);
    }
    struct lattice_calib c = hc_calib(0.2);
    assert_int_equal(lattice_calibrate(&c, &err), SPALL_ERR_PHYSICS);
    c = hc_calib(0.4);
    c.layers = 2;
    assert_int_equal(lattice_calibrate(&c, &err), SPALL_ERR_PHYSICS);
    c = hc_calib(0.4);
    c.angular = 1;
    assert_int_equal(lattice_calibrate(&c, &err), SPALL_ERR_PHYSICS);
}

static const char *const PLATE =
    "title: triple honeycomb plate\n"
    "model: {type: lattice}\n"
    "materials:\n"
    "  m: {density: 1140, youngs_modulus: 3.0e9, poisson_ratio: %g, tensile_strength: 60.0e6}\n"
    "lattice: {type: triple_honeycomb, spacing: 1.0e-3}\n"
    "geometry:\n"
    "  plate: {box: {min: [0, 0], max: [0.012, 0.020]}}\n"
    "body: {geometry: plate, material: m}\n"
    "groups:\n"
    "  bottom: {box: {min: [-1, -1], max: [1, 0.0015]}}\n"
    "  top: {box: {min: [-1, 0.0185], max: [1, 1]}}\n"
    "boundary_conditions:\n"
    "  - {group: bottom, type: velocity, components: [x, y], value: [0, -%g]}\n"
    "  - {group: top, type: velocity, components: [x, y], value: [0, %g]}\n"
    "run: {end_time: 1.0e-4}\n";

static void test_plate_families_and_fracture(void **state)
{
    (void)state;
    struct spall_error err = {0};
    char deck[2048];
    snprintf(deck, sizeof deck, PLATE, 0.443, 5.0, 5.0);
    struct sim *s = NULL;
    assert_int_equal(vlat_build("hc_plate", deck, &s, &err), 0);
    assert_true(s->lattice.kind == LATTICE_TRIPLE_HONEYCOMB); /* bond type = family */
    const struct bond_list *bl = s->ops->bonds(s->model);
    const struct particles *p = s->p;
    /* a bulk site has 6 bonds: 3 + 3 of the two families not its colour */
    size_t bulk = 0;
    for (size_t i = 0; i < p->n; i++) {
        size_t len = bl->offset[i + 1] - bl->offset[i];
        const double xi[2] = {p->x0[0][i], p->x0[1][i]};
        int c = lattice_sublattice(&s->lattice, xi);
        int nf[3] = {0, 0, 0};
        for (size_t q = bl->offset[i]; q < bl->offset[i + 1]; q++)
            nf[bl->type[q]]++;
        assert_int_equal(nf[c], 0);
        if (len == 6) {
            bulk++;
            assert_int_equal(nf[(c + 1) % 3], 3);
            assert_int_equal(nf[(c + 2) % 3], 3);
        }
    }
    assert_true(bulk > 100);
    /* grips at 5 m/s each: eps_max = 0.02 is reached in about 40 us */
    double broken = 0.0;
    while (s->t < 1.0e-4) {
        assert_int_equal(sim_step(s, &err), 0);
    }
    broken = vlat_history(s, "bonds_broken");
    assert_true(broken > 10.0);
    sim_destroy(&s);
    /* nu < 1/3 on the triple honeycomb: refused with the reason */
    snprintf(deck, sizeof deck, PLATE, 0.25, 5.0, 5.0);
    assert_int_equal(vlat_build("hc_bad", deck, &s, &err), SPALL_ERR_PHYSICS);
    assert_non_null(strstr(err.msg, "1/3"));
    assert_null(s);
}

static double hc_energy(struct sim *s)
{
    struct model_energy e;
    s->ops->energy(s->model, s, &e);
    double kin = 0.0;
    for (size_t i = 0; i < s->p->n; i++)
        kin += 0.5 * s->p->mass[i] * (s->p->v[0][i] * s->p->v[0][i] +
                                      s->p->v[1][i] * s->p->v[1][i]);
    return kin + e.strain;
}

/* elastic free plate with random velocities at the full Gershgorin step
 * (stable_dt, not the default half of it): the optical modes of the
 * sublattices stay stable and the energy bounded, at nu = 0.7 (stiffness
 * contrast beta/alpha = 10) */
static void test_stable_step(void **state)
{
    (void)state;
    struct spall_error err = {0};
    char deck[2048];
    snprintf(deck, sizeof deck, PLATE, 0.7, 0.0, 0.0);
    struct sim *s = NULL;
    assert_int_equal(vlat_build("hc_plate", deck, &s, &err), 0);
    s->n_bcs = 0; /* free plate */
    /* omega_max: power iteration on M^-1 H (H v = -dF/dx v, finite differences) */
    const size_t n = s->p->n;
    double *v = malloc(2 * n * sizeof *v);
    assert_non_null(v);
    for (size_t q = 0; q < 2 * n; q++)
        v[q] = 1.0 + 0.1 * (double)(q % 7) - 0.05 * (double)(q % 3);
    double lam = 0.0;
    for (int it = 0; it < 400; it++) {
        double nv = 0.0;
        for (size_t q = 0; q < 2 * n; q++)
            nv = fmax(nv, fabs(v[q]));
        for (size_t i = 0; i < n; i++)
            for (int d = 0; d < 2; d++)
                s->p->x[d][i] = s->p->x0[d][i] + 1e-9 * v[2 * i + (size_t)d] / nv;
        particles_zero_forces(s->p);
        assert_int_equal(s->ops->compute_forces(s->model, s, &err), 0);
        lam = 0.0;
        for (size_t i = 0; i < n; i++)
            for (int d = 0; d < 2; d++) {
                v[2 * i + (size_t)d] = -s->p->f[d][i] / (1e-9 * s->p->mass[i]);
                lam = fmax(lam, fabs(v[2 * i + (size_t)d]));
            }
    }
    free(v);
    for (size_t i = 0; i < n; i++)
        for (int d = 0; d < 2; d++)
            s->p->x[d][i] = s->p->x0[d][i];
    const double wdt = sqrt(lam) * s->ops->stable_dt(s->model, s);
    printf("  triple honeycomb nu = 0.7: omega_max stable_dt = %.4f (stable below 2)\n", wdt);
    assert_true(wdt < 2.0);
    unsigned seed = 12345u;
    for (size_t i = 0; i < s->p->n; i++)
        for (int d = 0; d < 2; d++) {
            seed = seed * 1103515245u + 12345u;
            s->p->v[d][i] = 0.1 * ((double)(seed >> 8) / 16777216.0 - 0.5);
        }
    s->dt = s->ops->stable_dt(s->model, s);
    assert_int_equal(sim_initial_forces(s, &err), 0);
    const double e0 = hc_energy(s);
    double emax = e0;
    for (int k = 0; k < 3000; k++) {
        assert_int_equal(sim_step(s, &err), 0);
        if (k % 100 == 99)
            emax = fmax(emax, hc_energy(s));
    }
    printf("  triple honeycomb nu = 0.7 at dt = stable_dt = %.3g s: energy max/initial = %.4f\n",
           s->dt, emax / e0);
    assert_true(emax < 1.5 * e0);
    assert_true(vlat_history(s, "bonds_broken") == 0.0);
    sim_destroy(&s);
}

/* examples/abg_plate builds as shipped (not run: that is `spall run`) */
static void test_example_builds(void **state)
{
    (void)state;
    const char *src = getenv("SPALL_SOURCE_DIR");
    char path[1024];
    snprintf(path, sizeof path, "%s/examples/abg_plate/abg_plate.yaml", src ? src : "..");
    struct spall_error err = {0};
    struct deck *d = NULL;
    assert_int_equal(deck_load_file(&d, path, &err), 0);
    struct sim *s = NULL;
    struct run_output ro;
    int rc = deck_build_sim(d, &s, &ro, &err);
    if (rc)
        fprintf(stderr, "%s\n", err.msg);
    assert_int_equal(rc, 0);
    assert_int_equal(s->lattice.kind, LATTICE_TRIPLE_HONEYCOMB);
    assert_true(s->p->n > 10000 && s->lattice.kind == LATTICE_TRIPLE_HONEYCOMB);
    sim_destroy(&s);
    deck_destroy(&d);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_sublattice_colouring),
        cmocka_unit_test(test_constants_and_moduli),
        cmocka_unit_test(test_patch_relaxed),
        cmocka_unit_test(test_plate_families_and_fracture),
        cmocka_unit_test(test_stable_step),
        cmocka_unit_test(test_example_builds),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
