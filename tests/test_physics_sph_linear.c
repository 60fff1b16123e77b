/**
 * @file test_physics_sph_linear.c
 * @brief Linear fields in an SPH body with free surfaces, with corrected
 *        gradients (CSPM, [Meng2021] Eqs. 3.10-3.11, paired in the forces
 *        as [BonetLok1999]): the corrected gradient of a linear velocity
 *        field is exact at every particle, surface included, so the forces
 *        of a uniformly stressed body do the exact virtual work.
 *
 * Continuum identity: a free body under a uniform stress sigma is loaded by
 * the surface jump of the stress only (div sigma = 0 inside, traction -sigma
 * n missing on the surface); under a homogeneous velocity v = L x its power
 * is -oint (sigma n) . L x dA = -V sigma : L.  The SPH forces with CSPM
 * pairing satisfy sum_i f_i . v_i = -sum_i V_i sigma_i : L_i with the same
 * corrected L_i, which is L exactly for a linear v: the identity holds to
 * round-off (measured 6e-16).  Pairing the plain kernel gradient with the
 * stress (CSPM dropped in the forces only) gives -sum_i V_i sigma : L_i^plain
 * instead, short by the surface particles' kernel deficiency (measured
 * 0.20 on this 12 x 8 block).  The check is static: one force evaluation, no time step.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include "core/fields.h"
#include "core/model.h"
#include "tests/test_support.h"

#include <stdio.h>
#include <stdlib.h>

static const double L_GRAD[2][2] = {{0.7, 1.9}, {-0.6, -0.4}}; /* 1/s */

static void test_cspm_linear_fields(void **state)
{
    (void)state;
    /* no artificial viscosity (it would add the compressive pairs' own
     * forces) and a rectangle with corners: every kind of surface particle */
    struct sim *s = test_build_ok(
        "model: {type: sph, kernel: wendland, h_factor: 1.3, cspm: true, viscosity: [0, 0]}\n"
        "materials: {m: {density: 1000, youngs_modulus: 1.0e9, poisson_ratio: 0.3}}\n"
        "lattice: {type: square, spacing: 1.0e-3, origin: [0.0005, 0.0005]}\n"
        "body: {geometry: {box: {min: [0, 0], max: [0.012, 0.008]}}, material: m}\n"
        "run: {steps: 1}\n");
    struct particles *p = s->p;
    const size_t n = p->n_owned;
    /* uniform deviatoric stress through the registry (the pressure is the
     * EOS's at the rest density, read back below) */
    const struct field_desc *fs = field_registry_find(s->fields, "deviatoric_stress");
    const struct field_desc *fp = field_registry_find(s->fields, "pressure");
    const struct field_desc *fr = field_registry_find(s->fields, "density");
    assert_non_null(fs);
    assert_non_null(fp);
    assert_non_null(fr);
    const double S0[6] = {2.0e6, -0.5e6, -1.5e6, 3.0e6, 0.0, 0.0}; /* xx yy zz xy yz xz */
    for (int c = 0; c < 6; c++)
        for (size_t i = 0; i < n; i++)
            (*(double **)fs->comp[c])[i] = S0[c];
    for (size_t i = 0; i < n; i++)
        for (int a = 0; a < 2; a++)
            p->v[a][i] = L_GRAD[a][0] * p->x[0][i] + L_GRAD[a][1] * p->x[1][i];
    struct spall_error err = {0};
    assert_int_equal(sim_initial_forces(s, &err), SPALL_OK);
    double *P = malloc(n * sizeof *P), *rho = malloc(n * sizeof *rho);
    assert_non_null(P);
    assert_non_null(rho);
    field_gather_f64(fp, n, P);
    field_gather_f64(fr, n, rho);
    double power = 0.0, expect = 0.0, scale = 0.0;
    for (size_t i = 0; i < n; i++) {
        const double V = p->mass[i] / rho[i];
        const double sig[2][2] = {{S0[0] - P[i], S0[3]}, {S0[3], S0[1] - P[i]}};
        double sl = 0.0;
        for (int a = 0; a < 2; a++)
            for (int b = 0; b < 2; b++)
                sl += sig[a][b] * L_GRAD[a][b];
        expect -= V * sl;
        for (int a = 0; a < 2; a++) {
            const double va = L_GRAD[a][0] * p->x[0][i] + L_GRAD[a][1] * p->x[1][i];
            power += p->f[a][i] * va;
            scale += fabs(p->f[a][i] * va);
        }
    }
    print_message("%zu particles: sum f.v = %.12e W, -sum V sigma:L = %.12e W, rel. diff %.2e\n",
                  n, power, expect, (power - expect) / fabs(expect));
    /* round-off of a sum of n terms of size <= scale / n */
    assert_true(fabs(power - expect) < 1e-12 * scale + 1e-12 * fabs(expect));
    free(P);
    free(rho);
    sim_destroy(&s);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_cspm_linear_fields),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
