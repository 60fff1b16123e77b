/* Tests for the macro-particle lattice calibration (macro_lattice.c: FCC
 * elastic constants by lattice sums, calibration: lattice) and the slip
 * detector (macro_slip.c: centro-symmetry, slip normals on a (111) slip). */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include "models/macroparticle/macro_calib.h"
#include "models/macroparticle/macro_slip.h"
#include "spall/error.h"

#include <math.h>
#include <stdbool.h>
#include <stdlib.h>
#include <string.h>

static struct macro_calib al(void)
{
    struct macro_calib c;
    memset(&c, 0, sizeof c);
    c.rho = 2700.0;
    c.atom_mass = 26.98 * MACRO_AMU;
    c.e0 = 3.39 * MACRO_EV;
    c.p = 4;
    c.q = 9;
    c.r0 = 1e-3;
    return c;
}

static void test_lattice_constants(void **state)
{
    (void)state;
    struct spall_error err = {0};
    struct macro_calib c = al();
    assert_int_equal(macro_calibrate(&c, &err), SPALL_OK);
    /* nearest shell only: C11 = 2 C12 = 2 C44 = sqrt2 phi''/r0, no residual
     * stress, E_[100] = (2 sqrt2/3) phi''/r0 = 1.886 Eq. 15, nu = 1/3 */
    assert_true(fabs(c.c11 / (sqrt(2.0) * c.k / c.r0) - 1.0) < 1e-6);
    assert_true(fabs(c.c12 / (0.5 * c.c11) - 1.0) < 1e-6);
    assert_true(fabs(c.c44 / c.c12 - 1.0) < 1e-9);
    assert_true(fabs(c.pressure) < 1e-6 * c.c11);
    assert_true(fabs(c.E_fcc100 / (2.0 * sqrt(2.0) / 3.0 * c.k / c.r0) - 1.0) < 1e-6);
    assert_true(fabs(c.nu_fcc100 - 1.0 / 3.0) < 1e-6);
    assert_true(c.d_scale == 1.0);
    /* lattice calibration: E_[100] hits Eq. 15, D scaled by 3/(4 sqrt2) */
    struct macro_calib l = al();
    l.mode = MACRO_CAL_LATTICE;
    assert_int_equal(macro_calibrate(&l, &err), SPALL_OK);
    assert_true(fabs(l.E_fcc100 / l.E - 1.0) < 1e-12);
    assert_true(fabs(l.d_scale / (3.0 / (4.0 * sqrt(2.0))) - 1.0) < 1e-6);
    assert_true(fabs(l.D / (l.d_scale * l.p_atom / 6.0) - 1.0) < 1e-12);
    assert_true(fabs(l.E / c.E - 1.0) < 1e-12); /* Eq. 15 reported unchanged */
    /* explicit target and a cut-off that takes the second shell (sqrt2 r0)
     * into the taper: residual tension (attractive second shell), target hit */
    struct macro_calib w = al();
    w.mode = MACRO_CAL_LATTICE;
    w.e_target = 70e9;
    w.cutoff = 1.6;
    w.taper = 1.3;
    assert_int_equal(macro_calibrate(&w, &err), SPALL_OK);
    assert_true(fabs(w.E_fcc100 / 70e9 - 1.0) < 1e-12);
    assert_true(w.pressure < 0.0);
    /* bad cut-off */
    struct macro_calib b = al();
    b.cutoff = 1.1;
    assert_int_equal(macro_calibrate(&b, &err), SPALL_ERR_PHYSICS);
    assert_non_null(strstr(err.msg, "cut-off"));
}

