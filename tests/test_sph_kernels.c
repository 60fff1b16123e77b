/**
 * @file test_sph_kernels.c
 * @brief The six SPH kernels ([Meng2021] Fig. 3.1): normalisation and the
 *        first moment of the gradient by lattice sums in 1D, 2D and 3D,
 *        and dK/dq against a finite difference.
 *
 * On a lattice of spacing dx = h/N the sum of W dx^d approximates the
 * integral (=1) and sum dx^d (x_j - x_i) (x) grad_i W = I (the "-I" of the
 * brief written with x_i - x_j).  The Gaussian is truncated at 3h with a
 * jump of e^-9: its lattice sums converge slowly (finer lattice), and its
 * gradient moment is I minus the surface term of the jump (computed here).
 */
#include "models/sph/sph_kernels.h"

#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include <math.h>

static void moments(enum sph_kernel k, int dim, int N, double *sum, double mom[3][3])
{
    const double h = 1.0, dx = h / N;
    const double a = sph_kernel_alpha(k, dim);
    const int R = (int)ceil(sph_kernel_support(k) * N) + 1;
    const double hd = pow(h, dim);
    *sum = 0.0;
    for (int a1 = 0; a1 < 3; a1++)
        for (int b = 0; b < 3; b++)
            mom[a1][b] = 0.0;
    int rz = dim == 3 ? R : 0, ry = dim >= 2 ? R : 0;
    /* the sample point sits at a generic offset from the lattice */
    const double off[3] = {0.31 * dx, 0.17 * dx, 0.43 * dx};
    for (int iz = -rz; iz <= rz; iz++)
        for (int iy = -ry; iy <= ry; iy++)
            for (int ix = -R; ix <= R; ix++) {
                double xj[3] = {ix * dx - off[0], dim >= 2 ? iy * dx - off[1] : 0,
                                dim == 3 ? iz * dx - off[2] : 0};
                double r = sqrt(xj[0] * xj[0] + xj[1] * xj[1] + xj[2] * xj[2]);
                double W, F;
                sph_kernel_eval(k, a, r, h, hd, &W, &F);
                double vol = pow(dx, dim);
                *sum += W * vol;
                for (int p = 0; p < dim; p++)
                    for (int q = 0; q < dim; q++)
                        mom[p][q] += vol * xj[p] * F * (-xj[q]); /* grad_i W = F (x_i - x_j) */
            }
}

static void test_normalisation(void **state)
{
    (void)state;
    for (int k = 1; k <= 6; k++)
        for (int dim = 1; dim <= 3; dim++) {
            int N = dim == 1 ? 2000 : dim == 2 ? 200 : 30;
            if (k == SPH_KERNEL_GAUSSIAN)
                N = dim == 1 ? 20000 : dim == 2 ? 600 : 30;
            double sum, mom[3][3];
            moments((enum sph_kernel)k, dim, N, &sum, mom);
            double tol = 1e-6;
            if (k == SPH_KERNEL_GAUSSIAN && dim == 3)
                tol = 2e-5; /* truncation jump: see the file comment */
            if (fabs(sum - 1.0) > tol)
                print_error("kernel %d dim %d: sum W dV = %.12f\n", k, dim, sum);
            assert_true(fabs(sum - 1.0) <= tol);
            for (int p = 0; p < dim; p++)
                for (int q = 0; q < dim; q++) {
                    double ref = p == q ? 1.0 : 0.0;
                    if (k == SPH_KERNEL_GAUSSIAN && p == q) {
                        /* the jump W(3h) at the cut adds the surface term
                         * W(3) * 3 * |S_d(3)| / d to -integral(x dW) */
                        double area = dim == 1 ? 2.0 : dim == 2 ? 6.0 * SPALL_PI : 36.0 * SPALL_PI;
                        ref -= sph_kernel_alpha(SPH_KERNEL_GAUSSIAN, dim) * exp(-9.0) * 3.0 *
                               area / dim;
                    }
                    if (fabs(mom[p][q] - ref) > tol)
                        print_error("kernel %d dim %d: moment[%d][%d] = %.12f\n", k, dim, p, q,
                                    mom[p][q]);
                    assert_true(fabs(mom[p][q] - ref) <= tol);
                }
        }
}

static void test_derivative(void **state)
{
    (void)state;
    for (int k = 1; k <= 6; k++)
        for (double q = 0.05; q < sph_kernel_support((enum sph_kernel)k) - 0.01; q += 0.0937) {
            double K0, d0, Kp, dp, Km, dm;
            const double e = 1e-6;
            sph_kernel_shape((enum sph_kernel)k, q, &K0, &d0);
            sph_kernel_shape((enum sph_kernel)k, q + e, &Kp, &dp);
            sph_kernel_shape((enum sph_kernel)k, q - e, &Km, &dm);
            assert_true(fabs((Kp - Km) / (2 * e) - d0) < 1e-5 * (1.0 + fabs(d0)));
        }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_normalisation),
        cmocka_unit_test(test_derivative),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
