/**
 * @file test_physics_tlsph_jacobian.c
 * @brief First Piola-Kirchhoff forces of total-Lagrangian SPH
 *        (src/models/sph/sph_tlsph.c, [Ganzenmuller2015]): a free body
 *        compressed uniformly, F = lambda I with J = det F = 0.9, is loaded
 *        by the Cauchy stress sigma = -p I acting on its CURRENT surface,
 *        P N dA0 = J sigma F^-T N dA0 = sigma n da.
 *
 * Continuum statement: the SPH forces of a free, uniformly stressed body are
 * the missing surface tractions.  Cut the body by the plane x = x_c (its
 * middle): the forces on the particles beyond it sum to the traction the
 * other half exerts through the cut, -sigma_xx H (x direction), with H the
 * cut's current length (plane strain, per unit thickness); likewise across
 * y = y_c.  In the reference configuration the cut is H0 = H / lambda long,
 * and PK_xx = J sigma_xx / lambda = lambda sigma_xx: the PK force
 * -PK_xx H0 = -sigma_xx H.  Without the factor J the force would be
 * -sigma_xx H / J, 11 % larger at J = 0.9.
 *
 * The discrete sum is that of the reference lattice (kernel, corrected
 * gradients and neighbours are all in the reference configuration) times
 * the uniform PK, so its error is the lattice's quadrature of the cut,
 * independent of J: the pair forces across the cut sum to the cut's length
 * to round-off on this mirror-symmetric lattice (measured 6.7e-16 and
 * 2.2e-16 relative; tolerance 1e-12).  The particles' own forces are not
 * zero away from the surface here (a 12 x 8 block: every particle is
 * within two supports of it, where the neighbours' correction matrices
 * differ), so the check is on the cut sums, which do not depend on that.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include "core/fields.h"
#include "models/sph/sph.h"
#include "tests/test_assert.h"
#include "tests/test_support.h"

#include <math.h>
#include <stdio.h>

#define RHO0 1000.0
#define J_VOL 0.9

static void test_pk_forces_compressed(void **state)
{
    (void)state;
    const double dx = 1.0e-3, W0 = 0.012, H0 = 0.008;
    struct sim *s = test_build_ok(
        "model: {type: tlsph, kernel: wendland, h_factor: 1.3,"
        " viscosity: [0, 0]}\n"
        "materials: {m: {density: 1000, youngs_modulus: 1.0e9, poisson_ratio: 0.3}}\n"
        "lattice: {type: square, spacing: 1.0e-3, origin: [0.0005, 0.0005]}\n"
        "body: {geometry: {box: {min: [0, 0], max: [0.012, 0.008]}}, material: m}\n"
        "run: {steps: 1}\n");
    struct particles *p = s->p;
    const size_t n = p->n_owned;
    /* uniform compression about the centre: F = lambda I (plane strain) */
    const double lam = sqrt(J_VOL), c[2] = {0.5 * W0, 0.5 * H0};
    for (size_t i = 0; i < n; i++)
        for (int d = 0; d < 2; d++)
            p->x[d][i] = c[d] + lam * (p->x[d][i] - c[d]);
    /* the density of the compressed state, rho0 / J, sets the EOS pressure */
    const struct field_desc *fr = field_registry_find(s->fields, "density");
    const struct field_desc *fp = field_registry_find(s->fields, "pressure");
    const struct field_desc *fs = field_registry_find(s->fields, "deviatoric_stress");
    assert_non_null(fr);
    assert_non_null(fp);
    assert_non_null(fs);
    for (size_t i = 0; i < n; i++)
        (*(double **)fr->comp[0])[i] = RHO0 / J_VOL;
    struct spall_error err = {0};
    assert_int_equal(sim_initial_forces(s, &err), SPALL_OK);
    const double *P = *(double **)fp->comp[0];
    const double *Sxx = *(double **)fs->comp[0], *Syy = *(double **)fs->comp[1];
    /* the state is homogeneous: F = lambda I and the same stress everywhere */
    double F[9];
    sph_tlsph_deformation(s->model, 0, F);
    assert_near(F[0] * F[4] - F[1] * F[3], J_VOL, 1e-12);
    const double sxx = Sxx[0] - P[0], syy = Syy[0] - P[0];
    assert_true(P[0] > 0.0); /* compressed */
    double fx_right = 0.0, fy_top = 0.0, fx_all = 0.0, fy_all = 0.0;
    for (size_t i = 0; i < n; i++) {
        sph_tlsph_deformation(s->model, i, F);
        assert_near(F[0], lam, 1e-12);
        assert_near(F[4], lam, 1e-12);
        assert_near(F[1], 0.0, 1e-12);
        assert_near(F[3], 0.0, 1e-12);
        assert_near(Sxx[i] - P[i], sxx, 1e-12 * fabs(sxx));
        assert_near(Syy[i] - P[i], syy, 1e-12 * fabs(syy));
        if (p->x[0][i] > c[0])
            fx_right += p->f[0][i];
        if (p->x[1][i] > c[1])
            fy_top += p->f[1][i];
        fx_all += p->f[0][i];
        fy_all += p->f[1][i];
    }
    /* a 2D particle's volume is m / rho0 = dx^2 t: the body's thickness t */
    const double t = p->mass[0] / (RHO0 * dx * dx);
    const double fx_exact = -sxx * lam * H0 * t, fy_exact = -syy * lam * W0 * t;
    print_message("J = %.2f, p = %.6e Pa: right half sum f_x = %.12e N (-sigma_xx H = %.12e, "
                  "rel. %.1e), top half sum f_y = %.12e (-sigma_yy W = %.12e, rel. %.1e), "
                  "|sum f| = %.1e N\n",
                  J_VOL, P[0], fx_right, fx_exact, fx_right / fx_exact - 1.0, fy_top, fy_exact,
                  fy_top / fy_exact - 1.0, hypot(fx_all, fy_all));
    assert_near(fx_right, fx_exact, 1e-12 * fabs(fx_exact));
    assert_near(fy_top, fy_exact, 1e-12 * fabs(fy_exact));
    assert_near(fx_all, 0.0, 1e-12 * fabs(fx_exact)); /* Newton III */
    assert_near(fy_all, 0.0, 1e-12 * fabs(fy_exact));
    sim_destroy(&s);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_pk_forces_compressed),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