/* FCC block of n^3 cubic cells, r0 = 1 (a = sqrt2). */
static size_t fcc_block(int n, double *x[3])
{
    static const double basis[4][3] = {{0, 0, 0}, {0.5, 0.5, 0}, {0.5, 0, 0.5}, {0, 0.5, 0.5}};
    const double a = sqrt(2.0);
    size_t k = 0;
    for (int i = 0; i < n; i++)
        for (int j = 0; j < n; j++)
            for (int l = 0; l < n; l++)
                for (int b = 0; b < 4; b++) {
                    x[0][k] = (i + basis[b][0]) * a;
                    x[1][k] = (j + basis[b][1]) * a;
                    x[2][k] = (l + basis[b][2]) * a;
                    k++;
                }
    return k;
}

static void test_slip_111(void **state)
{
    (void)state;
    const int nc = 6;
    const size_t cap = 4 * (size_t)nc * nc * nc;
    double *x0[3], *x[3];
    for (int d = 0; d < 3; d++) {
        x0[d] = malloc(cap * sizeof(double));
        x[d] = malloc(cap * sizeof(double));
        assert_non_null(x0[d]);
        assert_non_null(x[d]);
    }
    size_t n = fcc_block(nc, x0);
    const double a = sqrt(2.0), cut = 3.3 * a; /* between two (111) layers */
    struct spall_error err = {0};
    struct macro_slip_stats st;
    /* undeformed: nothing slipped, interior perfectly centro-symmetric */
    for (int d = 0; d < 3; d++)
        memcpy(x[d], x0[d], n * sizeof(double));
    assert_int_equal(macro_slip_analyse(n, x, x0, 1.0, 0.25, 10.0, &st, &err), SPALL_OK);
    assert_int_equal(st.n_slipped, 0);
    assert_true(st.csp_mean < 1e-12);
    /* full slip b = (a/2)[1 -1 0] (|b| = r0) of the half above a (111)
     * plane: the lattice is perfect again, the particles next to the plane
     * see 3 slipped partners across it */
    for (size_t i = 0; i < n; i++) {
        bool up = x0[0][i] + x0[1][i] + x0[2][i] > cut;
        x[0][i] = x0[0][i] + (up ? 0.5 * a : 0.0);
        x[1][i] = x0[1][i] - (up ? 0.5 * a : 0.0);
        x[2][i] = x0[2][i];
    }
    assert_int_equal(macro_slip_analyse(n, x, x0, 1.0, 0.25, 10.0, &st, &err), SPALL_OK);
    /* (particles at the block's faces keep fewer than 3 partners across:
     * unclassified, never another plane) */
    assert_true(st.n_slipped > 50);
    assert_true(st.n_111[0] >= 2 * st.n_slipped / 3);
    assert_int_equal(st.n_111[0] + st.n_unclear, st.n_slipped);
    const size_t fault_full = st.n_fault; /* > 0 only where the step meets a face */
    /* partial slip b = (a/6)[1 1 -2] (|b| = r0/sqrt3): a stacking fault, the
     * two layers next to it in an HCP environment (centro-symmetry 1) */
    for (size_t i = 0; i < n; i++) {
        bool up = x0[0][i] + x0[1][i] + x0[2][i] > cut;
        x[0][i] = x0[0][i] + (up ? a / 6.0 : 0.0);
        x[1][i] = x0[1][i] + (up ? a / 6.0 : 0.0);
        x[2][i] = x0[2][i] - (up ? a / 3.0 : 0.0);
    }
    assert_int_equal(macro_slip_analyse(n, x, x0, 1.0, 0.25, 10.0, &st, &err), SPALL_OK);
    /* (particles at the block's faces keep fewer than 3 partners across:
     * unclassified, never another plane) */
    assert_true(st.n_slipped > 50);
    assert_true(st.n_111[0] >= 2 * st.n_slipped / 3);
    assert_int_equal(st.n_111[0] + st.n_unclear, st.n_slipped);
    assert_true(st.n_fault > 4 * fault_full); /* measured: 31 vs 6 */
    for (int d = 0; d < 3; d++) {
        free(x0[d]);
        free(x[d]);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_lattice_constants),
        cmocka_unit_test(test_slip_111),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
